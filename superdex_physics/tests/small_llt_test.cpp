/// @file small_llt_test.cpp
/// The Cholesky factorization of small matrices in plain loops: on random symmetric positive
/// definite matrices of 1 to 20 rows (the unrolled sizes, the loops below SmallLLT::kSmall and
/// Eigen above), whose upper triangle holds values it must not read, its factor, solutions
/// (Eigen's and its own) and 1-norm match Eigen's LLT (an independent factorization); a matrix
/// that is not positive definite is reported as Eigen reports it.

#include <gtest/gtest.h>

#include <random>

#include "small_llt.h"

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
