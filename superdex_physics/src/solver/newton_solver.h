#pragma once
// The implicit step as a convex problem in the next generalized velocities v:
//
//   min_v  l(v) = 1/2 v^T A v - r^T v + sum_b l_b(J_b v)
//
// A is the SPD momentum matrix (mass matrices, armature, implicit damping), r the momentum
// of the free motion; each constraint block b (1 row, or 3 rows for a frictional contact)
// contributes a convex, C1, piecewise-smooth potential l_b of its velocity vc_b = J_b v whose
// negative gradient is the impulse gamma_b the block applies (Castro et al. 2022, SAP).
// Stationarity is the momentum balance A v = r + J^T gamma. Newton's method with an exact
// line search converges in a few iterations, and the reported impulses are exactly those
// applied. With StepSettings::drift_correction_iterations, the first iterations also correct
// contacts' normal targets for the cone model's drift (newton_loop.h): the solution is that of
// the problem with the corrected targets.

#include <Eigen/Cholesky>
#include <Eigen/Sparse>
#include <memory>
#include <span>
#include <vector>

#include "linalg/small_llt.h"
#include "superdex/physics/real.h"
#include "superdex/physics/scene.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

enum class BlockKind : unsigned char {
  // 1 row: gamma = max(0, (vhat - vc) / R); a compliant one-sided constraint (joint limits)
  Unilateral,
  // 1 row: gamma = clamp((vhat - vc) / R, -bound, bound): regularised Coulomb joint friction
  // (vhat = 0) and saturating joint drives (an implicit spring-damper towards vhat)
  Bounded,
  // 3 rows (t1, t2, n): gamma = projection of y = -R^-1 (vc - vhat) onto the friction cone
  // |gamma_t| <= mu gamma_n in the R-norm, R = diag(Rt, Rt, Rn), vhat = (0, 0, vhat_n)
  FrictionalContact,
};

struct ConstraintBlock {
  BlockKind kind = BlockKind::Unilateral;
  int row = 0;      // first row in J
  real R = 0;       // regularisation (velocity per impulse); tangential for contacts
  real Rn = 0;      // normal regularisation of contacts
  real vhat = 0;    // target velocity: unilateral and bounded rows, contact normals
  real bound = 0;   // impulse bound of bounded rows; mu of contacts

  int size() const { return kind == BlockKind::FrictionalContact ? 3 : 1; }
};

using SparseMat = Eigen::SparseMatrix<real>;                     // column-major
using SparseRowMat = Eigen::SparseMatrix<real, Eigen::RowMajor>;

struct ConstraintRows {
  SparseRowMat J;                      // constraint Jacobian (m x n), a few non-zeros per row
  std::vector<ConstraintBlock> blocks; // in row order, covering all m rows
};

struct ConvexResult {
  VecX v;            // solution (n)
  VecX gamma;        // constraint impulses (m)
  int iterations = 0;
  real residual = 0; // scaled gradient norm at the solution
  bool converged = false;
  ConvergenceStatus status = ConvergenceStatus::None;  // how the solve ended
  int line_search_iterations = 0;  // largest number of line-search trials of one Newton iteration
};

// Working storage of the Newton loop and of its dense algebra, and its result. Kept by the caller
// across solves (one per island, SceneData::island_workspaces): a solve of the same size as the
// last one does not allocate. Every member is resized before use.
struct NewtonScratch {
  ConvexResult result;  // the last solve's
  VecX D, vc, grad, dv, dvc, jc, smooth_grad, Av_r, Adv, v_alpha;
  std::vector<Eigen::Matrix<real, 3, 3>> G;
  std::vector<int> live;  // the line search's blocks whose impulse may be non-zero on its segment
  std::vector<ConstraintBlock> blocks;  // the solve's blocks, with contacts' drift corrections (newton_loop.h)
  std::vector<int> sliding;             // the corrections' prediction (newton_loop.h): its contacts,
  VecX pred_y, pred_Jty, pred_s;        // its right-hand sides and solves,
  std::vector<VecX> pred_z;             // and their constraint velocities
  MatXR J, J_active, GJ;  // dense algebra: J made dense (when given sparse), its active rows, G J on them
  MatX H;                 // and the Hessian
  SmallLLT llt;
};

// Solves the problem from the unconstrained optimum A^-1 r with dense linear algebra (small
// problems). `A_llt` is A's Cholesky factor.
ConvexResult solve_convex(const MatX& A, const Eigen::LLT<MatX>& A_llt, const VecX& r, const ConstraintRows& rows,
                          const StepSettings& params);
// The same from v_start (a warm start: the solution of a nearby problem), in `scratch`; the
// result is scratch.result.
ConvexResult& solve_convex(const MatX& A, const VecX& r, const ConstraintRows& rows, const StepSettings& params,
                           const VecX& v_start, NewtonScratch& scratch);
// The same with J as a dense matrix (m x n, read in place).
ConvexResult& solve_convex(const MatX& A, const VecX& r, const MatXR& J, const std::vector<ConstraintBlock>& blocks,
                           const StepSettings& params, const VecX& v_start, NewtonScratch& scratch);
// Large rigid islands, by bodies: A block diagonal, one dense block per body (A_blocks, in the
// order of J's bodies), and J by bodies (body_jacobian.h); Newton steps factor A + J^T G J by
// blocks (sparse_newton_system.h). From the unconstrained optimum A^-1 r:
class BodyJacobian;
class SparseNewtonSystem;
ConvexResult solve_convex(std::span<const MatX> A_blocks, const VecX& r, const BodyJacobian& J,
                          const std::vector<ConstraintBlock>& blocks, const StepSettings& params);
// and from v_start, in `scratch`, with the Newton matrices in `system` (kept across problems:
// it keeps its analysis while the island's structure allows).
ConvexResult& solve_convex(std::span<const MatX* const> A_blocks, const VecX& r, const BodyJacobian& J,
                           const std::vector<ConstraintBlock>& blocks, const StepSettings& params, const VecX& v_start,
                           SparseNewtonSystem& system, NewtonScratch& scratch);

// J^T G J for the blocks' Hessian blocks G (3 x 3, top-left used for 1-row blocks); Jt = J^T.
SparseMat constraint_hessian(const std::vector<ConstraintBlock>& blocks, const std::vector<Eigen::Matrix<real, 3, 3>>& G,
                             const SparseRowMat& J, const SparseMat& Jt);

// Impulse and Hessian block d(-gamma)/d(vc) of one block at constraint velocity vc (the
// block's segment). Exposed for tests.
void block_response(const ConstraintBlock& b, const real* vc, real* gamma, real* G);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
