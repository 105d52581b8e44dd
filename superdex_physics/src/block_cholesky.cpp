// Block-sparse Cholesky factorization (block_cholesky.h).

#include "block_cholesky.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

using MapMat = Eigen::Map<Eigen::MatrixXd>;
using ConstMapMat = Eigen::Map<const Eigen::MatrixXd>;

// In-place lower Cholesky factor of the s x s column-major block at D (its lower triangle is
// read and written); false when the block is not positive definite.
bool dense_cholesky(double* D, int s) {
  for (int k = 0; k < s; ++k) {
    double d = D[k + k * s];
    for (int m = 0; m < k; ++m) d -= D[k + m * s] * D[k + m * s];
    if (!(d > 0)) return false;
    const double l = std::sqrt(d);
    D[k + k * s] = l;
    for (int i = k + 1; i < s; ++i) {
      double v = D[i + k * s];
      for (int m = 0; m < k; ++m) v -= D[i + m * s] * D[k + m * s];
      D[i + k * s] = v / l;
    }
  }
  return true;
}

}  // namespace

void BlockCholesky::analyze(std::span<const int> block_sizes, std::span<const std::pair<int, int>> pairs) {
  const int nb = static_cast<int>(block_sizes.size());
  // the elimination order: approximate minimum degree on the block graph
  std::vector<Eigen::Triplet<int>> entries;
  for (int i = 0; i < nb; ++i) entries.emplace_back(i, i, 1);
  for (const auto& [i, j] : pairs)
    if (i != j) entries.emplace_back(i, j, 1), entries.emplace_back(j, i, 1);
  Eigen::SparseMatrix<int> graph(nb, nb);
  graph.setFromTriplets(entries.begin(), entries.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;  // k-th eliminated <- block
  Eigen::AMDOrdering<int>()(graph, order);
  position_.assign(nb, 0);
  for (int k = 0; k < nb; ++k) position_[order.indices()[k]] = k;

  // the factor's pattern, column by column: the later neighbours of a block, and those of its
  // children in the elimination tree (fill-in)
  std::vector<int> offset(nb + 1, 0);
  for (int i = 0; i < nb; ++i) offset[i + 1] = offset[i] + block_sizes[i];
  n_ = offset[nb];
  std::vector<std::vector<int>> later(nb);  // by elimination position
  for (int i = 0; i < nb; ++i)
    for (Eigen::SparseMatrix<int>::InnerIterator it(graph, i); it; ++it) {
      const int a = position_[it.row()], b = position_[i];
      if (a > b) later[b].push_back(a);
    }
  columns_.assign(nb, Column{});
  int next_value = 0, next_start = 0;
  for (int J = 0; J < nb; ++J) {
    Column& col = columns_[J];
    const int block = order.indices()[J];
    col.size = block_sizes[block];
    col.offset = offset[block];
    col.start = next_start;
    next_start += col.size;
    std::vector<int>& rows = later[J];
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    col.rows = rows;
    if (!rows.empty()) later[rows[0]].insert(later[rows[0]].end(), rows.begin() + 1, rows.end());
    col.diagonal = next_value;
    next_value += col.size * col.size;
    col.row_values.clear();
    for (int I : col.rows) {
      col.row_values.push_back(next_value);
      next_value += block_sizes[order.indices()[I]] * col.size;
    }
  }
  for (Column& col : columns_) {
    col.updates.clear();
    for (size_t a = 0; a < col.rows.size(); ++a)
      for (size_t b = 0; b <= a; ++b) col.updates.push_back(block_value(col.rows[a], col.rows[b]));
  }
  values_.assign(next_value, 0.0);
  factor_.assign(next_value, 0.0);
  work_.assign(n_, 0.0);
}

int BlockCholesky::block_value(int I, int J) const {
  const Column& col = columns_[J];
  if (I == J) return col.diagonal;
  const auto it = std::lower_bound(col.rows.begin(), col.rows.end(), I);
  return it != col.rows.end() && *it == I ? col.row_values[it - col.rows.begin()] : -1;
}

int BlockCholesky::value_index(int i, int r, int j, int c) const {
  const int I = position_[i], J = position_[j];
  if (I < J) return -1;
  const int at = block_value(I, J);
  return at < 0 ? -1 : at + r + c * columns_[I].size;
}

bool BlockCholesky::factor() {
  factor_ = values_;
  double* L = factor_.data();
  // right-looking: factor a block column, then subtract its outer products from the later blocks
  for (const Column& col : columns_) {
    const int s = col.size;
    if (!dense_cholesky(L + col.diagonal, s)) return false;
    const ConstMapMat L_JJ(L + col.diagonal, s, s);
    for (size_t k = 0; k < col.rows.size(); ++k) {
      // L_IJ = H_IJ L_JJ^-T
      MapMat B(L + col.row_values[k], columns_[col.rows[k]].size, s);
      L_JJ.triangularView<Eigen::Lower>().transpose().solveInPlace<Eigen::OnTheRight>(B);
    }
    const int* target = col.updates.data();
    for (size_t a = 0; a < col.rows.size(); ++a) {
      const int sa = columns_[col.rows[a]].size;
      const ConstMapMat Ba(L + col.row_values[a], sa, s);
      for (size_t b = 0; b <= a; ++b, ++target) {
        const int sb = columns_[col.rows[b]].size;
        MapMat(L + *target, sa, sb).noalias() -= Ba * ConstMapMat(L + col.row_values[b], sb, s).transpose();
      }
    }
  }
  return true;
}

void BlockCholesky::solve(const double* b, double* x) const {
  // y = P b, by blocks in elimination order
  double* y = work_.data();
  for (const Column& col : columns_) std::copy(b + col.offset, b + col.offset + col.size, y + col.start);
  const double* L = factor_.data();
  // forward: L y = P b
  for (size_t J = 0; J < columns_.size(); ++J) {
    const Column& col = columns_[J];
    Eigen::Map<Eigen::VectorXd> yJ(y + col.start, col.size);
    ConstMapMat(L + col.diagonal, col.size, col.size).triangularView<Eigen::Lower>().solveInPlace(yJ);
    for (size_t k = 0; k < col.rows.size(); ++k) {
      const int I = col.rows[k];
      Eigen::Map<Eigen::VectorXd>(y + columns_[I].start, columns_[I].size).noalias() -=
          ConstMapMat(L + col.row_values[k], columns_[I].size, col.size) * yJ;
    }
  }
  // backward: L^T z = y
  for (size_t J = columns_.size(); J-- > 0;) {
    const Column& col = columns_[J];
    Eigen::Map<Eigen::VectorXd> yJ(y + col.start, col.size);
    for (size_t k = 0; k < col.rows.size(); ++k) {
      const int I = col.rows[k];
      yJ.noalias() -= ConstMapMat(L + col.row_values[k], columns_[I].size, col.size).transpose() *
                      Eigen::Map<const Eigen::VectorXd>(y + columns_[I].start, columns_[I].size);
    }
    const ConstMapMat L_JJ(L + col.diagonal, col.size, col.size);
    L_JJ.triangularView<Eigen::Lower>().transpose().solveInPlace(yJ);
  }
  // x = P^T z
  for (const Column& col : columns_) std::copy(y + col.start, y + col.start + col.size, x + col.offset);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
