// DC_MOTOR: a geared permanent-magnet DC motor (law and what it models: dc_motor_law.h).
//
// The torque requested at the joint is
//   tau_req = effort_cmd + kp (q_cmd - q) + kd (v_cmd - v)
// (absent commands drop their term, v_cmd defaults to 0; kp = kd = 0 by default, so the
// effort command is the torque request), and the motor delivers what its torque-speed line
// and current limit allow. The rotor inertia "armature" (kg m^2, motor side) is reflected to
// the joint as gear_ratio^2 * armature and added to the joint's armature by create_bot when
// the actuator is declared in the bot file (an actuator created later cannot change the
// articulation: its armature is then not modelled).
//
// Params
//   "stall_torque"   N m, motor side, > 0        default 1
//   "no_load_speed"  rad/s, motor side, > 0      default 10
//   "gear_ratio"     > 0                          default 1
//   "torque_limit"   N m, motor side, < 0: none   default -1 (current limit, saturation)
//   "armature"       kg m^2, rotor, >= 0          default 0
//   "kp", "kd"       N m/rad, N m s/rad (joint)   default 0

#include "builtin_support.h"
#include "builtins.h"
#include "dc_motor_law.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

struct DcMotorSettings {
  motor::DcMotorParams law;
  double armature = 0;
  double kp = 0, kd = 0;

  void apply(const ComponentParams& p) {
    p.allow_only({"stall_torque", "no_load_speed", "gear_ratio", "torque_limit", "armature", "kp", "kd"});
    law.stall_torque = p.number("stall_torque", law.stall_torque);
    law.no_load_speed = p.number("no_load_speed", law.no_load_speed);
    law.gear_ratio = p.number("gear_ratio", law.gear_ratio);
    law.torque_limit = p.number("torque_limit", law.torque_limit);
    armature = p.number("armature", armature);
    kp = p.number("kp", kp), kd = p.number("kd", kd);
    if (!(law.stall_torque > 0)) throw Error(p.at("stall_torque") + ": must be > 0");
    if (!(law.no_load_speed > 0)) throw Error(p.at("no_load_speed") + ": must be > 0");
    if (!(law.gear_ratio > 0)) throw Error(p.at("gear_ratio") + ": must be > 0");
    if (armature < 0) throw Error(p.at("armature") + ": must be >= 0");
  }
};

class DcMotorActuator final : public ActuatorComponent {
 public:
  explicit DcMotorActuator(const ComponentArgs& args) : dof_(args.scene, args.actor, "DC_MOTOR") { configure(args.params); }

  void reset() override {}

  void configure(const std::string& json) override {
    ComponentParams p(json, "DC_MOTOR");
    DcMotorSettings next = settings_;
    next.apply(p);
    p.apply_rate(*this);
    settings_ = next;
  }

  real compute_effort(const Tick&, const DofCommand& command) override {
    const double v = dof_.velocity();
    double tau_req = command.effort.value_or(0);
    if (command.position) tau_req += settings_.kp * (*command.position - dof_.position());
    if (settings_.kd != 0) tau_req += settings_.kd * (command.velocity.value_or(0) - v);
    return static_cast<real>(motor::dc_motor_torque(settings_.law, tau_req, v));
  }

 private:
  ActuatedDof dof_;
  DcMotorSettings settings_;
};

}  // namespace

std::unique_ptr<Component> make_dc_motor_actuator(const ComponentArgs& args) { return std::make_unique<DcMotorActuator>(args); }

real dc_motor_armature(const std::string& params) {
  DcMotorSettings s;
  s.apply(ComponentParams(params, "DC_MOTOR"));
  return static_cast<real>(s.law.gear_ratio * s.law.gear_ratio * s.armature);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
