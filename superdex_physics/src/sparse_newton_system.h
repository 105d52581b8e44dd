#pragma once
// The Newton matrix H = A + J^T G J of a large island (newton_solver.h) on a fixed sparsity
// pattern: A's entries and, for every constraint block, the couplings among the columns its rows
// touch. The pattern and its symbolic factorization are built once per problem; each Newton
// iteration only writes values (a small dense J_b^T G_b J_b per block, scattered into known
// slots) and refactors numerically.

#include <vector>

#include "newton_solver.h"
#include "sparse_cholesky.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class SparseNewtonSystem {
 public:
  SparseNewtonSystem(const SparseMat& A, const ConstraintRows& rows);

  // Factors A + J^T G J for the blocks' Hessian blocks G (rows as given to the constructor);
  // false when the matrix is not positive definite.
  bool factor(const ConstraintRows& rows, const std::vector<Eigen::Matrix<real, 3, 3>>& G);
  // H^-1 b with the last factorization.
  VecX solve(const VecX& b) const { return cholesky_.solve(b); }

 private:
  SparseMat H_;                  // full symmetric storage; values rewritten by factor()
  std::vector<real> A_values_;   // A's entries in H's value order
  std::vector<int> col_start_;   // per block: first index into cols_ (size blocks + 1)
  std::vector<int> cols_;        // per block: the sorted columns its rows touch
  std::vector<real> J_blocks_;   // per block: its rows of J on those columns (size x nc, row-major)
  std::vector<int> J_start_;     // per block: first index into J_blocks_
  std::vector<int> slots_;       // per block: value index of (cols[i], cols[j]) in H (nc x nc)
  std::vector<int> slot_start_;  // per block: first index into slots_
  SparseCholesky cholesky_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
