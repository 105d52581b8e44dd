// The scene's constraint API (scene.h, constraint_params.h): creation with validation, lookup,
// parameters, targets, deviation and forces.

#include <cmath>
#include <string>

#include "constraint/constraint_terms.h"
#include "core/spatial.h"
#include "scene/actor_lookup.h"
#include "scene/step_stages.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

const char* constraint_type_name(ConstraintType type) {
  switch (type) {
    case ConstraintType::RigidSphericalJoint: return "RIGID_SPHERICAL_JOINT";
    case ConstraintType::RigidPrismaticJoint: return "RIGID_PRISMATIC_JOINT";
    case ConstraintType::JointRotationRange: return "JOINT_ROTATION_RANGE";
    case ConstraintType::JointRotationTracking: return "JOINT_ROTATION_TRACKING";
    case ConstraintType::RigidPivotPosition: return "RIGID_PIVOT_POSITION";
    case ConstraintType::RigidPivotToRigidTarget: return "RIGID_PIVOT_TO_RIGID_TARGET";
    case ConstraintType::RigidPivotRotation: return "RIGID_PIVOT_ROTATION";
    case ConstraintType::DeformableNodePosition: return "DEFORMABLE_NODE_POSITION";
    case ConstraintType::DeformableNodeToRigid: return "DEFORMABLE_NODE_TO_RIGID";
    case ConstraintType::DeformableNodeToDeformableNode: return "DEFORMABLE_NODE_TO_DEFORMABLE_NODE";
    case ConstraintType::ArticulatedSingleDofTarget: return "ARTICULATED_SINGLE_DOF_TARGET";
    case ConstraintType::Articulated3dRotationTarget: return "ARTICULATED_3D_ROTATION_TARGET";
    case ConstraintType::ArticulatedSingleDofRange: return "ARTICULATED_SINGLE_DOF_RANGE";
    case ConstraintType::RodElementRotationToRigid: return "ROD_ELEMENT_ROTATION_TO_RIGID";
  }
  return "?";
}

