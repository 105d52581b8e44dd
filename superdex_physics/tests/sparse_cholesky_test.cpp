/// @file sparse_cholesky_test.cpp
/// The sparse Cholesky of the soft bodies' Newton systems (CHOLMOD, on a matrix it keeps in its
/// own fill-reducing order): on a 3-D grid's stiffness-like matrix with random positive weights,
/// its solutions of one and of several right-hand sides match Eigen's own SimplicialLDLT (an
/// independent factorization), also after new values on the analysed structure and after a
/// matrix of another structure; values equal to the last factored ones keep the factor; an
/// indefinite matrix is reported, not factored.

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <random>

#include "linalg/sparse_cholesky.h"

namespace superdex::physics {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

// A symmetric matrix on an nx x ny x nz grid of nodes with 3 DOFs each: every edge of the grid
// couples its two nodes' 3 x 3 blocks by a random positive weight (a graph Laplacian), plus
// `shift` on the diagonal; full symmetric storage, as the soft bodies store theirs.
SpMat grid_matrix(int nx, int ny, int nz, double shift, std::mt19937& rng) {
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  const int n = nx * ny * nz;
  auto node = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
  std::vector<Eigen::Triplet<double>> entries;
  for (int a = 0; a < 3 * n; ++a) entries.emplace_back(a, a, shift);
  auto couple = [&](int p, int q) {
    const double w = weight(rng);
    for (int c = 0; c < 3; ++c) {
      entries.emplace_back(3 * p + c, 3 * p + c, w);
      entries.emplace_back(3 * q + c, 3 * q + c, w);
      entries.emplace_back(3 * p + c, 3 * q + c, -w);
      entries.emplace_back(3 * q + c, 3 * p + c, -w);
    }
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (i + 1 < nx) couple(node(i, j, k), node(i + 1, j, k));
        if (j + 1 < ny) couple(node(i, j, k), node(i, j + 1, k));
        if (k + 1 < nz) couple(node(i, j, k), node(i, j, k + 1));
      }
  SpMat H(3 * n, 3 * n);
  H.setFromTriplets(entries.begin(), entries.end());
  H.makeCompressed();
  return H;
}

// The reference: Eigen's simplicial LDL^T (its own ordering and factorization).
Eigen::MatrixXd reference_solve(const SpMat& H, const Eigen::MatrixXd& B) {
  Eigen::SimplicialLDLT<SpMat> ldlt(H);
  EXPECT_EQ(ldlt.info(), Eigen::Success);
  return ldlt.solve(B);
}

TEST(SparseCholesky, SolvesLikeAnIndependentFactorization) {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  const SpMat H = grid_matrix(6, 5, 4, 0.1, rng);
  SparseCholesky chol;
  chol.analyze(H);
  ASSERT_TRUE(chol.factorize(H));
  const Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(H.rows(), [&] { return normal(rng); });
  const Eigen::VectorXd x = chol.solve(b);
  EXPECT_LT((x - reference_solve(H, b)).norm(), 1e-10 * x.norm());
  EXPECT_LT((H * x - b).norm(), 1e-10 * b.norm());
  const Eigen::MatrixXd B = Eigen::MatrixXd::NullaryExpr(H.rows(), 4, [&] { return normal(rng); });
  const Eigen::MatrixXd X = chol.solve(B);
  EXPECT_LT((X - reference_solve(H, B)).norm(), 1e-10 * X.norm());

  // the same values again keep the factor; new values on the analysed structure replace it
  EXPECT_EQ(chol.factorizations(), 1);
  ASSERT_TRUE(chol.factorize(SpMat(H)));
  EXPECT_EQ(chol.factorizations(), 1);
  EXPECT_EQ(chol.solve(b), x);
  const SpMat H2 = grid_matrix(6, 5, 4, 0.3, rng);
  ASSERT_EQ(H2.nonZeros(), H.nonZeros());
  ASSERT_TRUE(chol.factorize(H2));
  EXPECT_EQ(chol.factorizations(), 2);
  const Eigen::VectorXd x2 = chol.solve(b);
  EXPECT_LT((x2 - reference_solve(H2, b)).norm(), 1e-10 * x2.norm());
  EXPECT_GT((x2 - x).norm(), 1e-3 * x.norm());  // the new values were used

  // a matrix of another structure is analysed anew
  const SpMat H3 = grid_matrix(3, 4, 5, 0.2, rng);
  ASSERT_TRUE(chol.factorize(H3));
  const Eigen::VectorXd b3 = Eigen::VectorXd::NullaryExpr(H3.rows(), [&] { return normal(rng); });
  const Eigen::VectorXd x3 = chol.solve(b3);
  EXPECT_LT((x3 - reference_solve(H3, b3)).norm(), 1e-10 * x3.norm());
}

TEST(SparseCholesky, ReportsAnIndefiniteMatrix) {
  std::mt19937 rng(5);
  const SpMat H = grid_matrix(4, 4, 3, -1.0, rng);  // the Laplacian's zero mode shifted below zero
  SparseCholesky chol;
  chol.analyze(H);
  EXPECT_FALSE(chol.factorize(H));
  // a failed factor is not kept: the same values are factored (and reported) again
  EXPECT_FALSE(chol.factorize(H));
  EXPECT_EQ(chol.factorizations(), 2);
}

}  // namespace
}  // namespace superdex::physics
