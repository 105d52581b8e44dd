// Block-sparse Cholesky factorization (block_cholesky.h).

#include "linalg/block_cholesky.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The dense kernels on column-major blocks. K > 0: every block involved is K x K, known at
// compile time (islands of free bodies: K = 6), so that the loops unroll; K = 0: sizes as given,
// with Eigen's vectorised kernels for blocks of a large articulation's size (from kEigenFrom
// DOFs: a 24-DOF hand's and a 35-DOF humanoid's blocks factor in about three quarters of the
// loops' time; smaller ones no faster than the loops).
constexpr int kEigenFrom = 20;
using MapX = Eigen::Map<Eigen::MatrixXd>;
using ConstMapX = Eigen::Map<const Eigen::MatrixXd>;

// In-place lower Cholesky factor of the s x s block at D (its lower triangle is read and
// written); false when the block is not positive definite.
template <int K>
bool dense_cholesky(double* D, int s_) {
  const int s = K > 0 ? K : s_;
  if (K == 0 && s >= kEigenFrom) {
    MapX M(D, s, s);
    return Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>>(M).info() == Eigen::Success;
  }
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

// B := B L^-T for the s x s lower factor L and B of `rows` x s.
template <int K>
void solve_right_lower_transposed(const double* L, int s_, double* B, int rows_) {
  const int s = K > 0 ? K : s_, rows = K > 0 ? K : rows_;
  if (K == 0 && s >= kEigenFrom) {
    // B L^-T = X  <=>  X L^T = B
    MapX X(B, rows, s);
    ConstMapX(L, s, s).transpose().triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(X);
    return;
  }
  for (int j = 0; j < s; ++j) {
    double* B_j = B + j * rows;
    for (int m = 0; m < j; ++m) {
      const double l = L[j + m * s];
      const double* B_m = B + m * rows;
      for (int r = 0; r < rows; ++r) B_j[r] -= B_m[r] * l;
    }
    const double inverse = 1 / L[j + j * s];
    for (int r = 0; r < rows; ++r) B_j[r] *= inverse;
  }
}

// C -= A B^T for C of sa x sb, A of sa x s and B of sb x s.
template <int K>
void subtract_product_transposed(double* C, const double* A, const double* B, int sa_, int sb_, int s_) {
  // 6 x 6 blocks: Eigen's fixed-size product kernel (about a fifth faster than the loops below,
  // BM_BlockCholeskyFactor)
  if constexpr (K == 6) {
    using M6 = Eigen::Matrix<double, 6, 6>;
    Eigen::Map<M6>(C).noalias() -= Eigen::Map<const M6>(A) * Eigen::Map<const M6>(B).transpose();
    return;
  }
  const int sa = K > 0 ? K : sa_, sb = K > 0 ? K : sb_, s = K > 0 ? K : s_;
  if (K == 0 && std::max({sa, sb, s}) >= kEigenFrom) {
    MapX(C, sa, sb).noalias() -= ConstMapX(A, sa, s) * ConstMapX(B, sb, s).transpose();
    return;
  }
  for (int c = 0; c < sb; ++c)
    for (int m = 0; m < s; ++m) {
      const double b = B[c + m * sb];
      const double* A_m = A + m * sa;
      double* C_c = C + c * sa;
      for (int r = 0; r < sa; ++r) C_c[r] -= A_m[r] * b;
    }
}

// y := L^-1 y (forward) or L^-T y (backward) for the s x s lower factor L.
template <int K>
void solve_lower(const double* L, int s_, double* y) {
  const int s = K > 0 ? K : s_;
  if (K == 0 && s >= kEigenFrom) {
    Eigen::Map<Eigen::VectorXd> v(y, s);
    ConstMapX(L, s, s).triangularView<Eigen::Lower>().solveInPlace(v);
    return;
  }
  for (int k = 0; k < s; ++k) {
    double v = y[k];
    for (int m = 0; m < k; ++m) v -= L[k + m * s] * y[m];
    y[k] = v / L[k + k * s];
  }
}
template <int K>
void solve_lower_transposed(const double* L, int s_, double* y) {
  const int s = K > 0 ? K : s_;
  if (K == 0 && s >= kEigenFrom) {
    Eigen::Map<Eigen::VectorXd> v(y, s);
    ConstMapX(L, s, s).transpose().triangularView<Eigen::Upper>().solveInPlace(v);
    return;
  }
  for (int k = s; k-- > 0;) {
    double v = y[k];
    for (int m = k + 1; m < s; ++m) v -= L[m + k * s] * y[m];
    y[k] = v / L[k + k * s];
  }
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
  uniform_size_ = nb > 0 && std::all_of(block_sizes.begin(), block_sizes.end(), [&](int size) { return size == block_sizes[0]; })
                      ? block_sizes[0]
                      : 0;
}

int BlockCholesky::block_value(int I, int J) const {
  const Column& col = columns_[J];
  if (I == J) return col.diagonal;
  const auto it = std::lower_bound(col.rows.begin(), col.rows.end(), I);
  return it != col.rows.end() && *it == I ? col.row_values[it - col.rows.begin()] : -1;
}

int BlockCholesky::block_offset(int i, int j) const {
  const int I = position_[i], J = position_[j];
  return I < J ? -1 : block_value(I, J);
}

int BlockCholesky::value_index(int i, int r, int j, int c) const {
  const int at = block_offset(i, j);
  return at < 0 ? -1 : at + r + c * columns_[position_[i]].size;
}

bool BlockCholesky::factor() { return uniform_size_ == 6 ? factor_blocks<6>() : factor_blocks<0>(); }

template <int K>
bool BlockCholesky::factor_blocks() {
  factor_ = values_;
  double* L = factor_.data();
  // right-looking: factor a block column, then subtract its outer products from the later blocks
  for (const Column& col : columns_) {
    const int s = col.size;
    if (!dense_cholesky<K>(L + col.diagonal, s)) return false;
    // L_IJ = H_IJ L_JJ^-T
    for (size_t k = 0; k < col.rows.size(); ++k)
      solve_right_lower_transposed<K>(L + col.diagonal, s, L + col.row_values[k], columns_[col.rows[k]].size);
    const int* target = col.updates.data();
    for (size_t a = 0; a < col.rows.size(); ++a) {
      const int sa = columns_[col.rows[a]].size;
      for (size_t b = 0; b <= a; ++b, ++target)
        subtract_product_transposed<K>(L + *target, L + col.row_values[a], L + col.row_values[b], sa,
                                       columns_[col.rows[b]].size, s);
    }
  }
  return true;
}

void BlockCholesky::solve(const double* b, double* x) const {
  if (uniform_size_ == 6) {
    solve_blocks<6>(b, x);
  } else {
    solve_blocks<0>(b, x);
  }
}

template <int K>
void BlockCholesky::solve_blocks(const double* b, double* x) const {
  // y = P b, by blocks in elimination order
  double* y = work_.data();
  for (const Column& col : columns_) std::copy(b + col.offset, b + col.offset + col.size, y + col.start);
  const double* L = factor_.data();
  // forward: L y = P b; y_I -= L_IJ y_J below each diagonal block
  for (const Column& col : columns_) {
    const int s = K > 0 ? K : col.size;
    double* y_J = y + col.start;
    solve_lower<K>(L + col.diagonal, s, y_J);
    for (size_t k = 0; k < col.rows.size(); ++k) {
      const Column& row = columns_[col.rows[k]];
      const int sr = K > 0 ? K : row.size;
      const double* L_IJ = L + col.row_values[k];
      double* y_I = y + row.start;
      for (int m = 0; m < s; ++m)
        for (int r = 0; r < sr; ++r) y_I[r] -= L_IJ[r + m * sr] * y_J[m];
    }
  }
  // backward: L^T z = y; z_J -= L_IJ^T z_I, then the diagonal block
  for (size_t J = columns_.size(); J-- > 0;) {
    const Column& col = columns_[J];
    const int s = K > 0 ? K : col.size;
    double* y_J = y + col.start;
    for (size_t k = 0; k < col.rows.size(); ++k) {
      const Column& row = columns_[col.rows[k]];
      const int sr = K > 0 ? K : row.size;
      const double* L_IJ = L + col.row_values[k];
      const double* y_I = y + row.start;
      for (int m = 0; m < s; ++m) {
        double v = 0;
        for (int r = 0; r < sr; ++r) v += L_IJ[r + m * sr] * y_I[r];
        y_J[m] -= v;
      }
    }
    solve_lower_transposed<K>(L + col.diagonal, s, y_J);
  }
  // x = P^T z
  for (const Column& col : columns_) std::copy(y + col.start, y + col.start + col.size, x + col.offset);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
