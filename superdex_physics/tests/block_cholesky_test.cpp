/// @file block_cholesky_test.cpp
/// The block-sparse Cholesky of rigid islands' Newton matrices: on random symmetric positive
/// definite matrices made of dense blocks of mixed sizes (bodies of 1 to 7 DOFs) coupled along a
/// random graph of block pairs, written through value_index() as the Newton system writes them,
/// its solution matches Eigen's dense LLT of the same matrix (an independent factorization),
/// also after new values on the analysed pattern, and with blocks of articulations' sizes (up
/// to 35 DOFs) among them; a matrix that is not positive definite is reported.

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <random>

#include "linalg/block_cholesky.h"
#include "block_problems.h"

namespace superdex::physics {
namespace {

// H (on p's pattern) loaded into `chol`, factored and solved, against Eigen's dense LLT of H; the
// solve in place the same.
void expect_solves_like_dense(BlockCholesky& chol, const BlockProblem& p, const Eigen::MatrixXd& H) {
  ASSERT_TRUE(load(chol, p, H));
  ASSERT_TRUE(chol.factor());
  const Eigen::VectorXd b = Eigen::VectorXd::Random(chol.dimension());
  Eigen::VectorXd x(chol.dimension());
  chol.solve(b.data(), x.data());
  const Eigen::VectorXd expected = H.llt().solve(b);
  EXPECT_LT((x - expected).norm(), 1e-9 * (1 + expected.norm()));
  Eigen::VectorXd y = b;
  chol.solve(y.data(), y.data());
  EXPECT_EQ(y, x);
}

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
      expect_solves_like_dense(chol, p, H);
      if (HasFailure()) return;
    }
  }
}

// Articulations' blocks (a humanoid's 35 DOFs, a hand's 24) beside free bodies and small
// mechanisms: the large blocks take the dense kernels' other path (20 DOFs and more).
BlockProblem articulation_pattern(std::mt19937& rng) {
  BlockProblem p;
  p.sizes = {35, 6, 24, 6, 1, 13, 12, 11, 6};
  int n = 0;
  for (int size : p.sizes) p.offsets.push_back(n), n += size;
  const int blocks = static_cast<int>(p.sizes.size());
  for (int i = 1; i < blocks; ++i) p.pairs.emplace_back(i, i - 1);
  std::uniform_int_distribution<int> other(0, blocks - 1);
  for (int i = 0; i < blocks; ++i) {
    const int a = other(rng), b = other(rng);
    if (a != b) p.pairs.emplace_back(a, b);
  }
  return p;
}

TEST(BlockCholesky, SolvesLikeDenseCholeskyWithArticulationSizedBlocks) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 6; ++trial) {
    const BlockProblem p = articulation_pattern(rng);
    BlockCholesky chol;
    chol.analyze(p.sizes, p.pairs);
    const Eigen::MatrixXd H = random_matrix(p, 0.1, rng);
    expect_solves_like_dense(chol, p, H);
    if (HasFailure()) return;
    // not positive definite within the largest block
    Eigen::MatrixXd bad = H;
    bad(3, 3) = -1;
    ASSERT_TRUE(load(chol, p, bad));
    EXPECT_FALSE(chol.factor()) << "trial " << trial;
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
