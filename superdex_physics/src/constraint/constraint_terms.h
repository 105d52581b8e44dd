#pragma once
// A constraint's part of one step's convex problem: its rows on the spatial velocities of the
// links it joins, each an implicit spring-damper block (constraint_params.h), from the state at
// the step's start. Also its deviation now.

#include <array>
#include <vector>

#include "constraint/constraint_record.h"
#include "solver/newton_solver.h"
#include "superdex/physics/transform.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// One side of a constraint: a link of an articulation (rigid actors are one-link ones), a node
// of a soft body, some DOFs of an articulation's joint, or none.
struct ConstraintSide {
  int body = -1;  // articulation index; -1: none
  int link = 0;
  Transform X_WL;                // the link's frame now
  Vec3 com_W = Vec3::Zero();     // its centre of mass (m, world)
  int soft = -1, node = -1;      // soft body index and node; -1: none
  Vec3 node_W = Vec3::Zero();    // the node's position now (m, world)
  // a rod's element (soft >= 0, element >= 0): its nodes (a, b and its ghost) and the map of their
  // velocities to its frame's angular velocity, w = sum_k omega_map[k] v_k; X_WL is its frame
  // (rotation) at its midpoint, whose velocity is (v_a + v_b) / 2
  int element = -1;
  std::array<int, 3> element_nodes{};
  std::array<Mat3, 3> omega_map{};
  // joint DOFs: the first (articulation DOF index; -1: none), a 1-DOF joint's value now (rad or
  // m) and a 3-D joint's rotation now (child link in joint frame)
  int dof = -1;
  real q_dof = 0;
  Quat R_joint = Quat::Identity();
};


// One row: its rate is g_a . V_a + g_b . V_b with V = (v, w) a side's spatial velocity (its
// link origin's velocity, m/s, and angular velocity, rad/s; world; a node side: its velocity, and
// g's angular part zero; a joint side: the velocities of its DOFs dof, dof + 1, ...). `block` is Bounded
// (equalities) or Unilateral (limits), R not yet floored against ill-conditioning.
struct ConstraintRow {
  Vec6 g_a = Vec6::Zero(), g_b = Vec6::Zero();
  ConstraintBlock block;
};

struct ConstraintTerms {
  ConstraintSide a, b;
  std::vector<ConstraintRow> rows;  // none when the spring-damper has no stiffness and no damping
};

// The rows of `c` for a step of dt (s) from sides a and b (b unused by one-actor kinds).
void constraint_terms(const ConstraintRecord& c, real dt, ConstraintTerms& t);

// The deviation of `c` with its sides at the given frames: per constrained component, target
// minus current (m; rad for rotations, as a rotation vector: world for the pivot rotation, joint
// axes for the joint rotations).
std::vector<real> constraint_deviation(const ConstraintRecord& c, const ConstraintSide& a, const ConstraintSide& b);

// The two points a constraint draws between (m, world): its point on A and its target or its
// point on B (the actors' origins for the joint rotations and the slider, the origin twice for
// the pivot rotation).
void constraint_anchor_points(const ConstraintRecord& c, const ConstraintSide& a, const ConstraintSide& b, Vec3& p_a, Vec3& p_b);

// A side's generalized force on its DOFs (constraint_dof_indices) from the spatial force
// (force, torque about the link origin; world) the rows put on it.
void side_generalized_force(const ConstraintSide& side, const Vec6& F_origin, const std::vector<int>& dofs, std::vector<real>& out);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
