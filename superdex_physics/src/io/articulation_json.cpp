// JSON reader for articulation descriptions (the link and joint fields of `.superdex_bot`).

#include "superdex/physics/articulation_json.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

using json = nlohmann::json;

const char* type_name(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::string: return "a string";
    case json::value_t::array: return "an array";
    case json::value_t::object: return "an object";
    default: return "a number";
  }
}

// "penalty_coefficient" -> "penaltyCoefficient": a params field as files name it.
std::string snake_to_camel(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '_' && i + 1 < s.size()) out += static_cast<char>(std::toupper(static_cast<unsigned char>(s[++i])));
    else out += s[i];
  }
  return out;
}

// Reads fields of one JSON object, naming the source and path in every error.
class Reader {
 public:
  Reader(const json& j, const std::string& source, std::string path, std::vector<std::string>* warnings)
      : j_(j), source_(source), path_(std::move(path)), warnings_(warnings) {
    if (!j_.is_object()) fail(path_, std::string("expected an object, got ") + type_name(j_));
  }

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw Error(source_ + ": " + (path.empty() ? std::string("(top level)") : path) + ": " + what);
  }
  std::string field_path(const char* key) const { return path_.empty() ? key : path_ + "." + key; }
  bool has(const char* key) const { return j_.contains(key) && !j_.at(key).is_null(); }
  // the value of a field the caller requires: "required" naming it when absent (or null)
  const json& at(const char* key) const {
    if (!has(key)) fail(field_path(key), "required");
    return j_.at(key);
  }

  real number(const char* key) const {
    const json& v = at(key);
    if (!v.is_number()) fail(field_path(key), std::string("expected a number, got ") + type_name(v));
    const real x = v.get<real>();
    if (!std::isfinite(x)) fail(field_path(key), "must be finite");
    return x;
  }
  std::optional<real> opt_number(const char* key) const { return has(key) ? std::optional<real>(number(key)) : std::nullopt; }
  int integer(const char* key) const {
    const json& v = at(key);
    if (!v.is_number_integer()) fail(field_path(key), std::string("expected an integer, got ") + type_name(v));
    constexpr int kMax = std::numeric_limits<int>::max(), kMin = std::numeric_limits<int>::min();
    const bool out_of_range = v.is_number_unsigned() ? v.get<std::uint64_t>() > static_cast<std::uint64_t>(kMax)
                                                     : v.get<std::int64_t>() < kMin || v.get<std::int64_t>() > kMax;
    if (out_of_range) fail(field_path(key), "integer " + v.dump() + " is out of range");
    return v.get<int>();
  }
  std::string string(const char* key) const {
    const json& v = at(key);
    if (!v.is_string()) fail(field_path(key), std::string("expected a string, got ") + type_name(v));
    return v.get<std::string>();
  }
  bool boolean(const char* key) const {
    const json& v = at(key);
    if (!v.is_boolean()) fail(field_path(key), std::string("expected true or false, got ") + type_name(v));
    return v.get<bool>();
  }
  template <int N>
  Eigen::Matrix<real, N, 1> vec(const char* key) const {
    const json& v = at(key);
    if (!v.is_array() || v.size() != N)
      fail(field_path(key), "expected an array of " + std::to_string(N) + " numbers, got " +
                                (v.is_array() ? "an array of " + std::to_string(v.size()) : std::string(type_name(v))));
    Eigen::Matrix<real, N, 1> out;
    for (int i = 0; i < N; ++i) {
      if (!v[i].is_number()) fail(field_path(key) + "[" + std::to_string(i) + "]", std::string("expected a number, got ") + type_name(v[i]));
      out[i] = v[i].get<real>();
      if (!std::isfinite(out[i])) fail(field_path(key) + "[" + std::to_string(i) + "]", "must be finite");
    }
    return out;
  }
  // A limit vector, also accepting a single number (the value along the axis).
  Vec3 limit(const char* key, const Vec3& axis) const {
    if (at(key).is_number()) return axis.normalized() * number(key);
    return vec<3>(key);
  }
  // Warns about keys not in `known`.
  void check_unknown(std::initializer_list<const char*> known, const std::vector<std::string>& extra) const {
    if (!warnings_) return;
    for (auto it = j_.begin(); it != j_.end(); ++it) {
      const std::string& k = it.key();
      if (std::find_if(known.begin(), known.end(), [&](const char* s) { return k == s; }) != known.end()) continue;
      if (std::find(extra.begin(), extra.end(), k) != extra.end()) continue;
      warnings_->push_back(source_ + ": " + field_path(k.c_str()) + ": unknown field, ignored");
    }
  }
  const std::string& path() const { return path_; }
  std::vector<std::string>* warnings() const { return warnings_; }

 private:
  const json& j_;
  const std::string& source_;
  std::string path_;
  std::vector<std::string>* warnings_;
};

