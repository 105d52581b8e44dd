/// @file island_solver_test.cpp
/// The island solve's sparse assembly: assemble_row_major builds the same matrix as Eigen's
/// setFromTriplets (values, sorted columns, duplicates summed in order), reusing one matrix for
/// problems of changing sizes.

#include <gtest/gtest.h>

#include <random>

#include "island_solver.h"

namespace superdex::physics {
namespace {

TEST(AssembleRowMajor, MatchesSetFromTripletsWithDuplicatesAndChangingSizes) {
  std::mt19937 rng(11);
  SparseRowMat J;  // reused across the trials, as an island's workspace keeps it
  std::vector<Eigen::Triplet<real>> by_row;
  std::vector<int> row_start;
  for (int trial = 0; trial < 200; ++trial) {
    const int m = std::uniform_int_distribution<int>(0, 15)(rng), n = std::uniform_int_distribution<int>(1, 12)(rng);
    const int count = m == 0 ? 0 : std::uniform_int_distribution<int>(0, 4 * m)(rng);
    std::vector<Eigen::Triplet<real>> entries;
    for (int k = 0; k < count; ++k)
      entries.emplace_back(std::uniform_int_distribution<int>(0, m - 1)(rng), std::uniform_int_distribution<int>(0, n - 1)(rng),
                           static_cast<real>(std::uniform_real_distribution<double>(-1, 1)(rng)));
    // some exact duplicates of earlier positions
    for (int k = 0; k < count / 3; ++k) {
      const auto& e = entries[std::uniform_int_distribution<int>(0, count - 1)(rng)];
      entries.emplace_back(e.row(), e.col(), real(0.25) * e.value() + real(0.5));
    }
    SparseRowMat reference(m, n);
    reference.setFromTriplets(entries.begin(), entries.end());
    assemble_row_major(J, m, n, entries, by_row, row_start);
    ASSERT_EQ(J.rows(), m);
    ASSERT_EQ(J.cols(), n);
    ASSERT_TRUE(J.isCompressed());
    ASSERT_EQ(J.nonZeros(), reference.nonZeros()) << "trial " << trial;
    for (int i = 0; i <= m; ++i) EXPECT_EQ(J.outerIndexPtr()[i], reference.outerIndexPtr()[i]) << "trial " << trial;
    for (Eigen::Index k = 0; k < J.nonZeros(); ++k) {
      EXPECT_EQ(J.innerIndexPtr()[k], reference.innerIndexPtr()[k]) << "trial " << trial;
      EXPECT_EQ(J.valuePtr()[k], reference.valuePtr()[k]) << "trial " << trial;  // the same sums, bit for bit
    }
  }
}

}  // namespace
}  // namespace superdex::physics
