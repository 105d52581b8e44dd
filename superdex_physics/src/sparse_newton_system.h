#pragma once
// The Newton matrix H = A + J^T G J of a large island (newton_solver.h) on a fixed sparsity
// pattern: A's diagonal blocks (one per body) and, for every constraint block, the couplings
// among the bodies its rows touch. The pattern and its block Cholesky analysis are built once
// per problem; each Newton iteration only writes values (a small dense J_b^T G_b J_b per block,
// scattered into known slots) and refactors numerically (block_cholesky.h).

#include <vector>

#include "block_cholesky.h"
#include "newton_solver.h"

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
  // reuse(), with the same J until the next reuse(): only G may change); false when the matrix
  // is not positive definite.
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
    // what they were gathered from: J's pattern, each block's first row and size, and the
    // index into J_values of each of J's entries (-1: in no block)
    std::vector<int> J_outer, J_inner, block_rows, value_of;
    void gather(const ConstraintRows& rows);
    // Takes the values of `rows` when its J pattern and blocks are those gathered; false,
    // changing nothing, otherwise.
    bool refill(const ConstraintRows& rows);
  };
  void load_A_values(const SparseMat& A);

  std::vector<int> A_outer_, A_inner_;  // A's pattern
  std::vector<int> A_slots_;         // value index in H of each of A's entries
  std::vector<double> A_values_;     // A's entries in H's value order
  BlockColumns blocks_;
  // per constraint block: value index in H of (cols[i], cols[j]) (nc x nc), -1 for the entries
  // whose transpose is the one stored
  std::vector<int> slots_;
  std::vector<int> slot_start_;      // per block: first index into slots_
  BlockCholesky H_;                  // H's values, and its factor
  // the Hessian blocks H's values were last written with; none when loaded_ is false (a new
  // problem: H is written from A)
  std::vector<Eigen::Matrix3d> G_loaded_;
  bool loaded_ = false;
  Eigen::Matrix<double, 3, Eigen::Dynamic> GJ_;  // factor()'s dG_b J_b of a 3-row block
  mutable Eigen::VectorXd x_;        // solve()'s right-hand side and solution
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
