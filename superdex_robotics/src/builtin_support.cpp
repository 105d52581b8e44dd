// Parameters and actor lookups shared by the built-in components.

#include "builtin_support.h"

#include <cmath>
#include <fstream>
#include <limits>

#include "superdex/physics/error.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

ComponentParams::ComponentParams(const std::string& text, std::string where) : where_(std::move(where)) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) {
    json_ = nlohmann::json::object();
    return;
  }
  std::string source = text;
  std::string origin = "params";
  if (text[first] != '{') {
    // a JSON file (the framework made the path absolute)
    const std::string path = text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
    std::ifstream in(path);
    if (!in) throw Error(where_ + ": params file '" + path + "' cannot be read");
    source.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    origin = "params file '" + path + "'";
  }
  try {
    json_ = nlohmann::json::parse(source);
  } catch (const nlohmann::json::exception& e) {  // syntax errors and numbers too large for a double
    throw Error(where_ + ": " + origin + " is not valid JSON: " + e.what());
  }
  if (!json_.is_object()) throw Error(where_ + ": " + origin + " must be a JSON object");
}

void ComponentParams::allow_only(std::initializer_list<const char*> known) const {
  for (const auto& [key, value] : json_.items()) {
    bool found = key == "rate";
    for (const char* k : known) found = found || key == k;
    if (found) continue;
    std::string list = "rate";
    for (const char* k : known) list += std::string(", ") + k;
    throw Error(where_ + ": unknown parameter '" + key + "' (known: " + list + ")");
  }
}

real ComponentParams::number(const char* key, real fallback) const {
  if (!has(key)) return fallback;
  const auto& v = json_.at(key);
  if (!v.is_number()) throw Error(at(key) + ": expected a number, got " + v.dump());
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw Error(at(key) + ": must be finite");
  return static_cast<real>(x);
}

bool ComponentParams::flag(const char* key, bool fallback) const {
  if (!has(key)) return fallback;
  const auto& v = json_.at(key);
  if (!v.is_boolean()) throw Error(at(key) + ": expected true or false, got " + v.dump());
  return v.get<bool>();
}

std::string ComponentParams::text(const char* key, const std::string& fallback) const {
  if (!has(key)) return fallback;
  const auto& v = json_.at(key);
  if (!v.is_string()) throw Error(at(key) + ": expected a string, got " + v.dump());
  return v.get<std::string>();
}

VecX ComponentParams::vector(const char* key, int n, const VecX& fallback, bool allow_null) const {
  if (!has(key)) return fallback;
  const auto& v = json_.at(key);
  auto value = [&](const nlohmann::json& x, const std::string& path) -> real {
    if (x.is_null() && allow_null) return std::numeric_limits<real>::quiet_NaN();
    if (!x.is_number()) throw Error(path + ": expected a number" + (allow_null ? " or null" : "") + ", got " + x.dump());
    const double d = x.get<double>();
    if (!std::isfinite(d)) throw Error(path + ": must be finite");
    return static_cast<real>(d);
  };
  if (v.is_number()) return VecX::Constant(n, value(v, at(key)));
  if (!v.is_array()) throw Error(at(key) + ": expected a number or an array of " + std::to_string(n) + " numbers");
  if (static_cast<int>(v.size()) != n)
    throw Error(at(key) + ": expected " + std::to_string(n) + " values (one per joint DOF), got " + std::to_string(v.size()));
  VecX out(n);
  for (int i = 0; i < n; ++i) out[i] = value(v[i], at(key) + "[" + std::to_string(i) + "]");
  return out;
}

Vec3 ComponentParams::vec3(const char* key, const Vec3& fallback) const {
  if (!has(key)) return fallback;
  if (!json_.at(key).is_array()) throw Error(at(key) + ": expected an array of 3 numbers");
  return vector(key, 3, fallback);
}