namespace {

void check(bool ok, const std::string& what, const std::string& message) {
  if (!ok) throw Error(what + ": " + message);
}

template <class V>
void check_finite(const V& v, const std::string& what, const char* field) {
  check(v.allFinite(), what, std::string(field) + " must be finite");
}

// A rotation given as a quaternion: finite and not zero (it is normalized where kept).
void check_rotation(const Quat& q, const std::string& what, const char* field) {
  check(q.coeffs().allFinite() && q.norm() > real(1e-6), what, std::string(field) + " must be a finite, non-zero quaternion");
}

void check_spring(const ConstraintParams& p, const std::string& what) {
  check(std::isfinite(p.stiffness) && p.stiffness >= 0, what, "stiffness must be finite and >= 0 (N/m or N m/rad), got " + std::to_string(p.stiffness));
  check(std::isfinite(p.damping) && p.damping >= 0, what, "damping must be finite and >= 0, got " + std::to_string(p.damping));
  check(std::isfinite(p.saturation) && p.saturation != 0, what,
        "saturation must be finite and not 0 (negative: no cap; positive: the force cap), got " + std::to_string(p.saturation));
}

// The frame of a rigid or link actor now; soft and whole articulated actors are refused.
Transform rigid_frame(SceneData& s, ActorHandle actor, const std::string& what, const char* field) {
  if (!actor.is_valid()) throw Error(what + ": " + field + " is not set");
  const ActorRef r = lookup(s, actor, (what + " (" + field + ")").c_str());
  if (r.soft || (r.link < 0 && !r.articulation->is_rigid))
    throw Error(what + ": " + field + " (" + describe(actor) + ") must be a rigid actor or an articulation's link");
  const SpatialTransform& X = r.articulation->kin.X_WL[r.link < 0 ? 0 : r.link];
  return {Quat(X.R).normalized(), X.p};
}

// Joint `joint` of an articulated actor (a whole articulation, not a rigid actor or a link).
const JointModel& articulated_joint(SceneData& s, ActorHandle actor, int joint, const std::string& what) {
  if (!actor.is_valid()) throw Error(what + ": actor is not set");
  const ActorRef r = lookup(s, actor, (what + " (actor)").c_str());
  if (r.soft || r.link >= 0 || r.articulation->is_rigid)
    throw Error(what + ": actor (" + describe(actor) + ") must be an articulated actor");
  const int n = r.articulation->model.num_links;
  check(joint >= 0 && joint < n, what, "joint_index " + std::to_string(joint) + " out of range [0, " + std::to_string(n) + ")");
  return r.articulation->model.joints[joint];
}

// The soft body of a soft actor whose node a constraint holds (full bodies: a reduced body's
// nodes are not variables of its solve).
const SoftBody& node_body(SceneData& s, ActorHandle actor, const std::string& what, const char* field) {
  if (!actor.is_valid()) throw Error(what + ": " + field + " is not set");
  const ActorRef r = lookup(s, actor, (what + " (" + field + ")").c_str());
  if (!r.soft) throw Error(what + ": " + field + " (" + describe(actor) + ") must be a soft actor");
  if (r.soft->reduced) throw Error(what + ": " + field + " (" + describe(actor) + ") is a reduced soft actor; node constraints need a full one");
  return *r.soft;
}

void check_node(const SoftBody& b, int node, const std::string& what, const char* field) {
  const int n = b.user_nodes();
  check(node >= 0 && node < n, what, std::string(field) + " " + std::to_string(node) + " out of range [0, " + std::to_string(n) + ")");
}

// The surface node of a soft body nearest a world point.
int closest_surface_node(const SoftBody& b, const Vec3& p_W) {
  int best = -1;
  real best_d2 = std::numeric_limits<real>::infinity();
  for (int n : b.model.surface_nodes) {
    const real d2 = (b.state.x.segment<3>(3 * n) - p_W).squaredNorm();
    if (d2 < best_d2) best = n, best_d2 = d2;
  }
  return best;
}

template <class Data>  // SceneData, const or not
auto& record(Data& s, ConstraintHandle h, const char* what) {
  auto it = s.constraints.find(h);
  if (it == s.constraints.end())
    throw Error(std::string(what) + ": constraint " + std::to_string(h) + " does not exist in scene '" + s.name + "' (destroyed, or never created here)");
  return it->second;
}

ConstraintHandle add(SceneData& s, ConstraintRecord c, const ConstraintParams& p) {
  c.handle = next_handle();
  c.stiffness = p.stiffness;
  c.damping = p.damping;
  c.saturation = p.saturation;
  settle_constraint_targets(c);
  const ConstraintHandle h = c.handle;
  s.constraints.emplace(h, std::move(c));
  return h;
}


[[noreturn]] void unsupported(const ConstraintRecord& c, const char* what) {
  throw Error(std::string(what) + ": not available for a " + constraint_type_name(c.type) + " constraint");
}

}  // namespace

ConstraintHandle Scene::create_rigid_spherical_joint_constraint(const RigidSphericalJointConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "create_rigid_spherical_joint_constraint";
  check_spring(p, what);
  check_finite(p.local_pos_a, what, "local_pos_a");
  check_finite(p.local_pos_b, what, "local_pos_b");
  rigid_frame(s, p.actor_a, what, "actor_a");
  rigid_frame(s, p.actor_b, what, "actor_b");
  check(p.actor_a != p.actor_b, what, "actor_a and actor_b must differ");
  ConstraintRecord c;
  c.type = ConstraintType::RigidSphericalJoint;
  c.actor_a = p.actor_a, c.actor_b = p.actor_b;
  c.p_A = p.local_pos_a, c.p_B = p.local_pos_b;
  return add(s, std::move(c), p);
}

ConstraintHandle Scene::create_rigid_prismatic_joint_constraint(const RigidPrismaticJointConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "create_rigid_prismatic_joint_constraint";
  check_spring(p, what);
  check_finite(p.free_axis, what, "free_axis");
  check(p.free_axis.norm() > real(1e-6), what, "free_axis must not be zero");
  check(!p.min || std::isfinite(*p.min), what, "min must be finite");
  check(!p.max || std::isfinite(*p.max), what, "max must be finite");
  check(!p.min || !p.max || *p.min <= *p.max, what, "min must not exceed max");
  const Transform X_WA = rigid_frame(s, p.actor_a, what, "actor_a");
  const Transform X_WB = rigid_frame(s, p.actor_b, what, "actor_b");
  check(p.actor_a != p.actor_b, what, "actor_a and actor_b must differ");
  ConstraintRecord c;
  c.type = ConstraintType::RigidPrismaticJoint;
  c.actor_a = p.actor_a, c.actor_b = p.actor_b;
  c.axis_A = X_WA.rotation.conjugate() * p.free_axis.normalized();
  c.offset_A = X_WA.rotation.conjugate() * (X_WB.translation - X_WA.translation);
  c.min = p.min, c.max = p.max;
  return add(s, std::move(c), p);
}

