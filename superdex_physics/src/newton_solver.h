#pragma once
// The implicit step as a convex problem in the next generalized velocities v:
//
//   min_v  l(v) = 1/2 v^T A v - r^T v + sum_i l_i(J_i v)
//
// A is the SPD momentum matrix (mass matrix, armature, implicit damping), r the momentum
// of the free motion; each constraint row i contributes a convex, C1, piecewise-quadratic
// potential l_i of its velocity vc_i = J_i v whose negative derivative is the impulse
// gamma_i the constraint applies (as in Castro et al. 2022, SAP). Stationarity gives the
// momentum balance A v = r + J^T gamma. Newton's method with an exact line search
// converges in a few iterations and the reported impulses are exactly those applied.

#include <vector>

#include "superdex/physics/real.h"
#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

enum class RowKind : unsigned char {
  // gamma = max(0, (vhat - vc) / R): a compliant one-sided constraint (limits, contact normals)
  Unilateral,
  // gamma = -clamp(vc / R, -bound, bound): regularised Coulomb friction with impulse bound
  BoundedFriction,
};

struct ConstraintRows {
  MatX J;                       // constraint Jacobian (m x n)
  std::vector<RowKind> kind;    // (m)
  VecX R;                       // regularisation, velocity per impulse (m)
  VecX vhat;                    // target velocity of unilateral rows (m)
  VecX bound;                   // impulse bound of friction rows (m)

  int size() const { return static_cast<int>(kind.size()); }
  void resize(int m, int n) {
    J.setZero(m, n);
    kind.assign(m, RowKind::Unilateral);
    R.setZero(m);
    vhat.setZero(m);
    bound.setZero(m);
  }
};

struct ConvexResult {
  VecX v;            // solution (n)
  VecX gamma;        // constraint impulses (m)
  int iterations = 0;
  real residual = 0; // scaled gradient norm at the solution
  bool converged = false;
};

// Solves the problem from the unconstrained optimum A^-1 r. `A_llt` is A's Cholesky factor.
ConvexResult solve_convex(const MatX& A, const Eigen::LLT<MatX>& A_llt, const VecX& r, const ConstraintRows& rows,
                          const SolverParams& params);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
