/// @file body_block_solve_test.cpp
/// The path of large rigid islands, by bodies: on random problems of bodies with 1 to 7 DOFs
/// (and islands of free bodies, 6 each), joint rows on one body and contacts between one or two
/// bodies (both sides on one body too), checked against the same problem as dense matrices:
/// - BodyJacobian's J x and J^T y equal the dense products, and pieces asked for twice in a
///   block add up;
/// - SparseNewtonSystem's solve equals Eigen's dense LLT of A + J^T G J (an independent
///   factorization), over a sequence of problems on the same bodies whose contacts come and go
///   (analysis kept while no new body pair is coupled, made anew otherwise), with Hessian blocks
///   updated between factorizations as Newton iterations do;
/// - the Newton solve by bodies gives the dense path's velocities and impulses.

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <random>

#include "multibody/body_jacobian.h"
#include "solver/newton_solver.h"
#include "solver/sparse_newton_system.h"
#include "solver/step_settings.h"

namespace superdex::physics {
namespace {

// A random problem: J by bodies and the same J as a dense matrix, A's blocks, r, the blocks.
struct Problem {
  std::vector<int> dofs;
  BodyJacobian J;
  MatX J_dense;
  std::vector<MatX> A;
  MatX A_dense;
  VecX r;
  std::vector<ConstraintBlock> blocks;
};

double uniform(std::mt19937& rng, double lo = -1, double hi = 1) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
int uniform_int(std::mt19937& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }

// `pairs`: the body pairs that contacts couple (each one at least once; the others take one of
// them, or one body alone).
Problem random_problem(const std::vector<int>& dofs, const std::vector<std::pair<int, int>>& pairs, int contacts,
                       std::mt19937& rng) {
  Problem p;
  p.dofs = dofs;
  const int nb = static_cast<int>(dofs.size());
  std::vector<int> start(nb + 1, 0);
  for (int b = 0; b < nb; ++b) start[b + 1] = start[b] + dofs[b];
  const int n = start[nb];
  p.A_dense = MatX::Zero(n, n);
  for (int b = 0; b < nb; ++b) {
    MatX L(dofs[b], dofs[b]);
    for (int c = 0; c < dofs[b]; ++c)
      for (int r = 0; r < dofs[b]; ++r) L(r, c) = uniform(rng);
    p.A.push_back(L * L.transpose() + dofs[b] * MatX::Identity(dofs[b], dofs[b]));
    p.A_dense.block(start[b], start[b], dofs[b], dofs[b]) = p.A.back();
  }
  p.r.resize(n);
  for (int i = 0; i < n; ++i) p.r[i] = 2 * uniform(rng);
  p.J.reset(dofs);
  std::vector<std::vector<double>> rows;  // dense rows as made
  auto add_rows = [&](int s, const std::vector<int>& bodies) {
    p.J.begin_block(s);
    const int row = static_cast<int>(rows.size());
    for (int i = 0; i < s; ++i) rows.emplace_back(n, 0.0);
    for (int b : bodies) {
      real* P = p.J.piece(b);
      for (int c = 0; c < dofs[b]; ++c)
        for (int i = 0; i < s; ++i) {
          const double v = uniform(rng);
          P[c * s + i] += static_cast<real>(v);
          rows[row + i][start[b] + c] += v;
        }
    }
    p.J.end_block();
    ConstraintBlock blk;
    blk.row = row;
    if (s == 3) {
      blk.kind = BlockKind::FrictionalContact;
      blk.R = 0.01 + 0.02 * std::abs(uniform(rng));
      blk.Rn = 0.05 + 0.1 * std::abs(uniform(rng));
      blk.bound = 0.3 + 0.5 * std::abs(uniform(rng));
      blk.vhat = 0.3 * uniform(rng);
    } else {
      blk.kind = BlockKind::Unilateral;
      blk.R = 0.05;
      blk.vhat = 0.3 * uniform(rng);
    }
    p.blocks.push_back(blk);
  };
  // joint rows on single bodies, a contact on each of the pairs, then more contacts: on a pair,
  // on one body, or with both sides on one body (its piece asked for twice)
  for (int k = 0; k < nb / 2; ++k) add_rows(1, {uniform_int(rng, 0, nb - 1)});
  for (const auto [a, b] : pairs) add_rows(3, {a, b});
  for (int c = 0; c < contacts; ++c) {
    const int kind = uniform_int(rng, 0, 5);
    if (kind == 0) {
      add_rows(3, {uniform_int(rng, 0, nb - 1)});
    } else if (kind == 1) {
      const int b = uniform_int(rng, 0, nb - 1);
      add_rows(3, {b, b});
    } else {
      const auto [a, b] = pairs[uniform_int(rng, 0, static_cast<int>(pairs.size()) - 1)];
      add_rows(3, {a, b});
    }
  }
  p.J_dense.resize(static_cast<int>(rows.size()), n);
  for (size_t i = 0; i < rows.size(); ++i)
    for (int c = 0; c < n; ++c) p.J_dense(static_cast<int>(i), c) = static_cast<real>(rows[i][c]);
  return p;
}

std::vector<std::pair<int, int>> random_pairs(int bodies, int count, std::mt19937& rng) {
  std::vector<std::pair<int, int>> pairs;
  for (int k = 0; k < count; ++k) {
    const int a = uniform_int(rng, 0, bodies - 1), b = uniform_int(rng, 0, bodies - 1);
    if (a != b) pairs.emplace_back(a, b);
  }
  if (pairs.empty()) pairs.emplace_back(0, bodies - 1);
  return pairs;
}

std::vector<int> random_dofs(int bodies, bool free_bodies, std::mt19937& rng) {
  std::vector<int> dofs;
  for (int b = 0; b < bodies; ++b) dofs.push_back(free_bodies ? 6 : uniform_int(rng, 1, 7));
  return dofs;
}

VecX random_vector(int size, std::mt19937& rng) {
  VecX v(size);
  for (int i = 0; i < size; ++i) v[i] = uniform(rng);
  return v;
}

TEST(BodyJacobian, ProductsEqualTheDenseMatrix) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    const int bodies = uniform_int(rng, 2, 9);
    const Problem p = random_problem(random_dofs(bodies, trial % 2 == 0, rng), random_pairs(bodies, 6, rng), 12, rng);
    ASSERT_EQ(p.J.rows(), p.J_dense.rows());
    ASSERT_EQ(p.J.cols(), p.J_dense.cols());
    const VecX x = random_vector(p.J.cols(), rng), y = random_vector(p.J.rows(), rng);
    VecX Jx, Jty;
    p.J.multiply(x, Jx);
    p.J.multiply_transposed(y, Jty);
    EXPECT_LT((Jx - p.J_dense * x).norm(), 1e-12 * (1 + Jx.norm())) << "trial " << trial;
    EXPECT_LT((Jty - p.J_dense.transpose() * y).norm(), 1e-12 * (1 + Jty.norm())) << "trial " << trial;
    // a block with both sides on one body has one piece
    for (int k = 0; k < p.J.num_blocks(); ++k) {
      std::vector<int> seen;
      for (const BodyJacobian::Piece& piece : p.J.pieces(k)) seen.push_back(piece.body);
      std::sort(seen.begin(), seen.end());
      EXPECT_TRUE(std::adjacent_find(seen.begin(), seen.end()) == seen.end());
    }
  }
}

