/// @file newton_solver_test.cpp
/// The convex solver's building blocks: the frictional-contact impulse is the R-norm
/// projection of y onto the friction cone (it lies in the cone, and nothing in the cone is
/// closer), its Hessian block matches finite differences in the stiction, sliding and
/// separation regions, and a solved problem satisfies the momentum balance
/// A v = r + J^T gamma with gamma from the block responses. With the drift correction, the
/// solution obeys Coulomb's law with a decoupled normal: sliding contacts keep their normal
/// target, with friction mu gamma_n against the slip.

#include <gtest/gtest.h>

#include <random>

#include "multibody/body_jacobian.h"
#include "solver/newton_solver.h"
#include "solver/step_settings.h"

namespace superdex::physics {
namespace {

ConstraintBlock contact_block(double Rt, double Rn, double mu, double vhat) {
  ConstraintBlock b;
  b.kind = BlockKind::FrictionalContact;
  b.R = Rt;
  b.Rn = Rn;
  b.bound = mu;
  b.vhat = vhat;
  return b;
}

// R-weighted distance between gamma and y.
double r_distance(const ConstraintBlock& b, const Vec3& g, const Vec3& y) {
  const Vec3 d = g - y;
  return b.R * (d[0] * d[0] + d[1] * d[1]) + b.Rn * d[2] * d[2];
}

Vec3 y_of(const ConstraintBlock& b, const Vec3& vc) { return Vec3(-vc[0] / b.R, -vc[1] / b.R, (b.vhat - vc[2]) / b.Rn); }

TEST(ContactProjection, LiesInConeAndIsTheClosestConePoint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const ConstraintBlock b = contact_block(0.01, 0.3, 0.6, 0.05);
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 vc(u(rng), u(rng), u(rng));
    Vec3 g;
    Mat3 G;
    block_response(b, vc.data(), g.data(), G.data());
    const double gt = std::hypot(g[0], g[1]);
    ASSERT_GE(g[2], -1e-12);
    ASSERT_LE(gt, b.bound * g[2] + 1e-9);
    // no sampled cone point is closer to y in the R-norm
    const Vec3 y = y_of(b, vc);
    const double best = r_distance(b, g, y);
    for (int k = 0; k < 200; ++k) {
      const double gn = std::abs(u(rng)) * 3 * std::max(1.0, std::abs(y[2]));
      const double ang = 3.14159265 * u(rng), rad = b.bound * gn * std::abs(u(rng));
      const Vec3 c(rad * std::cos(ang), rad * std::sin(ang), gn);
      ASSERT_GE(r_distance(b, c, y), best - 1e-9);
    }
  }
}

TEST(ContactProjection, HessianMatchesFiniteDifferencesInEveryRegion) {
  const ConstraintBlock b = contact_block(0.02, 0.5, 0.5, 0.1);
  // stiction (small tangential, approaching), sliding, separation
  const Vec3 cases[] = {Vec3(0.0005, -0.0003, -0.2), Vec3(0.3, -0.1, -0.1), Vec3(0.1, 0.2, 0.6)};
  for (const Vec3& vc : cases) {
    Vec3 g;
    Mat3 G;
    block_response(b, vc.data(), g.data(), G.data());
    Mat3 fd;
    const double h = 1e-7;
    for (int k = 0; k < 3; ++k) {
      Vec3 vp = vc, vm = vc, gp, gm;
      Mat3 unused;
      vp[k] += h, vm[k] -= h;
      block_response(b, vp.data(), gp.data(), unused.data());
      block_response(b, vm.data(), gm.data(), unused.data());
      fd.col(k) = -(gp - gm) / (2 * h);  // G = d(-gamma)/d(vc)
    }
    EXPECT_LT((G - fd).norm(), 1e-5 * (1 + fd.norm())) << "vc = " << vc.transpose() << "\nG =\n" << G << "\nfd =\n" << fd;
    EXPECT_LT((G - G.transpose()).norm(), 1e-9);
  }
}

// A matrix of uniform entries in [-1, 1] from the test's own generator (not std::rand, which
// other code may consume or reseed).
MatX uniform_matrix(int rows, int cols, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  MatX M(rows, cols);
  for (int c = 0; c < cols; ++c)
    for (int r = 0; r < rows; ++r) M(r, c) = u(rng);
  return M;
}

TEST(ConvexSolve, SatisfiesMomentumBalanceWithContactsAndLimits) {
  std::mt19937 rng(3);
  std::normal_distribution<double> nd;
  const int n = 6;
  MatX L = uniform_matrix(n, n, rng);
  const MatX A = L * L.transpose() + n * MatX::Identity(n, n);
  VecX r(n);
  for (int i = 0; i < n; ++i) r[i] = nd(rng);
  ConstraintRows rows;
  rows.J = uniform_matrix(7, n, rng).sparseView();
  rows.blocks.push_back(contact_block(0.01, 0.1, 0.4, 0.2));
  rows.blocks.back().row = 0;
  rows.blocks.push_back(contact_block(0.02, 0.05, 1.0, -0.1));
  rows.blocks.back().row = 3;
  ConstraintBlock lim;
  lim.kind = BlockKind::Unilateral;
  lim.row = 6;
  lim.R = 0.05;
  lim.vhat = 0.3;
  rows.blocks.push_back(lim);
  const Eigen::LLT<MatX> llt(A);
  StepSettings params;
  params.relative_tolerance = 1e-12;
  params.drift_correction_iterations = 0;  // the convex problem as given
  const ConvexResult res = solve_convex(A, llt, r, rows, params);
  ASSERT_TRUE(res.converged);
  EXPECT_LE(res.iterations, 30);
  // gamma recomputed from the solution's constraint velocities balances the momentum
  const VecX vc = rows.J * res.v;
  VecX gamma(7);
  for (const ConstraintBlock& blk : rows.blocks) {
    double G[9];
    block_response(blk, vc.data() + blk.row, gamma.data() + blk.row, G);
  }
  EXPECT_LT((A * res.v - r - rows.J.transpose() * gamma).norm(), 1e-9 * (1 + r.norm()));
  EXPECT_LT((gamma - res.gamma).norm(), 1e-12 * (1 + gamma.norm()));

  // the path of large islands (by bodies; here one body of n DOFs) solves the same problem
  BodyJacobian J_bodies;
  const int dofs[] = {n};
  J_bodies.reset(dofs);
  const MatX J_dense(rows.J);
  for (const ConstraintBlock& blk : rows.blocks) {
    J_bodies.begin_block(blk.size());
    real* P = J_bodies.piece(0);
    for (int c = 0; c < n; ++c)
      for (int i = 0; i < blk.size(); ++i) P[c * blk.size() + i] = J_dense(blk.row + i, c);
    J_bodies.end_block();
  }
  const MatX A_blocks[] = {A};
  const ConvexResult sparse = solve_convex(A_blocks, r, J_bodies, rows.blocks, params);
  ASSERT_TRUE(sparse.converged);
  EXPECT_LT((sparse.v - res.v).norm(), 1e-9 * (1 + res.v.norm()));
  EXPECT_LT((sparse.gamma - res.gamma).norm(), 1e-9 * (1 + res.gamma.norm()));
}

// A random problem of `contacts` contacts pushed sideways: 12 variables, tangential R 0.002,
// normal 0.02, friction mu, normal targets of about 0.3.
struct SlidingProblem {
  MatX A;
  VecX r;
  ConstraintRows rows;
};
SlidingProblem sliding_problem(std::mt19937& rng, int contacts, double mu) {
  std::normal_distribution<double> nd;
  const int n = 12;
  SlidingProblem p;
  const MatX L = uniform_matrix(n, n, rng);
  p.A = L * L.transpose() + n * MatX::Identity(n, n);
  p.r.resize(n);
  for (int i = 0; i < n; ++i) p.r[i] = 3 * nd(rng);
  p.rows.J = uniform_matrix(3 * contacts, n, rng).sparseView();
  for (int c = 0; c < contacts; ++c) {
    p.rows.blocks.push_back(contact_block(0.002, 0.02, mu, 0.3 * nd(rng)));
    p.rows.blocks.back().row = 3 * c;
  }
  return p;
}

// How far a contact's impulse g (at its constraint velocity vc, both its 3 rows) is from its
// normal law gamma_n = max(0, (vhat - v_n) / Rn) and from Coulomb's law: sticking (gamma_t =
// -v_t / Rt inside the disk mu gamma_n) or sliding (gamma_t = -mu gamma_n v_t / |v_t|), relative to
// the scale 1 + |vhat| / Rn.
struct LawError {
  double normal = 0, coulomb = 0;
  bool sliding = false;
};
LawError law_error(const ConstraintBlock& b, const VecX& vc, const VecX& g) {
  const int k = b.row;
  const double scale = 1 + std::abs(b.vhat) / b.Rn;
  LawError e;
  e.normal = std::abs(g[k + 2] - std::max(0.0, (b.vhat - vc[k + 2]) / b.Rn)) / scale;
  const Eigen::Vector2d gt(g[k], g[k + 1]), vt(vc[k], vc[k + 1]);
  const double limit = b.bound * g[k + 2];
  e.sliding = vt.norm() > b.R * limit * (1 + 1e-9);
  e.coulomb = (e.sliding ? (gt + limit * vt.normalized()).norm() : (gt + vt / b.R).norm()) / scale;
  return e;
}

// The corrected solve's impulses satisfy, for each contact, the normal law of its own target
// and Coulomb's law; the pure cone model (no correction) violates the normal law.
TEST(ConvexSolve, DriftCorrectionGivesCoulombsLawWithTheNormalTarget) {
  std::mt19937 rng(11);
  int sliding = 0;
  double normal_error_cone = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const auto [A, r, rows] = sliding_problem(rng, 4, 0.5);
    StepSettings params;
    params.relative_tolerance = 1e-12;
    const Eigen::LLT<MatX> llt(A);
    const ConvexResult res = solve_convex(A, llt, r, rows, params);
    ASSERT_TRUE(res.converged);
    const VecX vc = rows.J * res.v;
    EXPECT_LT((A * res.v - r - rows.J.transpose() * res.gamma).norm(), 1e-8 * (1 + r.norm()));
    for (const ConstraintBlock& b : rows.blocks) {
      const LawError e = law_error(b, vc, res.gamma);
      EXPECT_LT(e.normal, 1e-7);
      EXPECT_LT(e.coulomb, 1e-7);
      sliding += e.sliding;
    }
    // the same problem in the pure cone model: sliding contacts move apart
    params.drift_correction_iterations = 0;
    const ConvexResult cone = solve_convex(A, llt, r, rows, params);
    const VecX vc_cone = rows.J * cone.v;
    for (const ConstraintBlock& b : rows.blocks) normal_error_cone = std::max(normal_error_cone, law_error(b, vc_cone, cone.gamma).normal);
  }
  EXPECT_GT(sliding, 10);  // the problems do slide
  EXPECT_GT(normal_error_cone, 1e-2);
}