std::string index_path(const char* list, size_t i) { return std::string(list) + "[" + std::to_string(i) + "]"; }

JointType joint_type_from(const Reader& r, const char* key) {
  const std::string s = r.string(key);
  for (JointType t : {JointType::Hard, JointType::Free, JointType::Revolute, JointType::Prismatic, JointType::Spherical})
    if (s == joint_type_name(t)) return t;
  r.fail(r.field_path(key), "unknown joint type '" + s + "' (expected Hard, Free, Revolute, Prismatic or Spherical)");
}

LinkDesc link_from(const Reader& r, const std::vector<std::string>& extra) {
  LinkDesc L;
  L.name = r.has("name") ? r.string("name") : "";
  if (r.has("parentLink")) {
    L.parent_link = r.integer("parentLink");
    // -1 means "no parent" inside the engine; in a file the field is simply left out
    if (L.parent_link < 0) r.fail(r.field_path("parentLink"), "refers to link " + std::to_string(L.parent_link) +
                                                               ", which does not exist (omit the field for the root)");
  }
  L.mass = r.opt_number("mass");
  if (r.has("centerOfMass")) L.center_of_mass = r.vec<3>("centerOfMass");
  if (r.has("momentOfInertia")) {
    const auto v = r.vec<6>("momentOfInertia");
    L.moment_of_inertia = std::array<real, 6>{v[0], v[1], v[2], v[3], v[4], v[5]};
  }
  L.density = r.opt_number("density");
  if (r.has("shape")) {
    if (r.at("shape").is_string()) {
      L.shape_file = r.string("shape");
    } else {
      if (!r.at("shape").is_object())
        r.fail(r.field_path("shape"), std::string("expected a shape file path or an inline primitive such as {\"sphere\": {\"radius\": r}}, got ") +
                                          type_name(r.at("shape")));
      L.shape = shape_from_json(r.at("shape"), "", r.field_path("shape"));
      L.link_from_shape = shape_pose_from_json(r.at("shape"), "", r.field_path("shape"));
    }
  }
  if (r.has("shapeScale")) L.shape_scale = r.vec<3>("shapeScale");
  // the pose of a shape file in the link frame (an inline primitive gives its own)
  for (const char* key : {"shapeRotation", "shapeTranslation"})
    if (r.has(key) && !(r.has("shape") && r.at("shape").is_string()))
      r.fail(r.field_path(key), "only for a shape file (an inline primitive takes center and rotation)");
  if (r.has("shapeTranslation")) L.link_from_shape.translation = r.vec<3>("shapeTranslation");
  if (r.has("shapeRotation")) {
    const auto q = r.vec<4>("shapeRotation");
    if (q.norm() < real(1e-6)) r.fail(r.field_path("shapeRotation"), "must be a non-zero quaternion [x, y, z, w]");
    L.link_from_shape.rotation = Quat(q[3], q[0], q[1], q[2]).normalized();
  }
  if (r.has("jointFromLink")) L.joint_from_link = r.vec<3>("jointFromLink");
  if (r.has("colliderType")) {
    L.collider_type = r.string("colliderType");
    static const char* const kColliders[] = {"Auto", "None", "Sphere", "Box", "Plane", "Mesh", "Sdf"};
    if (std::find(std::begin(kColliders), std::end(kColliders), L.collider_type) == std::end(kColliders))
      r.fail(r.field_path("colliderType"), "unknown collider type '" + L.collider_type +
                                               "' (expected Auto, None, Sphere, Box, Plane, Mesh or Sdf)");
  }
  if (r.has("renderModel")) L.render_model = r.string("renderModel");
  if (r.has("renderModelScale")) L.render_model_scale = r.vec<3>("renderModelScale");
  if (r.has("contact")) L.contact = contact_params_from_json(r.at("contact"), "", r.field_path("contact"), r.warnings());
  if (r.has("layer")) L.layer = r.integer("layer");
  if (r.has("hasGravity")) L.has_gravity = r.boolean("hasGravity");
  r.check_unknown({"name", "parentLink", "mass", "centerOfMass", "momentOfInertia", "density", "shape", "shapeScale",
                   "shapeRotation", "shapeTranslation", "jointFromLink", "colliderType", "renderModel", "renderModelScale", "contact", "layer", "hasGravity", "sensors",
                   "actuators", "boundaryElementType"},
                  extra);
  return L;
}

