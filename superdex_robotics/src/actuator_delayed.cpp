// DELAYED: wraps another actuator type and delays the commands it receives.
//
// At each run at time t the wrapper records (t, command) and hands the inner actuator the
// latest command recorded at or before t - delay (none before the first such command). Only
// the command is delayed: the inner actuator still measures the joint's current state. With
// discrete steps the delay is realised at the first run at least `delay` after the command
// (to within 1/1000 of a step).
//
// Params
//   "inner"  {"type": "<actuator type>", "params": {...} or "<inline JSON>"}  required
//   "delay"  s, >= 0                                                         default 0
// configure accepts "delay" and {"inner": {"params": {...}}} (forwarded to the inner one).

#include <deque>

#include "builtin_support.h"
#include "builtins.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The inner's params as text: an object is written out, a string passed as it is.
std::string inner_params(const nlohmann::json& inner, const std::string& where) {
  if (!inner.contains("params") || inner.at("params").is_null()) return "";
  const auto& p = inner.at("params");
  if (p.is_object()) return p.dump();
  if (p.is_string()) return p.get<std::string>();
  throw Error(where + ".params: expected an object or a JSON string");
}

class DelayedActuator final : public ActuatorComponent {
 public:
  DelayedActuator(const Context& context, const ComponentArgs& args) {
    ComponentParams p(args.params, "DELAYED");
    if (!p.has("inner") || !p.json().at("inner").is_object())
      throw Error(p.at("inner") + ": required: {\"type\": <actuator type>, \"params\": {...}}");
    const auto& inner = p.json().at("inner");
    if (!inner.contains("type") || !inner.at("type").is_string())
      throw Error(p.at("inner") + ".type: required: the name of a registered actuator type");
    const std::string type = inner.at("type").get<std::string>();
    ComponentArgs inner_args = args;
    inner_args.params = inner_params(inner, p.at("inner"));
    std::unique_ptr<Component> made = context.construct(ComponentKind::Actuator, type, inner_args, "DELAYED inner '" + type + "'");
    auto* actuator = dynamic_cast<ActuatorComponent*>(made.get());
    if (!actuator || !made->takes_part_in_pipeline())
      throw Error(p.at("inner") + ".type: actuator type '" + type + "' does not take part in the pipeline");
    made.release();
    inner_.reset(actuator);
    configure_self(p);
  }

  void reset() override {
    history_.clear();
    inner_->reset();
  }

  void configure(const std::string& json) override {
    ComponentParams p(json, "DELAYED");
    if (p.has("inner")) {
      const auto& inner = p.json().at("inner");
      if (!inner.is_object() || inner.contains("type"))
        throw Error(p.at("inner") + ": only {\"params\": {...}} can be changed at run time (the type is fixed at creation)");
      inner_->configure(inner_params(inner, p.at("inner")));
    }
    configure_self(p);
  }

  real compute_effort(const Tick& tick, const DofCommand& command) override {
    history_.push_back({tick.time, command});
    // the latest command issued at least `delay` ago; older ones are no longer needed
    const double cutoff = tick.time - delay_ + 1e-3 * tick.step_dt;
    DofCommand delayed;
    while (!history_.empty() && history_.front().time <= cutoff) {
      if (history_.size() >= 2 && history_[1].time <= cutoff) {
        history_.pop_front();
        continue;
      }
      delayed = history_.front().command;
      break;
    }
    return inner_->compute_effort(tick, delayed);
  }

 private:
  void configure_self(const ComponentParams& p) {
    p.allow_only({"inner", "delay"});
    const real delay = p.number("delay", delay_);
    if (delay < 0) throw Error(p.at("delay") + ": must be >= 0 s");
    p.apply_rate(*this);
    delay_ = delay;
  }

  struct Entry {
    double time;
    DofCommand command;
  };
  std::unique_ptr<ActuatorComponent> inner_;
  std::deque<Entry> history_;
  double delay_ = 0;
};

}  // namespace

std::unique_ptr<Component> make_delayed_actuator(const Context& context, const ComponentArgs& args) {
  return std::make_unique<DelayedActuator>(context, args);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