ConstraintHandle Scene::create_joint_rotation_range_constraint(const JointRotationRangeConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "create_joint_rotation_range_constraint";
  check_spring(p, what);
  check_finite(p.ref_frame_rot_vec, what, "ref_frame_rot_vec");
  const Real2* ranges[3] = {&p.angle_range_x, &p.angle_range_y, &p.angle_range_z};
  const char* names[3] = {"angle_range_x", "angle_range_y", "angle_range_z"};
  for (int i = 0; i < 3; ++i) {
    check_finite(*ranges[i], what, names[i]);
    check((*ranges[i])[0] <= (*ranges[i])[1], what, std::string(names[i]) + " must be [min, max] with min <= max");
  }
  const Transform X_WA = rigid_frame(s, p.actor_a, what, "actor_a");
  const Transform X_WB = rigid_frame(s, p.actor_b, what, "actor_b");
  check(p.actor_a != p.actor_b, what, "actor_a and actor_b must differ");
  ConstraintRecord c;
  c.type = ConstraintType::JointRotationRange;
  c.actor_a = p.actor_a, c.actor_b = p.actor_b;
  // the joint frame given in the world now, fixed in A; in B the same frame now (the rest is no
  // rotation) or A's (B's rotation measured against A's own)
  const Quat joint_W = quat_exp(p.ref_frame_rot_vec);
  c.J_A = (X_WA.rotation.conjugate() * joint_W).normalized();
  c.J_B = p.range_around_rest ? (X_WB.rotation.conjugate() * joint_W).normalized() : c.J_A;
  for (int i = 0; i < 3; ++i) c.lower[i] = (*ranges[i])[0], c.upper[i] = (*ranges[i])[1];
  return add(s, std::move(c), p);
}

ConstraintHandle Scene::create_joint_rotation_tracking_constraint(const JointRotationTrackingConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "create_joint_rotation_tracking_constraint";
  check_spring(p, what);
  check_finite(p.ref_frame_rot_vec, what, "ref_frame_rot_vec");
  const Transform X_WA = rigid_frame(s, p.actor_a, what, "actor_a");
  const Transform X_WB = rigid_frame(s, p.actor_b, what, "actor_b");
  check(p.actor_a != p.actor_b, what, "actor_a and actor_b must differ");
  ConstraintRecord c;
  c.type = ConstraintType::JointRotationTracking;
  c.actor_a = p.actor_a, c.actor_b = p.actor_b;
  c.J_A = (X_WA.rotation.conjugate() * quat_exp(p.ref_frame_rot_vec)).normalized();
  // the target: the relative rotation now
  c.target_rotation = (X_WA.rotation.conjugate() * X_WB.rotation).normalized();
  return add(s, std::move(c), p);
}

ConstraintHandle Scene::create_rod_element_rotation_to_rigid_constraint(const RodElementRotationToRigidConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "create_rod_element_rotation_to_rigid_constraint";
  check_spring(p, what);
  check_finite(p.ref_frame_rot_vec, what, "ref_frame_rot_vec");
  const Transform X_WA = rigid_frame(s, p.rigid_actor, what, "rigid_actor");
  if (!p.rod_actor.is_valid()) throw Error(what + ": rod_actor is not set");
  const ActorRef r = lookup(s, p.rod_actor, (what + " (rod_actor)").c_str());
  if (!r.soft || !r.soft->model.rod) throw Error(what + ": rod_actor (" + describe(p.rod_actor) + ") must be a rod actor");
  const SoftBody& b = *r.soft;
  const int ne = static_cast<int>(b.model.rod->elements.size());
  check(p.element_index >= 0 && p.element_index < ne, what,
        "element_index " + std::to_string(p.element_index) + " out of range [0, " + std::to_string(ne) + ")");
  const Mat3 R_e = rod_element_frame(*b.model.rod, p.element_index, b.state.x);
  ConstraintRecord c;
  c.type = ConstraintType::RodElementRotationToRigid;
  c.actor_a = p.rigid_actor, c.actor_b = p.rod_actor;
  c.element = p.element_index;
  // the target: the element's frame relative to the rigid actor now, turned in the element's frame
  c.target_rotation = (X_WA.rotation.conjugate() * Quat(R_e) * quat_exp(p.ref_frame_rot_vec)).normalized();
  return add(s, std::move(c), p);
}

