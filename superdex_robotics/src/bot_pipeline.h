#pragma once
// One bot's pipeline: runs its controllers, actuators (before the step) and sensors (after it)
// from the scene's step callbacks, at their rates, and applies the resulting generalized
// forces. Owned jointly by the bot record and the scene callbacks (a shared_ptr captured by
// both), so that a callback being run never outlives its pipeline; the context detaches it
// (turning its callbacks into no-ops) before the components it points to go away.

#include <memory>
#include <string>
#include <vector>

#include "superdex/robotics/context.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class BotPipeline {
 public:
  BotPipeline(Context& context, BotHandle bot, Scene scene, ActorHandle articulation);

  // names of its scene callbacks
  const std::string& pre_name() const { return pre_name_; }
  const std::string& post_name() const { return post_name_; }
  // the scene callbacks that run it
  void set_callbacks(physics::CallbackHandle pre, physics::CallbackHandle post) { pre_callback_ = pre, post_callback_ = post; }
  physics::CallbackHandle pre_callback() const { return pre_callback_; }
  physics::CallbackHandle post_callback() const { return post_callback_; }
  // controllers and actuators, then the forces (pre-step callback)
  void pre_step(real dt);
  // sensors (post-step callback)
  void post_step(real dt);

  // the context stops using it: its callbacks do nothing from now on
  void detach() { context_ = nullptr; }
  // components were created or destroyed: rebuild the member lists before the next run
  void invalidate() { stale_ = true; }
  // forget held outputs and restart every component's rate timer
  void reset_timing();
  // true while one of its callbacks runs components
  bool running() const { return running_ > 0; }
  // true once it has applied generalized forces
  bool wrote_forces() const { return wrote_forces_; }

 private:
  // When a component is due, at its rate.
  struct Timer {
    double last_run = -1;  // scene time of the last run (s), < 0 before the first
    double next_due = 0;   // scene time at which it is due again (s)
    bool due(double t, double rate, real step_dt) const;
    // marks a run at t; returns the time since the previous run (its dt)
    real run(double t, double rate, real step_dt);
  };
  struct ControllerSlot {
    ComponentHandle handle;
    ControllerComponent* impl;
    Timer timer;
    DofCommands held;  // its last commands
  };
  struct ActuatorSlot {
    ComponentHandle handle;
    ActuatorComponent* impl;
    int dof;
    Timer timer;
    real held = 0;  // its last effort
  };
  struct SensorSlot {
    ComponentHandle handle;
    SensorComponent* impl;
    Timer timer;
  };

  void refresh();

  Context* context_;
  BotHandle bot_;
  Scene scene_;
  ActorHandle articulation_;
  std::string pre_name_, post_name_;
  physics::CallbackHandle pre_callback_, post_callback_;
  bool stale_ = true;
  int running_ = 0;
  bool wrote_forces_ = false;
  std::int64_t steps_ = 0;  // pre-steps run
  std::vector<ControllerSlot> controllers_;
  std::vector<ActuatorSlot> actuators_;
  std::vector<SensorSlot> sensors_;
  DofCommands merged_;
  // the generalized forces written each step, kept so that a step does not allocate
  std::vector<real> tau_;
  std::vector<std::uint8_t> driven_;
  std::vector<int> all_dofs_;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
