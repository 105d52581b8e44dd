#pragma once
// The velocity servo's PI law (VELOCITY_SERVO), kept apart from the scene so that it can be
// tested against hand-computed sequences. It is the seed's MyVelocityServoActuator exactly:
//
//   w_traj <- w_traj + clip(w_goal - w_traj, -profile_accel dt, +profile_accel dt)
//             (w_traj = w_goal when profile_accel <= 0: no smoothing)
//   e = w_traj - w_present
//   integral_next = integral + e dt
//   effort_unsat = k_p e + k_i integral_next
//   effort = clip(effort_unsat, -effort_limit, effort_limit)
//   anti-windup by clamping: integral = integral_next only when effort == effort_unsat (not
//   saturated) or e * effort_unsat < 0 (the error pulls the output back out of saturation).
//
// Computed in double whatever the build's `real`, like the seed's Python floats.

#include <algorithm>

namespace superdex::robotics::servo {

struct VelocityServoParams {
  double k_p = 1.0;            // N m / (rad/s)
  double k_i = 0.3;            // N m / rad
  double effort_limit = 1.0;   // N m, the torque at 100 % PWM
  double profile_accel = 0.0;  // rad/s^2, 0: no smoothing
};

struct VelocityServoLaw {
  VelocityServoParams params;
  double integral = 0;  // integral of the error (rad)
  double w_traj = 0;    // profiled velocity target (rad/s)

  void reset() { integral = 0, w_traj = 0; }

  // One update: the effort (N m) for goal and measured velocities (rad/s) over dt seconds.
  double step(double w_goal, double w_present, double dt) {
    w_traj = ramp_toward(w_goal, dt);
    const double e = w_traj - w_present;
    const double integral_next = integral + e * dt;
    const double effort_unsat = params.k_p * e + params.k_i * integral_next;
    const double effort = std::clamp(effort_unsat, -params.effort_limit, params.effort_limit);
    if (effort == effort_unsat || e * effort_unsat < 0) integral = integral_next;
    return effort;
  }

 private:
  double ramp_toward(double goal, double dt) const {
    if (params.profile_accel <= 0) return goal;
    const double max_step = params.profile_accel * dt;
    return w_traj + std::clamp(goal - w_traj, -max_step, max_step);
  }
};

}  // namespace superdex::robotics::servo
