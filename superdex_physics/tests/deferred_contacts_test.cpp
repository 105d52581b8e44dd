/// @file deferred_contacts_test.cpp
/// Rigid contacts that the motion keeps more than half their gap apart are left out of an
/// island's first solve (ImplicitStepParams::defer_separating_contacts) and admitted to a second
/// one when its result would close them. Leaving them out must not change the step:
/// - Newton's cradle without gravity: a sphere (1 kg) thrown at 1 m/s against a touching one,
///   which rests 3 mm from a third. The free motion keeps the second gap open, so its contact
///   starts deferred; the impact would push the middle sphere 5 mm within the step (0.01 s), so
///   the contact joins. Near-rigid contacts close a gap within the step and no faster, and
///   conserve momentum: the first two move together, the third 0.3 m/s slower than the middle
///   one (its gap closed), v3 = (1 - 2 * 0.3) / 3 m/s, up to the contacts' regularisation (3 % of
///   the speed), and the same as when every contact is in the solve from the start. Without the
///   admission the third sphere would rest until the next step, and the middle one pass into it.
/// - A cluster of tilted boxes dropped onto the ground and onto each other, many of their
///   speculative contacts apart: every step equals the one that keeps all contacts in the solve.

#include <random>

#include "test_helpers.h"

namespace superdex::physics::test {
namespace {

class DeferredContactsTest : public EngineTest {};

Scene scene_deferring(const std::string& name, bool defer) {
  Scene scene = create_scene(name);
  SolverParams params = scene.solver_params();
  params.implicit_step.defer_separating_contacts = defer;
  scene.set_solver_params(params);
  return scene;
}

// One step of the cradle (ball radius r, the third ball `gap` from the second, the first
// thrown at `speed` m/s): the balls' velocities along x (m/s) and the island's solves.
struct CradleStep {
  std::array<real, 3> v;
  int solves = 0;
};
constexpr real kBallRadius = real(0.05), kCradleDt = real(0.01), kCradleGap = real(0.003);

CradleStep cradle_step(bool defer, real speed) {
  Scene scene = scene_deferring(defer ? "cradle_deferring" : "cradle", defer);
  scene.set_gravity(Vec3::Zero());
  const real r = kBallRadius;
  const ShapeHandle ball = create_shape(SphereShape{Vec3::Zero(), r});
  std::array<ActorHandle, 3> balls;
  const std::array<real, 3> x = {0, 2 * r, 4 * r + kCradleGap};
  for (int i = 0; i < 3; ++i) {
    Transform X;
    X.translation = Vec3(x[i], 0, 0);
    balls[i] = scene.create_rigid_actor(rigid_params("ball" + std::to_string(i), ball, X, real(1)));
  }
  scene.set_velocity(balls[0], Vec3(speed, 0, 0), Vec3::Zero());
  scene.step(kCradleDt);
  CradleStep out;
  for (int i = 0; i < 3; ++i) out.v[i] = scene.velocity(balls[i])[0];
  out.solves = scene.solver_stats().num_island_solves;
  // momentum conserved, and no ball passes into the next
  real momentum = 0;
  for (int i = 0; i < 3; ++i) momentum += out.v[i];
  EXPECT_NEAR(momentum, speed, 1e-6);
  for (int i = 0; i < 2; ++i)
    EXPECT_GT(scene.root_transform(balls[i + 1]).translation.x() - scene.root_transform(balls[i]).translation.x(), 2 * r - real(1e-3));
  return out;
}

TEST_F(DeferredContactsTest, AContactTheImpactClosesJoinsTheStep) {
  const real speed = 1;
  const real v3 = (speed - 2 * kCradleGap / kCradleDt) / 3;
  const std::array<real, 3> expected = {v3 + kCradleGap / kCradleDt, v3 + kCradleGap / kCradleDt, v3};
  const CradleStep deferring = cradle_step(true, speed), all = cradle_step(false, speed);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(deferring.v[i], expected[i], 0.03 * speed) << "ball " << i << ", deferring";
    EXPECT_NEAR(all.v[i], expected[i], 0.03 * speed) << "ball " << i;
    EXPECT_NEAR(deferring.v[i], all.v[i], kUsesDoublePrecision ? 1e-9 : 1e-4) << "ball " << i;
  }
  // the deferred contact joined a second solve
  EXPECT_EQ(deferring.solves, 2);
  EXPECT_EQ(all.solves, 1);
}

// Thrown at 0.4 m/s, the first two balls leave the impact together at 0.2 m/s: the second gap
// closes at 0.2 m/s, more than half but less than all of the 0.3 m/s its contact lets close
// within the step. The contact stays inactive and no second solve is needed; the step is the one
// that keeps every contact.
TEST_F(DeferredContactsTest, AContactTheSolutionLeavesInactiveDoesNotJoin) {
  const real speed = real(0.4);
  const CradleStep deferring = cradle_step(true, speed), all = cradle_step(false, speed);
  const std::array<real, 3> expected = {speed / 2, speed / 2, 0};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(all.v[i], expected[i], 0.03 * speed) << "ball " << i;
    EXPECT_NEAR(deferring.v[i], all.v[i], kUsesDoublePrecision ? 1e-9 : 1e-4) << "ball " << i;
  }
  EXPECT_EQ(deferring.solves, 1);
}