TEST(SparseNewtonSystem, SolvesLikeDenseCholeskyAsContactsComeAndGo) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 6; ++trial) {
    const int bodies = 4 + 3 * trial;
    const std::vector<int> dofs = random_dofs(bodies, trial % 2 == 1, rng);
    std::vector<std::pair<int, int>> all_pairs = random_pairs(bodies, 2 * bodies, rng);
    SparseNewtonSystem system;
    int expected_analyses = 0;
    std::vector<std::pair<int, int>> analysed;  // (max, min) pairs of the last analysis
    for (int step = 0; step < 8; ++step) {
      // contacts on all the pairs, then on random parts of them (the structure changes from step
      // to step); a new pair at step 4
      if (step == 4) {
        auto known = [&](int a, int b) {
          return std::any_of(all_pairs.begin(), all_pairs.end(), [&](const auto& q) { return q == std::pair(a, b) || q == std::pair(b, a); });
        };
        for (int a = 0, added = 0; a < bodies && !added; ++a)
          for (int b = 0; b < a && !added; ++b)
            if (!known(a, b)) all_pairs.emplace_back(a, b), added = 1;
      }
      std::vector<std::pair<int, int>> pairs;
      for (const auto& pair : all_pairs)
        if (step == 0 || step == 4 || uniform(rng, 0, 1) < 0.9) pairs.push_back(pair);
      const Problem p = random_problem(dofs, pairs, 3 * bodies, rng);
      // the pairs this problem couples
      std::vector<std::pair<int, int>> coupled;
      for (int k = 0; k < p.J.num_blocks(); ++k) {
        const auto pieces = p.J.pieces(k);
        for (size_t a = 0; a < pieces.size(); ++a)
          for (size_t b = 0; b < a; ++b)
            coupled.emplace_back(std::max(pieces[a].body, pieces[b].body), std::min(pieces[a].body, pieces[b].body));
      }
      std::sort(coupled.begin(), coupled.end());
      coupled.erase(std::unique(coupled.begin(), coupled.end()), coupled.end());
      const bool kept = step > 0 && std::includes(analysed.begin(), analysed.end(), coupled.begin(), coupled.end()) &&
                        4 * coupled.size() >= 3 * analysed.size();
      if (!kept) ++expected_analyses, analysed = coupled;
      system.prepare(p.J);
      EXPECT_EQ(system.analyses(), expected_analyses) << "trial " << trial << " step " << step;
      for (int b = 0; b < bodies; ++b) system.load_A(b, p.A[b]);
      // Hessian blocks as Newton iterations change them: some blocks change, others stay
      std::vector<Eigen::Matrix<real, 3, 3>> G(p.blocks.size(), Eigen::Matrix<real, 3, 3>::Zero());
      for (int iteration = 0; iteration < 3; ++iteration) {
        for (size_t k = 0; k < G.size(); ++k) {
          if (iteration > 0 && uniform(rng, 0, 1) < 0.5) continue;
          const int s = p.blocks[k].size();
          MatX M(s, s);
          for (int c = 0; c < s; ++c)
            for (int r = 0; r < s; ++r) M(r, c) = uniform(rng);
          G[k].topLeftCorner(s, s) = M * M.transpose();
          if (uniform(rng, 0, 1) < 0.2) G[k].setZero();  // a block apart
        }
        MatX H = p.A_dense;
        for (size_t k = 0; k < G.size(); ++k) {
          const int s = p.blocks[k].size(), r0 = p.blocks[k].row;
          H += p.J_dense.middleRows(r0, s).transpose() * G[k].topLeftCorner(s, s) * p.J_dense.middleRows(r0, s);
        }
        ASSERT_TRUE(system.factor(p.J, G));
        const VecX b = random_vector(H.rows(), rng);
        VecX x;
        system.solve(b, x);
        const VecX expected = H.llt().solve(b);
        EXPECT_LT((x - expected).norm(), 1e-9 * (1 + expected.norm())) << "trial " << trial << " step " << step;
      }
    }
    EXPECT_GT(expected_analyses, 1);  // some steps coupled new pairs
    EXPECT_LT(expected_analyses, 8);  // and some kept the analysis
  }
}

TEST(ConvexSolve, ByBodiesAsTheDensePath) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 8; ++trial) {
    const int bodies = uniform_int(rng, 3, 8);
    const Problem p = random_problem(random_dofs(bodies, trial % 2 == 0, rng), random_pairs(bodies, 5, rng), 2 * bodies, rng);
    ConstraintRows rows;
    rows.J = p.J_dense.sparseView();
    rows.blocks = p.blocks;
    StepSettings params;
    params.relative_tolerance = 1e-12;
    const ConvexResult dense = solve_convex(p.A_dense, p.A_dense.llt(), p.r, rows, params);
    const ConvexResult by_bodies = solve_convex(p.A, p.r, p.J, p.blocks, params);
    ASSERT_TRUE(dense.converged);
    ASSERT_TRUE(by_bodies.converged);
    EXPECT_LT((by_bodies.v - dense.v).norm(), 1e-8 * (1 + dense.v.norm())) << "trial " << trial;
    EXPECT_LT((by_bodies.gamma - dense.gamma).norm(), 1e-8 * (1 + dense.gamma.norm())) << "trial " << trial;
    EXPECT_GT(dense.gamma.norm(), 0);  // constraints act
  }
}

}  // namespace
}  // namespace superdex::physics
