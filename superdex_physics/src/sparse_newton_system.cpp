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

void SparseNewtonSystem::BlockColumns::gather(const ConstraintRows& rows) {
  cols.clear();
  col_start.assign(1, 0);
  J_values.clear();
  J_start.assign(1, 0);
  for (const ConstraintBlock& b : rows.blocks) {
    const int first = static_cast<int>(cols.size());
    for (int i = 0; i < b.size(); ++i)
      for (SparseRowMat::InnerIterator it(rows.J, b.row + i); it; ++it) cols.push_back(static_cast<int>(it.col()));
    std::sort(cols.begin() + first, cols.end());
    cols.erase(std::unique(cols.begin() + first, cols.end()), cols.end());
    const int nc = static_cast<int>(cols.size()) - first;
    const int J_first = static_cast<int>(J_values.size());
    J_values.resize(J_first + b.size() * nc, real(0));
    for (int i = 0; i < b.size(); ++i)
      for (SparseRowMat::InnerIterator it(rows.J, b.row + i); it; ++it) {
        const int c = static_cast<int>(std::lower_bound(cols.begin() + first, cols.end(), static_cast<int>(it.col())) -
                                       (cols.begin() + first));
        J_values[J_first + i * nc + c] = it.value();
      }
    col_start.push_back(static_cast<int>(cols.size()));
    J_start.push_back(static_cast<int>(J_values.size()));
  }
}

SparseNewtonSystem::SparseNewtonSystem(const SparseMat& A, const ConstraintRows& rows) {
  const int n = static_cast<int>(A.rows());
  blocks_.gather(rows);
  const std::vector<int>& cols = blocks_.cols;
  const std::vector<int>& col_start = blocks_.col_start;
  const size_t num_blocks = rows.blocks.size();
  A_outer_.assign(A.outerIndexPtr(), A.outerIndexPtr() + n + 1);
  A_inner_.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  // the pattern: A's entries, the diagonal, and every block's column pairs
  std::vector<Eigen::Triplet<real>> entries;
  for (int c = 0; c < n; ++c) {
    entries.emplace_back(c, c, real(0));
    for (SparseMat::InnerIterator it(A, c); it; ++it) entries.emplace_back(static_cast<int>(it.row()), c, real(0));
  }
  for (size_t k = 0; k < num_blocks; ++k)
    for (int i = col_start[k]; i < col_start[k + 1]; ++i)
      for (int j = col_start[k]; j < col_start[k + 1]; ++j) entries.emplace_back(cols[i], cols[j], real(0));
  H_.resize(n, n);
  H_.setFromTriplets(entries.begin(), entries.end());
  H_.makeCompressed();
  A_slots_.clear();
  for (int c = 0; c < n; ++c)
    for (SparseMat::InnerIterator it(A, c); it; ++it) A_slots_.push_back(value_slot(H_, static_cast<int>(it.row()), c));
  load_A_values(A);
  slot_start_.assign(1, 0);
  for (size_t k = 0; k < num_blocks; ++k) {
    for (int i = col_start[k]; i < col_start[k + 1]; ++i)
      for (int j = col_start[k]; j < col_start[k + 1]; ++j) slots_.push_back(value_slot(H_, cols[i], cols[j]));
    slot_start_.push_back(static_cast<int>(slots_.size()));
  }
  H_double_ = H_.cast<double>();
  cholesky_.analyzePattern(H_double_);
}

void SparseNewtonSystem::load_A_values(const SparseMat& A) {
  A_values_.assign(H_.nonZeros(), real(0));
  for (Eigen::Index k = 0; k < A.nonZeros(); ++k) A_values_[A_slots_[k]] += A.valuePtr()[k];
}

bool SparseNewtonSystem::reuse(const SparseMat& A, const ConstraintRows& rows) {
  if (A.rows() != H_.rows() || !A.isCompressed() ||
      !std::equal(A_outer_.begin(), A_outer_.end(), A.outerIndexPtr()) ||
      static_cast<size_t>(A.nonZeros()) != A_inner_.size() ||
      !std::equal(A_inner_.begin(), A_inner_.end(), A.innerIndexPtr()))
    return false;
  BlockColumns next;
  next.gather(rows);
  if (next.cols != blocks_.cols || next.col_start != blocks_.col_start) return false;
  blocks_ = std::move(next);
  load_A_values(A);
  return true;
}

VecX SparseNewtonSystem::solve(const VecX& b) const {
  const Eigen::VectorXd x = cholesky_.solve(b.cast<double>());
  return x.cast<real>();
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
    const int nc = blocks_.col_start[k + 1] - blocks_.col_start[k];
    const MapRowMat Jb(blocks_.J_values.data() + blocks_.J_start[k], s, nc);
    // J_b^T G_b J_b, scattered into the block's slots
    Hb.resize(nc, nc);
    Hb.noalias() = Jb.transpose() * (Gk * Jb);
    const int* slot = slots_.data() + slot_start_[k];
    for (int j = 0; j < nc; ++j)
      for (int i = 0; i < nc; ++i) values[slot[i * nc + j]] += Hb(i, j);
  }
  Eigen::Map<Eigen::VectorXd>(H_double_.valuePtr(), H_double_.nonZeros()) =
      Eigen::Map<const VecX>(values, H_.nonZeros()).cast<double>();
  cholesky_.factorize(H_double_);
  return cholesky_.info() == Eigen::Success;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
