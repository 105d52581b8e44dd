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
  // pivot rotation: the rotated frame of A that the target turns (frame A)
  Quat local_rotation = Quat::Identity();
  // targets now and at the last step's end (their difference over the step is the target's
  // motion, which the damping follows): a position (world), a rotation (world for the pivot
  // rotation, of B relative to A for the tracking), a transform (world)
  Vec3 target_position = Vec3::Zero(), old_target_position = Vec3::Zero();
  Quat target_rotation = Quat::Identity(), old_target_rotation = Quat::Identity();
  Transform target_transform, old_target_transform;
  // the last step's generalized forces on each actor's DOFs (dof_indices), world frame, torques
  // about the centre of mass; zero before the first step
  std::vector<real> force;
  std::set<QueryHandle> queries;       // registered CONSTRAINT_FORCE queries
  long long query_since = 0;           // the step count when the first of them was registered
  long long force_step = -1;           // the step count when `force` was written
};

// The DOF indices of actor `index` (0: A, 1: B) a constraint acts on: 0-2 the translation and
// 3-5 the rotation of a rigid body; 3 n + 0-2 node n's position on a soft body.
std::vector<int> constraint_dof_indices(const ConstraintRecord& c, int index);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