ConstraintHandle Scene::create_rigid_pivot_position_constraint(const RigidPivotPositionConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "create_rigid_pivot_position_constraint";
  check_spring(p, what);
  check_finite(p.target_position, what, "target_position");
  check_finite(p.local_position, what, "local_position");
  rigid_frame(s, p.actor, what, "actor");
  ConstraintRecord c;
  c.type = ConstraintType::RigidPivotPosition;
  c.actor_a = p.actor;
  c.p_A = p.local_position;
  c.target_position = p.target_position;
  return add(s, std::move(c), p);
}

ConstraintHandle Scene::create_rigid_pivot_to_rigid_target_constraint(const RigidPivotToRigidTargetConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "create_rigid_pivot_to_rigid_target_constraint";
  check_spring(p, what);
  check_finite(p.local_position, what, "local_position");
  check_finite(p.target_transform.translation, what, "target_transform.translation");
  check_rotation(p.target_transform.rotation, what, "target_transform.rotation");
  rigid_frame(s, p.actor, what, "actor");
  ConstraintRecord c;
  c.type = ConstraintType::RigidPivotToRigidTarget;
  c.actor_a = p.actor;
  c.p_A = p.local_position;
  c.target_transform = {p.target_transform.rotation.normalized(), p.target_transform.translation};
  return add(s, std::move(c), p);
}

ConstraintHandle Scene::create_rigid_pivot_rotation_constraint(const RigidPivotRotationConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "create_rigid_pivot_rotation_constraint";
  check_spring(p, what);
  check_finite(p.target_rotation, what, "target_rotation");
  check_finite(p.local_rotation, what, "local_rotation");
  rigid_frame(s, p.actor, what, "actor");
  ConstraintRecord c;
  c.type = ConstraintType::RigidPivotRotation;
  c.actor_a = p.actor;
  c.local_rotation = quat_exp(p.local_rotation);
  c.target_rotation = quat_exp(p.target_rotation);
  return add(s, std::move(c), p);
}

ConstraintHandle Scene::create_deformable_node_position_constraint(const DeformableNodePositionConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "create_deformable_node_position_constraint";
  check_spring(p, what);
  check_finite(p.position, what, "position");
  check_node(node_body(s, p.actor, what, "actor"), p.node_index, what, "node_index");
  ConstraintRecord c;
  c.type = ConstraintType::DeformableNodePosition;
  c.actor_a = p.actor;
  c.node_a = p.node_index;
  c.target_position = p.position;
  return add(s, std::move(c), p);
}

ConstraintHandle Scene::create_deformable_node_to_rigid_constraint(const DeformableNodeToRigidConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "create_deformable_node_to_rigid_constraint";
  check_spring(p, what);
  check_finite(p.rigid_local_pos, what, "rigid_local_pos");
  const Transform X_WA = rigid_frame(s, p.rigid_actor, what, "rigid_actor");
  const SoftBody& body = node_body(s, p.deformable_actor, what, "deformable_actor");
  ConstraintRecord c;
  c.type = ConstraintType::DeformableNodeToRigid;
  c.actor_a = p.rigid_actor, c.actor_b = p.deformable_actor;
  c.node_b = p.find_closest ? closest_surface_node(body, X_WA * p.rigid_local_pos) : p.deformable_node_index;
  check_node(body, c.node_b, what, "deformable_node_index");
  // the rigid actor's point: where the node is now, or as given
  c.p_A = p.fix_to_deformable_pos ? Vec3(X_WA.rotation.conjugate() * (body.state.x.segment<3>(3 * c.node_b) - X_WA.translation))
                                  : Vec3(p.rigid_local_pos);
  return add(s, std::move(c), p);
}

