#pragma once
// The convex problem of an island with soft bodies (newton_solver.h), in the variables
// [articulation DOFs (n_r) | free DOFs of each soft body]. The objective adds the soft bodies'
// elastic energies (soft_body.h) to the quadratic part. The first Newton system of a solve is
// factored by block elimination: every soft block by a sparse Cholesky whose symbolic analysis
// the soft body keeps across steps, then the dense Schur complement of the articulation DOFs.
// Later systems, whose matrices differ from it near the contacts and the deforming elements, are
// solved by conjugate gradients preconditioned by that factorization, and factored in their turn
// only when a few iterations do not reach the tolerance.

#include <vector>

#include "solver/newton_solver.h"
#include "soft/soft_body.h"
#include "solver/step_settings.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// A_rigid (n_r x n_r) and r (n_r + sum of soft sizes); `soft` in variable order; v_start the
// initial iterate; the Newton loop's vectors and its result in `scratch`. Throws superdex::Error when a soft
// block cannot be factored.
ConvexResult& solve_convex_with_soft(const MatX& A_rigid, const VecX& r, const ConstraintRows& rows,
                                    const std::vector<SoftStep*>& soft, const VecX& v_start, const StepSettings& params,
                                    NewtonScratch& scratch);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
