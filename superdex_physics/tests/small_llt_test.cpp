/// @file small_llt_test.cpp
/// The Cholesky factorization of small matrices in plain loops: on random symmetric positive
/// definite matrices of 1 to 20 rows (the unrolled sizes, the loops below SmallLLT::kSmall and
/// Eigen above), whose upper triangle holds values it must not read, its factor, solutions
/// (Eigen's and its own) and 1-norm match Eigen's LLT (an independent factorization); a matrix
/// that is not positive definite is reported as Eigen reports it. Its forward substitution
/// L^-1 X, on blocks of a larger matrix, matches Eigen's triangular solve at 1 to 40 rows.

#include <gtest/gtest.h>

#include <random>

#include "linalg/small_llt.h"

namespace superdex::physics {
namespace {

TEST(SmallLLT, FactorsLikeEigensLLT) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  SmallLLT llt;  // reused across sizes, as the solver's workspaces keep it
  for (int n = 1; n <= 20; ++n) {
    MatX L(n, n), b(n, 2);
    for (int c = 0; c < n; ++c)
      for (int r = 0; r < n; ++r) L(r, c) = u(rng);
    for (int c = 0; c < 2; ++c)
      for (int r = 0; r < n; ++r) b(r, c) = u(rng);
    MatX A = L * L.transpose() + 0.1 * MatX::Identity(n, n);
    const Eigen::LLT<MatX> reference(A);
    // the upper triangle is not read
    for (int c = 1; c < n; ++c)
      for (int r = 0; r < c; ++r) A(r, c) = 1e6 * u(rng);
    llt.compute(A);
    ASSERT_EQ(llt.info(), Eigen::Success) << "n = " << n;
    const MatX L_ours = llt.matrixL(), L_ref = reference.matrixL();
    EXPECT_LT((L_ours - L_ref).norm(), 1e-10 * L_ref.norm()) << "n = " << n;
    EXPECT_LT((llt.solve(b) - reference.solve(b)).norm(), 1e-9 * (1 + reference.solve(b).norm())) << "n = " << n;
    // its own solve with one vector
    VecX x = b.col(0);
    llt.solve_in_place(x);
    EXPECT_LT((x - reference.solve(b.col(0))).norm(), 1e-9 * (1 + x.norm())) << "n = " << n;
    EXPECT_NEAR(llt.rcond(), reference.rcond(), 1e-9 * reference.rcond()) << "n = " << n;
  }
}

TEST(SmallLLT, ForwardSubstitutionMatchesEigensTriangularSolve) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int n = 1; n <= 40; ++n) {
    MatX L(n, n);
    for (int c = 0; c < n; ++c)
      for (int r = 0; r < n; ++r) L(r, c) = u(rng);
    const MatX A = L * L.transpose() + 0.1 * MatX::Identity(n, n);
    const SmallLLT llt(A);
    const Eigen::LLT<MatX> reference(A);
    // L^-1 X on a block of 3 columns of a taller matrix (its columns n + 2 apart)
    MatX X(n + 2, 5);
    for (int c = 0; c < 5; ++c)
      for (int r = 0; r < n + 2; ++r) X(r, c) = u(rng);
    const MatX expected = reference.matrixL().solve(X.block(1, 1, n, 3));
    const MatX untouched = X;
    llt.solve_lower_in_place(X.block(1, 1, n, 3));
    EXPECT_LT((X.block(1, 1, n, 3) - expected).norm(), 1e-9 * (1 + expected.norm())) << "n = " << n;
    // the rest of the matrix is left as it was
    X.block(1, 1, n, 3) = untouched.block(1, 1, n, 3);
    EXPECT_EQ(X, untouched) << "n = " << n;
  }
}

TEST(SmallLLT, ReportsAMatrixThatIsNotPositiveDefinite) {
  for (int n : {1, 2, 3, 4, 6, 12}) {
    MatX A = MatX::Identity(n, n);
    A(n - 1, n - 1) = -0.5;
    SmallLLT llt(A);
    EXPECT_EQ(llt.info(), Eigen::NumericalIssue) << "n = " << n;
    EXPECT_EQ(Eigen::LLT<MatX>(A).info(), Eigen::NumericalIssue) << "n = " << n;
  }
}

}  // namespace
}  // namespace superdex::physics
