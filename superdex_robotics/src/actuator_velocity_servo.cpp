// VELOCITY_SERVO: the seed's velocity-controlled servo (PI law with profile acceleration and
// anti-windup by clamping: velocity_servo_law.h). Its goal is the DOF's velocity command
// (0 when none); it runs at its rate with dt = the time since its last run.
//
// Params
//   "k_p"            N m/(rad/s)   default 1.0
//   "k_i"            N m/rad       default 0.3
//   "effort_limit"   N m           default 1.0 (the torque at 100 % PWM)
//   "profile_accel"  rad/s^2       default 0 (no smoothing)

#include "builtin_support.h"
#include "builtins.h"
#include "velocity_servo_law.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

class VelocityServoActuator final : public ActuatorComponent {
 public:
  explicit VelocityServoActuator(const ComponentArgs& args) : dof_(args.scene, args.actor, "VELOCITY_SERVO") {
    configure(args.params);
  }

  void reset() override { law_.reset(); }

  void configure(const std::string& json) override {
    ComponentParams p(json, "VELOCITY_SERVO");
    p.allow_only({"k_p", "k_i", "effort_limit", "profile_accel"});
    servo::VelocityServoParams next = law_.params;
    next.k_p = p.number("k_p", next.k_p);
    next.k_i = p.number("k_i", next.k_i);
    next.effort_limit = p.number("effort_limit", next.effort_limit);
    next.profile_accel = p.number("profile_accel", next.profile_accel);
    if (next.effort_limit < 0) throw Error(p.at("effort_limit") + ": must be >= 0");
    p.apply_rate(*this);
    law_.params = next;
  }

  real compute_effort(const Tick& tick, const DofCommand& command) override {
    return static_cast<real>(law_.step(command.velocity.value_or(0), dof_.velocity(), tick.dt));
  }

 private:
  ActuatedDof dof_;
  servo::VelocityServoLaw law_;
};

}  // namespace

std::unique_ptr<Component> make_velocity_servo_actuator(const ComponentArgs& args) {
  return std::make_unique<VelocityServoActuator>(args);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
