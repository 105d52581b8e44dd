/// @file free_fall_test.cpp
/// A dynamic rigid sphere thrown upwards must follow x0 + v0 t - g t^2 / 2, with an error
/// that is first order in dt (symplectic Euler: exactly g t dt / 2 for constant gravity).
/// A spinning free body with an offset COM, without gravity, must move its COM uniformly
/// and keep its world angular momentum, up to first-order integration error.

#include "test_helpers.h"

namespace superdex::physics::test {
namespace {

constexpr double kX0 = 10.0;  // initial height (m)
constexpr double kV0 = 3.0;   // initial upward speed (m/s)
constexpr double kT = 1.0;    // simulated time (s)

/// |simulated height - analytic height| after kT seconds at step dt.
double height_error(double dt) {
  Scene scene = z_up_scene("free_fall");
  const ShapeHandle ball = create_shape(SphereShape{Vec3::Zero(), real(0.1)});
  Transform X_WL;
  X_WL.translation = Vec3(0, 0, kX0);
  const ActorHandle body = scene.create_rigid_actor(rigid_params("ball", ball, X_WL));
  scene.set_velocity(body, Vec3(0, 0, kV0), Vec3::Zero());
  const int steps = static_cast<int>(std::lround(kT / dt));
  for (int n = 0; n < steps; ++n) scene.step(dt);
  const Vec3 p = scene.root_transform(body).translation;
  // no horizontal motion
  EXPECT_NEAR(p.x(), 0, 1e-12);
  EXPECT_NEAR(p.y(), 0, 1e-12);
  return std::abs(p.z() - (kX0 + kV0 * kT - 0.5 * kG * kT * kT));
}

class FreeFallTest : public EngineTest {};

TEST_F(FreeFallTest, HeightMatchesBallisticWithinHalfPercentOfTravel) {
  // path length: up to the apex at v0 / g, then down to the final height
  const double apex_rise = kV0 * kV0 / (2 * kG);
  const double net = kV0 * kT - 0.5 * kG * kT * kT;
  const double travelled = apex_rise + (apex_rise - net);
  EXPECT_LT(height_error(1e-3), 0.005 * travelled);
}

TEST_F(FreeFallTest, ErrorIsFirstOrderInDt) {
  const double e1 = height_error(1e-3);
  const double e2 = height_error(0.5e-3);
  EXPECT_GT(e1, 0);
  EXPECT_LE(e2, 0.5 * e1 * (1 + 1e-6));
}

TEST_F(FreeFallTest, VelocityFollowsGravity) {
  Scene scene = z_up_scene("free_fall_velocity");
  const ShapeHandle ball = create_shape(SphereShape{Vec3::Zero(), real(0.1)});
  const ActorHandle body = scene.create_rigid_actor(rigid_params("ball", ball));
  scene.set_velocity(body, Vec3(1, 0, kV0), Vec3::Zero());
  for (int n = 0; n < 1000; ++n) scene.step(1e-3);
  // v(t) = v0 + g t exactly for any first-order integrator with constant force
  const Vec6 v = scene.velocity(body);
  EXPECT_NEAR(v[0], 1, 1e-12);
  EXPECT_NEAR(v[2], kV0 - kG * kT, 1e-9);
}

/// Torque-free body whose COM is off the link origin; returns the COM error after 2 s and
/// the relative change of the world angular momentum about the COM.
void spin(double dt, double& com_error, double& momentum_change, double& travelled) {
  const Vec3 com_L(0.3, -0.1, 0.2), inertia(0.1, 0.2, 0.3);
  ArticulationDesc desc;
  desc.name = "spinner";
  desc.links = {make_link("body", -1, 2.0, com_L, inertia)};
  desc.joints = {make_joint("free", JointType::Free)};
  Scene scene = create_scene("spin");
  scene.set_gravity(Vec3::Zero());
  const ActorHandle body = scene.create_articulated_actor(desc, "spinner");
  scene.set_velocity(body, Vec3(0.5, 0, 0), Vec3(1.0, 2.0, -0.5));
  auto com = [&] { return Vec3(scene.root_transform(body) * com_L); };
  // COM velocity (Scene::velocity reports the centre of mass's) and angular momentum R I R^T w,
  // from the reported state
  auto com_velocity = [&] { return Vec3(scene.velocity(body).head<3>()); };
  auto momentum = [&] {
    const Mat3 R = scene.root_transform(body).rotation.toRotationMatrix();
    return Vec3(R * inertia.asDiagonal() * R.transpose() * scene.velocity(body).tail<3>());
  };
  const Vec3 c0 = com(), vc0 = com_velocity(), h0 = momentum();
  const double t = 2.0;
  const int steps = static_cast<int>(std::lround(t / dt));
  for (int n = 0; n < steps; ++n) scene.step(dt);
  com_error = (com() - (c0 + t * vc0)).norm();
  momentum_change = (momentum() - h0).norm() / h0.norm();
  travelled = t * vc0.norm();
}

TEST_F(FreeFallTest, SpinningBodyMovesComUniformlyAndKeepsAngularMomentum) {
  double e1, h1, d1, e2, h2, d2;
  spin(1e-3, e1, h1, d1);
  spin(0.5e-3, e2, h2, d2);
  EXPECT_LT(e1, 0.01 * d1);
  EXPECT_LT(h1, 0.01);
  // both errors are integration errors: first order in dt
  EXPECT_NEAR(e2 / e1, 0.5, 0.05);
  EXPECT_NEAR(h2 / h1, 0.5, 0.05);
}

}  // namespace
}  // namespace superdex::physics::test