JointDesc joint_from(const Reader& r, const std::vector<std::string>& extra) {
  JointDesc J;
  J.name = r.has("name") ? r.string("name") : "";
  if (!r.has("type")) r.fail(r.field_path("type"), "required (Hard, Free, Revolute, Prismatic or Spherical)");
  J.type = joint_type_from(r, "type");
  if (r.has("axis")) J.axis = r.vec<3>("axis");
  else if (J.type == JointType::Revolute || J.type == JointType::Prismatic) r.fail(r.field_path("axis"), "required for a " + std::string(joint_type_name(J.type)) + " joint");
  if (r.has("parentLinkFromJoint")) J.parent_link_from_joint = transform_from_json(r.at("parentLinkFromJoint"), "", r.field_path("parentLinkFromJoint"));
  const Vec3 axis = J.axis.norm() > 0 ? J.axis : Vec3::UnitZ();
  if (r.has("minLimit")) J.min_limit = r.limit("minLimit", axis);
  if (r.has("maxLimit")) J.max_limit = r.limit("maxLimit", axis);
  if (r.has("effortLimit")) J.effort_limit = r.number("effortLimit");
  if (r.has("friction")) {
    Reader f(r.at("friction"), "", r.field_path("friction"), nullptr);
    J.coulomb_friction = f.opt_number("coulomb").value_or(0);
    J.viscous_friction = f.opt_number("viscous").value_or(0);
  }
  if (r.has("inertia")) J.armature = r.number("inertia");
  if (r.has("limitStiffness")) J.limit_stiffness = r.number("limitStiffness");
  if (r.has("limitDamping")) J.limit_damping = r.number("limitDamping");
  r.check_unknown({"name", "type", "axis", "parentLinkFromJoint", "minLimit", "maxLimit", "effortLimit", "friction",
                   "inertia", "limitStiffness", "limitDamping"},
                  extra);
  return J;
}

// Prefixes nested readers' errors (which carry an empty source) with the real source.
template <class F>
auto with_source(const std::string& source, F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    const std::string msg = e.what();
    if (msg.rfind(": ", 0) == 0) throw Error(source + msg);
    throw;
  }
}

}  // namespace

json read_json_file(const std::string& path, const std::string& kind) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the " + kind + " file (does it exist?)");
  try {
    return json::parse(in, nullptr, true, true);
  } catch (const json::exception& e) {
    // parse errors, and numbers too large for a double (out_of_range 406)
    throw Error(path + ": not valid JSON: " + e.what());
  }
}

