// Tree-structured L^T D L factorization (tree_ldlt.h).

#include "linalg/tree_ldlt.h"

#include <cmath>

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// Whether A's lower triangle lies on the tree's pattern: DOFs numbered parents first, and every
// non-zero A(k, j), j < k, between DOF k and one of its ancestors.
bool on_tree_pattern(const MatX& A, std::span<const int> parent, std::vector<char>& ancestor) {
  const Eigen::Index n = A.rows();
  for (Eigen::Index k = 0; k < n; ++k)
    if (parent[k] >= k) return false;
  ancestor.assign(n, 0);
  for (Eigen::Index k = 1; k < n; ++k) {
    for (int i = parent[k]; i >= 0; i = parent[i]) ancestor[i] = 1;
    for (Eigen::Index j = 0; j < k; ++j)
      if (!ancestor[j] && A(k, j) != 0) return false;
    for (int i = parent[k]; i >= 0; i = parent[i]) ancestor[i] = 0;
  }
  return true;
}

}  // namespace

TreeLDLT& TreeLDLT::compute(const MatX& A, std::span<const int> parent) {
  n_ = A.rows();
  thread_local std::vector<char> ancestor;
  tree_ = static_cast<Eigen::Index>(parent.size()) == n_ && on_tree_pattern(A, parent, ancestor);
  if (!tree_) {
    dense_.compute(A);
    info_ = dense_.info();
    return *this;
  }
  parent_.assign(parent.begin(), parent.end());
  F_ = A;
  inverse_sqrt_D_.resize(n_);
  info_ = Eigen::Success;
  // from the leaves: DOF k's row divided by its pivot, and its Schur complement taken out of its
  // ancestors' rows (only ancestor pairs: no fill-in)
  for (Eigen::Index k = n_ - 1; k >= 0; --k) {
    const real d = F_(k, k);
    if (!(d > 0) || !std::isfinite(d)) {
      info_ = Eigen::NumericalIssue;
      return *this;
    }
    inverse_sqrt_D_[k] = 1 / std::sqrt(d);
    for (int i = parent_[k]; i >= 0; i = parent_[i]) {
      const real a = F_(k, i) / d;
      for (int j = i; j >= 0; j = parent_[j]) F_(i, j) -= a * F_(k, j);
      F_(k, i) = a;
    }
  }
  return *this;
}

void TreeLDLT::leaves_to_roots(real* x) const {
  // L^T's rows are a DOF's and its ancestors': each solved entry taken out of its ancestors' (a
  // zero entry passes nothing on)
  for (Eigen::Index k = n_ - 1; k > 0; --k) {
    const real x_k = x[k];
    if (x_k == 0) continue;
    for (int i = parent_[k]; i >= 0; i = parent_[i]) x[i] -= F_(k, i) * x_k;
  }
}

void TreeLDLT::solve_in_place(VecX& x) const {
  if (!tree_) {
    dense_.solve_in_place(x);
    return;
  }
  leaves_to_roots(x.data());
  for (Eigen::Index k = 0; k < n_; ++k) x[k] *= inverse_sqrt_D_[k] * inverse_sqrt_D_[k];
  // x <- L^-1 x, from the roots
  for (Eigen::Index k = 1; k < n_; ++k) {
    real x_k = x[k];
    for (int i = parent_[k]; i >= 0; i = parent_[i]) x_k -= F_(k, i) * x[i];
    x[k] = x_k;
  }
}

void TreeLDLT::half_solve_in_place(Eigen::Ref<MatX> X) const {
  if (!tree_) {
    dense_.solve_lower_in_place(X);
    return;
  }
  for (Eigen::Index c = 0; c < X.cols(); ++c) {
    real* x = X.col(c).data();
    leaves_to_roots(x);
    for (Eigen::Index k = 0; k < n_; ++k) x[k] *= inverse_sqrt_D_[k];
  }
}

void TreeLDLT::inverse_diagonal(VecX& d) const {
  d.resize(n_);
  if (!tree_) {
    MatX H = MatX::Identity(n_, n_);
    dense_.solve_lower_in_place(H);
    d = H.colwise().squaredNorm().transpose();
    return;
  }
  // column k of L^-T: leaves_to_roots of e_k, which only passes values up k's ancestor chain;
  // diag(A^-1)_k = sum over the chain of x_i^2 / D_i
  VecX& x = scratch_;
  if (x.size() != n_) x.setZero(n_);
  for (Eigen::Index k = 0; k < n_; ++k) {
    x[k] = 1;
    real sum = 0;
    for (int m = static_cast<int>(k); m >= 0; m = parent_[m]) {
      const real x_m = x[m];
      for (int i = parent_[m]; i >= 0; i = parent_[i]) x[i] -= F_(m, i) * x_m;
      sum += x_m * x_m * inverse_sqrt_D_[m] * inverse_sqrt_D_[m];
      x[m] = 0;
    }
    d[k] = sum;
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
