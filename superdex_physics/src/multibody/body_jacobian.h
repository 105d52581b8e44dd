#pragma once
// The constraint Jacobian J of a large rigid island by bodies. The island's variables are its
// bodies' DOFs, body after body; each constraint block (a joint row, a contact's normal and
// tangent rows) moves at most a few bodies, and its rows on one body's DOFs are stored as one
// piece, so that J's structure is the list of (block, body) pairs: the same from step to step
// while the same bodies touch, whatever the values. A piece keeps only its body's DOFs that the
// block moves (a contact on an articulation's link moves the DOFs of the joints between the link
// and the root, a joint row one DOF): its non-zero columns, listed. Products with J and J^T and
// the Newton matrix's J_b^T G_b J_b run on those columns (sparse_newton_system.h).

#include <span>
#include <vector>

#include "solver/newton_solver.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class BodyJacobian {
 public:
  // One block's rows on one body's DOFs.
  struct Piece {
    int body = 0;   // the body, by island order
    int value = 0;  // its values: s x num_cols, column-major, from this index in values()
    int col_start = 0;  // its columns: the body's DOFs columns(piece)[0..num_cols), ascending
    int num_cols = 0;
  };

  // Starts a new J (no blocks) over bodies of the given DOF counts (each > 0), keeping the storage.
  void reset(std::span<const int> body_dofs);
  // Opens the next block, of `s` rows (1 to 3), right below the last one.
  void begin_block(int s);
  // The open block's piece on `body` (s x its DOFs, column-major), zero when first asked for;
  // the same piece when asked for again within the block (rows that add up).
  real* piece(int body);
  // Closes the open block, keeping only the non-zero columns of its pieces.
  void end_block();

  int rows() const { return rows_; }
  int cols() const { return body_start_.empty() ? 0 : body_start_.back(); }
  int num_bodies() const { return static_cast<int>(body_start_.size()) - 1; }
  int body_dofs(int body) const { return body_start_[body + 1] - body_start_[body]; }
  // the body's first variable
  int body_start(int body) const { return body_start_[body]; }
  int num_blocks() const { return static_cast<int>(block_row_.size()); }
  int block_row(int k) const { return block_row_[k]; }
  int block_size(int k) const { return (k + 1 < num_blocks() ? block_row_[k + 1] : rows_) - block_row_[k]; }
  std::span<const Piece> pieces(int k) const {
    return {pieces_.data() + piece_start_[k], static_cast<size_t>(piece_start_[k + 1] - piece_start_[k])};
  }
  const real* values() const { return values_.data(); }
  // the body DOFs of a piece's columns (num_cols of them)
  const int* columns(const Piece& p) const { return columns_.data() + p.col_start; }

  // out = J x (x: cols(), out: rows()).
  void multiply(const VecX& x, VecX& out) const;
  // out = J^T y (y: rows(), out: cols()).
  void multiply_transposed(const VecX& y, VecX& out) const;

 private:
  std::vector<int> body_start_;   // per body: its first variable (size bodies + 1)
  std::vector<int> block_row_;    // per block: its first row
  std::vector<int> piece_start_{0};  // per block: its first piece (size blocks + 1)
  std::vector<Piece> pieces_;
  std::vector<real> values_;
  std::vector<int> columns_;
  int rows_ = 0;
  int open_ = 0;  // rows of the open block
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