ConstraintHandle Scene::create_deformable_node_to_deformable_node_constraint(const DeformableNodeToDeformableNodeConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "create_deformable_node_to_deformable_node_constraint";
  check_spring(p, what);
  const SoftBody& body_a = node_body(s, p.actor_a, what, "actor_a");
  const SoftBody& body_b = node_body(s, p.actor_b, what, "actor_b");
  ConstraintRecord c;
  c.type = ConstraintType::DeformableNodeToDeformableNode;
  c.actor_a = p.actor_a, c.actor_b = p.actor_b;
  if (p.find_closest) {
    // each surface's node nearest the midpoint of the two actors' origins
    const Vec3 mid = (body_a.X_WL.translation + body_b.X_WL.translation) / 2;
    c.node_a = closest_surface_node(body_a, mid), c.node_b = closest_surface_node(body_b, mid);
  } else {
    c.node_a = p.node_index_a, c.node_b = p.node_index_b;
  }
  check_node(body_a, c.node_a, what, "node_index_a");
  check_node(body_b, c.node_b, what, "node_index_b");
  check(p.actor_a != p.actor_b || c.node_a != c.node_b, what, "node_index_a and node_index_b are the same node of the same actor");
  return add(s, std::move(c), p);
}

ConstraintHandle Scene::create_articulated_single_dof_target_constraint(const ArticulatedSingleDofTargetConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "create_articulated_single_dof_target_constraint";
  check_spring(p, what);
  check(std::isfinite(p.target_value), what, "target_value must be finite");
  const JointModel& j = articulated_joint(s, p.actor, p.joint_index, what);
  check(j.nv == 1, what, "joint_index " + std::to_string(p.joint_index) + " is a " + joint_type_name(j.type) +
                             " joint; this constraint takes a revolute or prismatic one");
  check(p.dof_index == 0, what, "dof_index must be 0 (the joint has one DOF), got " + std::to_string(p.dof_index));
  ConstraintRecord c;
  c.type = ConstraintType::ArticulatedSingleDofTarget;
  c.actor_a = p.actor;
  c.joint = p.joint_index, c.dof = j.v_offset;
  c.target_value = p.target_value;
  return add(s, std::move(c), p);
}

ConstraintHandle Scene::create_articulated_3d_rotation_target_constraint(const Articulated3dRotationTargetConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  const std::string what = "create_articulated_3d_rotation_target_constraint";
  check_spring(p, what);
  check_rotation(p.target, what, "target");
  const JointModel& j = articulated_joint(s, p.actor, p.joint_index, what);
  check(j.type == JointType::Spherical || j.type == JointType::Free, what,
        "joint_index " + std::to_string(p.joint_index) + " is a " + joint_type_name(j.type) + " joint; this constraint takes a spherical or free one");
  ConstraintRecord c;
  c.type = ConstraintType::Articulated3dRotationTarget;
  c.actor_a = p.actor;
  c.joint = p.joint_index, c.dof = j.v_offset + (j.type == JointType::Free ? 3 : 0);
  c.target_rotation = p.target.normalized();
  return add(s, std::move(c), p);
}

void Scene::destroy_constraint(ConstraintHandle h) {
  SceneData& s = scene_data(handle_);
  const ConstraintRecord& c = record(s, h, "destroy_constraint");
  if (c.owner.is_valid())
    throw Error("destroy_constraint: constraint " + std::to_string(h) + " belongs to actor " + std::to_string(c.owner) +
                (c.type == ConstraintType::ArticulatedSingleDofRange ? " (one of its joint limits); it goes with the actor"
                 : c.type == ConstraintType::DeformableNodeToRigid   ? " (a soft body's tie to its skeleton); it goes with the actor"
                                                                     : " (its pose controller); remove_articulated_pose_controller removes it"));
  s.constraints.erase(h);
}

bool Scene::has_constraint(ConstraintHandle h) const { return scene_data(handle_).constraints.count(h) > 0; }

std::vector<ConstraintHandle> Scene::constraints() const {
  std::vector<ConstraintHandle> out;
  for (const auto& [h, c] : scene_data(handle_).constraints) out.push_back(h);
  return out;
}

ConstraintType Scene::constraint_type(ConstraintHandle h) const { return record(scene_data(handle_), h, "get_type").type; }

ConstraintParams Scene::constraint_params(ConstraintHandle h) const {
  const ConstraintRecord& c = record(scene_data(handle_), h, "constraint_params");
  return {c.stiffness, c.damping, c.saturation};
}

