/// @file pendulum_test.cpp
/// A physical pendulum (welded base + one revolute link about Y, COM a distance L below the
/// pivot) checked against the analytic small-amplitude period 2 pi sqrt(I_pivot / (m g L)),
/// which for a point mass reduces to 2 pi sqrt(L / g), and for energy conservation.

#include <vector>

#include "test_helpers.h"

namespace superdex::physics::test {
namespace {

constexpr double kL = 1.0;   // pivot-to-COM distance (m)
constexpr double kM = 1.0;   // mass (kg)
constexpr double kDt = 1e-3;

/// Pendulum with COM at (0, 0, -L) in the link frame and isotropic inertia `i_com` about the COM.
ActorHandle make_pendulum(Scene& scene, double i_com, double theta0) {
  ArticulationDesc desc = one_dof_desc(JointType::Revolute, Vec3::UnitY(), kM, Vec3(0, 0, -kL), Vec3::Constant(i_com));
  desc.default_pose = {theta0};
  return scene.create_articulated_actor(desc, "pendulum");
}

/// Period from linearly interpolated zero crossings of the joint angle over `duration` seconds.
double measure_period(Scene& scene, ActorHandle pendulum, double duration) {
  std::vector<double> crossings;
  double prev = scene.pose(pendulum)[0];
  const int steps = static_cast<int>(std::lround(duration / kDt));
  for (int n = 1; n <= steps; ++n) {
    scene.step(kDt);
    const double cur = scene.pose(pendulum)[0];
    if ((prev < 0) != (cur < 0)) crossings.push_back((n - 1) * kDt + kDt * prev / (prev - cur));
    prev = cur;
  }
  EXPECT_GE(crossings.size(), 8u);
  if (crossings.size() < 2) return 0;
  // consecutive crossings are half a period apart
  return 2 * (crossings.back() - crossings.front()) / double(crossings.size() - 1);
}

class PendulumTest : public EngineTest {};

TEST_F(PendulumTest, SmallAmplitudePeriodMatchesPhysicalPendulum) {
  Scene scene = z_up_scene("pendulum");
  const double i_com = 0.4 * kM * 0.05 * 0.05;  // a solid ball of radius 5 cm
  const double theta0 = 0.05;
  const ActorHandle p = make_pendulum(scene, i_com, theta0);
  const double i_pivot = i_com + kM * kL * kL;
  const double t_linear = 2 * kPi * std::sqrt(i_pivot / (kM * kG * kL));
  const double period = measure_period(scene, p, 5.3 * t_linear);
  EXPECT_NEAR(period, t_linear, 1e-3 * t_linear);
  // finite-amplitude series T0 (1 + theta0^2/16 + 11 theta0^4/3072): a much tighter check
  const double t_series = t_linear * (1 + theta0 * theta0 / 16 + 11 * std::pow(theta0, 4) / 3072);
  EXPECT_NEAR(period, t_series, 2e-5 * t_series);
}

TEST_F(PendulumTest, PointMassPeriodIsTwoPiSqrtLOverG) {
  Scene scene = z_up_scene("point_pendulum");
  const ActorHandle p = make_pendulum(scene, 1e-8, 0.05);
  const double t_point = 2 * kPi * std::sqrt(kL / kG);
  EXPECT_NEAR(measure_period(scene, p, 5.3 * t_point), t_point, 1e-3 * t_point);
}

TEST_F(PendulumTest, EnergyDriftBelowOnePercentOverTwentySeconds) {
  Scene scene = z_up_scene("pendulum_energy");
  const double i_com = 0.4 * kM * 0.05 * 0.05;
  const double theta0 = 0.5;
  const ActorHandle p = make_pendulum(scene, i_com, theta0);
  const ActorHandle arm = scene.nested_link_actors(p)[1];
  // kinetic 0.5 v^T M v plus potential m g z_com, with z_com from the link pose
  auto energy = [&] {
    const VecX v = scene.joint_velocities(p);
    const double kinetic = 0.5 * v.dot(scene.mass_matrix(p) * v);
    const Vec3 com_W = scene.root_transform(arm) * Vec3(0, 0, -kL);
    return kinetic + kM * kG * com_W.z();
  };
  const double e0 = energy();
  EXPECT_NEAR(e0, -kM * kG * kL * std::cos(theta0), 1e-12);
  // drift measured against the swing energy m g L (1 - cos theta0), stricter than |E|
  const double swing = kM * kG * kL * (1 - std::cos(theta0));
  double max_drift = 0;
  for (int n = 0; n < 20000; ++n) {
    scene.step(kDt);
    max_drift = std::max(max_drift, std::abs(energy() - e0));
  }
  EXPECT_LT(max_drift, 0.01 * swing);
}

}  // namespace
}  // namespace superdex::physics::test
