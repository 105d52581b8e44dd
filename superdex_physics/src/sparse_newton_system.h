#pragma once
// The Newton matrix H = A + J^T G J of a large island (newton_solver.h) on a fixed sparsity
// pattern: A's entries and, for every constraint block, the couplings among the columns its rows
// touch. The pattern and its symbolic factorization are built once per problem; each Newton
// iteration only writes values (a small dense J_b^T G_b J_b per block, scattered into known
// slots) and refactors numerically.

#include <vector>

#include "newton_solver.h"
#include <Eigen/SparseCholesky>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class SparseNewtonSystem {
 public:
  SparseNewtonSystem(const SparseMat& A, const ConstraintRows& rows);

  // Takes the values of a new problem with the same structure (A's pattern, and every block
  // touching the same columns: the same contacts as before, as in a resting pile), keeping the
  // pattern and its analysis; false, changing nothing, when the structure differs.
  bool reuse(const SparseMat& A, const ConstraintRows& rows);
  // Factors A + J^T G J for the blocks' Hessian blocks G (rows as given to the constructor or
  // reuse()); false when the matrix is not positive definite.
  bool factor(const ConstraintRows& rows, const std::vector<Eigen::Matrix<real, 3, 3>>& G);
  // H^-1 b with the last factorization.
  VecX solve(const VecX& b) const;

 private:
  // Each block's columns and its rows of J on them.
  struct BlockColumns {
    std::vector<int> cols;       // per block: the sorted columns its rows touch
    std::vector<int> col_start;  // per block: first index into cols (size blocks + 1)
    std::vector<real> J_values;  // per block: its rows of J on those columns (size x nc, row-major)
    std::vector<int> J_start;    // per block: first index into J_values
    void gather(const ConstraintRows& rows);
  };
  void load_A_values(const SparseMat& A);

  SparseMat H_;                      // full symmetric storage; values rewritten by factor()
  std::vector<int> A_outer_, A_inner_;  // A's pattern
  std::vector<int> A_slots_;         // value index in H of each of A's entries
  std::vector<real> A_values_;       // A's entries in H's value order
  BlockColumns blocks_;
  std::vector<int> slots_;           // per block: value index of (cols[i], cols[j]) in H (nc x nc)
  std::vector<int> slot_start_;      // per block: first index into slots_
  // rigid islands have a few hundred DOFs: a simplicial factorization (no BLAS, no OpenMP team)
  // in double precision
  Eigen::SparseMatrix<double> H_double_;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> cholesky_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
