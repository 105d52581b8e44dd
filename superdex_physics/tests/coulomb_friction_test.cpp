/// @file coulomb_friction_test.cpp
/// Coulomb joint friction on a horizontal prismatic joint (gravity perpendicular to it):
/// a force below the friction bound F_c leaves the slider (nearly) stuck, a force above it
/// accelerates the slider at (F - F_c) / m.

#include "test_helpers.h"

namespace superdex::physics::test {
namespace {

constexpr double kM = 2.0;    // slider mass (kg)
constexpr double kFc = 10.0;  // Coulomb friction bound (N)
constexpr double kDt = 1e-3;

class CoulombFrictionTest : public EngineTest {
 protected:
  /// Slider along world X with friction kFc, pushed by `force` for 1 s; returns its DOF-0 state.
  void push(double force, double& x, double& v) {
    ArticulationDesc desc = one_dof_desc(JointType::Prismatic, Vec3::UnitX(), kM, Vec3::Zero(), Vec3::Constant(real(0.01)));
    desc.joints[1].coulomb_friction = kFc;
    Scene scene = z_up_scene("slider");
    const ActorHandle slider = scene.create_articulated_actor(desc, "slider");
    scene.set_external_forces_on_dofs(slider, {0}, {real(force)});
    for (int n = 0; n < 1000; ++n) scene.step(kDt);
    x = scene.pose(slider)[0];
    v = scene.joint_velocities(slider)[0];
  }
};

TEST_F(CoulombFrictionTest, ForceBelowBoundOnlyCreeps) {
  for (double force : {5.0, -9.0}) {
    double x = 0, v = 0;
    push(force, x, v);
    EXPECT_LT(std::abs(x), 1e-4) << "force " << force;
  }
}

TEST_F(CoulombFrictionTest, ForceAboveBoundAcceleratesAtNetForceOverMass) {
  for (double force : {15.0, -25.0}) {
    double x = 0, v = 0;
    push(force, x, v);
    const double a = (force - std::copysign(kFc, force)) / kM;
    // after 1 s from rest: v = a t
    EXPECT_NEAR(v / 1.0, a, 0.01 * std::abs(a)) << "force " << force;
    // and x = a t^2 / 2 up to the first-order integration error a t dt / 2
    EXPECT_NEAR(x, 0.5 * a, 0.01 * std::abs(0.5 * a)) << "force " << force;
  }
}

}  // namespace
}  // namespace superdex::physics::test