Quat ComponentParams::quaternion(const char* key, const Quat& fallback) const {
  if (!has(key)) return fallback;
  if (!json_.at(key).is_array()) throw Error(at(key) + ": expected [x, y, z, w]");
  const VecX q = vector(key, 4, VecX());
  if (q.norm() < real(1e-6)) throw Error(at(key) + ": the quaternion must not be zero");
  return Quat(q[3], q[0], q[1], q[2]).normalized();
}

void ComponentParams::apply_rate(Component& component) const {
  if (!has("rate")) return;
  const real r = number("rate", 0);
  if (r < 0) throw Error(at("rate") + ": must be >= 0 Hz (0: every step), got " + std::to_string(r));
  component.set_rate(r);
}

ActorHandle articulation_of(const Scene& scene, ActorHandle actor, const std::string& where) {
  if (actor == 0) throw Error(where + ": needs an actor (an articulation or one of its links)");
  if (scene.is_nested_link_actor(actor)) return scene.articulated_actor_of_link(actor);
  if (scene.actor_type(actor) == physics::ActorType::Articulated) return actor;
  throw Error(where + ": actor " + std::to_string(actor) + " is not an articulation or a link of one");
}

void require_link(const Scene& scene, ActorHandle actor, const std::string& where) {
  if (actor == 0 || !scene.is_nested_link_actor(actor))
    throw Error(where + ": needs a link actor (got " + (actor == 0 ? std::string("none") : "actor " + std::to_string(actor)) + ")");
}

physics::ArticulatedDofInfo joint_dofs_of_link(const Scene& scene, ActorHandle link, const std::string& where) {
  require_link(scene, link, where);
  const ActorHandle art = scene.articulated_actor_of_link(link);
  return scene.articulated_shape_info(art).dof_info.at(scene.link_index(link));
}

physics::Vec6 link_origin_velocity(const Scene& scene, ActorHandle link) {
  physics::Vec6 V = scene.velocity(link);
  const Vec3 r_W = scene.root_transform(link).rotation * Vec3(scene.center_of_mass_local(link));
  V.head<3>() -= Vec3(V.tail<3>()).cross(r_W);
  return V;
}

Vec3 contact_torque_about_origin(const Scene& scene, ActorHandle link) {
  const Vec3 r_W = scene.root_transform(link).rotation * Vec3(scene.center_of_mass_local(link));
  return Vec3(scene.contact_torque(link)) + r_W.cross(Vec3(scene.contact_force(link)));
}

int single_dof_of_link(const Scene& scene, ActorHandle link, const std::string& where) {
  const physics::ArticulatedDofInfo d = joint_dofs_of_link(scene, link, where);
  if (d.size() != 1) {
    const ActorHandle art = scene.articulated_actor_of_link(link);
    const auto info = scene.articulated_shape_info(art);
    const int i = scene.link_index(link);
    throw Error(where + ": link '" + info.link_names[i] + "' has joint '" + info.joint_names[i] + "' (" +
                physics::joint_type_name(info.joint_types[i]) + ", " + std::to_string(d.size()) +
                " DOFs): an actuator drives the single DOF of its link's joint (Revolute or Prismatic)");
  }
  return d.offset;
}

ActuatedDof::ActuatedDof(const Scene& s, ActorHandle link, const std::string& where)
    : scene(s), articulation(0), dof(single_dof_of_link(s, link, where)) {
  articulation = s.articulated_actor_of_link(link);
}

int root_dofs(const Scene& scene, ActorHandle articulation) {
  return scene.articulated_shape_info(articulation).dof_info.at(0).size();
}

int link_index_by_name(const Scene& scene, ActorHandle articulation, const std::string& name, const std::string& where) {
  const auto info = scene.articulated_shape_info(articulation);
  std::string known;
  for (size_t i = 0; i < info.link_names.size(); ++i) {
    if (info.link_names[i] == name) return static_cast<int>(i);
    known += (i ? ", " : "") + info.link_names[i];
  }
  throw Error(where + ": no link named '" + name + "' (links: " + known + ")");
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
