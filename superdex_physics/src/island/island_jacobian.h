#pragma once
// The constraint Jacobian J of one island solve, written block by block (a joint row, a contact's
// three rows) in the form its path solves with: by bodies on the sparse path (BodyJacobian), a
// dense matrix on the dense path (the dense algebra's own), and with full soft bodies compressed
// rows (ConstraintRows::J) assembled block by block (RowBlockAssembler).

#include "island/island_stages.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class IslandJacobian {
 public:
  enum class Form { Bodies, Dense, Rows };

  // An empty J for the layout's rows and variables, in the workspace's storage; clears the
  // constraint blocks (island_jacobian.cpp).
  IslandJacobian(const IslandInputs& in, const IslandLayout& layout, bool sparse, IslandWorkspace& w);

  Form form() const { return form_; }
  // The open block's first row; between blocks, the next block's.
  int row = 0;

  // Opens a block of `size` rows at `row`.
  void begin_block(int size) {
    block_rows_ = size;
    if (form_ == Form::Bodies) bodies_.begin_block(size);
    if (form_ == Form::Rows) rows_.begin_block(size);
  }
  // Closes the open block (its constraint block and the next `row` are the caller's).
  void end_block() {
    if (form_ == Form::Bodies) bodies_.end_block();
    if (form_ == Form::Rows) rows_.end_block();
  }
  // Adds the open block's values v[0..block rows) in column `col` (dense and compressed forms).
  void add_column(int col, const real* v) {
    if (form_ == Form::Dense) {
      for (int i = 0; i < block_rows_; ++i) dense_(row + i, col) += v[i];
    } else {
      rows_.add(col, v);
    }
  }
  // The open block's values on the island's j-th body (by bodies), column-major.
  real* piece(int j) { return bodies_.piece(j); }
  // J as ConstraintRows::J, with full soft bodies (same-row entries of a contact with both bodies
  // on one articulation have added up).
  void finish(int n, SparseRowMat& J) const {
    if (form_ == Form::Rows) rows_.finish(n, J);
  }

 private:
  Form form_;
  BodyJacobian& bodies_;
  RowBlockAssembler& rows_;
  MatXR& dense_;
  int block_rows_ = 0;  // the open block's rows
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
