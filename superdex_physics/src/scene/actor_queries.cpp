// Queries of actors: their registration, and the contact results of the last step they read.

#include <algorithm>

#include "scene/scene_data.h"
#include "superdex/physics/error.h"
#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

const char* query_type_name(QueryType type) {
  switch (type) {
    case QueryType::NodePositions: return "NODE_POSITIONS";
    case QueryType::ElementsDeformationGradient: return "ELEMENTS_DEFORMATION_GRADIENT";
    case QueryType::SurfaceNodePositions: return "SURFACE_NODE_POSITIONS";
    case QueryType::SurfaceNodeNormals: return "SURFACE_NODE_NORMALS";
    case QueryType::VisualNodePositions: return "VISUAL_NODE_POSITIONS";
    case QueryType::VisualNodeNormals: return "VISUAL_NODE_NORMALS";
    case QueryType::ContactPoints: return "CONTACT_POINTS";
    case QueryType::ElasticEnergy: return "ELASTIC_ENERGY";
    case QueryType::NodeContactForces: return "NODE_CONTACT_FORCES";
    case QueryType::ConstraintForce: return "CONSTRAINT_FORCE";
    case QueryType::ArticulatedControllerForce: return "ARTICULATED_CONTROLLER_FORCE";
    case QueryType::SdfDistances: return "SDF_DISTANCES";
    case QueryType::TotalContactForce: return "TOTAL_CONTACT_FORCE";
  }
  return "?";
}

namespace {

const ActorRef& lookup(const SceneData& s, ActorHandle h, const char* what) {
  auto it = s.actors.find(h);
  if (it == s.actors.end())
    throw Error(std::string(what) + ": actor " + std::to_string(h) + " does not exist in scene '" + s.name + "'");
  return it->second;
}

// Whether side (body, link) of a contact belongs to the actor `ref`.
// Soft sides are bodies -1 - (soft body index).
bool belongs(const SceneData& s, const ActorRef& ref, int body, int link) {
  if (body < 0) return ref.soft && s.soft_bodies[-1 - body].get() == ref.soft;
  if (s.articulations[body].get() != ref.articulation) return false;
  return ref.link < 0 || ref.articulation->is_rigid || ref.link == link;
}

// Calls fn(record, sign) for each contact side of the actor: sign +1 when it is side a.
template <class F>
void for_each_side(const SceneData& s, const ActorRef& ref, F&& fn) {
  for (const ContactRecord& c : s.contacts) {
    if (belongs(s, ref, c.body_a, c.link_a)) fn(c, real(1));
    if (belongs(s, ref, c.body_b, c.link_b)) fn(c, real(-1));
  }
}

// The velocity (m/s, world) of the material point of contact side (body, link) at p_W.
Vec3 point_velocity(const SceneData& s, int body, int link, const Vec3& p_W) {
  if (body < 0) {
    // a soft side's link is its nearest node
    const SoftBody& b = *s.soft_bodies[-1 - body];
    return b.state.v.segment<3>(3 * link);
  }
  const Articulation& a = *s.articulations[body];
  const SpatialTransform& X = a.kin.X_WL[link];
  const Vec6& V = a.kin.V_L[link];  // (linear, angular) at the link origin, link frame
  const Vec3 v_W = X.R * V.head<3>(), w_W = X.R * V.tail<3>();
  return v_W + w_W.cross(p_W - X.p);
}

}  // namespace

bool Scene::is_query_supported(ActorHandle actor, QueryType type) const {
  const SceneData& s = scene_data(handle_);
  const ActorRef& r = lookup(s, actor, "is_query_supported");
  switch (type) {
    case QueryType::ContactPoints:
    case QueryType::TotalContactForce:
      return true;
    case QueryType::SurfaceNodePositions:
    case QueryType::SurfaceNodeNormals:
      if (!r.soft && r.link < 0 && r.articulation->skin) return true;  // a skinned articulation's skin surface
      [[fallthrough]];
    case QueryType::NodePositions:
    case QueryType::ElementsDeformationGradient:
    case QueryType::ElasticEnergy:
    case QueryType::NodeContactForces:
    case QueryType::SdfDistances:
      return r.soft != nullptr && !(type == QueryType::ElementsDeformationGradient && r.soft->reduced);
    case QueryType::ArticulatedControllerForce:
      return !r.soft && r.link < 0 && !r.articulation->is_rigid;
    default:
      return false;
  }
}