Transform transform_from_json(const json& j, const std::string& source, const std::string& path) {
  return with_source(source, [&] {
    Reader r(j, source, path, nullptr);
    Transform X;
    if (r.has("translation")) X.translation = r.vec<3>("translation");
    if (r.has("rotation")) {
      const auto q = r.vec<4>("rotation");
      if (q.norm() < real(1e-6)) r.fail(r.field_path("rotation"), "must be a non-zero quaternion [x, y, z, w]");
      X.rotation = Quat(q[3], q[0], q[1], q[2]).normalized();
    }
    return X;
  });
}

ShapeGeometry shape_from_json(const json& j, const std::string& source, const std::string& path) {
  return with_source(source, [&]() -> ShapeGeometry {
    Reader r(j, source, path, nullptr);
    if (j.size() != 1) r.fail(path, "expected exactly one of sphere, box, capsule, plane");
    if (r.has("sphere")) {
      Reader s(r.at("sphere"), source, r.field_path("sphere"), nullptr);
      SphereShape sh;
      sh.radius = s.number("radius");
      if (s.has("center")) sh.center = s.vec<3>("center");
      return sh;
    }
    if (r.has("box")) {
      Reader s(r.at("box"), source, r.field_path("box"), nullptr);
      return BoxShape{s.vec<3>("halfExtents")};
    }
    if (r.has("capsule")) {
      Reader s(r.at("capsule"), source, r.field_path("capsule"), nullptr);
      return CapsuleShape{s.number("radius"), s.number("halfLength")};
    }
    if (r.has("plane")) {
      Reader s(r.at("plane"), source, r.field_path("plane"), nullptr);
      PlaneShape p;
      if (s.has("normal")) p.normal = s.vec<3>("normal");
      if (s.has("distance")) p.distance = s.number("distance");
      return p;
    }
    r.fail(path, "unknown inline shape '" + j.begin().key() + "' (expected sphere, box, capsule or plane)");
  });
}

Transform shape_pose_from_json(const json& j, const std::string& source, const std::string& path) {
  return with_source(source, [&] {
    Transform X;
    for (const char* kind : {"box", "capsule"}) {
      if (!j.is_object() || !j.contains(kind)) continue;
      Reader s(j.at(kind), source, path + "." + kind, nullptr);
      if (s.has("center")) X.translation = s.vec<3>("center");
      if (s.has("rotation")) {
        const auto q = s.vec<4>("rotation");
        if (q.norm() < real(1e-6)) s.fail(s.field_path("rotation"), "must be a non-zero quaternion [x, y, z, w]");
        X.rotation = Quat(q[3], q[0], q[1], q[2]).normalized();
      }
    }
    return X;
  });
}

ContactParams contact_params_from_json(const json& j, const std::string& source, const std::string& path,
                                       std::vector<std::string>* warnings) {
  return with_source(source, [&] {
    Reader c(j, source, path, warnings);
    ContactParams p;
    auto number = [&](const char* key, real& field) {
      if (c.has(key)) field = c.number(key);
    };
    number("penaltyCoefficient", p.penalty_coefficient);
    number("penaltySmoothingHalfDistance", p.penalty_smoothing_half_distance);
    number("penaltyThresholdDefault", p.penalty_threshold_default);
    number("penaltyThresholdExtraPadding", p.penalty_threshold_extra_padding);
    if (c.has("frictionWithColliderNormal")) p.friction_with_collider_normal = c.boolean("frictionWithColliderNormal");
    number("maxAlignmentNormals", p.max_alignment_normals);
    number("viscousFrictionCoefficient", p.viscous_friction_coefficient);
    number("coulombFrictionCoefficient", p.coulomb_friction_coefficient);
    number("frictionFalloffVel", p.friction_falloff_vel);
    number("normalViscousDampingCoefficient", p.normal_viscous_damping_coefficient);
    number("distanceErrorBound", p.distance_error_bound);
    number("objScale", p.obj_scale);
    number("collidingPenaltyLengthScale", p.colliding_penalty_length_scale);
    number("contactStiffness", p.contact_stiffness);
    number("dissipationTimeScale", p.dissipation_time_scale);
    c.check_unknown({"penaltyCoefficient", "penaltySmoothingHalfDistance", "penaltyThresholdDefault", "penaltyThresholdExtraPadding",
                     "frictionWithColliderNormal", "maxAlignmentNormals", "viscousFrictionCoefficient", "coulombFrictionCoefficient",
                     "frictionFalloffVel", "normalViscousDampingCoefficient", "distanceErrorBound", "objScale",
                     "collidingPenaltyLengthScale", "contactStiffness", "dissipationTimeScale"},
                    {});
    try {
      validate(p, "contact");
    } catch (const Error& e) {
      // name the file and the JSON path of the field
      std::string what = e.what();
      const std::string prefix = "contact.";
      std::string field = what.substr(prefix.size(), what.find(':') - prefix.size());
      c.fail(c.field_path(snake_to_camel(field).c_str()), what.substr(what.find(':') + 2));
    }
    return p;
  });
}

