// Writing a ScenePrefab as a prefab document (prefab_json.h): the fields prefab_json_read.cpp
// reads, optional ones only when set or different from their defaults.

#include "io/prefab_json.h"
#include "superdex/physics/error.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {
namespace prefab {

using json = nlohmann::json;

namespace {

template <int N>
json array(const Eigen::Matrix<real, N, 1>& v) {
  json a = json::array();
  for (int k = 0; k < N; ++k) a.push_back(v[k]);
  return a;
}
json array(const Quaternion& q) { return json{q.x(), q.y(), q.z(), q.w()}; }
bool identity(const Quaternion& q) { return q.coeffs() == Quaternion::Identity().coeffs(); }
json transform(const Transform& X) { return {{"rotation", array(X.rotation)}, {"translation", array(X.translation)}}; }

void put_comment(json& j, const std::optional<std::string>& comment) {
  if (comment) j["comment"] = *comment;
}

// the fields of ContactParams that differ from the defaults, by their file names
json contact(const ContactParams& p) {
  const ContactParams d;
  json j = json::object();
  auto put = [&](const char* key, const auto& value, const auto& fallback) {
    if (value != fallback) j[key] = value;
  };
  put("penaltyCoefficient", p.penalty_coefficient, d.penalty_coefficient);
  put("penaltySmoothingHalfDistance", p.penalty_smoothing_half_distance, d.penalty_smoothing_half_distance);
  put("penaltyThresholdDefault", p.penalty_threshold_default, d.penalty_threshold_default);
  put("penaltyThresholdExtraPadding", p.penalty_threshold_extra_padding, d.penalty_threshold_extra_padding);
  put("frictionWithColliderNormal", p.friction_with_collider_normal, d.friction_with_collider_normal);
  put("maxAlignmentNormals", p.max_alignment_normals, d.max_alignment_normals);
  put("viscousFrictionCoefficient", p.viscous_friction_coefficient, d.viscous_friction_coefficient);
  put("coulombFrictionCoefficient", p.coulomb_friction_coefficient, d.coulomb_friction_coefficient);
  put("frictionFalloffVel", p.friction_falloff_vel, d.friction_falloff_vel);
  put("normalViscousDampingCoefficient", p.normal_viscous_damping_coefficient, d.normal_viscous_damping_coefficient);
  put("distanceErrorBound", p.distance_error_bound, d.distance_error_bound);
  put("objScale", p.obj_scale, d.obj_scale);
  put("collidingPenaltyLengthScale", p.colliding_penalty_length_scale, d.colliding_penalty_length_scale);
  put("contactStiffness", p.contact_stiffness, d.contact_stiffness);
  put("dissipationTimeScale", p.dissipation_time_scale, d.dissipation_time_scale);
  return j;
}

// an inline primitive, with its pose in the link frame where it has one (box, capsule)
json primitive(const ShapeGeometry& g, const ShapeSource& s) {
  auto posed = [&](json j) {
    if (!s.translation.isZero()) j["center"] = array(s.translation);
    if (!identity(s.rotation)) j["rotation"] = array(s.rotation);
    return j;
  };
  if (auto* x = std::get_if<SphereShape>(&g)) {
    // a sphere has no pose of its own in files: its place is its centre
    const Real3 center = s.rotation.normalized() * x->center + s.translation;
    json j = {{"radius", x->radius}};
    if (!center.isZero()) j["center"] = array(center);
    return {{"sphere", j}};
  }
  if (auto* x = std::get_if<BoxShape>(&g)) return {{"box", posed({{"halfExtents", array(x->half_extents)}})}};
  if (auto* x = std::get_if<CapsuleShape>(&g)) return {{"capsule", posed({{"radius", x->radius}, {"halfLength", x->half_length}})}};
  if (auto* x = std::get_if<PlaneShape>(&g)) return {{"plane", {{"normal", array(x->normal)}, {"distance", x->distance}}}};
  throw Error("save_to_json: " + std::string("only sphere, box, capsule and plane primitives can be written inline"));
}

// `shape` (a file or a primitive) with its bake; `where` names an actor whose shape is only a handle
void put_shape(json& j, const ShapeSource& s, const char* scale_key, const std::string& where) {
  if (!s.file.empty()) {
    j["shape"] = s.file;
    if (!identity(s.rotation)) j["shapeRotation"] = array(s.rotation);
    if (!s.translation.isZero()) j["shapeTranslation"] = array(s.translation);
  } else if (s.primitive) {
    j["shape"] = primitive(*s.primitive, s);
  } else {
    if (!where.empty()) throw Error(where + ".shape_file: a shape given only as a handle cannot be saved: name its file");
    return;
  }
  if (s.scale != Real3::Ones()) j[scale_key] = array(s.scale);
}

void put_render_model(json& j, const RenderModel& m) {
  if (m.file.empty()) return;
  j["renderModel"] = m.file;
  if (m.scale != Real3::Ones()) j["renderModelScale"] = array(m.scale);
  if (!identity(m.rotation)) j["renderModelRotation"] = array(m.rotation);
  if (!m.translation.isZero()) j["renderModelTranslation"] = array(m.translation);
}

template <class P>
void put_pose(json& j, const P& p) {
  j["rotation"] = array(p.rotation);
  j["translation"] = array(p.translation);
}

template <class Opt>
void put_optional(json& j, const char* key, const Opt& value) {
  if (value) j[key] = array(*value);
}

json rigid(const RigidActorPrefab& a, const std::string& where) {
  json j = {{"name", a.name}};
  put_comment(j, a.comment);
  put_shape(j, a.shape_source, "scale", where);
  put_pose(j, a);
  if (!a.layer.empty()) j["layer"] = a.layer;
  if (a.collider_type != ColliderType::Auto) j["colliderType"] = collider_type_name(a.collider_type);
  if (a.is_static) j["isStatic"] = true;
  if (!a.has_gravity) j["hasGravity"] = false;
  if (a.density) j["density"] = *a.density;
  if (a.mass) j["mass"] = *a.mass;
  put_optional(j, "centerOfMass", a.center_of_mass);
  put_optional(j, "momentOfInertia", a.moment_of_inertia);
  put_optional(j, "linearVelocity", a.linear_velocity);
  put_optional(j, "angularVelocity", a.angular_velocity);
  if (json c = contact(a.contact); !c.empty()) j["contact"] = c;
  put_render_model(j, a.render_model);
  return j;
}

json soft_material(const SoftActorPrefab& a, const std::string& where) {
  const SoftMaterialParams& p = a.material;
  json m = {{"density", p.density}};
  auto moduli = [&](const char* type, real E, real nu) { m["type"] = type, m["youngsModulus"] = E, m["poissonRatio"] = nu; };
  switch (p.type) {
    case SoftMaterialType::NeoHookean: moduli("NeoHookean", p.neo_hookean.youngs_modulus, p.neo_hookean.poisson_ratio); break;
    case SoftMaterialType::StVenantKirchhoff: moduli("StVK", p.st_venant_kirchhoff.youngs_modulus, p.st_venant_kirchhoff.poisson_ratio); break;
    case SoftMaterialType::LinearElastic: moduli("Linear", p.linear_elastic.youngs_modulus, p.linear_elastic.poisson_ratio); break;
    default:
      // the file format holds the models this engine simulates; a file naming another could not be read back
      throw Error(where + ".material.type: " + soft_material_type_name(p.type) +
                  " cannot be written to a prefab file (NeoHookean, StVenantKirchhoff or LinearElastic)");
  }
  if (p.stiffness_damping_coefficient != 0) m["damping"] = p.stiffness_damping_coefficient;
  if (p.mass_damping_coefficient != 0) m["dampingAlpha"] = p.mass_damping_coefficient;
  if (a.reduced_modes != 0) m["reducedModes"] = a.reduced_modes;
  return m;
}

json soft(const SoftActorPrefab& a, const std::string& where) {
  json j = {{"name", a.name}};
  put_comment(j, a.comment);
  put_shape(j, a.shape_source, "scale", where);
  put_pose(j, a);
  j["material"] = soft_material(a, where);
  if (!a.layer.empty()) j["layer"] = a.layer;
  if (!a.has_gravity) j["hasGravity"] = false;
  if (!a.use_recentering) j["useRecentering"] = false;
  if (json c = contact(a.contact); !c.empty()) j["contact"] = c;
  if (!a.fixed_nodes.empty()) j["fixedNodes"] = a.fixed_nodes;
  if (a.fixed_region) j["fixedRegion"] = {{"min", array(a.fixed_region->min)}, {"max", array(a.fixed_region->max)}};
  put_render_model(j, a.render_model);
  return j;
}

json link(const ArticulatedLinkPrefab& l, const std::string& where) {
  json j = json::object();
  if (!l.name.empty()) j["name"] = l.name;
  if (l.parent_link >= 0) j["parentLink"] = l.parent_link;
  if (l.mass) j["mass"] = *l.mass;
  if (l.density) j["density"] = *l.density;
  put_optional(j, "centerOfMass", l.center_of_mass);
  put_optional(j, "momentOfInertia", l.moment_of_inertia);
  put_shape(j, l.shape_source, "shapeScale", l.shape.is_valid() ? where : "");
  if (l.collider_type != ColliderType::Auto) j["colliderType"] = collider_type_name(l.collider_type);
  if (json c = contact(l.contact); !c.empty()) j["contact"] = c;
  if (!l.layer.empty()) {
    // a layer number (as bot files give them) or a layer name
    const bool number = l.layer.find_first_not_of("0123456789") == std::string::npos && l.layer.size() <= 2;
    if (number) j["layer"] = std::stoi(l.layer);
    else j["layer"] = l.layer;
  }
  if (!l.parent_joint_from_link.translation.isZero()) j["jointFromLink"] = array(l.parent_joint_from_link.translation);
  if (!l.has_gravity) j["hasGravity"] = false;
  put_render_model(j, l.render_model);
  return j;
}

json joint(const ArticulatedJointPrefab& p) {
  json j = {{"type", articulated_joint_type_name(p.type)}, {"axis", array(p.axis)},
            {"parentLinkFromJoint", transform(p.parent_link_from_joint)},
            {"limitStiffness", p.limit_stiffness}, {"limitDamping", p.limit_damping}};
  if (!p.name.empty()) j["name"] = p.name;
  put_optional(j, "minLimit", p.min_limit);
  put_optional(j, "maxLimit", p.max_limit);
  if (p.friction.coulomb != 0 || p.friction.viscous != 0) j["friction"] = {{"coulomb", p.friction.coulomb}, {"viscous", p.friction.viscous}};
  if (p.inertia) j["inertia"] = *p.inertia;
  return j;
}

json articulated(const ArticulatedActorPrefab& a, const std::string& where) {
  json j = json::object();
  if (!a.name.empty()) j["name"] = a.name;
  put_comment(j, a.comment);
  put_pose(j, a);
  if (a.scale != 1) j["scale"] = a.scale;
  if (a.joint_velocities) j["jointVelocities"] = *a.joint_velocities;
  if (!a.bot_file.empty()) {
    j["bot"] = a.bot_file;
    return j;
  }
  if (!a.cycles.empty()) throw Error(where + ".cycles: cycle joints cannot be written to prefab files yet");
  j["links"] = json::array();
  for (size_t i = 0; i < a.links.size(); ++i) j["links"].push_back(link(a.links[i], where + ".links[" + std::to_string(i) + "]"));
  j["joints"] = json::array();
  for (const ArticulatedJointPrefab& p : a.joints) j["joints"].push_back(joint(p));
  if (!a.default_pose.empty()) j["defaultPose"] = a.default_pose;
  for (const ContactOverride& o : a.contact_overrides) j["contactOverrides"].push_back({{"linkA", o.link_a}, {"linkB", o.link_b}, {"enable", o.enable}});
  return j;
}

template <class E>
void put_entries(json& j, const char* key, const std::optional<std::vector<E>>& entries) {
  if (!entries) return;
  j[key] = json::array();
  for (const E& e : *entries) {
    if constexpr (requires { e.actors; })
      j[key].push_back({{"enable", e.enable}, {"actors", e.actors}, {"includeNestedActors", e.include_nested_actors}});
    else
      j[key].push_back({{"enable", e.enable}, {"layers", e.layers}});
  }
}

json contact_filter(const ContactFilter& f) {
  json j = json::object();
  put_comment(j, f.comment);
  put_entries(j, "actorContactAsymmetric", f.actor_contact_asymmetric);
  put_entries(j, "actorContactSymmetric", f.actor_contact_symmetric);
  put_entries(j, "layerContactAsymmetric", f.layer_contact_asymmetric);
  put_entries(j, "layerContactSymmetric", f.layer_contact_symmetric);
  return j;
}

json scene(const SceneParams& s) {
  json j = {{"description", s.description}};
  put_comment(j, s.comment);
  put_optional(j, "gravity", s.gravity);
  if (s.solver) j["solver"] = solver_params_to_json(*s.solver);
  return j;
}

template <class T, class F>
json list(const std::vector<T>& items, const std::string& path, F write) {
  json a = json::array();
  for (size_t i = 0; i < items.size(); ++i) a.push_back(write(items[i], path + "[" + std::to_string(i) + "]"));
  return a;
}

}  // namespace

json scene_prefab_to_json(const ScenePrefab& p) {
  json doc = json::object();
  put_comment(doc, p.comment);
  const std::string at = "save_to_json: " + error_prefix(p) + "actors";
  json actors = {{"rigid", list(p.actors.rigid, at + ".rigid", rigid)},
                 {"soft", list(p.actors.soft, at + ".soft", soft)},
                 {"articulated", list(p.actors.articulated, at + ".articulated", articulated)}};
  put_comment(actors, p.actors.comment);
  doc["actors"] = actors;
  doc["prefabs"] = json::array();
  for (const PrefabReference& r : p.prefabs) {
    json j = {{"name", r.name}, {"path", r.path}, {"scale", r.scale}};
    put_comment(j, r.comment);
    put_pose(j, r);
    doc["prefabs"].push_back(j);
  }
  if (p.contact_filter) doc["contactFilter"] = contact_filter(*p.contact_filter);
  if (p.scene) doc["scene"] = scene(*p.scene);
  return doc;
}

}  // namespace prefab
}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
