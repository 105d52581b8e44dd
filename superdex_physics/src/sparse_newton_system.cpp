// Newton matrices of large islands on a fixed pattern (sparse_newton_system.h).

#include "sparse_newton_system.h"

#include <algorithm>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void SparseNewtonSystem::BlockColumns::gather(const ConstraintRows& rows) {
  cols.clear();
  col_start.assign(1, 0);
  J_values.clear();
  J_start.assign(1, 0);
  block_rows.clear();
  value_of.assign(rows.J.nonZeros(), -1);
  for (const ConstraintBlock& b : rows.blocks) {
    block_rows.push_back(b.row);
    block_rows.push_back(b.size());
    const int first = static_cast<int>(cols.size());
    for (int i = 0; i < b.size(); ++i)
      for (SparseRowMat::InnerIterator it(rows.J, b.row + i); it; ++it) cols.push_back(static_cast<int>(it.col()));
    std::sort(cols.begin() + first, cols.end());
    cols.erase(std::unique(cols.begin() + first, cols.end()), cols.end());
    const int nc = static_cast<int>(cols.size()) - first;
    const int J_first = static_cast<int>(J_values.size());
    J_values.resize(J_first + b.size() * nc, real(0));
    for (int i = 0; i < b.size(); ++i) {
      const int row_first = rows.J.outerIndexPtr()[b.row + i];
      for (SparseRowMat::InnerIterator it(rows.J, b.row + i); it; ++it) {
        const int c = static_cast<int>(std::lower_bound(cols.begin() + first, cols.end(), static_cast<int>(it.col())) -
                                       (cols.begin() + first));
        J_values[J_first + i * nc + c] = it.value();
        value_of[row_first + (&it.value() - &rows.J.valuePtr()[row_first])] = J_first + i * nc + c;
      }
    }
    col_start.push_back(static_cast<int>(cols.size()));
    J_start.push_back(static_cast<int>(J_values.size()));
  }
  J_outer.assign(rows.J.outerIndexPtr(), rows.J.outerIndexPtr() + rows.J.rows() + 1);
  J_inner.assign(rows.J.innerIndexPtr(), rows.J.innerIndexPtr() + rows.J.nonZeros());
}

bool SparseNewtonSystem::BlockColumns::refill(const ConstraintRows& rows) {
  const SparseRowMat& J = rows.J;
  if (!J.isCompressed() || static_cast<size_t>(J.rows()) + 1 != J_outer.size() ||
      static_cast<size_t>(J.nonZeros()) != J_inner.size() || 2 * rows.blocks.size() != block_rows.size() ||
      !std::equal(J_outer.begin(), J_outer.end(), J.outerIndexPtr()) ||
      !std::equal(J_inner.begin(), J_inner.end(), J.innerIndexPtr()))
    return false;
  for (size_t k = 0; k < rows.blocks.size(); ++k)
    if (block_rows[2 * k] != rows.blocks[k].row || block_rows[2 * k + 1] != rows.blocks[k].size()) return false;
  // every entry lands where it did (the entries J lacks stay zero)
  for (size_t e = 0; e < value_of.size(); ++e)
    if (value_of[e] >= 0) J_values[value_of[e]] = J.valuePtr()[e];
  return true;
}

SparseNewtonSystem::SparseNewtonSystem(const SparseMat& A, const ConstraintRows& rows) {
  const int n = static_cast<int>(A.rows());
  blocks_.gather(rows);
  const std::vector<int>& cols = blocks_.cols;
  const std::vector<int>& col_start = blocks_.col_start;
  const size_t num_blocks = rows.blocks.size();
  A_outer_.assign(A.outerIndexPtr(), A.outerIndexPtr() + n + 1);
  A_inner_.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  // the bodies: A is block diagonal, each body's block dense, so a body starts at the column whose
  // first entry is on the diagonal (an empty column is a block of its own)
  std::vector<int> body_of(n), local_of(n), body_sizes;
  for (int c = 0; c < n; ++c) {
    const bool starts = A.outerIndexPtr()[c] == A.outerIndexPtr()[c + 1] || A.innerIndexPtr()[A.outerIndexPtr()[c]] >= c;
    if (starts || body_sizes.empty()) body_sizes.push_back(0);
    body_of[c] = static_cast<int>(body_sizes.size()) - 1;
    local_of[c] = body_sizes.back()++;
  }
  // the body pairs that constraint blocks couple
  std::vector<std::pair<int, int>> pairs;
  for (size_t k = 0; k < num_blocks; ++k)
    for (int i = col_start[k]; i < col_start[k + 1]; ++i)
      for (int j = col_start[k]; j < i; ++j)
        if (body_of[cols[i]] != body_of[cols[j]]) pairs.emplace_back(body_of[cols[i]], body_of[cols[j]]);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  H_.analyze(body_sizes, pairs);
  auto slot = [&](int row, int col) { return H_.value_index(body_of[row], local_of[row], body_of[col], local_of[col]); };
  A_slots_.clear();
  for (int c = 0; c < n; ++c)
    for (SparseMat::InnerIterator it(A, c); it; ++it) A_slots_.push_back(slot(static_cast<int>(it.row()), c));
  load_A_values(A);
  slots_.clear();
  slot_start_.assign(1, 0);
  for (size_t k = 0; k < num_blocks; ++k) {
    for (int i = col_start[k]; i < col_start[k + 1]; ++i)
      for (int j = col_start[k]; j < col_start[k + 1]; ++j) slots_.push_back(slot(cols[i], cols[j]));
    slot_start_.push_back(static_cast<int>(slots_.size()));
  }
}

