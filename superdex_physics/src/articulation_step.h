#pragma once
// Per-articulation terms of the implicit step: the momentum matrix A = M + dt D (implicit
// viscous joint friction), the free-motion momentum r = M v + dt (tau - c), A's Cholesky
// factor, and the joint-limit and joint-friction rows.

#include "newton_solver.h"
#include "scene_data.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// A one-row block acting on a single DOF with Jacobian entry `sign`.
// A one-row block of an articulation: on a single DOF with Jacobian entry `sign`, or with a full
// Jacobian row `J` (nv) when J is not empty (link drives).
struct JointRow {
  int dof = 0;
  real sign = 1;
  ConstraintBlock block;
  bool drive = false;  // a joint drive: its impulse is reported as the drive's effort
  VecX J;              // full row, for rows that involve several DOFs
};

struct ArticulationTerms {
  MatX A;                        // nv x nv
  VecX r;                        // nv
  // factored from an empty matrix until computed: a default-constructed LLT leaves its status
  // uninitialized, and copying the terms of a body without DOFs read it (UBSan, issue 9)
  Eigen::LLT<MatX> A_llt{MatX(0, 0)};
  std::vector<JointRow> joint_rows;
  double seconds = 0;            // time spent computing these
  // working storage: bias forces, A's inverse Cholesky factor and the diagonal of A^-1
  VecX c;
  MatX L_inv;
  VecX A_inv_diagonal;
};

ArticulationTerms articulation_terms(const Articulation& a, const Vec3& g_W, real dt, const SolverParams& params);
// The same into `t`, whose matrices and row list keep their storage (no allocation when the
// articulation's terms had the same sizes last time).
void articulation_terms(const Articulation& a, const Vec3& g_W, real dt, const SolverParams& params, ArticulationTerms& t);

// Near-rigid compliance factor beta^2 / (4 pi^2).
real near_rigid_factor(const SolverParams& params);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
