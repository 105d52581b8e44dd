// Query registration and the contact results they read, and contact filtering switches.

#include "scene/scene_data.h"
#include "superdex/physics/error.h"
#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

const char* query_type_name(QueryType type) {
  switch (type) {
    case QueryType::TotalContactForce: return "TOTAL_CONTACT_FORCE";
    case QueryType::ContactPoints: return "CONTACT_POINTS";
    case QueryType::NodePositions: return "NODE_POSITIONS";
    case QueryType::NodeContactForces: return "NODE_CONTACT_FORCES";
    case QueryType::ConstraintForce: return "CONSTRAINT_FORCE";
    case QueryType::ArticulatedControllerForce: return "ARTICULATED_CONTROLLER_FORCE";
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

// Throws unless `type` is registered on `actor` and a step completed since.
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

}  // namespace

std::int64_t Scene::register_query(ActorHandle actor, QueryType type) {
  SceneData& s = scene_data(handle_);
  lookup(s, actor, "register_query");
  const bool soft = s.actors.at(actor).soft != nullptr;
  const bool ok = soft ? (type == QueryType::TotalContactForce || type == QueryType::ContactPoints ||
                          type == QueryType::NodePositions || type == QueryType::NodeContactForces)
                       : (type == QueryType::TotalContactForce || type == QueryType::ContactPoints);
  if (!ok)
    throw Error(std::string("register_query: ") + query_type_name(type) + " is not available for actor " + std::to_string(actor) +
                (soft ? " (soft actors offer TOTAL_CONTACT_FORCE, CONTACT_POINTS, NODE_POSITIONS and NODE_CONTACT_FORCES)"
                      : " (rigid and articulated actors offer TOTAL_CONTACT_FORCE and CONTACT_POINTS)"));
  const std::int64_t id = next_handle();
  s.queries[id] = {actor, static_cast<int>(type), s.step_count};
  return id;
}

void Scene::cancel_query(ActorHandle actor, std::int64_t query) {
  SceneData& s = scene_data(handle_);
  auto it = s.queries.find(query);
  if (it == s.queries.end() || it->second.actor != actor)
    throw Error("cancel_query: query " + std::to_string(query) + " is not registered on actor " + std::to_string(actor));
  s.queries.erase(it);
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
  // about the link origin, or a soft body's centre of mass
  Vec3 origin = Vec3::Zero();
  if (ref.soft) {
    const SoftModel& m = ref.soft->model;
    for (int i = 0; i < m.node_mass.size(); ++i) origin += m.node_mass[i] * ref.soft->state.x.segment<3>(3 * i);
    origin /= m.total_mass;
  } else {
    origin = ref.articulation->kin.X_WL[ref.link < 0 ? 0 : ref.link].p;
  }
  Vec3 t = Vec3::Zero();
  for_each_side(s, ref, [&](const ContactRecord& c, real sign) { t += (c.position - origin).cross(sign * c.force); });
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

std::vector<ContactPointInfo> Scene::contact_points(ActorHandle actor) const {
  const SceneData& s = scene_data(handle_);
  const ActorRef& ref = lookup(s, actor, "get_contact_points_world");
  require_query(s, actor, QueryType::ContactPoints, "get_contact_points_world");
  std::vector<ContactPointInfo> out;
  for_each_side(s, ref, [&](const ContactRecord& c, real sign) {
    ContactPointInfo p;
    p.actor_a = sign > 0 ? c.actor_a : c.actor_b;
    p.actor_b = sign > 0 ? c.actor_b : c.actor_a;
    p.position = c.position;
    p.normal = sign * c.normal;
    p.distance = c.distance;
    p.force = sign * c.force;
    out.push_back(p);
  });
  return out;
}

std::vector<Vec3> Scene::node_contact_forces(ActorHandle actor) const {
  const SceneData& s = scene_data(handle_);
  const ActorRef& ref = lookup(s, actor, "get_node_contact_forces_world");
  if (!ref.soft) throw Error("get_node_contact_forces_world: actor " + std::to_string(actor) + " is not a soft actor");
  require_query(s, actor, QueryType::NodeContactForces, "get_node_contact_forces_world");
  const VecX& f = ref.soft->node_contact_forces;
  std::vector<Vec3> out(ref.soft->state.x.size() / 3, Vec3::Zero());
  for (size_t i = 0; i < out.size() && 3 * i + 2 < static_cast<size_t>(f.size()); ++i) out[i] = f.segment<3>(3 * i);
  return out;
}

void Scene::enable_actor_contact(ActorHandle a, ActorHandle b, bool enable) {
  SceneData& s = scene_data(handle_);
  lookup(s, a, "enable_actor_contact_symmetric");
  lookup(s, b, "enable_actor_contact_symmetric");
  const auto key = std::make_pair(std::min(a, b), std::max(a, b));
  if (enable) s.disabled_actor_pairs.erase(key);
  else s.disabled_actor_pairs.insert(key);
}

void Scene::enable_layer_contact(int la, int lb, bool enable) {
  SceneData& s = scene_data(handle_);
  for (int l : {la, lb})
    if (l < 0 || l > 63) throw Error("enable_layer_contact_symmetric: layers are 0..63, got " + std::to_string(l));
  const std::uint64_t bit_a = std::uint64_t(1) << la, bit_b = std::uint64_t(1) << lb;
  if (enable) {
    s.layer_masks[la] |= bit_b;
    s.layer_masks[lb] |= bit_a;
  } else {
    s.layer_masks[la] &= ~bit_b;
    s.layer_masks[lb] &= ~bit_a;
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
