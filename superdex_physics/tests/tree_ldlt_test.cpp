/// @file tree_ldlt_test.cpp
/// The factorization along an articulation's tree (A = L^T D L, Featherstone's LTDL): on random
/// trees of 1 to 40 DOFs (forests included) and random symmetric positive definite matrices on
/// their pattern, whose upper triangle holds values it must not read, its solves equal Eigen's
/// LLT's (an independent dense factorization), and its half solve H X gives X^T A^-1 X; a right
/// side on one DOF's ancestors stays there. A matrix with an entry between two branches, or DOFs
/// not numbered parents first, is factored densely with the same results; a matrix that is not
/// positive definite is reported on both paths.

#include <gtest/gtest.h>

#include <random>

#include "linalg/tree_ldlt.h"

namespace superdex::physics {
namespace {

// A random forest of n DOFs, parents first: DOF k hangs from a random earlier DOF, every seventh
// from none.
std::vector<int> random_tree(int n, std::mt19937& rng) {
  std::vector<int> parent(n, -1);
  for (int k = 1; k < n; ++k) parent[k] = k % 7 == 0 ? -1 : std::uniform_int_distribution<int>(0, k - 1)(rng);
  return parent;
}

// A symmetric positive definite matrix on the tree's pattern: sum over DOFs k of r_k r_k^T with
// r_k random on k and its ancestors (a link's Jacobian row), plus a small diagonal.
MatX tree_matrix(const std::vector<int>& parent, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = static_cast<int>(parent.size());
  MatX A = 0.05 * MatX::Identity(n, n);
  for (int k = 0; k < n; ++k) {
    VecX r = VecX::Zero(n);
    for (int i = k; i >= 0; i = parent[i]) r[i] = u(rng);
    A += r * r.transpose();
  }
  return A;
}

// The upper triangle overwritten with values the factorization must not read.
MatX garbled_upper(MatX A, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  for (int c = 1; c < A.cols(); ++c)
    for (int r = 0; r < c; ++r) A(r, c) = 1e6 * u(rng);
  return A;
}

// Checks solve and half solve against Eigen's LLT of A.
void expect_matches_dense(const TreeLDLT& f, const MatX& A, const std::string& what) {
  const Eigen::LLT<MatX> reference(A);
  const int n = static_cast<int>(A.rows());
  const VecX b = VecX::Random(n);
  VecX x = b;
  f.solve_in_place(x);
  const VecX x_ref = reference.solve(b);
  EXPECT_LT((x - x_ref).norm(), 1e-9 * (1 + x_ref.norm())) << what;
  MatX X = MatX::Random(n, 3);
  const MatX compliance_ref = X.transpose() * reference.solve(X);
  f.half_solve_in_place(X);
  EXPECT_LT((X.transpose() * X - compliance_ref).norm(), 1e-9 * (1 + compliance_ref.norm())) << what;
  // twice: the second use must find its working column clean
  const VecX diagonal_ref = reference.solve(MatX::Identity(n, n)).diagonal();
  for (int pass = 0; pass < 2; ++pass) {
    VecX d;
    f.inverse_diagonal(d);
    EXPECT_LT((d - diagonal_ref).norm(), 1e-9 * (1 + diagonal_ref.norm())) << what << ", diag(A^-1), pass " << pass;
  }
}

TEST(TreeLDLT, SolvesLikeADenseCholeskyOnRandomTrees) {
  std::mt19937 rng(31);
  TreeLDLT f;  // reused across sizes, as articulation terms keep it
  for (int n = 1; n <= 40; ++n) {
    const std::vector<int> parent = random_tree(n, rng);
    const MatX A = tree_matrix(parent, rng);
    f.compute(garbled_upper(A, rng), parent);
    ASSERT_EQ(f.info(), Eigen::Success) << "n = " << n;
    EXPECT_TRUE(f.follows_tree()) << "n = " << n;
    expect_matches_dense(f, A, "n = " + std::to_string(n));
  }
}

TEST(TreeLDLT, HalfSolveOfALinksJacobianStaysOnItsAncestors) {
  std::mt19937 rng(37);
  const int n = 30;
  const std::vector<int> parent = random_tree(n, rng);
  const MatX A = tree_matrix(parent, rng);
  TreeLDLT f;
  f.compute(A, parent);
  ASSERT_TRUE(f.follows_tree());
  for (int k = 0; k < n; ++k) {
    std::vector<char> on_chain(n, 0);
    VecX x = VecX::Zero(n);
    for (int i = k; i >= 0; i = parent[i]) on_chain[i] = 1, x[i] = 1 + i;
    MatX X = x;
    f.half_solve_in_place(X);
    for (int i = 0; i < n; ++i) {
      if (!on_chain[i]) {
        EXPECT_EQ(X(i, 0), 0) << "DOF " << k << ", entry " << i;
      }
    }
    EXPECT_NEAR(X.col(0).squaredNorm(), x.dot(Eigen::LLT<MatX>(A).solve(x)), 1e-9 * X.col(0).squaredNorm());
  }
}

TEST(TreeLDLT, MatricesOffTheTreeAreFactoredDensely) {
  std::mt19937 rng(41);
  std::vector<int> parent = {-1, 0, 1, 2, 0, 4, 5, 1, 7, -1, 9, 10};
  // a tendon between two branches (DOFs 3 and 6): an entry off the tree's pattern
  MatX A = tree_matrix(parent, rng);
  A(6, 3) = A(3, 6) = 0.2;
  A(6, 6) += 1, A(3, 3) += 1;
  TreeLDLT f;
  f.compute(garbled_upper(A, rng), parent);
  ASSERT_EQ(f.info(), Eigen::Success);
  EXPECT_FALSE(f.follows_tree());
  expect_matches_dense(f, A, "cross-branch entry");
  // DOFs not numbered parents first
  std::vector<int> late = parent;
  late[1] = 5;
  const MatX B = tree_matrix(late, rng);
  f.compute(B, late);
  ASSERT_EQ(f.info(), Eigen::Success);
  EXPECT_FALSE(f.follows_tree());
  expect_matches_dense(f, B, "child before parent");
  // and back on a tree
  const MatX C = tree_matrix(parent, rng);
  f.compute(C, parent);
  EXPECT_TRUE(f.follows_tree());
  expect_matches_dense(f, C, "tree again");
}

TEST(TreeLDLT, ReportsAMatrixThatIsNotPositiveDefinite) {
  std::mt19937 rng(43);
  const std::vector<int> parent = {-1, 0, 1, 1, 3};
  MatX A = tree_matrix(parent, rng);
  A(4, 4) = -1;  // a leaf's pivot
  TreeLDLT f;
  f.compute(A, parent);
  EXPECT_EQ(f.info(), Eigen::NumericalIssue);
  // a root's pivot, reached last
  A = tree_matrix(parent, rng);
  A(0, 0) = -10;
  f.compute(A, parent);
  EXPECT_EQ(f.info(), Eigen::NumericalIssue);
  // the dense path
  A(2, 4) = A(4, 2) = 0.1;
  f.compute(A, parent);
  EXPECT_FALSE(f.follows_tree());
  EXPECT_EQ(f.info(), Eigen::NumericalIssue);
}

}  // namespace
}  // namespace superdex::physics