QueryHandle Scene::register_query(ActorHandle actor, QueryType type, bool compute_now) {
  SceneData& s = scene_data(handle_);
  const ActorRef& r = lookup(s, actor, "register_query");
  if (!is_query_supported(actor, type))
    throw Error(std::string("register_query: ") + query_type_name(type) + " is not available for actor " + std::to_string(actor) +
                (r.soft ? " (a soft actor)" : " (rigid and articulated actors offer TOTAL_CONTACT_FORCE and CONTACT_POINTS)"));
  // queries read from the current state are readable at once when asked to compute now
  const bool from_state = type == QueryType::NodePositions || type == QueryType::ElementsDeformationGradient ||
                          type == QueryType::SurfaceNodePositions || type == QueryType::SurfaceNodeNormals ||
                          type == QueryType::ElasticEnergy;
  const QueryHandle id = next_handle();
  s.queries[id] = {actor, static_cast<int>(type), compute_now && from_state ? s.step_count - 1 : s.step_count};
  return id;
}

void Scene::cancel_query(ActorHandle actor, QueryHandle query) {
  SceneData& s = scene_data(handle_);
  auto it = s.queries.find(query);
  if (it != s.queries.end() && it->second.actor == actor) s.queries.erase(it);
}

void require_query(const SceneData& s, ActorHandle actor, QueryType type, const char* what) {
  bool registered = false;
  for (const auto& [id, q] : s.queries) {
    if (q.actor != actor || q.type != static_cast<int>(type)) continue;
    registered = true;
    if (s.step_count > q.since_step) return;
  }
  const std::string name = query_type_name(type);
  if (!registered)
    throw Error(std::string(what) + ": actor " + std::to_string(actor) + " has no " + name +
                " query; call register_query(QueryType." + name + ") on it first");
  throw Error(std::string(what) + ": the " + name + " query of actor " + std::to_string(actor) +
              " has no result yet; results are valid after the next scene.step()");
}

Vec3 Scene::contact_force(ActorHandle actor) const {
  const SceneData& s = scene_data(handle_);
  const ActorRef& ref = lookup(s, actor, "get_contact_force_world");
  require_query(s, actor, QueryType::TotalContactForce, "get_contact_force_world");
  if (ref.soft) {
    Vec3 f = Vec3::Zero();
    const VecX& nodes = ref.soft->node_contact_forces;
    for (Eigen::Index i = 0; i + 2 < nodes.size(); i += 3) f += nodes.segment<3>(i);
    return f;
  }
  Vec3 f = Vec3::Zero();
  for_each_side(s, ref, [&](const ContactRecord& c, real sign) { f += sign * c.force; });
  return f;
}

Vec3 Scene::contact_torque(ActorHandle actor) const {
  const SceneData& s = scene_data(handle_);
  const ActorRef& ref = lookup(s, actor, "get_contact_torque_world");
  require_query(s, actor, QueryType::TotalContactForce, "get_contact_torque_world");
  // about the centre of mass
  Vec3 com = Vec3::Zero();
  if (ref.soft) {
    const SoftModel& m = ref.soft->model;
    for (int i = 0; i < m.node_mass.size(); ++i) com += m.node_mass[i] * ref.soft->state.x.segment<3>(3 * i);
    com /= m.total_mass;
  } else {
    const int link = ref.link < 0 ? 0 : ref.link;
    const SpatialTransform& X = ref.articulation->kin.X_WL[link];
    com = X.R * ref.articulation->model.inertia[link].com + X.p;
  }
  Vec3 t = Vec3::Zero();
  for_each_side(s, ref, [&](const ContactRecord& c, real sign) { t += (c.position - com).cross(sign * c.force); });
  return t;
}

