/// @file velocity_servo_law_test.cpp
/// The VELOCITY_SERVO's PI law (velocity_servo_law.h) against sequences computed by hand from
/// the seed's MyVelocityServoActuator: saturation, anti-windup by clamping (the integrator
/// freezes while saturated unless the error pulls the output back), the profile ramp, reset.

#include <gtest/gtest.h>

#include "velocity_servo_law.h"

namespace superdex::robotics::test {
namespace {

using servo::VelocityServoLaw;

TEST(VelocityServoLaw, SaturatesAndFreezesTheIntegratorWhileSaturated) {
  VelocityServoLaw law;
  law.params = {2.0, 10.0, 1.0, 0.0};  // k_p, k_i, effort_limit, profile_accel
  const double dt = 0.1;
  // step 1: e = 1, integral_next = 0.1, unsat = 2 + 1 = 3 -> 1, saturated in the error's
  // direction: the integral stays 0
  EXPECT_DOUBLE_EQ(law.step(1.0, 0.0, dt), 1.0);
  EXPECT_DOUBLE_EQ(law.integral, 0.0);
  // step 2: e = 0.4, unsat = 0.8 + 10 x 0.04 = 1.2 -> 1, still frozen
  EXPECT_DOUBLE_EQ(law.step(1.0, 0.6, dt), 1.0);
  EXPECT_DOUBLE_EQ(law.integral, 0.0);
  // step 3: e = 0.1, unsat = 0.2 + 10 x 0.01 = 0.3: unsaturated, the integral commits
  EXPECT_NEAR(law.step(1.0, 0.9, dt), 0.3, 1e-15);
  EXPECT_NEAR(law.integral, 0.01, 1e-15);
  // step 4: e = -0.2, integral_next = -0.01, unsat = -0.4 - 0.1 = -0.5
  EXPECT_NEAR(law.step(1.0, 1.2, dt), -0.5, 1e-15);
  EXPECT_NEAR(law.integral, -0.01, 1e-15);
  // step 5: e = -0.5, unsat = -1.0 - 0.6 = -1.6 -> -1, saturated: integral stays -0.01
  EXPECT_DOUBLE_EQ(law.step(1.0, 1.5, dt), -1.0);
  EXPECT_NEAR(law.integral, -0.01, 1e-15);
}

TEST(VelocityServoLaw, IntegratorUnwindsWhenTheErrorPullsOutOfSaturation) {
  VelocityServoLaw law;
  law.params = {2.0, 10.0, 1.0, 0.0};
  law.integral = 0.5;  // wound up
  // e = -0.1, integral_next = 0.49, unsat = -0.2 + 4.9 = 4.7 -> 1 (saturated), but
  // e * unsat < 0: the integrator commits and unwinds
  EXPECT_DOUBLE_EQ(law.step(1.0, 1.1, 0.1), 1.0);
  EXPECT_NEAR(law.integral, 0.49, 1e-15);
}

TEST(VelocityServoLaw, ProfileAccelerationRampsTheTarget) {
  VelocityServoLaw law;
  law.params = {1.0, 0.0, 100.0, 5.0};  // effort = w_traj when w_present = 0
  const double dt = 0.1;                // ramp steps of 0.5 rad/s
  for (double expected : {0.5, 1.0, 1.5, 2.0, 2.0}) EXPECT_NEAR(law.step(2.0, 0.0, dt), expected, 1e-15);
  for (double expected : {1.5, 1.0, 0.5, 0.0, -0.5, -1.0, -1.0}) EXPECT_NEAR(law.step(-1.0, 0.0, dt), expected, 1e-15);
  // no smoothing when profile_accel <= 0
  law.params.profile_accel = 0;
  EXPECT_DOUBLE_EQ(law.step(3.0, 0.0, dt), 3.0);
}

TEST(VelocityServoLaw, ResetClearsIntegratorAndProfile) {
  VelocityServoLaw law;
  law.params = {1.0, 1.0, 10.0, 1.0};
  law.step(5.0, 0.0, 0.5);
  law.step(5.0, 0.0, 0.5);
  ASSERT_NE(law.integral, 0.0);
  ASSERT_NE(law.w_traj, 0.0);
  law.reset();
  EXPECT_EQ(law.integral, 0.0);
  EXPECT_EQ(law.w_traj, 0.0);
}

}  // namespace
}  // namespace superdex::robotics::test