void SparseNewtonSystem::load_A_values(const SparseMat& A) {
  A_values_.assign(H_.values().size(), 0.0);
  for (Eigen::Index k = 0; k < A.nonZeros(); ++k) A_values_[A_slots_[k]] += A.valuePtr()[k];
}

bool SparseNewtonSystem::reuse(const SparseMat& A, const ConstraintRows& rows) {
  if (A.rows() != H_.dimension() || !A.isCompressed() ||
      !std::equal(A_outer_.begin(), A_outer_.end(), A.outerIndexPtr()) ||
      static_cast<size_t>(A.nonZeros()) != A_inner_.size() ||
      !std::equal(A_inner_.begin(), A_inner_.end(), A.innerIndexPtr()))
    return false;
  // the same J pattern and blocks take J's values in place; otherwise every block must touch
  // the same columns as before
  if (!blocks_.refill(rows)) {
    BlockColumns next;
    next.gather(rows);
    if (next.cols != blocks_.cols || next.col_start != blocks_.col_start) return false;
    blocks_ = std::move(next);
  }
  load_A_values(A);
  loaded_ = false;
  return true;
}

VecX SparseNewtonSystem::solve(const VecX& b) const {
  x_ = b.cast<double>();
  H_.solve(x_.data(), x_.data());
  return x_.cast<real>();
}

bool SparseNewtonSystem::factor(const ConstraintRows& rows, const std::vector<Eigen::Matrix<real, 3, 3>>& G) {
  std::vector<double>& values = H_.values();
  // the first factorization of a problem writes A + J^T G J; the next ones of the same problem
  // (Newton iterations, friction passes) add J_b^T (G_b - G_b') J_b only for the blocks whose
  // Hessian block changed since (most do not: sticking and separated contacts)
  if (!loaded_ || G_loaded_.size() != G.size()) {
    std::copy(A_values_.begin(), A_values_.end(), values.begin());
    G_loaded_.assign(G.size(), Eigen::Matrix3d::Zero());
    loaded_ = true;
  }
  // J_b^T dG J_b of each block, entry by entry into the slots stored (a block has 1 or 3 rows)
  Eigen::Matrix<double, 3, Eigen::Dynamic>& GJ = GJ_;
  for (size_t k = 0; k < rows.blocks.size(); ++k) {
    const int s = rows.blocks[k].size();
    const Eigen::Matrix3d G_k = G[k].template cast<double>();
    // the difference of two floats is exact in double: the sum stays that of the blocks' own
    const Eigen::Matrix3d dG = G_k - G_loaded_[k];
    if (s == 3 ? dG.isZero(0) : dG(0, 0) == 0) continue;
    G_loaded_[k] = G_k;
    const int nc = blocks_.col_start[k + 1] - blocks_.col_start[k];
    const real* Jb = blocks_.J_values.data() + blocks_.J_start[k];  // s x nc, row-major
    const int* slot = slots_.data() + slot_start_[k];
    if (s == 1) {
      for (int i = 0; i < nc; ++i)
        for (int j = 0; j < nc; ++j)
          if (slot[i * nc + j] >= 0) values[slot[i * nc + j]] += dG(0, 0) * Jb[i] * Jb[j];
      continue;
    }
    // GJ = dG J_b (3 x nc), then entry (i, j) = J_b(:, i) . GJ(:, j)
    GJ.resize(3, nc);
    for (int j = 0; j < nc; ++j) GJ.col(j) = dG * Eigen::Vector3d(Jb[j], Jb[nc + j], Jb[2 * nc + j]);
    for (int i = 0; i < nc; ++i) {
      const Eigen::Vector3d Ji(Jb[i], Jb[nc + i], Jb[2 * nc + i]);
      for (int j = 0; j < nc; ++j)
        if (slot[i * nc + j] >= 0) values[slot[i * nc + j]] += Ji.dot(GJ.col(j));
    }
  }
  return H_.factor();
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