// Random problems of `contacts` contacts (seeds 1000 on), `corrections` drift-correction
// iterations at most, tolerance 1e-12 relative: whether each converged with both laws to 1e-7,
// and its Newton iterations.
struct LawCheck {
  int violations = 0, unconverged = 0, worst_iterations = 0;
};
LawCheck solve_sliding_problems(int contacts, double mu, int corrections, int problems) {
  LawCheck out;
  for (int seed = 0; seed < problems; ++seed) {
    std::mt19937 rng(1000 + seed);
    const auto [A, r, rows] = sliding_problem(rng, contacts, mu);
    StepSettings params;
    params.relative_tolerance = 1e-12;
    params.drift_correction_iterations = corrections;
    params.max_newton_iterations = corrections + 100;
    const Eigen::LLT<MatX> llt(A);
    const ConvexResult res = solve_convex(A, llt, r, rows, params);
    if (!res.converged) {
      ++out.unconverged;
      continue;
    }
    out.worst_iterations = std::max(out.worst_iterations, res.iterations);
    const VecX vc = rows.J * res.v;
    for (const ConstraintBlock& b : rows.blocks) {
      const LawError e = law_error(b, vc, res.gamma);
      out.violations += !(e.normal <= 1e-7 && e.coulomb <= 1e-7);
    }
  }
  return out;
}

