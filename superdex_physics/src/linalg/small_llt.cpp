// Cholesky factorization of small matrices in plain loops (small_llt.h).

#include "linalg/small_llt.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The kernels on column-major storage of n x n (L(i, j) = L[i + n j]). N > 0 fixes n at compile
// time (the loops unroll: the sizes of a free body, a few joints, a free body's island); N = 0
// reads n at run time.

// The 1-norm of the symmetric matrix given by its lower triangle (for rcond(), as Eigen's).
template <int N>
real lower_l1_norm(const real* A, Eigen::Index n_runtime) {
  const Eigen::Index n = N > 0 ? N : n_runtime;
  real norm = 0;
  for (Eigen::Index c = 0; c < n; ++c) {
    real sum = 0;
    for (Eigen::Index r = c; r < n; ++r) sum += std::abs(A[r + n * c]);
    for (Eigen::Index k = 0; k < c; ++k) sum += std::abs(A[c + n * k]);
    norm = std::max(norm, sum);
  }
  return norm;
}

// The lower factor in place, column by column, and its diagonal's reciprocals (one division per
// column: the entries below the diagonal are multiplied by it); false when not positive definite.
template <int N>
bool factor_lower(real* L, real* inverse, Eigen::Index n_runtime) {
  const Eigen::Index n = N > 0 ? N : n_runtime;
  for (Eigen::Index k = 0; k < n; ++k) {
    real d = L[k + n * k];
    for (Eigen::Index j = 0; j < k; ++j) d -= L[k + n * j] * L[k + n * j];
    if (!(d > 0)) return false;
    const real l = std::sqrt(d), inv = 1 / l;
    L[k + n * k] = l;
    inverse[k] = inv;
    for (Eigen::Index i = k + 1; i < n; ++i) {
      real v = L[i + n * k];
      for (Eigen::Index j = 0; j < k; ++j) v -= L[i + n * j] * L[k + n * j];
      L[i + n * k] = v * inv;
    }
  }
  return true;
}

// X <- L^-1 X for the k columns of X (column c at X + c stride).
template <int N>
void solve_lower_columns(const real* L, const real* inverse, real* X, Eigen::Index k, Eigen::Index stride, Eigen::Index n_runtime) {
  const Eigen::Index n = N > 0 ? N : n_runtime;
  // column by column of L: each solved entry taken out of those below it (contiguous in L)
  for (Eigen::Index c = 0; c < k; ++c) {
    real* x = X + c * stride;
    for (Eigen::Index j = 0; j < n; ++j) {
      const real x_j = x[j] * inverse[j];
      x[j] = x_j;
      if (x_j == 0) continue;  // (a Jacobian's columns start with zeros)
      for (Eigen::Index i = j + 1; i < n; ++i) x[i] -= L[i + n * j] * x_j;
    }
  }
}

// x <- (L L^T)^-1 x: L y = x, then L^T x = y.
template <int N>
void solve_factored(const real* L, const real* inverse, real* x, Eigen::Index n_runtime) {
  const Eigen::Index n = N > 0 ? N : n_runtime;
  solve_lower_columns<N>(L, inverse, x, 1, n, n);
  for (Eigen::Index i = n - 1; i >= 0; --i) {
    real v = x[i];
    for (Eigen::Index j = i + 1; j < n; ++j) v -= L[j + n * i] * x[j];
    x[i] = v * inverse[i];
  }
}

// Calls kernel.template operator()<N>() with N = n for the unrolled sizes, N = 0 otherwise.
template <class Kernel>
auto by_size(Eigen::Index n, Kernel&& kernel) {
  switch (n) {
    case 1: return kernel.template operator()<1>();
    case 2: return kernel.template operator()<2>();
    case 3: return kernel.template operator()<3>();
    case 6: return kernel.template operator()<6>();
    default: return kernel.template operator()<0>();
  }
}

}  // namespace

SmallLLT& SmallLLT::compute(const MatX& A) {
  const Eigen::Index n = A.rows();
  if (n > kSmall) {
    Eigen::LLT<MatX>::compute(A);
    return *this;
  }
  m_matrix = A;
  inverse_diagonal_.resize(n);
  real* L = m_matrix.data();
  m_l1_norm = by_size(n, [&]<int N>() { return lower_l1_norm<N>(L, n); });
  const bool positive = by_size(n, [&]<int N>() { return factor_lower<N>(L, inverse_diagonal_.data(), n); });
  m_info = positive ? Eigen::Success : Eigen::NumericalIssue;
  m_isInitialized = true;
  return *this;
}

void SmallLLT::solve_in_place(VecX& x) const {
  const Eigen::Index n = m_matrix.rows();
  if (n > kSmall) {
    solveInPlace(x);
    return;
  }
  by_size(n, [&]<int N>() { solve_factored<N>(m_matrix.data(), inverse_diagonal_.data(), x.data(), n); });
}

void SmallLLT::solve_lower_in_place(Eigen::Ref<MatX> X) const {
  const Eigen::Index n = m_matrix.rows();
  if (n <= kSmall) {
    by_size(n, [&]<int N>() { solve_lower_columns<N>(m_matrix.data(), inverse_diagonal_.data(), X.data(), X.cols(), X.outerStride(), n); });
    return;
  }
  if (n > 32) {
    matrixL().solveInPlace(X);
    return;
  }
  // 17 to 32 rows (factored by Eigen: no reciprocals kept): the same kernel, with the diagonal's
  // reciprocals taken here
  std::array<real, 32> inverse;
  for (Eigen::Index i = 0; i < n; ++i) inverse[i] = 1 / m_matrix(i, i);
  solve_lower_columns<0>(m_matrix.data(), inverse.data(), X.data(), X.cols(), X.outerStride(), n);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
