// The per-bot pipeline run inside Scene::step (order and ownership rules: context.h).

#include "bot_pipeline.h"

#include <algorithm>
#include <cmath>

#include "superdex/physics/error.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// Counts a running callback for as long as it is in scope (exceptions included).
struct RunningScope {
  int& count;
  explicit RunningScope(int& c) : count(c) { ++count; }
  ~RunningScope() { --count; }
};

// A step's dt fraction below which two scene times count as equal (scene time accumulates
// the step's dt, in float in the float build).
constexpr double kTimeTolerance = 1e-3;

}  // namespace

bool BotPipeline::Timer::due(double t, double rate, real step_dt) const {
  if (rate <= 0 || last_run < 0) return true;
  return t >= next_due - kTimeTolerance * step_dt;
}

real BotPipeline::Timer::run(double t, double rate, real step_dt) {
  const double period = rate > 0 ? 1.0 / rate : 0.0;
  const real dt = last_run < 0 ? static_cast<real>(period > 0 ? period : step_dt) : static_cast<real>(t - last_run);
  // drift-free schedule: the next run is one period after the previous due time
  if (period > 0) {
    next_due = (last_run < 0 ? t : next_due) + period;
    if (next_due <= t) next_due = t + period;
  }
  last_run = t;
  return dt;
}

BotPipeline::BotPipeline(Context& context, BotHandle bot, Scene scene, ActorHandle articulation)
    : context_(&context), bot_(bot), scene_(scene), articulation_(articulation) {
  const std::string base = "superdex.robotics.bot" + std::to_string(bot) + ".pipeline";
  pre_name_ = base + ".pre";
  post_name_ = base + ".post";
}

void BotPipeline::reset_timing() {
  for (auto& c : controllers_) c.timer = {}, c.held.clear(0);
  for (auto& a : actuators_) a.timer = {}, a.held = 0;
  for (auto& s : sensors_) s.timer = {};
  steps_ = 0;
}

void BotPipeline::refresh() {
  // keeps the timers and held outputs of the members that remain
  auto keep = [](auto& old, ComponentHandle h) -> decltype(&old[0]) {
    for (auto& slot : old)
      if (slot.handle == h) return &slot;
    return nullptr;
  };
  std::vector<ControllerSlot> controllers;
  for (ComponentHandle h : context_->attached_components(ComponentKind::Controller, bot_)) {
    Component* impl = context_->component(ComponentKind::Controller, h).impl.get();
    auto* c = dynamic_cast<ControllerComponent*>(impl);
    if (!c || !impl->takes_part_in_pipeline()) continue;
    const ControllerSlot* old = keep(controllers_, h);
    controllers.push_back(old ? *old : ControllerSlot{h, c, {}, {}});
  }
  std::vector<ActuatorSlot> actuators;
  for (ComponentHandle h : context_->attached_components(ComponentKind::Actuator, bot_)) {
    const ComponentRecord& rec = context_->component(ComponentKind::Actuator, h);
    auto* a = dynamic_cast<ActuatorComponent*>(rec.impl.get());
    if (!a || !rec.impl->takes_part_in_pipeline() || rec.dof < 0) continue;
    const ActuatorSlot* old = keep(actuators_, h);
    actuators.push_back(old ? *old : ActuatorSlot{h, a, rec.dof, {}, 0});
  }
  std::vector<SensorSlot> sensors;
  for (ComponentHandle h : context_->attached_components(ComponentKind::Sensor, bot_)) {
    Component* impl = context_->component(ComponentKind::Sensor, h).impl.get();
    auto* s = dynamic_cast<SensorComponent*>(impl);
    if (!s || !impl->takes_part_in_pipeline()) continue;
    const SensorSlot* old = keep(sensors_, h);
    sensors.push_back(old ? *old : SensorSlot{h, s, {}});
  }
  controllers_ = std::move(controllers);
  actuators_ = std::move(actuators);
  sensors_ = std::move(sensors);
  stale_ = false;
}

void BotPipeline::pre_step(real dt) {
  if (!context_ || !scene_.has_actor(articulation_)) return;
  if (stale_) refresh();
  RunningScope scope(running_);
  const double t = scene_.total_simulation_time();
  const int nv = scene_.num_dofs(articulation_);

  // 1. controllers due now write their commands; the others hold theirs
  for (ControllerSlot& c : controllers_) {
    const double rate = c.impl->rate();
    if (c.held.size() != nv) c.held.clear(nv);
    if (!c.timer.due(t, rate, dt)) continue;
    const Tick tick{t, c.timer.run(t, rate, dt), dt, steps_};
    c.held.clear(nv);
    c.impl->compute(tick, c.held);
    if (!context_) return;  // the context stopped this pipeline from inside the component
  }
  merged_.clear(nv);
  for (const ControllerSlot& c : controllers_) merged_.merge(c.held);

  // 2. actuators due now turn their DOF's command into an effort
  for (ActuatorSlot& a : actuators_) {
    const double rate = a.impl->rate();
    if (!a.timer.due(t, rate, dt)) continue;
    const Tick tick{t, a.timer.run(t, rate, dt), dt, steps_};
    const real effort = a.impl->compute_effort(tick, merged_.at(a.dof));
    if (!context_) return;
    if (!std::isfinite(effort)) {
      const ComponentRecord& rec = context_->component(ComponentKind::Actuator, a.handle);
      throw Error("pipeline of bot " + std::to_string(bot_) + ": actuator '" + rec.name + "' (type " + rec.type +
                  ") returned a non-finite effort for DOF " + std::to_string(a.dof));
    }
    a.held = effort;
  }
  ++steps_;
  if (controllers_.empty() && actuators_.empty()) return;

  // 3. generalized forces: actuator efforts, and commanded efforts on DOFs without an actuator
  std::vector<real>& tau = tau_;
  std::vector<std::uint8_t>& driven = driven_;
  tau.assign(nv, 0);
  driven.assign(nv, 0);
  for (const ActuatorSlot& a : actuators_) tau[a.dof] += a.held, driven[a.dof] = 1;
  for (int d = 0; d < nv; ++d)
    if (!driven[d] && merged_.has_effort[d]) tau[d] += merged_.effort[d];
  if (static_cast<int>(all_dofs_.size()) != nv) {
    all_dofs_.resize(nv);
    for (int d = 0; d < nv; ++d) all_dofs_[d] = d;
  }
  scene_.set_external_forces_on_dofs(articulation_, all_dofs_, tau);
  wrote_forces_ = true;
}

void BotPipeline::post_step(real dt) {
  if (!context_ || !scene_.has_actor(articulation_)) return;
  if (stale_) refresh();
  RunningScope scope(running_);
  const double t = scene_.total_simulation_time();
  for (SensorSlot& s : sensors_) {
    const double rate = s.impl->rate();
    if (!s.timer.due(t, rate, dt)) continue;
    const Tick tick{t, s.timer.run(t, rate, dt), dt, std::max<std::int64_t>(0, steps_ - 1)};
    s.impl->update(tick);
    if (!context_) return;
  }
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