SoftMaterial soft_material_from_json(const json& j, const std::string& source, const std::string& path,
                                     std::vector<std::string>* warnings) {
  return with_source(source, [&] {
    Reader r(j, source, path, warnings);
    SoftMaterial m;
    if (r.has("type")) m.type = r.string("type");
    auto got = [](real x) { return ", got " + json(x).dump(); };
    if (r.has("youngsModulus")) {
      m.youngs_modulus = r.number("youngsModulus");
      if (!(*m.youngs_modulus > 0)) r.fail(r.field_path("youngsModulus"), "must be positive (Pa)" + got(*m.youngs_modulus));
    }
    if (r.has("poissonRatio")) {
      m.poisson_ratio = r.number("poissonRatio");
      if (!(*m.poisson_ratio > -1 && *m.poisson_ratio < real(0.5)))
        r.fail(r.field_path("poissonRatio"), "must be in (-1, 0.5)" + got(*m.poisson_ratio));
    }
    if (r.has("density")) {
      m.density = r.number("density");
      if (!(m.density > 0)) r.fail(r.field_path("density"), "must be positive (kg/m^3)" + got(m.density));
    }
    if (r.has("damping")) {
      m.damping_beta = r.number("damping");
      if (!(m.damping_beta >= 0)) r.fail(r.field_path("damping"), "must be >= 0 (s)" + got(m.damping_beta));
    }
    if (r.has("dampingAlpha")) {
      m.damping_alpha = r.number("dampingAlpha");
      if (!(m.damping_alpha >= 0)) r.fail(r.field_path("dampingAlpha"), "must be >= 0 (1/s)" + got(m.damping_alpha));
    }
    if (r.has("reducedModes")) {
      const real modes = r.number("reducedModes");
      if (!(modes >= 0 && modes <= 10000 && modes == std::floor(modes)))
        r.fail(r.field_path("reducedModes"), "must be a whole number of modes from 0 (the full model) to 10000" + got(modes));
      m.reduced_modes = static_cast<int>(modes);
    }
    r.check_unknown({"type", "youngsModulus", "poissonRatio", "density", "damping", "dampingAlpha", "reducedModes"}, {});
    return m;
  });
}

