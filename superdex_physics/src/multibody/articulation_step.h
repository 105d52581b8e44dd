#pragma once
// Per-articulation terms of the implicit step: the momentum matrix A = M + dt D (implicit
// viscous joint friction), the free-motion momentum r = M v + dt (tau - c), A's Cholesky
// factor, and the joint-limit and joint-friction rows.

#include "solver/newton_solver.h"
#include "linalg/tree_ldlt.h"
#include "scene/scene_data.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// A one-row block of an articulation: on a single DOF with Jacobian entry `sign`, or with a full
// Jacobian row `J` (nv) when J is not empty (link drives).
struct JointRow {
  int dof = 0;
  real sign = 1;
  ConstraintBlock block;
  bool drive = false;  // a joint drive: its impulse is reported as the drive's effort
  // a joint-limit row that the free motion keeps well inside its limit
  // (StepSettings::defer_inactive_joint_limits): left out of the solve, and inactive as long as
  // sign * v[dof] >= block.vhat. Its block.R lacks the near-rigid floor, which needs (A^-1)_kk:
  // deferred_compliance() completes it.
  bool deferred = false;
  VecX J;              // full row, for rows that involve several DOFs
};

// diag(X^T A^-1 X) for the SPD matrix A factored in A_factor: the squared column norms of H X
// (H^T H = A^-1), one triangular solve. X (n x k: a matrix, or a block of one) is overwritten by
// H X; the result reads it.
template <class Derived>
auto compliance_diagonal(const TreeLDLT& A_factor, Eigen::MatrixBase<Derived>& X) {
  A_factor.half_solve_in_place(X.derived());
  return X.colwise().squaredNorm().transpose();
}

struct ArticulationTerms {
  MatX A;                        // nv x nv
  VecX r;                        // nv
  TreeLDLT A_factor;             // A's factor, along the articulation's tree
  std::vector<JointRow> joint_rows;
  VecX v_free;                   // nv: the free (unconstrained) motion A^-1 r
  // working storage: bias forces
  VecX c;

  // (A^-1)_kk, the effective compliance of DOF k (1 / (kg m^2) or 1 / kg). The whole diagonal is
  // computed at the first call after articulation_terms(), from A_factor, and read by later calls.
  real inverse_diagonal(int k) const;

 private:
  friend void articulation_terms(const Articulation&, const Vec3&, real, const StepSettings&, ArticulationTerms&);
  // cache of inverse_diagonal(): the diagonal of A^-1
  mutable VecX A_inv_diagonal_;
  mutable bool have_inverse_diagonal_ = false;
};

ArticulationTerms articulation_terms(const Articulation& a, const Vec3& g_W, real dt, const StepSettings& params);
// The same into `t`, whose matrices and row list keep their storage (no allocation when the
// articulation's terms had the same sizes last time).
void articulation_terms(const Articulation& a, const Vec3& g_W, real dt, const StepSettings& params, ArticulationTerms& t);

// The compliance of a deferred joint-limit row of t once it joins a solve: its R floored at the
// near-rigid compliance of its DOF.
real deferred_compliance(const ArticulationTerms& t, const JointRow& row, const StepSettings& params);

// Near-rigid compliance factor beta^2 / (4 pi^2).
real near_rigid_factor(const StepSettings& params);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
