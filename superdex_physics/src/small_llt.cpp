// Cholesky factorization of small matrices in plain loops (small_llt.h).

#include "small_llt.h"

#include <cmath>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

SmallLLT& SmallLLT::compute(const MatX& A) {
  const Eigen::Index n = A.rows();
  if (n > kSmall) {
    Eigen::LLT<MatX>::compute(A);
    return *this;
  }
  m_matrix = A;
  // the 1-norm of the symmetric matrix given by its lower triangle (for rcond(), as Eigen's)
  m_l1_norm = 0;
  for (Eigen::Index c = 0; c < n; ++c) {
    real sum = 0;
    for (Eigen::Index r = c; r < n; ++r) sum += std::abs(m_matrix(r, c));
    for (Eigen::Index k = 0; k < c; ++k) sum += std::abs(m_matrix(c, k));
    m_l1_norm = std::max(m_l1_norm, sum);
  }
  // the lower factor in place, column by column (one division per column: its entries below the
  // diagonal are multiplied by the diagonal's reciprocal)
  m_info = Eigen::Success;
  inverse_diagonal_.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    real d = m_matrix(k, k);
    for (Eigen::Index j = 0; j < k; ++j) d -= m_matrix(k, j) * m_matrix(k, j);
    if (!(d > 0)) {
      m_info = Eigen::NumericalIssue;
      break;
    }
    const real l = std::sqrt(d), inverse = 1 / l;
    m_matrix(k, k) = l;
    inverse_diagonal_[k] = inverse;
    for (Eigen::Index i = k + 1; i < n; ++i) {
      real v = m_matrix(i, k);
      for (Eigen::Index j = 0; j < k; ++j) v -= m_matrix(i, j) * m_matrix(k, j);
      m_matrix(i, k) = v * inverse;
    }
  }
  m_isInitialized = true;
  return *this;
}

void SmallLLT::solve_in_place(VecX& x) const {
  const Eigen::Index n = m_matrix.rows();
  if (n > kSmall) {
    solveInPlace(x);
    return;
  }
  const real* L = m_matrix.data();  // column-major: L(i, j) = L[i + n j]
  const real* inverse = inverse_diagonal_.data();
  // L y = x, then L^T x = y
  for (Eigen::Index i = 0; i < n; ++i) {
    real v = x[i];
    for (Eigen::Index j = 0; j < i; ++j) v -= L[i + n * j] * x[j];
    x[i] = v * inverse[i];
  }
  for (Eigen::Index i = n - 1; i >= 0; --i) {
    real v = x[i];
    for (Eigen::Index j = i + 1; j < n; ++j) v -= L[j + n * i] * x[j];
    x[i] = v * inverse[i];
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