namespace {

// "linearTransmissions": SuperDex's transmissions, kept as they are written. Building the bot holds
// one of two joints as a coupling (coupling_of); the spring and damper and transmissions of more
// joints are named in warnings here.
void read_linear_transmissions(const Reader& top, ArticulationDesc& d, const std::string& source, std::vector<std::string>* warnings) {
  const json& list = top.at("linearTransmissions");
  if (!list.is_array()) top.fail("linearTransmissions", std::string("expected an array, got ") + type_name(list));
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = index_path("linearTransmissions", i);
    Reader t(list[i], source, path, warnings);
    auto numbers = [&](const char* key) {
      const json& v = t.at(key);
      if (!v.is_array()) t.fail(t.field_path(key), std::string("expected an array, got ") + type_name(v));
      std::vector<real> out;
      for (size_t k = 0; k < v.size(); ++k) {
        if (!v[k].is_number()) t.fail(t.field_path(key) + "[" + std::to_string(k) + "]", std::string("expected a number, got ") + type_name(v[k]));
        out.push_back(v[k].get<real>());
        if (!std::isfinite(out.back())) t.fail(t.field_path(key) + "[" + std::to_string(k) + "]", "must be finite");
      }
      return out;
    };
    LinearTransmission lt;
    if (t.has("name")) lt.name = t.string("name");
    const std::vector<real> index = numbers("jointIndices");
    lt.joint_coefficients = numbers("jointCoefficients");
    if (lt.joint_coefficients.size() != index.size())
      t.fail(t.field_path("jointCoefficients"), "expected " + std::to_string(index.size()) + " coefficients (one per joint index), got " +
                                                    std::to_string(lt.joint_coefficients.size()));
    for (size_t k = 0; k < index.size(); ++k) {
      if (index[k] != std::floor(index[k]) || index[k] < 0 || index[k] >= static_cast<real>(d.joints.size()))
        t.fail(t.field_path("jointIndices") + "[" + std::to_string(k) + "]", "expected the index of a joint (0 to " +
                                                                             std::to_string(d.joints.size() - 1) + ")");
      lt.joint_indices.push_back(static_cast<int>(index[k]));
    }
    if (t.has("jointAxisDisps")) {
      lt.joint_axis_disps = numbers("jointAxisDisps");
      if (lt.joint_axis_disps.size() != index.size())
        t.fail(t.field_path("jointAxisDisps"), "expected " + std::to_string(index.size()) + " values (one per joint index), got " +
                                                   std::to_string(lt.joint_axis_disps.size()));
      for (real x : lt.joint_axis_disps)
        if (x != 0 && warnings) {
          warnings->push_back(source + ": " + t.field_path("jointAxisDisps") + ": non-zero joint axis displacements are not modelled");
          break;
        }
    }
    lt.target_displacement = t.opt_number("targetDisplacement").value_or(0);
    lt.stiffness = t.opt_number("stiffness").value_or(0);
    lt.damping = t.opt_number("damping").value_or(0);
    if (t.has("allowCompressiveForce")) lt.allow_compressive_force = t.boolean("allowCompressiveForce");
    t.check_unknown({"name", "jointIndices", "jointCoefficients", "jointAxisDisps", "targetDisplacement", "stiffness", "damping",
                     "allowCompressiveForce"}, {});
    if (lt.joint_indices.size() != 2) {
      if (warnings) warnings->push_back(source + ": " + path + ": a transmission of " + std::to_string(lt.joint_indices.size()) +
                                        " joints is not modelled yet (two joints become a coupling); ignored");
    } else {
      // the coupling it makes, checked now so that the error names the file
      const JointCoupling c = coupling_of(lt, d.joints, source + ": " + path);
      if (warnings && (t.has("stiffness") || t.has("damping")))
        warnings->push_back(source + ": " + path + ": held as a rigid coupling of joints '" + c.leader + "' and '" + c.joint +
                            "'; its stiffness and damping are not modelled yet");
    }
    d.linear_transmissions.push_back(std::move(lt));
  }
}

}  // namespace

LinkDesc link_desc_from_json(const json& j, const std::string& source, const std::string& path, std::vector<std::string>* warnings) {
  return with_source(source, [&] { return link_from(Reader(j, source, path, warnings), {}); });
}

JointDesc joint_desc_from_json(const json& j, const std::string& source, const std::string& path, std::vector<std::string>* warnings) {
  return with_source(source, [&] { return joint_from(Reader(j, source, path, warnings), {}); });
}

