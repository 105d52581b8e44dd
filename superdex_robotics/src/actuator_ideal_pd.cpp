// IDEAL_PD: an ideal actuator with a PD position/velocity loop and effort feed-forward.
//
//   tau = effort_cmd + kp (q_cmd - q) + kd (v_cmd - v),  |tau| <= effort_limit (< 0: none)
// A term whose command is absent is dropped, except that v_cmd defaults to 0 (kd damps) and
// q_cmd to default_position where given (a servo that holds a set point until commanded, as
// MuJoCo's position actuators hold ctrl = 0). With kp = kd = 0 it passes the effort command through.
//
// Params
//   "kp"                N m/rad (N/m)        default 0
//   "kd"                N m s/rad (N s/m)    default 0
//   "effort_limit"      N m (N), < 0: none   default -1
//   "default_position"  rad (m)              default none: no position term until commanded

#include <algorithm>
#include <optional>

#include "builtin_support.h"
#include "builtins.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

class IdealPdActuator final : public ActuatorComponent {
 public:
  explicit IdealPdActuator(const ComponentArgs& args) : dof_(args.scene, args.actor, "IDEAL_PD") { configure(args.params); }

  void reset() override {}

  void configure(const std::string& json) override {
    ComponentParams p(json, "IDEAL_PD");
    p.allow_only({"kp", "kd", "effort_limit", "default_position"});
    p.apply_rate(*this);
    kp_ = p.number("kp", kp_);
    kd_ = p.number("kd", kd_);
    effort_limit_ = p.number("effort_limit", effort_limit_);
    if (p.has("default_position")) default_position_ = p.number("default_position", 0);
  }

  real compute_effort(const Tick&, const DofCommand& command) override {
    real tau = command.effort.value_or(0);
    if (const std::optional<real> q_cmd = command.position ? command.position : default_position_) tau += kp_ * (*q_cmd - dof_.position());
    if (kd_ != 0) tau += kd_ * (command.velocity.value_or(0) - dof_.velocity());
    return effort_limit_ >= 0 ? std::clamp(tau, -effort_limit_, effort_limit_) : tau;
  }

 private:
  ActuatedDof dof_;
  real kp_ = 0, kd_ = 0, effort_limit_ = -1;
  std::optional<real> default_position_;
};

}  // namespace

std::unique_ptr<Component> make_ideal_pd_actuator(const ComponentArgs& args) { return std::make_unique<IdealPdActuator>(args); }

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