// The corrections are solved by Newton's method together with the step (newton_loop.h): within
// the default 20 correction iterations, problems of up to 4 contacts reach Coulomb's law (the
// plain fixed point left 40 of these 360 problems' contacts off it), one contact within 8
// Newton iterations (the plain fixed point took up to 21).
TEST(ConvexSolve, DriftCorrectionsReachTheirFixedPointWithinTheDefaultIterations) {
  const int corrections = StepSettings().drift_correction_iterations;
  for (int contacts : {1, 2, 4}) {
    for (double mu : {0.3, 0.5, 1.0}) {
      const LawCheck check = solve_sliding_problems(contacts, mu, corrections, 40);
      EXPECT_EQ(check.unconverged, 0) << contacts << " contacts, mu " << mu;
      EXPECT_EQ(check.violations, 0) << contacts << " contacts, mu " << mu;
      if (contacts == 1) {
        EXPECT_LE(check.worst_iterations, 8) << "mu " << mu;
      }
    }
  }
}

// With unlimited corrections, contacts that switch between sliding and sticking or touching can
// make the predictions cycle; they then give way to the plain fixed point, which converges.
TEST(ConvexSolve, DriftCorrectionsConvergeWhenThePredictionsCycle) {
  for (int contacts : {4, 8}) {
    for (double mu : {0.3, 1.0}) {
      const LawCheck check = solve_sliding_problems(contacts, mu, 200, 40);
      EXPECT_EQ(check.unconverged, 0) << contacts << " contacts, mu " << mu;
      EXPECT_EQ(check.violations, 0) << contacts << " contacts, mu " << mu;
      EXPECT_LE(check.worst_iterations, 120) << contacts << " contacts, mu " << mu;
    }
  }
}

}  // namespace

}  // namespace superdex::physics