Vec3 Scene::contact_force_from(ActorHandle actor, ActorHandle other) const {
  const SceneData& s = scene_data(handle_);
  const ActorRef& ref = lookup(s, actor, "get_contact_force_from_actor_world");
  const ActorRef& other_ref = lookup(s, other, "get_contact_force_from_actor_world: other");
  require_query(s, actor, QueryType::TotalContactForce, "get_contact_force_from_actor_world");
  Vec3 f = Vec3::Zero();
  for (const ContactRecord& c : s.contacts) {
    if (belongs(s, ref, c.body_a, c.link_a) && belongs(s, other_ref, c.body_b, c.link_b)) f += c.force;
    if (belongs(s, ref, c.body_b, c.link_b) && belongs(s, other_ref, c.body_a, c.link_a)) f -= c.force;
  }
  return f;
}

std::vector<ContactPoint> Scene::contact_points(ActorHandle actor) const {
  const SceneData& s = scene_data(handle_);
  const ActorRef& ref = lookup(s, actor, "get_contact_points_world");
  require_query(s, actor, QueryType::ContactPoints, "get_contact_points_world");
  std::vector<ContactPoint> out;
  for_each_side(s, ref, [&](const ContactRecord& c, real sign) {
    ContactPoint p;
    const bool a_side = sign > 0;
    p.actor_a = a_side ? c.actor_a : c.actor_b;
    p.actor_b = a_side ? c.actor_b : c.actor_a;
    p.distance = c.distance;
    p.normal = sign * c.normal;
    // the recorded point lies on side a; seen from side b, the points swap
    p.pos_a = a_side ? Vec3(c.position) : Vec3(c.position - c.normal * c.distance);
    p.pos_b = p.pos_a - p.normal * p.distance;
    p.force = sign * c.force;
    p.point_velocity_a = a_side ? point_velocity(s, c.body_a, c.link_a, p.pos_a) : point_velocity(s, c.body_b, c.link_b, p.pos_a);
    p.point_velocity_b = a_side ? point_velocity(s, c.body_b, c.link_b, p.pos_b) : point_velocity(s, c.body_a, c.link_a, p.pos_b);
    p.sample_index = static_cast<int>(out.size());
    out.push_back(p);
  });
  return out;
}

std::vector<NodeContactForce> Scene::node_contact_forces(ActorHandle actor) const {
  const SceneData& s = scene_data(handle_);
  const ActorRef& ref = lookup(s, actor, "get_node_contact_forces_world");
  if (!ref.soft) throw Error("get_node_contact_forces_world: actor " + std::to_string(actor) + " is not a soft actor");
  require_query(s, actor, QueryType::NodeContactForces, "get_node_contact_forces_world");
  const VecX& f = ref.soft->node_contact_forces;
  std::vector<NodeContactForce> out;
  for (Eigen::Index i = 0; i + 2 < f.size(); i += 3)
    if (!f.segment<3>(i).isZero(0)) out.push_back({static_cast<int>(i / 3), f.segment<3>(i)});
  return out;
}

SdfDistances Scene::sdf_distances(ActorHandle actor) const {
  const SceneData& s = scene_data(handle_);
  const ActorRef& ref = lookup(s, actor, "get_sdf_distances");
  if (!ref.soft) throw Error("get_sdf_distances: actor " + std::to_string(actor) + " is not a soft actor");
  require_query(s, actor, QueryType::SdfDistances, "get_sdf_distances");
  SdfDistances out;
  for_each_side(s, ref, [&](const ContactRecord& c, real sign) {
    if (sign < 0) return;
    out.sample_indices.push_back(c.link_a);  // a soft side's nearest node
    out.world_positions.push_back(c.position);
    out.distances.push_back(c.distance);
    out.distance_grads.push_back(c.normal);
  });
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
