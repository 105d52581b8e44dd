#pragma once
// Cholesky factorization of a symmetric positive definite matrix made of dense blocks on a sparse
// block pattern: the Newton matrices of rigid islands, with one diagonal block per body (its
// DOFs) and one off-diagonal block per pair of bodies that share a constraint. The elimination
// order (approximate minimum degree on the graph of blocks) and the factor's block pattern are
// computed once per pattern (analyze); each factorization then runs on dense blocks, in double
// precision (a near-rigid contact makes the matrix too ill-conditioned for float).

#include <span>
#include <utility>
#include <vector>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class BlockCholesky {
 public:
  // The pattern: block sizes (> 0), and the off-diagonal block pairs (i, j), i != j, in either
  // order (repeats allowed). Entries of the matrix are then addressed by value_index().
  void analyze(std::span<const int> block_sizes, std::span<const std::pair<int, int>> pairs);

  // Index into values() of the matrix entry (row r of block i, column c of block j), for i == j
  // or a pair given to analyze(); -1 for an entry of the strict upper triangle of the stored
  // form (its transpose is stored: write one of the two). Every diagonal block is stored whole.
  int value_index(int i, int r, int j, int c) const;
  // Value offset of the stored block of block i's rows and block j's columns (block_sizes[i] x
  // block_sizes[j], column-major), for i == j or a pair given to analyze() with i eliminated
  // after j; -1 otherwise (for such a pair, the block (j, i) is the one stored).
  int block_offset(int i, int j) const;
  // Whether block i is eliminated after block j (then block (i, j) is stored, not (j, i)).
  bool eliminated_after(int i, int j) const { return position_[i] > position_[j]; }
  // The matrix's entries (size set by analyze); write them, then factor().
  std::vector<double>& values() { return values_; }

  // Factors the matrix held in values(); false when it is not positive definite.
  bool factor();
  // x = H^-1 b with the last factorization (b and x of size dimension(), may alias).
  void solve(const double* b, double* x) const;
  int dimension() const { return n_; }

 private:
  struct Column {               // one block column of the factor, in elimination order
    int size = 0, offset = 0;   // the block's size, and its first variable in the original order
    int start = 0;              // its first variable in elimination order
    int diagonal = 0;           // value offset of its diagonal block (size x size)
    std::vector<int> rows;      // blocks below the diagonal, by elimination position, ascending
    std::vector<int> row_values;  // value offset of each of those blocks (rows[k]'s size x size)
    // the Schur updates of this column: for each pair (a, b) of indices into rows with a >= b, the
    // value offset of block (rows[a], rows[b]) (its diagonal block when a == b)
    std::vector<int> updates;
  };
  int block_value(int i, int j) const;  // value offset of stored block (i, j), by elimination position
  // factor() and solve() with every block K x K (K > 0), or of any sizes (K = 0)
  template <int K>
  bool factor_blocks();
  template <int K>
  void solve_blocks(const double* b, double* x) const;

  int n_ = 0;
  int uniform_size_ = 0;        // the size of every block when they are all alike, else 0
  std::vector<int> position_;   // elimination position of each block
  std::vector<Column> columns_;
  std::vector<double> values_, factor_;
  mutable std::vector<double> work_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
