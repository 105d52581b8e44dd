#pragma once
// Rigid-body dynamics of an articulation in generalized coordinates:
//   M(q) vdot + c(q, v) = tau
// with c the bias forces (Coriolis, centrifugal and gravity).

#include "multibody/articulation_model.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// Inverse dynamics by the recursive Newton-Euler algorithm: tau = M(q) a + c(q, v), for
// gravity g_W (m/s^2, world frame). With a = 0 it returns the bias forces c(q, v).
VecX inverse_dynamics(const ArticulationModel& model, const ArticulationState& state,
                      const ArticulationKinematics& kin, const VecX& a, const Vec3& g_W);

// Bias forces c(q, v) (N, N m): inverse dynamics at zero acceleration.
VecX bias_forces(const ArticulationModel& model, const ArticulationState& state, const ArticulationKinematics& kin,
                 const Vec3& g_W);
// The same into c (resized; no allocation when it has the size already).
void bias_forces(const ArticulationModel& model, const ArticulationState& state, const ArticulationKinematics& kin,
                 const Vec3& g_W, VecX& c);

// Fills model.dynamics_order and model.dynamics_inertia from the links, joints and inertias
// (build_articulation_model calls it).
void merge_welded_links(ArticulationModel& model);
// Joint-space mass matrix M(q) (nv x nv) by the composite rigid body algorithm, armature
// added on the diagonal.
MatX mass_matrix(const ArticulationModel& model, const ArticulationKinematics& kin);
// The same into M (resized; no allocation when it has the size already).
void mass_matrix(const ArticulationModel& model, const ArticulationKinematics& kin, MatX& M);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
