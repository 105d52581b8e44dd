/// @file row_block_assembler_test.cpp
/// The constraint Jacobian's assembly block of rows by block of rows: the same matrix as
/// Eigen's setFromTriplets from the non-zero entries (values, sorted columns, a repeated column's
/// values summed in the order given, exact zeros left out), reusing one assembler
/// and one matrix for problems of changing sizes.

#include <gtest/gtest.h>

#include <random>

#include "solver/row_block_assembler.h"

namespace superdex::physics {
namespace {

TEST(RowBlockAssembler, MatchesSetFromTripletsWithRepeatsZerosAndChangingSizes) {
  std::mt19937 rng(11);
  RowBlockAssembler assembler;  // reused across the trials, as an island's workspace keeps it
  SparseRowMat J;
  auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  for (int trial = 0; trial < 300; ++trial) {
    const int n = uniform(1, 12), blocks = uniform(0, 8);
    std::vector<Eigen::Triplet<real>> kept;  // the entries J must hold, as triplets
    assembler.clear();
    int row = 0;
    for (int b = 0; b < blocks; ++b) {
      const int s = uniform(1, 3), columns = uniform(0, 6);
      assembler.begin_block(s);
      for (int c = 0; c < columns; ++c) {
        // columns in any order, some repeated; values with exact zeros among them
        const int col = uniform(0, n - 1);
        real v[3];
        for (int i = 0; i < s; ++i)
          v[i] = uniform(0, 3) == 0 ? real(0) : static_cast<real>(std::uniform_real_distribution<double>(-1, 1)(rng));
        assembler.add(col, v);
        // a left-out zero adds nothing to a repeated column's sum
        for (int i = 0; i < s; ++i)
          if (v[i] != 0) kept.emplace_back(row + i, col, v[i]);
      }
      assembler.end_block();
      row += s;
    }
    ASSERT_EQ(assembler.rows(), row);
    SparseRowMat reference(row, n);
    reference.setFromTriplets(kept.begin(), kept.end());
    assembler.finish(n, J);
    ASSERT_EQ(J.rows(), row);
    ASSERT_EQ(J.cols(), n);
    ASSERT_TRUE(J.isCompressed());
    ASSERT_EQ(J.nonZeros(), reference.nonZeros()) << "trial " << trial;
    for (int i = 0; i <= row; ++i) EXPECT_EQ(J.outerIndexPtr()[i], reference.outerIndexPtr()[i]) << "trial " << trial;
    for (Eigen::Index k = 0; k < J.nonZeros(); ++k) {
      EXPECT_EQ(J.innerIndexPtr()[k], reference.innerIndexPtr()[k]) << "trial " << trial;
      EXPECT_EQ(J.valuePtr()[k], reference.valuePtr()[k]) << "trial " << trial;  // the same sums, bit for bit
    }
  }
}

}  // namespace
}  // namespace superdex::physics
