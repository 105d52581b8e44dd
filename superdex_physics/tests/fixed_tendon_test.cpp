/// @file fixed_tendon_test.cpp
/// Fixed tendons (ArticulationDesc::fixed_tendons): a tendon spring on a slider oscillates about
/// rest / c at the analytic frequency sqrt(K c^2 / m); a tendon range stops a falling slider at
/// its bound and holds it there; a slider starting beyond a tendon's bound comes back no faster
/// than the depenetration bound; bad tendons name the field.

#include <gmock/gmock.h>

#include <numbers>

#include "solver/step_settings.h"
#include "superdex/physics/error.h"
#include "test_helpers.h"

namespace superdex::physics::test {
namespace {

constexpr double kMass = 2.0;

/// A slider of kMass along world x (or z), its tendon length c q.
ArticulationDesc slider(const Vec3& axis, double c) {
  ArticulationDesc desc = one_dof_desc(JointType::Prismatic, axis, kMass, Vec3::Zero(), Vec3::Constant(0.01));
  FixedTendon t;
  t.name = "t";
  t.joints = {"dof"};
  t.coefficients = {c};
  desc.fixed_tendons = {t};
  return desc;
}

class FixedTendonTest : public EngineTest {};

TEST_F(FixedTendonTest, SpringOscillatesAtTheAnalyticFrequency) {
  // K = 50 N/m on L = 2 q towards 0.2: equilibrium q = 0.1, omega = sqrt(K c^2 / m) = 10 rad/s
  const double K = 50, c = 2, rest = 0.2, dt = 1e-4;
  ArticulationDesc desc = slider(Vec3::UnitX(), c);
  desc.fixed_tendons[0].stiffness = K;
  desc.fixed_tendons[0].rest_length = rest;
  Scene scene = create_scene("tendon_spring");
  scene.set_gravity(Vec3::Zero());
  const ActorHandle s = scene.create_articulated_actor(desc, "slider");
  const double omega = std::sqrt(K * c * c / kMass), period = 2 * std::numbers::pi / omega;
  const int half = static_cast<int>(std::lround(period / 2 / dt));
  for (int n = 0; n < half; ++n) scene.step(dt);
  // q(t) = 0.1 (1 - cos(omega t)): at the far end after half a period (implicit Euler loses
  // amplitude as exp(-omega^2 dt t / 2): 1.6e-3 of it here)
  EXPECT_NEAR(scene.pose(s)[0], 0.2, 5e-4);
  for (int n = 0; n < half; ++n) scene.step(dt);
  EXPECT_NEAR(scene.pose(s)[0], 0.0, 1e-3);
  EXPECT_NEAR(scene.joint_velocities(s)[0], 0.0, 0.2 * omega * 1e-2);
}

TEST_F(FixedTendonTest, DampedSpringComesToRestAtRestOverC) {
  ArticulationDesc desc = slider(Vec3::UnitZ(), -4);
  desc.fixed_tendons[0].stiffness = 400;
  desc.fixed_tendons[0].damping = 40;
  desc.fixed_tendons[0].rest_length = 0.1;
  Scene scene = z_up_scene("tendon_damper");
  const ActorHandle s = scene.create_articulated_actor(desc, "slider");
  for (int n = 0; n < 2000; ++n) scene.step(0.005);
  // the tendon's force on the joint, c K (rest - c q), balances gravity -m g along z:
  // c q = rest - m g / (K c)
  const double c = -4, K = 400;
  EXPECT_NEAR(scene.pose(s)[0], (0.1 - kMass * kG / (K * c)) / c, 1e-9);
}

TEST_F(FixedTendonTest, RangeStopsAFallingSliderAtItsBound) {
  // L = -3 q <= 0.3: the slider falls until q = -0.1 and stays there
  ArticulationDesc desc = slider(Vec3::UnitZ(), -3);
  desc.fixed_tendons[0].has_upper = true;
  desc.fixed_tendons[0].upper = 0.3;
  Scene scene = z_up_scene("tendon_range");
  const ActorHandle s = scene.create_articulated_actor(desc, "slider");
  double lowest = 0;
  for (int n = 0; n < 500; ++n) {
    scene.step(0.002);
    lowest = std::min(lowest, scene.pose(s)[0]);
  }
  EXPECT_GT(lowest, -0.1 - 1e-3);
  EXPECT_NEAR(scene.pose(s)[0], -0.1, 1e-5);
  EXPECT_NEAR(scene.joint_velocities(s)[0], 0.0, 1e-6);
}

TEST_F(FixedTendonTest, SliderBeyondTheBoundReturnsAtTheDepenetrationSpeed) {
  ArticulationDesc desc = slider(Vec3::UnitX(), 1);
  desc.fixed_tendons[0].has_lower = true;
  desc.fixed_tendons[0].lower = 0.5;
  Scene scene = create_scene("tendon_beyond");
  scene.set_gravity(Vec3::Zero());
  const ActorHandle s = scene.create_articulated_actor(desc, "slider");
  const double bound = StepSettings{}.max_depenetration_speed;
  double fastest = 0;
  for (int n = 0; n < 100; ++n) {  // 0.2 s at 1 m/s: 0.2 of the 0.5 m
    scene.step(0.002);
    fastest = std::max(fastest, scene.joint_velocities(s)[0]);
  }
  EXPECT_LE(fastest, bound * (1 + 1e-9));
  EXPECT_NEAR(scene.pose(s)[0], 0.2, 1e-4);  // (the near-rigid row gives up 2.5e-4 of the speed)
  EXPECT_NEAR(scene.joint_velocities(s)[0], bound, 1e-3);
}

TEST_F(FixedTendonTest, BadTendonsNameTheField) {
  Scene scene = create_scene("bad_tendons");
  auto expect_error = [&](const ArticulationDesc& desc, const std::string& what) {
    try {
      scene.create_articulated_actor(desc, "slider");
      ADD_FAILURE() << "expected an error containing " << what;
    } catch (const superdex::Error& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr(what));
    }
  };
  ArticulationDesc desc = slider(Vec3::UnitX(), 1);
  desc.fixed_tendons[0].joints = {"weld"};
  expect_error(desc, "fixedTendons[0].joints[0]: joint 'weld' is Hard; tendons run over revolute and prismatic joints");
  desc = slider(Vec3::UnitX(), 1);
  desc.fixed_tendons[0].damping = -1;
  expect_error(desc, "fixedTendons[0].damping: must be a finite number >= 0, got -1");
  desc = slider(Vec3::UnitX(), 1);
  desc.fixed_tendons[0].has_lower = desc.fixed_tendons[0].has_upper = true;
  desc.fixed_tendons[0].lower = 1;
  expect_error(desc, "fixedTendons[0].range: lower (1) is above upper (0)");
  EXPECT_TRUE(scene.all_actors().empty());
}

}  // namespace
}  // namespace superdex::physics::test
