#pragma once
// Sparse symmetric positive definite factorization for the Newton systems: CHOLMOD's supernodal
// Cholesky (SuiteSparse, through Eigen's CholmodSupport), always in double precision so that the
// float build factors as accurately as the double one. The symbolic analysis of a pattern is
// kept and reused by every numeric factorization with the same structure.

#include <Eigen/Sparse>
#include <memory>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // Symbolic analysis (fill-reducing ordering) of H's structure; H square, full symmetric storage.
  void analyze(const Eigen::SparseMatrix<real>& H);
  // Numeric factorization of H with the analysed structure (a new analysis first when H's size
  // or number of entries differs from the analysed matrix's, or H is not compressed); false when
  // H is not positive definite. Values equal bit for bit to those of the
  // last successful factorization keep that factor.
  bool factorize(const Eigen::SparseMatrix<real>& H);
  // Numeric factorizations done so far (those kept are not counted).
  int factorizations() const;
  // Analysis and factorization of a matrix of any structure.
  bool compute(const Eigen::SparseMatrix<real>& H);
  // H^-1 b for one or several right-hand sides.
  VecX solve(const VecX& b) const;
  MatX solve(const MatX& b) const;
  // H^-1 b in double precision whatever `real` is, in place.
  void solve_in_place(Eigen::MatrixXd& b) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
