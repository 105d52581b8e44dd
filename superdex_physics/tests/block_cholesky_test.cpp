/// @file block_cholesky_test.cpp
/// The block-sparse Cholesky of rigid islands' Newton matrices: on random symmetric positive
/// definite matrices made of dense blocks of mixed sizes (bodies of 1 to 7 DOFs) coupled along a
/// random graph of block pairs, written through value_index() as the Newton system writes them,
/// its solution matches Eigen's dense LLT of the same matrix (an independent factorization),
/// also after new values on the analysed pattern; a matrix that is not positive definite is
/// reported.

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <random>

#include "linalg/block_cholesky.h"
#include "block_problems.h"

namespace superdex::physics {
namespace {

TEST(BlockCholesky, SolvesLikeDenseCholesky) {
  std::mt19937 rng(7);
  // mixed sizes, then every block 6 x 6 (free bodies: the kernels of fixed size)
  for (int trial = 0; trial < 10; ++trial) {
    const BlockProblem p = random_pattern(5 + 7 * (trial % 6), 3, rng, trial < 6 ? 0 : 6);
    BlockCholesky chol;
    chol.analyze(p.sizes, p.pairs);
    const int n = chol.dimension();
    ASSERT_EQ(n, p.offsets.back() + p.sizes.back());
    // two value sets on one analysis
    for (int values = 0; values < 2; ++values) {
      const Eigen::MatrixXd H = random_matrix(p, 0.1 + values, rng);
      ASSERT_TRUE(load(chol, p, H));
      ASSERT_TRUE(chol.factor());
      const Eigen::VectorXd b = Eigen::VectorXd::Random(n);
      Eigen::VectorXd x(n);
      chol.solve(b.data(), x.data());
      const Eigen::VectorXd expected = H.llt().solve(b);
      EXPECT_LT((x - expected).norm(), 1e-9 * (1 + expected.norm())) << "trial " << trial << " values " << values;
      // in place
      Eigen::VectorXd y = b;
      chol.solve(y.data(), y.data());
      EXPECT_EQ(y, x);
    }
  }
}

TEST(BlockCholesky, ReportsAMatrixThatIsNotPositiveDefinite) {
  std::mt19937 rng(3);
  const BlockProblem p = random_pattern(12, 2, rng);
  BlockCholesky chol;
  chol.analyze(p.sizes, p.pairs);
  Eigen::MatrixXd H = random_matrix(p, 0.1, rng);
  const int n = chol.dimension();
  H(n - 1, n - 1) = -1;
  ASSERT_TRUE(load(chol, p, H));
  EXPECT_FALSE(chol.factor());
}

}  // namespace
}  // namespace superdex::physics
