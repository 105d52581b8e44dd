/// @file joint_limits_test.cpp
/// Joint limits and implicit viscous friction at a large step (25 ms): a rigid limit stops a
/// falling arm with little penetration and brings it to rest; a very stiff damper gives a
/// stable, monotone creep matching the overdamped analytic solution; a compliant limit of
/// stiffness k deflects by torque / k under a static load.

#include "solver/step_settings.h"
#include "test_helpers.h"

namespace superdex::physics::test {
namespace {

constexpr double kM = 1.0, kL = 1.0;
constexpr double kICom = 0.001;
constexpr double kIPivot = kICom + kM * kL * kL;

/// Arm about Y with its COM at (L, 0, 0): positive angles lower it, gravity torque m g L cos(theta).
ArticulationDesc horizontal_arm() {
  return one_dof_desc(JointType::Revolute, Vec3::UnitY(), kM, Vec3(kL, 0, 0), Vec3::Constant(kICom));
}

class JointLimitsTest : public EngineTest {};

TEST_F(JointLimitsTest, RigidLimitStopsFallingArmAtLargeStep) {
  const double dt = 0.025, upper = 0.5;
  ArticulationDesc desc = horizontal_arm();
  desc.joints[1].max_limit = Vec3(0, upper, 0);  // limit value = axis . vector
  desc.default_pose = {-1.0};                     // arm raised: it swings 1.5 rad down onto the limit
  Scene scene = z_up_scene("rigid_limit");
  const ActorHandle arm = scene.create_articulated_actor(desc, "arm");
  double max_penetration = 0;
  for (int n = 0; n < 160; ++n) {  // 4 s
    scene.step(dt);
    const double q = scene.pose(arm)[0];
    ASSERT_TRUE(std::isfinite(q));
    max_penetration = std::max(max_penetration, q - upper);
  }
  EXPECT_LT(max_penetration, 0.01);
  // at rest against the limit
  EXPECT_NEAR(scene.pose(arm)[0], upper, 0.01);
  EXPECT_LT(std::abs(scene.joint_velocities(arm)[0]), 1e-6);
  EXPECT_EQ(scene.solver_stats().convergence_status, ConvergenceStatus::Converged);
}

TEST_F(JointLimitsTest, JointStartingBeyondItsLimitComesBackAtTheDepenetrationSpeed) {
  // no gravity; the arm starts 0.8 rad past its upper limit: it returns at the bound (1 rad/s by
  // default), not 0.8 rad in one 2 ms step (400 rad/s), and, nothing slowing it, goes on at that
  // speed once back within its range
  const double dt = 0.002, upper = 0.5;
  ArticulationDesc desc = horizontal_arm();
  desc.joints[1].max_limit = Vec3(0, upper, 0);
  desc.default_pose = {upper + 0.8};
  Scene scene = create_scene("beyond_limit");
  scene.set_gravity(Vec3::Zero());
  const ActorHandle arm = scene.create_articulated_actor(desc, "arm");
  const double bound = StepSettings{}.max_depenetration_speed;
  ASSERT_EQ(bound, 1.0);
  double fastest = 0;
  for (int n = 0; n < 500; ++n) {  // 1 s
    scene.step(dt);
    fastest = std::max(fastest, std::abs(scene.joint_velocities(arm)[0]));
    if (n == 100) EXPECT_NEAR(scene.pose(arm)[0], upper + 0.8 - 101 * dt * bound, 1e-3);  // moving back at the bound
  }
  EXPECT_LE(fastest, bound * (1 + 1e-6));
  EXPECT_NEAR(scene.pose(arm)[0], upper + 0.8 - 500 * dt * bound, 1e-3);
  EXPECT_NEAR(scene.joint_velocities(arm)[0], -bound, 1e-6);
}

TEST_F(JointLimitsTest, StiffViscousFrictionIsStableAndMonotone) {
  const double dt = 0.025, damping = 1e4, theta0 = 0.5;
  ArticulationDesc desc = one_dof_desc(JointType::Revolute, Vec3::UnitY(), kM, Vec3(0, 0, -kL), Vec3::Constant(kICom));
  desc.joints[1].viscous_friction = damping;
  desc.default_pose = {theta0};
  Scene scene = z_up_scene("stiff_damper");
  const ActorHandle p = scene.create_articulated_actor(desc, "pendulum");
  const int steps = 400;  // 10 s
  double prev = theta0;
  for (int n = 0; n < steps; ++n) {
    scene.step(dt);
    const double q = scene.pose(p)[0];
    const double v = scene.joint_velocities(p)[0];
    ASSERT_TRUE(std::isfinite(q));
    // always moving down towards 0, never overshooting back
    EXPECT_LE(v, 0) << "step " << n;
    EXPECT_LE(q, prev) << "step " << n;
    EXPECT_GT(q, 0) << "step " << n;
    prev = q;
  }
  // overdamped limit D theta' = -m g L sin(theta): tan(theta/2) = tan(theta0/2) exp(-m g L t / D)
  const double t = steps * dt;
  const double expected = 2 * std::atan(std::tan(theta0 / 2) * std::exp(-kM * kG * kL * t / damping));
  EXPECT_NEAR(theta0 - prev, theta0 - expected, 0.01 * (theta0 - expected));
}

TEST_F(JointLimitsTest, CompliantLimitDeflectsByTorqueOverStiffness) {
  const double dt = 0.01, k = 500;
  ArticulationDesc desc = horizontal_arm();
  desc.joints[1].min_limit = Vec3(0, -0.2, 0);
  desc.joints[1].max_limit = Vec3(0, 0.3, 0);
  desc.joints[1].limit_stiffness = k;
  desc.joints[1].limit_damping = 30;
  // a constant torque pushing into the upper, then into the lower limit
  for (const auto& [torque, limit] : {std::pair{5.0, 0.3}, std::pair{-4.0, -0.2}}) {
    Scene scene = z_up_scene("compliant_limit");
    scene.set_gravity(Vec3::Zero());
    const ActorHandle arm = scene.create_articulated_actor(desc, "arm");
    scene.set_external_forces_on_dofs(arm, {0}, {real(torque)});
    for (int n = 0; n < 500; ++n) scene.step(dt);  // 5 s, many damped periods
    const double deflection = scene.pose(arm)[0] - limit;
    EXPECT_NEAR(deflection, torque / k, 0.05 * std::abs(torque / k)) << "torque " << torque;
    EXPECT_LT(std::abs(scene.joint_velocities(arm)[0]), 1e-6);
  }
}

TEST_F(JointLimitsTest, CompliantLimitHoldsGravityLoad) {
  const double dt = 0.01, k = 1000;
  ArticulationDesc desc = horizontal_arm();
  desc.joints[1].max_limit = Vec3(0, 0, 0);
  desc.joints[1].limit_stiffness = k;
  desc.joints[1].limit_damping = 40;
  Scene scene = z_up_scene("compliant_limit_gravity");
  const ActorHandle arm = scene.create_articulated_actor(desc, "arm");
  for (int n = 0; n < 500; ++n) scene.step(dt);
  // gravity torque m g L cos(delta) ~ m g L for the small deflection delta
  const double expected = kM * kG * kL / k;
  EXPECT_NEAR(scene.pose(arm)[0], expected, 0.05 * expected);
}

/// A horizontal two-link arm (gravity off): a shoulder about Z at the base and an elbow about Z
/// at the end of the upper arm, the elbow 1 mrad from each of its limits.
ArticulationDesc two_link_arm(real elbow) {
  ArticulationDesc desc;
  desc.name = "two_link";
  desc.links = {make_link("base", -1, 1, Vec3::Zero(), Vec3::Constant(real(0.01))),
                make_link("upper", 0, 1, Vec3(0.25, 0, 0), Vec3(0.001, 0.02, 0.02)),
                make_link("fore", 1, 1, Vec3(0.25, 0, 0), Vec3(0.001, 0.02, 0.02))};
  desc.joints = {make_joint("weld", JointType::Hard), make_joint("shoulder", JointType::Revolute, Vec3::UnitZ()),
                 make_joint("elbow", JointType::Revolute, Vec3::UnitZ(), Transform(Quat::Identity(), Vec3(0.5, 0, 0)))};
  desc.joints[2].min_limit = Vec3(0, 0, elbow - real(1e-3));
  desc.joints[2].max_limit = Vec3(0, 0, elbow + real(1e-3));
  desc.default_pose = {0, elbow};
  return desc;
}

// Limit rows that the free motion keeps far from acting are left out of the solve
// (ImplicitStepParams::defer_inactive_joint_limits). Here the elbow rests, so its free motion leaves
// both rows out; a stiff shoulder drive whips the arm, and the elbow's reaction in that solve
// would cross a limit: the island is solved again with the rows. The elbow must hold within its
// limits, and every step must equal the one that keeps all rows in the solve.
TEST_F(JointLimitsTest, DeferredLimitRowsGiveTheSameStepAsKeepingThemAll) {
  const real dt = real(0.01), elbow = real(0.4);
  // runs 0 and 1: every limit row in every solve, and deferred rows; run 2: no elbow limits
  std::array<std::vector<VecX>, 3> q, v;
  for (int run = 0; run < 3; ++run) {
    Scene scene = z_up_scene("arm_" + std::to_string(run));
    scene.set_gravity(Vec3::Zero());
    SolverParams params = scene.solver_params();
    params.implicit_step.defer_inactive_joint_limits = run == 1;
    scene.set_solver_params(params);
    ArticulationDesc desc = two_link_arm(elbow);
    if (run == 2) desc.joints[2].min_limit = desc.joints[2].max_limit = std::nullopt;
    const ActorHandle arm = scene.create_articulated_actor(desc, "arm");
    JointDrive drive;
    drive.damping = 200;
    for (int n = 0; n < 60; ++n) {
      // the shoulder's target speed reverses every 20 steps
      drive.target_velocity = (n / 20) % 2 == 0 ? 3 : -3;
      scene.set_joint_drive(arm, 0, drive);
      scene.step(dt);
      q[run].push_back(scene.pose(arm));
      v[run].push_back(scene.joint_velocities(arm));
      ASSERT_EQ(scene.solver_stats().convergence_status, ConvergenceStatus::Converged) << "run " << run << ", step " << n;
    }
  }
  const real tolerance = kUsesDoublePrecision ? real(1e-9) : real(2e-4);
  real free_elbow_swing = 0;
  for (size_t n = 0; n < q[0].size(); ++n) {
    EXPECT_NEAR((q[1][n] - q[0][n]).cwiseAbs().maxCoeff(), 0, tolerance) << "step " << n;
    EXPECT_NEAR((v[1][n] - v[0][n]).cwiseAbs().maxCoeff(), 0, 100 * tolerance) << "step " << n;
    // at its limits, up to the near-rigid compliance of the rows (the whip is violent)
    EXPECT_NEAR(q[1][n][1], elbow, real(0.02)) << "step " << n;
    free_elbow_swing = std::max(free_elbow_swing, std::abs(q[2][n][1] - elbow));
  }
  // without its limits the elbow swings far: the limits acted
  EXPECT_GT(free_elbow_swing, real(0.2)) << free_elbow_swing;
  EXPECT_GT(std::abs(q[1].back()[0]), real(0.5));
}

}  // namespace
}  // namespace superdex::physics::test
