#pragma once
// Eigen's LLT whose factorization of small matrices (the momentum matrices of articulations and
// the Newton matrices of small islands), and its solves with one vector, run in plain loops,
// unrolled at the commonest sizes (1, 2, 3 and 6: joints, a free body). Eigen's own runs a
// matrix-vector product per column, whose set-up costs more than its arithmetic below some 16
// variables. The factor, its storage and every other method are Eigen's, so it goes wherever an
// LLT<MatX> is read.

#include <Eigen/Cholesky>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class SmallLLT : public Eigen::LLT<MatX> {
 public:
  // matrices up to this size are factored by the loops below
  static constexpr Eigen::Index kSmall = 16;

  SmallLLT() = default;
  explicit SmallLLT(const MatX& A) { compute(A); }
  // Factors A (its lower triangle is read), as Eigen::LLT::compute does: info() tells whether
  // it is positive definite.
  SmallLLT& compute(const MatX& A);
  // x <- A^-1 x: up to kSmall rows by forward and back substitution in plain loops (Eigen's
  // triangular solves set up a blocked kernel), above by Eigen's solveInPlace.
  void solve_in_place(VecX& x) const;
  // X <- L^-1 X (X: n x k, a matrix or a block of one): forward substitution column by column
  // in plain loops up to 32 rows, Eigen's blocked solve above.
  void solve_lower_in_place(Eigen::Ref<MatX> X) const;

 private:
  // up to kSmall rows: the reciprocals of the factor's diagonal (the solves multiply by them)
  VecX inverse_diagonal_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