void Scene::set_constraint_params(ConstraintHandle h, const ConstraintParams& p) {
  SceneData& s = scene_data(handle_);
  ConstraintRecord& c = record(s, h, "set_constraint_params");
  check_spring(p, "set_constraint_params");
  if (c.type == ConstraintType::ArticulatedSingleDofRange) {
    // a handle on the joint's own limits: their stiffness and damping (no force cap)
    check(p.saturation < 0, "set_constraint_params", "a joint limit has no force cap (saturation must be negative)");
    JointModel& j = s.actors.at(c.actor_a).articulation->model.joints[c.joint];
    j.limit_stiffness = p.stiffness, j.limit_damping = p.damping;
  }
  c.stiffness = p.stiffness, c.damping = p.damping, c.saturation = p.saturation;
}

void add_joint_limit_constraints(SceneData& s, Articulation& a) {
  for (int i = 0; i < a.model.num_links; ++i) {
    const JointModel& j = a.model.joints[i];
    if (j.nv != 1 || !(j.has_lower || j.has_upper)) continue;
    ConstraintRecord c;
    c.type = ConstraintType::ArticulatedSingleDofRange;
    c.actor_a = a.handle;
    c.owner = a.handle;
    c.joint = i, c.dof = j.v_offset;
    if (j.has_lower) c.min = j.lower;
    if (j.has_upper) c.max = j.upper;
    ConstraintParams p;
    p.stiffness = j.limit_stiffness, p.damping = j.limit_damping;
    a.limit_constraints.push_back(add(s, std::move(c), p));
  }
}

std::vector<ConstraintHandle> Scene::joint_limit_constraints(ActorHandle h) const {
  return articulated(scene_data(handle_), h, "get_articulated_joint_limit_constraints").limit_constraints;
}

std::vector<ActorHandle> Scene::constraint_actors(ConstraintHandle h) const {
  const ConstraintRecord& c = record(scene_data(handle_), h, "get_actor");
  if (c.actor_b.is_valid()) return {c.actor_a, c.actor_b};
  return {c.actor_a};
}

std::vector<int> Scene::constraint_dof_indices(ConstraintHandle h, int actor_index) const {
  const ConstraintRecord& c = record(scene_data(handle_), h, "get_dof_indices_for_actor");
  const int n = c.actor_b.is_valid() ? 2 : 1;
  if (actor_index < 0 || actor_index >= n)
    throw Error("get_dof_indices_for_actor: actor_index " + std::to_string(actor_index) + " out of range [0, " + std::to_string(n) + ")");
  return physics::constraint_dof_indices(c, actor_index);
}

std::vector<real> Scene::constraint_deviation(ConstraintHandle h) const {
  SceneData& s = scene_data(handle_);
  const ConstraintRecord& c = record(s, h, "get_deviation");
  return physics::constraint_deviation(c, constraint_side(s, c, 0), constraint_side(s, c, 1));
}

std::vector<real> Scene::constraint_force(ConstraintHandle h) const {
  const SceneData& s = scene_data(handle_);
  const ConstraintRecord& c = record(s, h, "get_force");
  if (c.queries.empty())
    throw Error("get_force: constraint " + std::to_string(h) + " has no CONSTRAINT_FORCE query; call register_query(QueryType.CONSTRAINT_FORCE) on it first");
  if (c.force_step < c.query_since)
    throw Error("get_force: the CONSTRAINT_FORCE query of constraint " + std::to_string(h) + " has no result yet; results are valid after the next scene.step()");
  return c.force;
}

void Scene::set_constraint_target_position(ConstraintHandle h, const Vec3& position) {
  ConstraintRecord& c = record(scene_data(handle_), h, "set_target_position");
  check_finite(position, "set_target_position", "position");
  if (c.type == ConstraintType::RigidPivotPosition || c.type == ConstraintType::DeformableNodePosition) {
    c.target_position = position;
  } else if (c.type == ConstraintType::RigidPivotToRigidTarget) {
    c.target_transform.translation = position;
  } else {
    unsupported(c, "set_target_position");
  }
}

void Scene::set_constraint_target_rotation(ConstraintHandle h, const Quat& rotation) {
  ConstraintRecord& c = record(scene_data(handle_), h, "set_target_rotation");
  check_rotation(rotation, "set_target_rotation", "rotation");
  if (c.type == ConstraintType::RigidPivotRotation || c.type == ConstraintType::JointRotationTracking ||
      c.type == ConstraintType::Articulated3dRotationTarget) {
    c.target_rotation = rotation.normalized();
  } else if (c.type == ConstraintType::RigidPivotToRigidTarget) {
    c.target_transform.rotation = rotation.normalized();
  } else {
    unsupported(c, "set_target_rotation");
  }
}