// Poses (m, world) of a cluster of boxes after each step, with or without deferral.
std::vector<std::vector<Transform>> drop_cluster(bool defer) {
  Scene scene = scene_deferring(defer ? "cluster_deferring" : "cluster", defer);
  scene.set_gravity(Vec3(0, 0, real(-kG)));
  scene.create_rigid_actor(static_params("ground", create_shape(PlaneShape{Vec3::UnitZ(), 0})));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const ShapeHandle box = create_shape(BoxShape{Vec3(0.05, 0.04, 0.03)});
  std::vector<ActorHandle> boxes;
  for (int i = 0; i < 8; ++i) {
    // two layers of four, 4 to 8 mm apart, tilted a little
    const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
    Transform X{Quat(Eigen::AngleAxis<real>(real(0.15 * u(rng)), axis)),
                Vec3(real(0.106 * (i % 2) + 0.002 * u(rng)), real(0.086 * ((i / 2) % 2)), real(0.035 + 0.068 * (i / 4)))};
    boxes.push_back(scene.create_rigid_actor(rigid_params("box" + std::to_string(i), box, X)));
    scene.set_velocity(boxes.back(), Vec3(real(0.3 * u(rng)), real(0.3 * u(rng)), 0), Vec3::Zero());
  }
  std::vector<std::vector<Transform>> poses;
  for (int n = 0; n < 60; ++n) {
    scene.step(real(0.005));
    EXPECT_EQ(scene.solver_stats().convergence_status, ConvergenceStatus::Converged) << "step " << n;
    poses.emplace_back();
    for (ActorHandle b : boxes) poses.back().push_back(scene.root_transform(b));
  }
  return poses;
}

TEST_F(DeferredContactsTest, DeferringGivesTheSameStepsAsKeepingEveryContact) {
  const auto all = drop_cluster(false), deferred = drop_cluster(true);
  const real tolerance = kUsesDoublePrecision ? real(1e-7) : real(2e-4);
  real moved = 0;
  for (size_t n = 0; n < all.size(); ++n)
    for (size_t i = 0; i < all[n].size(); ++i) {
      EXPECT_LT((all[n][i].translation - deferred[n][i].translation).norm(), tolerance) << "step " << n << ", box " << i;
      EXPECT_NEAR(std::abs(all[n][i].rotation.dot(deferred[n][i].rotation)), 1, tolerance) << "step " << n << ", box " << i;
      moved = std::max(moved, (all[n][i].translation - all[0][i].translation).norm());
    }
  // the boxes fell, slid and met
  EXPECT_GT(moved, real(0.01));
}

}  // namespace
}  // namespace superdex::physics::test
