#pragma once
// A row-major compressed sparse matrix (a constraint Jacobian J) built block of rows by block of
// rows, in row order, with no triplet list and no global sort: each block (1 to 3 rows: a joint
// row, a contact's normal and tangent rows) takes its entries column by column, one value per
// row of the block, in any column order.

#include <vector>

#include "solver/newton_solver.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class RowBlockAssembler {
 public:
  // Starts a new matrix (keeping the storage).
  void clear();
  // Opens the next block, of `s` rows (1 to 3).
  void begin_block(int s);
  // Adds to the open block the values v[0..s) of column `col` in its s rows. A value that is
  // exactly zero is left out of J's pattern. A column given twice in a block adds up, in the
  // order given.
  void add(int col, const real* v);
  // Closes the open block as the next s rows, its columns sorted within each row.
  void end_block();
  // The rows closed so far.
  int rows() const { return static_cast<int>(outer_.size()) - 1; }
  // J (rows() x n) in J's own storage (compressed).
  void finish(int n, SparseRowMat& J) const;

 private:
  struct Column {
    int col;
    unsigned present;  // bit i: row i of the block stores this entry
    real v[3];
  };
  int s_ = 0;  // the open block's rows
  std::vector<Column> open_;
  std::vector<int> outer_{0};
  std::vector<int> inner_;
  std::vector<real> values_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
