/// @file dc_motor_law_test.cpp
/// The DC_MOTOR's torque-speed law (dc_motor_law.h) at hand-computed operating points:
/// stall torque through the gearbox, the torque-speed line driving and braking, the no-load
/// speed, requests inside the envelope passed through, the current limit.

#include <gtest/gtest.h>

#include "dc_motor_law.h"

namespace superdex::robotics::test {
namespace {

using motor::dc_motor_torque;
using motor::DcMotorParams;

// stall 0.5 N m, no-load 100 rad/s at the motor, gear ratio 10
constexpr DcMotorParams kMotor{0.5, 100.0, 10.0, -1.0};

TEST(DcMotorLaw, StallTorqueThroughTheGearbox) {
  EXPECT_DOUBLE_EQ(dc_motor_torque(kMotor, 100.0, 0.0), 5.0);
  EXPECT_DOUBLE_EQ(dc_motor_torque(kMotor, -100.0, 0.0), -5.0);
}

TEST(DcMotorLaw, TorqueSpeedLine) {
  // joint 5 rad/s = motor 50 rad/s: driving at most 0.5 (1 - 0.5) = 0.25 N m -> 2.5 N m
  EXPECT_DOUBLE_EQ(dc_motor_torque(kMotor, 100.0, 5.0), 2.5);
  // braking against the motion: down to 0.5 (-1 - 0.5) = -0.75 N m -> -7.5 N m
  EXPECT_DOUBLE_EQ(dc_motor_torque(kMotor, -100.0, 5.0), -7.5);
  // turning backwards, pushing forwards: up to 0.5 (1 + 0.5) -> 7.5 N m
  EXPECT_DOUBLE_EQ(dc_motor_torque(kMotor, 100.0, -5.0), 7.5);
  // at the no-load speed (10 rad/s at the joint) it cannot push forwards any more
  EXPECT_DOUBLE_EQ(dc_motor_torque(kMotor, 100.0, 10.0), 0.0);
}

TEST(DcMotorLaw, RequestsInsideTheEnvelopePass) {
  EXPECT_DOUBLE_EQ(dc_motor_torque(kMotor, 1.0, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(dc_motor_torque(kMotor, -2.0, 2.0), -2.0);
}

TEST(DcMotorLaw, CurrentLimit) {
  DcMotorParams limited = kMotor;
  limited.torque_limit = 0.2;
  EXPECT_DOUBLE_EQ(dc_motor_torque(limited, 100.0, 0.0), 2.0);
  EXPECT_DOUBLE_EQ(dc_motor_torque(limited, -100.0, 5.0), -2.0);
  // the torque-speed line still applies below the current limit: 0.5 (1 - 0.9) = 0.05 N m
  EXPECT_NEAR(dc_motor_torque(limited, 100.0, 9.0), 0.5, 1e-12);
}

}  // namespace
}  // namespace superdex::robotics::test