ArticulationDesc articulation_desc_from_json(const json& doc, const std::string& source, std::vector<std::string>* warnings,
                                             const std::vector<std::string>& extra) {
  return with_source(source, [&] {
    Reader top(doc, source, "", warnings);
    ArticulationDesc d;
    if (top.has("name")) d.name = top.string("name");
    for (const char* key : {"links", "joints"}) {
      if (!top.has(key)) top.fail(key, "required: an array of objects");
      if (!top.at(key).is_array()) top.fail(key, std::string("expected an array, got ") + type_name(top.at(key)));
    }
    const json& links = top.at("links");
    for (size_t i = 0; i < links.size(); ++i) d.links.push_back(link_from(Reader(links[i], source, index_path("links", i), warnings), extra));
    // SuperDex's surface quadrature per link: checked, then named once (this engine samples
    // rigid surfaces its own way)
    size_t quadrature = 0;
    for (size_t i = 0; i < links.size(); ++i) {
      if (!links[i].is_object() || !links[i].contains("boundaryElementType")) continue;
      const json& v = links[i].at("boundaryElementType");
      static const char* const kTypes[] = {"P1Q1", "P1Q3", "P1Q6", "EXPERIMENTAL_P1Q7", "EXPERIMENTAL_P1Q12", "EXPERIMENTAL_P1Q16"};
      if (!v.is_string() || std::find_if(std::begin(kTypes), std::end(kTypes), [&](const char* t) { return v.get<std::string>() == t; }) == std::end(kTypes))
        top.fail(index_path("links", i) + ".boundaryElementType", "expected one of P1Q1, P1Q3, P1Q6, EXPERIMENTAL_P1Q7, EXPERIMENTAL_P1Q12, EXPERIMENTAL_P1Q16, got " + v.dump());
      ++quadrature;
    }
    if (warnings && quadrature > 0)
      warnings->push_back(source + ": links[].boundaryElementType (" + std::to_string(quadrature) +
                          " links): rigid links' contact surfaces are sampled by this engine's own rule; ignored");
    const json& joints = top.at("joints");
    for (size_t i = 0; i < joints.size(); ++i) d.joints.push_back(joint_from(Reader(joints[i], source, index_path("joints", i), warnings), extra));
    // a bot is fixed to the world or floating: its root joint is Hard or Free
    if (!d.joints.empty() && d.joints[0].type != JointType::Hard && d.joints[0].type != JointType::Free)
      top.fail("joints[0].type", std::string("the root joint must be Hard or Free, got ") + joint_type_name(d.joints[0].type));
    if (top.has("defaultPose")) {
      const json& p = top.at("defaultPose");
      if (!p.is_array()) top.fail("defaultPose", std::string("expected an array of numbers, got ") + type_name(p));
      for (size_t i = 0; i < p.size(); ++i) {
        if (!p[i].is_number()) top.fail(index_path("defaultPose", i), std::string("expected a number, got ") + type_name(p[i]));
        d.default_pose.push_back(p[i].get<real>());
      }
    }
    if (top.has("worldFromRoot")) d.world_from_root = transform_from_json(top.at("worldFromRoot"), source, "worldFromRoot");
    if (top.has("contactOverrides")) {
      const json& list = top.at("contactOverrides");
      if (!list.is_array()) top.fail("contactOverrides", std::string("expected an array, got ") + type_name(list));
      for (size_t i = 0; i < list.size(); ++i) {
        Reader o(list[i], source, index_path("contactOverrides", i), warnings);
        for (const char* key : {"linkA", "linkB", "enable"})
          if (!o.has(key)) o.fail(o.field_path(key), "required");
        d.contact_overrides.push_back({o.string("linkA"), o.string("linkB"), o.boolean("enable")});
      }
    }
    if (top.has("linearTransmissions")) read_linear_transmissions(top, d, source, warnings);
    top.check_unknown({"name", "links", "joints", "defaultPose", "worldFromRoot", "contactOverrides", "linearTransmissions"}, extra);
    return d;
  });
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
