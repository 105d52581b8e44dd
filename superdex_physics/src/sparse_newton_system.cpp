// Newton matrices of large islands on a fixed pattern (sparse_newton_system.h).

#include "sparse_newton_system.h"

#include <algorithm>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// Value index of entry (row, col) of a compressed column-major matrix, or -1.
int value_slot(const SparseMat& H, int row, int col) {
  const int* begin = H.innerIndexPtr() + H.outerIndexPtr()[col];
  const int* end = H.innerIndexPtr() + H.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  return it != end && *it == row ? static_cast<int>(it - H.innerIndexPtr()) : -1;
}

}  // namespace

SparseNewtonSystem::SparseNewtonSystem(const SparseMat& A, const ConstraintRows& rows) {
  const int n = static_cast<int>(A.rows());
  const size_t num_blocks = rows.blocks.size();
  // each block's columns and its dense rows of J on them
  col_start_.assign(1, 0);
  J_start_.assign(1, 0);
  for (const ConstraintBlock& b : rows.blocks) {
    const int first = static_cast<int>(cols_.size());
    for (int i = 0; i < b.size(); ++i)
      for (SparseRowMat::InnerIterator it(rows.J, b.row + i); it; ++it) cols_.push_back(static_cast<int>(it.col()));
    std::sort(cols_.begin() + first, cols_.end());
    cols_.erase(std::unique(cols_.begin() + first, cols_.end()), cols_.end());
    const int nc = static_cast<int>(cols_.size()) - first;
    const int J_first = static_cast<int>(J_blocks_.size());
    J_blocks_.resize(J_first + b.size() * nc, real(0));
    for (int i = 0; i < b.size(); ++i)
      for (SparseRowMat::InnerIterator it(rows.J, b.row + i); it; ++it) {
        const int c = static_cast<int>(std::lower_bound(cols_.begin() + first, cols_.end(), static_cast<int>(it.col())) -
                                       (cols_.begin() + first));
        J_blocks_[J_first + i * nc + c] = it.value();
      }
    col_start_.push_back(static_cast<int>(cols_.size()));
    J_start_.push_back(static_cast<int>(J_blocks_.size()));
  }
  // the pattern: A's entries, the diagonal, and every block's column pairs
  std::vector<Eigen::Triplet<real>> entries;
  for (int c = 0; c < n; ++c) {
    entries.emplace_back(c, c, real(0));
    for (SparseMat::InnerIterator it(A, c); it; ++it) entries.emplace_back(static_cast<int>(it.row()), c, real(0));
  }
  for (size_t k = 0; k < num_blocks; ++k)
    for (int i = col_start_[k]; i < col_start_[k + 1]; ++i)
      for (int j = col_start_[k]; j < col_start_[k + 1]; ++j) entries.emplace_back(cols_[i], cols_[j], real(0));
  H_.resize(n, n);
  H_.setFromTriplets(entries.begin(), entries.end());
  H_.makeCompressed();
  A_values_.assign(H_.nonZeros(), real(0));
  for (int c = 0; c < n; ++c)
    for (SparseMat::InnerIterator it(A, c); it; ++it) A_values_[value_slot(H_, static_cast<int>(it.row()), c)] += it.value();
  slot_start_.assign(1, 0);
  for (size_t k = 0; k < num_blocks; ++k) {
    for (int i = col_start_[k]; i < col_start_[k + 1]; ++i)
      for (int j = col_start_[k]; j < col_start_[k + 1]; ++j) slots_.push_back(value_slot(H_, cols_[i], cols_[j]));
    slot_start_.push_back(static_cast<int>(slots_.size()));
  }
  cholesky_.analyze(H_);
}

bool SparseNewtonSystem::factor(const ConstraintRows& rows, const std::vector<Eigen::Matrix<real, 3, 3>>& G) {
  real* values = H_.valuePtr();
  std::copy(A_values_.begin(), A_values_.end(), values);
  using MapRowMat = Eigen::Map<const Eigen::Matrix<real, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;
  MatX Hb;  // reallocated only when a block's column count changes
  for (size_t k = 0; k < rows.blocks.size(); ++k) {
    const int s = rows.blocks[k].size();
    const auto Gk = G[k].topLeftCorner(s, s);
    if (Gk.isZero(0)) continue;  // an inactive block adds nothing
    const int nc = col_start_[k + 1] - col_start_[k];
    const MapRowMat Jb(J_blocks_.data() + J_start_[k], s, nc);
    // J_b^T G_b J_b, scattered into the block's slots
    Hb.resize(nc, nc);
    Hb.noalias() = Jb.transpose() * (Gk * Jb);
    const int* slot = slots_.data() + slot_start_[k];
    for (int j = 0; j < nc; ++j)
      for (int i = 0; i < nc; ++i) values[slot[i * nc + j]] += Hb(i, j);
  }
  return cholesky_.factorize(H_);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
