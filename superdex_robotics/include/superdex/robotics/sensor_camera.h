#pragma once
/// @file sensor_camera.h
/// SENSOR_CAMERA: a camera's intrinsics and mounting, for renderers. It produces no signal in
/// the physics step (it does not take part in the bot pipeline); a renderer reads its params
/// and the sensor's world pose (Context::sensor_world_transform).
///
/// Camera frame conventions: the camera looks along `forward_axis` and `up_axis_local` points
/// up in the image, both in the frame of the actor it is mounted on (wrist cameras). A fixed
/// (actor-less) camera looks from its world position towards `look_at`.

#include <array>
#include <string>

#include "superdex/physics/real.h"
#include "superdex/robotics/component.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::Vec3;

/// Parameters of a camera; a value of 0 means "the renderer's default" for the numeric fields.
struct CameraSensorParams {
  std::string name;             ///< the camera's name in the params (not the instance name)
  int image_width = 0;          ///< px, >= 0
  int image_height = 0;         ///< px, >= 0
  real fov_vertical_deg = 0;    ///< vertical field of view, degrees, in [0, 180)
  real near_clip = 0;           ///< m, >= 0
  real far_clip = 0;            ///< m, >= 0; > near_clip when both are set
  Vec3 look_at = Vec3::Zero();  ///< world point a fixed camera looks at (m)
  Vec3 offset_local = Vec3::Zero();         ///< wrist cameras: offset from the link origin (m)
  Vec3 forward_axis = Vec3::UnitX();        ///< wrist cameras: viewing direction, link frame
  Vec3 up_axis_local = Vec3::UnitZ();       ///< wrist cameras: image up direction, link frame
  real look_distance = 0;       ///< wrist cameras: distance to the look-at point (m), >= 0

  bool operator==(const CameraSensorParams&) const = default;

  /// Throws superdex::Error naming `where` and the field for an out-of-range value.
  void validate(const std::string& where) const;
  /// JSON object with camelCase keys (imageWidth, fovVerticalDeg, ...); absent keys keep their
  /// defaults, unknown keys are errors. Throws superdex::Error naming `where` and the key.
  static CameraSensorParams from_json_text(const std::string& text, const std::string& where);
  std::string to_json_text() const;
  /// Reads / writes a `.superdex_sensor` JSON file; errors name the file.
  static CameraSensorParams load_from_file(const std::string& path);
  void save_to_file(const std::string& path) const;
  /// Focal lengths and principal point in pixels (fx, fy, cx, cy) of a pinhole camera with square
  /// pixels; throws when the image size or the field of view is unset (0).
  std::array<real, 4> pinhole_intrinsics() const;
};

/// The live camera sensor.
class CameraSensor : public Component {
 public:
  static constexpr const char* kTypeName = "SENSOR_CAMERA";
  explicit CameraSensor(CameraSensorParams params) : params_(std::move(params)) {}
  void reset() override {}
  /// Accepts the keys of CameraSensorParams' JSON; absent keys keep their value.
  void configure(const std::string& json_params) override;
  const CameraSensorParams& params() const { return params_; }
  /// Validates, then replaces the params.
  void set_params(const CameraSensorParams& params);

 private:
  CameraSensorParams params_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
