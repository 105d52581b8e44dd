// SENSOR_CAMERA: camera intrinsics and mounting kept for renderers (sensor_camera.h).
//
// Params (camelCase JSON, all optional; 0 means the renderer's default):
//   "name"            string
//   "imageWidth"      px          "imageHeight"   px
//   "fovVerticalDeg"  degrees     "nearClip", "farClip"   m
//   "lookAt"          [3] m, world (fixed cameras)
//   "offsetLocal", "forwardAxis", "upAxisLocal"   [3], link frame (wrist cameras)
//   "lookDistance"    m

#include "superdex/robotics/sensor_camera.h"

#include <cmath>
#include <fstream>

#include "builtin_support.h"
#include "builtins.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

constexpr real kPi = real(3.14159265358979323846);

std::vector<real> vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

// a non-negative integer key (image sizes)
int pixels(const ComponentParams& p, const char* key, int fallback) {
  const real x = p.number(key, static_cast<real>(fallback));
  if (x != std::floor(x)) throw Error(p.at(key) + ": expected a whole number of pixels, got " + std::to_string(x));
  return static_cast<int>(x);
}

}  // namespace

void CameraSensorParams::validate(const std::string& where) const {
  auto fail = [&](const char* field, const std::string& what) { throw Error(where + ": " + field + " " + what); };
  if (image_width < 0) fail("image_width", "must be >= 0 px (0: default), got " + std::to_string(image_width));
  if (image_height < 0) fail("image_height", "must be >= 0 px (0: default), got " + std::to_string(image_height));
  if (!(fov_vertical_deg >= 0 && fov_vertical_deg < 180))
    fail("fov_vertical_deg", "must be in [0, 180) degrees (0: default), got " + std::to_string(fov_vertical_deg));
  if (!(near_clip >= 0) || !std::isfinite(near_clip)) fail("near_clip", "must be a finite distance >= 0 m, got " + std::to_string(near_clip));
  if (!(far_clip >= 0) || !std::isfinite(far_clip)) fail("far_clip", "must be a finite distance >= 0 m, got " + std::to_string(far_clip));
  if (near_clip > 0 && far_clip > 0 && far_clip <= near_clip)
    fail("far_clip", "must be greater than near_clip (" + std::to_string(near_clip) + " m), got " + std::to_string(far_clip));
  if (!(look_distance >= 0) || !std::isfinite(look_distance))
    fail("look_distance", "must be a finite distance >= 0 m, got " + std::to_string(look_distance));
  for (auto [field, v] : {std::pair{"look_at", look_at}, {"offset_local", offset_local}})
    if (!v.allFinite()) fail(field, "must be finite");
  for (auto [field, v] : {std::pair{"forward_axis", forward_axis}, {"up_axis_local", up_axis_local}})
    if (!v.allFinite() || v.norm() == 0) fail(field, "must be a finite, non-zero direction");
}

CameraSensorParams CameraSensorParams::from_json_text(const std::string& text, const std::string& where) {
  ComponentParams p(text, where);
  p.allow_only({"name", "imageWidth", "imageHeight", "fovVerticalDeg", "nearClip", "farClip", "lookAt", "offsetLocal",
                "forwardAxis", "upAxisLocal", "lookDistance"});
  if (p.has("rate")) throw Error(p.at("rate") + ": a camera has no rate (it does not run in the step)");
  CameraSensorParams c;
  c.name = p.text("name", c.name);
  c.image_width = pixels(p, "imageWidth", c.image_width);
  c.image_height = pixels(p, "imageHeight", c.image_height);
  c.fov_vertical_deg = p.number("fovVerticalDeg", c.fov_vertical_deg);
  c.near_clip = p.number("nearClip", c.near_clip);
  c.far_clip = p.number("farClip", c.far_clip);
  c.look_at = p.vec3("lookAt", c.look_at);
  c.offset_local = p.vec3("offsetLocal", c.offset_local);
  c.forward_axis = p.vec3("forwardAxis", c.forward_axis);
  c.up_axis_local = p.vec3("upAxisLocal", c.up_axis_local);
  c.look_distance = p.number("lookDistance", c.look_distance);
  c.validate(where);
  return c;
}

std::string CameraSensorParams::to_json_text() const {
  nlohmann::json j = {{"name", name},
                      {"imageWidth", image_width},
                      {"imageHeight", image_height},
                      {"fovVerticalDeg", fov_vertical_deg},
                      {"nearClip", near_clip},
                      {"farClip", far_clip},
                      {"lookAt", vec(look_at)},
                      {"offsetLocal", vec(offset_local)},
                      {"forwardAxis", vec(forward_axis)},
                      {"upAxisLocal", vec(up_axis_local)},
                      {"lookDistance", look_distance}};
  return j.dump(2);
}

CameraSensorParams CameraSensorParams::load_from_file(const std::string& path) {
  if (path.empty() || path.find_first_not_of(" \t\r\n") == std::string::npos || path[path.find_first_not_of(" \t\r\n")] == '{')
    throw Error("CameraSensorParams.load_from_file: path: expected a file path, got '" + path + "'");
  return from_json_text(path, "CameraSensorParams.load_from_file('" + path + "')");
}

void CameraSensorParams::save_to_file(const std::string& path) const {
  validate("CameraSensorParams.save_to_file('" + path + "')");
  std::ofstream out(path);
  if (!out) throw Error("CameraSensorParams.save_to_file: path: cannot write '" + path + "'");
  out << to_json_text() << "\n";
}

std::array<real, 4> CameraSensorParams::pinhole_intrinsics() const {
  if (image_width <= 0 || image_height <= 0 || fov_vertical_deg <= 0)
    throw Error("CameraSensorParams.pinhole_intrinsics: image_width, image_height and fov_vertical_deg must be set (> 0)");
  // square pixels: the vertical field of view fixes both focal lengths
  const real fy = real(0.5) * image_height / std::tan(real(0.5) * fov_vertical_deg * kPi / 180);
  return {fy, fy, real(0.5) * image_width, real(0.5) * image_height};
}

void CameraSensor::configure(const std::string& json_params) {
  // absent keys keep their value: merge the given keys over the current params
  nlohmann::json merged = nlohmann::json::parse(params_.to_json_text());
  ComponentParams given(json_params, kTypeName);
  for (const auto& [key, value] : given.json().items()) merged[key] = value;
  params_ = CameraSensorParams::from_json_text(merged.dump(), kTypeName);
}

void CameraSensor::set_params(const CameraSensorParams& params) {
  params.validate(std::string(kTypeName) + ".set_params");
  params_ = params;
}

std::unique_ptr<Component> make_camera_sensor(const ComponentArgs& args) {
  // the actor is optional: a fixed camera stands in the scene root's frame
  return std::make_unique<CameraSensor>(CameraSensorParams::from_json_text(args.params, CameraSensor::kTypeName));
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
