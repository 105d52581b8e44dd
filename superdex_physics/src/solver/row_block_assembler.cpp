// Block-by-block assembly of row-major sparse matrices (row_block_assembler.h).

#include "solver/row_block_assembler.h"

#include <algorithm>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void RowBlockAssembler::clear() {
  open_.clear();
  outer_.assign(1, 0);
  inner_.clear();
  values_.clear();
}

void RowBlockAssembler::begin_block(int s) {
  s_ = s;
  open_.clear();
}

void RowBlockAssembler::add(int col, const real* v) {
  Column c{col, 0u, {0, 0, 0}};
  for (int i = 0; i < s_; ++i) {
    c.v[i] = v[i];
    if (v[i] != 0) c.present |= 1u << i;
  }
  // a column with no value adds nothing
  if (c.present != 0) open_.push_back(c);
}

void RowBlockAssembler::end_block() {
  const int s = s_;
  // columns in order, stably (insertion: a block's columns come in a few sorted runs, one per
  // body it touches), then a repeated column's values summed into its first
  for (size_t k = 1; k < open_.size(); ++k) {
    const Column c = open_[k];
    size_t at = k;
    while (at > 0 && open_[at - 1].col > c.col) open_[at] = open_[at - 1], --at;
    open_[at] = c;
  }
  size_t kept = 0;
  for (size_t k = 0; k < open_.size(); ++k) {
    if (kept > 0 && open_[kept - 1].col == open_[k].col) {
      Column& into = open_[kept - 1];
      for (int i = 0; i < s; ++i) into.v[i] += open_[k].v[i];
      into.present |= open_[k].present;
    } else {
      open_[kept++] = open_[k];
    }
  }
  for (int i = 0; i < s; ++i) {
    for (size_t k = 0; k < kept; ++k) {
      if (!(open_[k].present >> i & 1u)) continue;
      inner_.push_back(open_[k].col);
      values_.push_back(open_[k].v[i]);
    }
    outer_.push_back(static_cast<int>(inner_.size()));
  }
  open_.clear();
}

void RowBlockAssembler::finish(int n, SparseRowMat& J) const {
  const int m = rows();
  if (J.rows() != m || J.cols() != n || !J.isCompressed()) J.resize(m, n);
  J.data().clear();
  J.resizeNonZeros(static_cast<Eigen::Index>(inner_.size()));
  std::copy(outer_.begin(), outer_.end(), J.outerIndexPtr());
  std::copy(inner_.begin(), inner_.end(), J.innerIndexPtr());
  std::copy(values_.begin(), values_.end(), J.valuePtr());
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
