#pragma once
// A constraint as the scene keeps it (SceneData::constraints): its type, spring-damper
// parameters, actors, geometry fixed at creation, targets, and the last step's force.

#include <optional>
#include <set>
#include <vector>

#include "superdex/physics/params/constraint_params.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

struct ConstraintRecord {
  ConstraintHandle handle;
  ConstraintType type = ConstraintType::RigidPivotPosition;
  real stiffness = 0, damping = 0, saturation = -1;
  ActorHandle actor_a, actor_b;  // actor_b invalid for the one-actor kinds
  int node_a = -1, node_b = -1;  // the constrained node of a soft actor A or B
  int element = -1;              // the constrained element of a rod actor B
  // the constrained points (m): on A in frame A, on B in frame B
  Vec3 p_A = Vec3::Zero(), p_B = Vec3::Zero();
  // prismatic: the free axis in frame A (unit), B's origin relative to A's at creation (frame A),
  // and the optional bounds (m) of the motion along the axis
  Vec3 axis_A = Vec3::UnitX(), offset_A = Vec3::Zero();
  std::optional<real> min, max;
  // joint rotations: the joint frame in A (J_A) and in B (J_B); the relative rotation of the
  // joint frames is J_A^T R_A^T R_B J_B
  Quat J_A = Quat::Identity(), J_B = Quat::Identity();
  Vec3 lower = Vec3::Zero(), upper = Vec3::Zero();  // rotation range (rad) per joint axis
  // articulated joint targets: the joint (index of the link it attaches) and the first of its
  // DOFs constrained (the articulation's DOF index: the one DOF, or the first of the rotation)
  int joint = -1, dof = -1;
  // the pose controller (pose_controller.h) owning the constraint: its articulated actor
  ActorHandle owner;
  // pivot rotation: the rotated frame of A that the target turns (frame A)
  Quat local_rotation = Quat::Identity();
  // targets now and at the last step's end (their difference over the step is the target's
  // motion, which the damping follows): a position (world), a rotation (world for the pivot
  // rotation, of B relative to A for the tracking, the joint's for a 3-D joint target), a
  // transform (world), a joint value (rad or m)
  Vec3 target_position = Vec3::Zero(), old_target_position = Vec3::Zero();
  Quat target_rotation = Quat::Identity(), old_target_rotation = Quat::Identity();
  Transform target_transform, old_target_transform;
  real target_value = 0, old_target_value = 0;
  // the last step's generalized forces on each actor's DOFs (dof_indices), world frame, torques
  // about the centre of mass; zero before the first step
  std::vector<real> force;
  std::set<QueryHandle> queries;       // registered CONSTRAINT_FORCE queries
  long long query_since = 0;           // the step count when the first of them was registered
  long long force_step = -1;           // the step count when `force` was written
};

// The DOF indices of actor `index` (0: A, 1: B) a constraint acts on: 0-2 the translation and
// 3-5 the rotation of a rigid body; 3 n + 0-2 node n's position on a soft body; an articulated
// actor's joint DOFs for the joint targets.
std::vector<int> constraint_dof_indices(const ConstraintRecord& c, int index);

// The target's motion over the step is done: the old targets become the current ones.
void settle_constraint_targets(ConstraintRecord& c);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
