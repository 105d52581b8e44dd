#pragma once
// Factorization of an articulation's momentum matrix A = M + dt D (+ tendon terms) that follows
// its kinematic tree: A = L^T D L with L unit lower triangular, L(k, i) non-zero only where DOF i
// is an ancestor of DOF k (Featherstone's LTDL). A tree's mass matrix has no entry between DOFs
// on different branches, and eliminating from the leaves creates none, so the factorization
// costs the sum over DOFs of their depth squared instead of n^3 / 6, and a solve with a right
// side on one link's ancestors (a contact's Jacobian) touches only those. A matrix with entries
// outside the tree's pattern (a tendon across branches) or DOFs not numbered parents first is
// factored densely (SmallLLT) instead; the methods serve both.

#include <span>
#include <vector>

#include "linalg/small_llt.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class TreeLDLT {
 public:
  // Factors A (n x n, symmetric: its lower triangle is read), whose DOF k hangs from DOF
  // parent[k] (-1: a root DOF). info() tells whether it is positive definite.
  TreeLDLT& compute(const MatX& A, std::span<const int> parent);
  Eigen::ComputationInfo info() const { return info_; }
  // Whether the last compute() used the tree (else the dense factor).
  bool follows_tree() const { return tree_; }
  Eigen::Index rows() const { return n_; }

  // x <- A^-1 x.
  void solve_in_place(VecX& x) const;
  // X <- H X (X: n x k, a matrix or a block of one) for a factor H with H^T H = A^-1:
  // D^-1/2 L^-T on the tree, L^-1 of A = L L^T on the dense path. (H X)^T (H X) = X^T A^-1 X:
  // compliances without forming A^-1.
  void half_solve_in_place(Eigen::Ref<MatX> X) const;
  // d <- diag(A^-1). On the tree, column k of L^-T is non-zero only on DOF k and its ancestors:
  // the sum over DOFs of their depth squared; the dense factor solves the identity.
  void inverse_diagonal(VecX& d) const;

 private:
  // x <- L^-T x (n entries), from the leaves to the roots
  void leaves_to_roots(real* x) const;

  Eigen::Index n_ = 0;
  bool tree_ = false;
  Eigen::ComputationInfo info_ = Eigen::Success;
  std::vector<int> parent_;
  MatX F_;                  // L below the diagonal (column-major), D on it
  VecX inverse_sqrt_D_;
  mutable VecX scratch_;    // inverse_diagonal's column, zero between uses
  SmallLLT dense_{MatX(0, 0)};
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
