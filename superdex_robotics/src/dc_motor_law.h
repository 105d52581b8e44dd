#pragma once
// The DC motor's torque-speed law (DC_MOTOR), kept apart from the scene for testing.
//
// A permanent-magnet DC motor driven by a voltage-limited amplifier, behind a gearbox of
// ratio N (joint speed = motor speed / N, joint torque = N x motor torque, lossless):
//   motor speed      w_m = N v                       (v: joint velocity)
//   requested torque t_req = tau_req / N            (tau_req: joint torque wanted)
//   the voltage limit bounds the motor torque by the torque-speed line through the stall
//   torque t_s (at w_m = 0) and the no-load speed w_0 (at t = 0):
//       t_s (-1 - w_m / w_0) <= t_m <= t_s (1 - w_m / w_0)
//   (driving: at most t_s (1 - |w_m| / w_0); braking against the motion may exceed t_s,
//   as back-EMF adds to the applied voltage);
//   the current limit (saturation) bounds |t_m| <= torque_limit (< 0: none);
//   joint torque tau = N t_m.
// Rotor inertia is not part of this law: it is the joint's armature (N^2 J_rotor), added to
// the articulation when the actuator is declared in the bot file.

#include <algorithm>
#include <limits>

namespace superdex::robotics::motor {

struct DcMotorParams {
  double stall_torque = 1.0;    // N m at the motor shaft
  double no_load_speed = 10.0;  // rad/s at the motor shaft
  double gear_ratio = 1.0;      // motor turns per joint turn
  double torque_limit = -1.0;   // N m at the motor shaft (current limit), < 0: none
};

// The joint torque (N m) the motor delivers for a requested joint torque at joint velocity v.
inline double dc_motor_torque(const DcMotorParams& p, double tau_request, double v) {
  const double w_m = p.gear_ratio * v;
  const double t_req = tau_request / p.gear_ratio;
  const double upper = p.stall_torque * (1.0 - w_m / p.no_load_speed);
  const double lower = p.stall_torque * (-1.0 - w_m / p.no_load_speed);
  double t_m = std::clamp(t_req, lower, upper);
  if (p.torque_limit >= 0) t_m = std::clamp(t_m, -p.torque_limit, p.torque_limit);
  return p.gear_ratio * t_m;
}

}  // namespace superdex::robotics::motor