void Scene::set_constraint_target_dof(ConstraintHandle h, real value) {
  ConstraintRecord& c = record(scene_data(handle_), h, "set_target_dof");
  check(std::isfinite(value), "set_target_dof", "value must be finite");
  if (c.type != ConstraintType::ArticulatedSingleDofTarget) unsupported(c, "set_target_dof");
  c.target_value = value;
}

void Scene::update_constraint_old_target(ConstraintHandle h) {
  ConstraintRecord& c = record(scene_data(handle_), h, "update_old_target");
  if (c.type != ConstraintType::RigidPivotPosition && c.type != ConstraintType::DeformableNodePosition &&
      c.type != ConstraintType::RigidPivotToRigidTarget && c.type != ConstraintType::RigidPivotRotation &&
      c.type != ConstraintType::JointRotationTracking && c.type != ConstraintType::ArticulatedSingleDofTarget &&
      c.type != ConstraintType::Articulated3dRotationTarget)
    unsupported(c, "update_old_target");
  settle_constraint_targets(c);
}

void Scene::set_constraint_ref_relative_rotation(ConstraintHandle h, const Quat& rotation_a, const Quat& rotation_b) {
  ConstraintRecord& c = record(scene_data(handle_), h, "set_ref_relative_rotation");
  check_rotation(rotation_a, "set_ref_relative_rotation", "rotation_a");
  check_rotation(rotation_b, "set_ref_relative_rotation", "rotation_b");
  const Quat a = rotation_a.normalized(), b = rotation_b.normalized();
  if (c.type == ConstraintType::JointRotationTracking) {
    c.target_rotation = (a.conjugate() * b).normalized();
  } else if (c.type == ConstraintType::JointRotationRange) {
    // B's joint frame such that the joint frames coincide at these rotations
    c.J_B = (b.conjugate() * a * c.J_A).normalized();
  } else {
    unsupported(c, "set_ref_relative_rotation");
  }
}

std::vector<real> Scene::constraint_limit_min_values(ConstraintHandle h) const {
  const ConstraintRecord& c = record(scene_data(handle_), h, "get_limit_min_values");
  if (c.type == ConstraintType::JointRotationRange) return {c.lower.x(), c.lower.y(), c.lower.z()};
  if (c.type == ConstraintType::RigidPrismaticJoint || c.type == ConstraintType::ArticulatedSingleDofRange)
    return {c.min ? *c.min : -std::numeric_limits<real>::infinity()};
  unsupported(c, "get_limit_min_values");
}

std::vector<real> Scene::constraint_limit_max_values(ConstraintHandle h) const {
  const ConstraintRecord& c = record(scene_data(handle_), h, "get_limit_max_values");
  if (c.type == ConstraintType::JointRotationRange) return {c.upper.x(), c.upper.y(), c.upper.z()};
  if (c.type == ConstraintType::RigidPrismaticJoint || c.type == ConstraintType::ArticulatedSingleDofRange)
    return {c.max ? *c.max : std::numeric_limits<real>::infinity()};
  unsupported(c, "get_limit_max_values");
}

QueryHandle Scene::register_constraint_query(ConstraintHandle h, QueryType type) {
  SceneData& s = scene_data(handle_);
  ConstraintRecord& c = record(s, h, "register_query");
  if (type != QueryType::ConstraintForce)
    throw Error(std::string("register_query: ") + query_type_name(type) + " is not available for a constraint (CONSTRAINT_FORCE is)");
  if (c.type == ConstraintType::ArticulatedSingleDofRange)
    throw Error("register_query: a joint limit's force is not reported (the articulation's own limit rows carry it)");
  const QueryHandle q = next_handle();
  if (c.queries.empty()) c.query_since = s.step_count;
  c.queries.insert(q);
  return q;
}

void Scene::cancel_constraint_query(ConstraintHandle h, QueryHandle query) {
  SceneData& s = scene_data(handle_);
  auto it = s.constraints.find(h);
  if (it != s.constraints.end()) it->second.queries.erase(query);
}

bool Scene::is_constraint_query_supported(ConstraintHandle h, QueryType type) const {
  const ConstraintRecord& c = record(scene_data(handle_), h, "is_query_supported");
  return type == QueryType::ConstraintForce && c.type != ConstraintType::ArticulatedSingleDofRange;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
