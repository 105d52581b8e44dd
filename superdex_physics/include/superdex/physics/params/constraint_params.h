#pragma once
/// @file constraint_params.h
/// Constraints between actors, or between an actor and a target (Scene::create_*_constraint).
/// Every constraint is an implicit spring-damper on its deviation, solved in the same convex
/// problem as contacts and joints: per constrained component, force = stiffness * deviation +
/// damping * (target rate - rate), evaluated at the end of the step, each component capped at
/// `saturation` when positive. Frames: W the world, A and B the actors' frames (a rigid
/// actor's world_from_local, a link's frame). SI units.

#include <numbers>
#include <optional>

#include "superdex/physics/handles.h"
#include "superdex/physics/real.h"
#include "superdex/physics/transform.h"
#include "superdex/physics/types.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

enum class ConstraintType {
  RigidSphericalJoint,
  RigidPrismaticJoint,
  JointRotationRange,
  JointRotationTracking,
  RigidPivotPosition,
  RigidPivotToRigidTarget,
  RigidPivotRotation,
  DeformableNodePosition,
  DeformableNodeToRigid,
  DeformableNodeToDeformableNode,
  ArticulatedSingleDofTarget,
  Articulated3dRotationTarget,
  /// The position limits of a revolute or prismatic joint of an articulated actor (made with the
  /// actor; Actor.get_articulated_joint_limit_constraints): a handle on the articulation's own
  /// limit rows. Its stiffness and damping are the joint's limit stiffness and damping (0: near
  /// rigid); no force cap, no force query.
  ArticulatedSingleDofRange,
  RodElementRotationToRigid,
};
const char* constraint_type_name(ConstraintType type);

/// What every constraint has. Units per constrained component: N/m and N s/m on positions,
/// N m/rad and N m s/rad on rotations; saturation in N (or N m): negative for none, never 0.
struct ConstraintParams {
  real stiffness = 1e6;
  real damping = 0;
  real saturation = -1;
};

/// A ball joint between two rigid actors: the point local_pos_a of A (frame A, m) on the point
/// local_pos_b of B (frame B, m).
struct RigidSphericalJointConstraintParams : ConstraintParams {
  Real3 local_pos_a = Real3::Zero();
  Real3 local_pos_b = Real3::Zero();
  ActorHandle actor_a, actor_b;
};

/// A slider between two rigid actors: B keeps its rotation relative to A and moves relative to
/// A only along free_axis (world frame at creation, then fixed in A), from the offset it had at
/// creation; min and max (m) bound that motion when given.
struct RigidPrismaticJointConstraintParams : ConstraintParams {
  Real3 free_axis = Real3::Zero();
  ActorHandle actor_a, actor_b;
  std::optional<real> max;
  std::optional<real> min;
};

/// Bounds on B's rotation relative to A: the rotation vector (rad) of B's rotation in the
/// joint frame (ref_frame_rot_vec: its world rotation at creation, then fixed in A) stays
/// within angle_range_x/y/z per axis. range_around_rest: measured from the relative rotation at
/// creation (else from the joint frame itself).
struct JointRotationRangeConstraintParams : ConstraintParams {
  Real3 ref_frame_rot_vec = Real3::Zero();
  Real2 angle_range_x{-2 * std::numbers::pi_v<real>, 2 * std::numbers::pi_v<real>};
  Real2 angle_range_y{-2 * std::numbers::pi_v<real>, 2 * std::numbers::pi_v<real>};
  Real2 angle_range_z{-2 * std::numbers::pi_v<real>, 2 * std::numbers::pi_v<real>};
  ActorHandle actor_a, actor_b;
  bool range_around_rest = true;
};

/// Drives B's rotation relative to A towards a target relative rotation (at creation: the
/// relative rotation then; Constraint set_target_rotation changes it).
struct JointRotationTrackingConstraintParams : ConstraintParams {
  Real3 ref_frame_rot_vec = Real3::Zero();
  ActorHandle actor_a, actor_b;
};

/// Pulls the point local_position (frame A, m) of a rigid or link actor to target_position
/// (world, m).
struct RigidPivotPositionConstraintParams : ConstraintParams {
  Real3 target_position = Real3::Zero();
  Real3 local_position = Real3::Zero();
  ActorHandle actor;
};

/// Pulls the point local_position (frame A, m) of a rigid or link actor to where it would be
/// with the actor's frame at target_transform (world).
struct RigidPivotToRigidTargetConstraintParams : ConstraintParams {
  TransformRT target_transform;
  Real3 local_position = Real3::Zero();
  ActorHandle actor;
};

/// Turns a rigid or link actor so that its frame rotated by local_rotation (a rotation vector,
/// rad) has the world rotation target_rotation (a rotation vector, rad).
struct RigidPivotRotationConstraintParams : ConstraintParams {
  Real3 target_rotation = Real3::Zero();
  Real3 local_rotation = Real3::Zero();
  ActorHandle actor;
};

/// Pulls node node_index of a soft actor to `position` (world, m).
struct DeformableNodePositionConstraintParams : ConstraintParams {
  int node_index = -1;
  Real3 position = Real3::Zero();
  ActorHandle actor;
};

/// Ties node deformable_node_index of a soft actor to a point of a rigid or link actor: where the
/// node is at creation (fix_to_deformable_pos), else rigid_local_pos (frame of the rigid actor,
/// m). find_closest: the soft actor's surface node nearest that point instead of the index.
struct DeformableNodeToRigidConstraintParams : ConstraintParams {
  Real3 rigid_local_pos = Real3::Zero();
  int deformable_node_index = -1;
  ActorHandle rigid_actor, deformable_actor;
  bool find_closest = false;
  bool fix_to_deformable_pos = true;
};

/// Holds node node_index_a of soft actor actor_a and node node_index_b of soft actor actor_b (the
/// same actor or another) together: a spring-damper on their separation (m, world).
/// find_closest: instead of the indices, each actor's surface node nearest the midpoint of the
/// two actors' origins (a seam where two bodies meet).
struct DeformableNodeToDeformableNodeConstraintParams : ConstraintParams {
  int node_index_a = -1, node_index_b = -1;
  ActorHandle actor_a, actor_b;
  bool find_closest = false;
};

/// Holds the material frame of element element_index of a rod actor at a fixed rotation relative
/// to a rigid or link actor: the relative rotation at creation, turned by ref_frame_rot_vec (a
/// rotation vector in the element's frame, rad).
struct RodElementRotationToRigidConstraintParams : ConstraintParams {
  Real3 ref_frame_rot_vec = Real3::Zero();
  ActorHandle rigid_actor, rod_actor;
  int element_index = 0;
};

/// Pulls one DOF of a revolute or prismatic joint of an articulated actor to target_value (rad or
/// m): joint joint_index (the joint attaching link joint_index), its DOF dof_index (0).
struct ArticulatedSingleDofTargetConstraintParams : ConstraintParams {
  ActorHandle actor;
  int joint_index = 0;
  int dof_index = 0;
  real target_value = 0;
};

/// Turns the rotation of a spherical or free joint of an articulated actor (its child link's
/// frame relative to the joint frame) to `target`.
struct Articulated3dRotationTargetConstraintParams : ConstraintParams {
  ActorHandle actor;
  int joint_index = 0;
  Quat target = Quat::Identity();
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
