#pragma once
// Random problems for the block-sparse Cholesky (block_cholesky.h), shared by its test and its
// micro-benchmark: a pattern of dense blocks coupled along a random graph, a symmetric positive
// definite matrix on it, and its entries written through value_index() as the Newton system
// writes them.

#include <Eigen/Core>
#include <random>
#include <utility>
#include <vector>

#include "linalg/block_cholesky.h"

namespace superdex::physics {

struct BlockProblem {
  std::vector<int> sizes, offsets;
  std::vector<std::pair<int, int>> pairs;
};

// Block sizes in [1, 7] (or all `fixed_size`) and about `degree` random partners per block (a
// chain keeps it connected).
inline BlockProblem random_pattern(int blocks, int degree, std::mt19937& rng, int fixed_size = 0) {
  BlockProblem p;
  std::uniform_int_distribution<int> size(fixed_size > 0 ? fixed_size : 1, fixed_size > 0 ? fixed_size : 7),
      other(0, blocks - 1);
  int n = 0;
  for (int i = 0; i < blocks; ++i) p.sizes.push_back(size(rng)), p.offsets.push_back(n), n += p.sizes.back();
  for (int i = 1; i < blocks; ++i) p.pairs.emplace_back(i, i - 1);
  for (int i = 0; i < blocks * degree / 2; ++i) {
    const int a = other(rng), b = other(rng);
    if (a != b) p.pairs.emplace_back(a, b);
  }
  return p;
}

// A random SPD matrix on the pattern: a sum of random rank-s couplings J^T J over the pairs, and
// of each block's own, plus `shift` on the diagonal.
inline Eigen::MatrixXd random_matrix(const BlockProblem& p, double shift, std::mt19937& rng) {
  const int n = p.offsets.back() + p.sizes.back();
  std::normal_distribution<double> normal;
  Eigen::MatrixXd H = shift * Eigen::MatrixXd::Identity(n, n);
  auto add_coupling = [&](int a, int b) {
    // a 3-row "constraint" on the DOFs of blocks a and b
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, n);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < p.sizes[a]; ++c) J(r, p.offsets[a] + c) = normal(rng);
      for (int c = 0; c < p.sizes[b]; ++c) J(r, p.offsets[b] + c) = normal(rng);
    }
    H += J.transpose() * J;
  };
  for (int i = 0; i < static_cast<int>(p.sizes.size()); ++i) add_coupling(i, i);
  for (const auto& [a, b] : p.pairs) add_coupling(a, b);
  return H;
}

// Writes H's entries through value_index(), as the Newton system does: every entry, skipping those
// whose transpose is stored; entries outside the pattern are zero. False when an entry of a
// diagonal block, or a non-zero one, is left out without its transpose stored.
inline bool load(BlockCholesky& chol, const BlockProblem& p, const Eigen::MatrixXd& H) {
  std::fill(chol.values().begin(), chol.values().end(), 0.0);
  const int nb = static_cast<int>(p.sizes.size());
  for (int i = 0; i < nb; ++i)
    for (int j = 0; j < nb; ++j)
      for (int r = 0; r < p.sizes[i]; ++r)
        for (int c = 0; c < p.sizes[j]; ++c) {
          const double value = H(p.offsets[i] + r, p.offsets[j] + c);
          const int at = chol.value_index(i, r, j, c);
          if (at >= 0) {
            chol.values()[at] = value;
          } else if ((i == j || value != 0) && chol.value_index(j, c, i, r) == -1) {
            return false;  // an entry left out must be one whose transpose is stored
          }
        }
  return true;
}

}  // namespace superdex::physics
