#pragma once
/// @file component.h
/// Components (controllers, sensors, actuators) and the interfaces through which a bot's
/// pipeline runs them inside `Scene::step` (see pipeline order in context.h).
///
/// Every component has `reset()`. A component that also implements one of the pipeline
/// interfaces below (SensorComponent, ControllerComponent, ActuatorComponent) and says so with
/// `takes_part_in_pipeline()` is run by its bot's pipeline at its declared rate:
///   - controllers write per-DOF commands (position, velocity, effort) before the step,
///   - actuators turn the command of their DOF into an effort before the step,
///   - sensors update after the step.
/// Components that do not take part (for example Python components without pipeline
/// methods) are left to the user's own loop, exactly as before the pipeline existed.
///
/// Units: SI (m, rad, s, N, N m). DOF indices are indices into the articulation's
/// generalized velocities (0 .. num_dofs - 1, root joint DOFs first).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "superdex/physics/real.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::real;
using physics::VecX;

/// When and for how long a pipeline component runs.
struct Tick {
  /// Scene time (s): the start of the step for controllers and actuators, its end for sensors.
  double time = 0;
  /// Time since this component last ran (s); on its first run its period (1 / rate), or the
  /// step's dt when it runs every step.
  real dt = 0;
  /// The dt of the scene step being taken (s).
  real step_dt = 0;
  /// Pipeline steps run before this one for this bot (0 on the first).
  std::int64_t step = 0;
};

/// The command of one DOF; an empty optional was not commanded.
struct DofCommand {
  std::optional<real> position;  ///< rad or m
  std::optional<real> velocity;  ///< rad/s or m/s
  std::optional<real> effort;    ///< N m or N
};

/// Per-DOF commands for one articulation (num_dofs entries each); `has_*` says which were set.
struct DofCommands {
  VecX position, velocity, effort;
  std::vector<std::uint8_t> has_position, has_velocity, has_effort;

  /// Sizes to `num_dofs` entries, none commanded.
  void clear(int num_dofs);
  int size() const { return static_cast<int>(position.size()); }
  void set_position(int dof, real value);
  void set_velocity(int dof, real value);
  void set_effort(int dof, real value);
  /// The command of one DOF.
  DofCommand at(int dof) const;
  /// Merges `other` into this: its positions and velocities replace ours where set, its
  /// efforts add to ours.
  void merge(const DofCommands& other);
};

/// A controller, sensor or actuator.
class Component {
 public:
  virtual ~Component() = default;
  /// Returns the component to its initial state (integrators, filters, delay lines).
  virtual void reset() = 0;
  /// Changes parameters at run time from a JSON object (text); keys that are absent keep their
  /// value. Throws superdex::Error for unknown keys or bad values, or if the component has no
  /// run-time parameters.
  virtual void configure(const std::string& json_params);
  /// Configures the component from a scene file's entry: `params` and `init_args` are inline
  /// JSON or absolute JSON file paths, each possibly empty ("use the defaults"). The default
  /// applies each non-empty one through configure(); types with a params struct override it.
  virtual void configure_from_scene_entry(const std::string& params, const std::string& init_args);
  /// True when the bot's pipeline runs this component (it implements a pipeline interface).
  virtual bool takes_part_in_pipeline() const { return false; }
  /// Rate (Hz) at which the pipeline runs it; 0 runs it every step.
  double rate() const { return rate_hz_; }
  /// Sets the rate (Hz, >= 0, 0: every step). Throws superdex::Error for a negative value.
  void set_rate(double rate_hz);

 private:
  double rate_hz_ = 0;
};

/// A sensor the pipeline updates after each step (at its rate).
class SensorComponent : public Component {
 public:
  bool takes_part_in_pipeline() const override { return true; }
  /// Samples the scene (called after the step; `tick.time` is the time after the step).
  virtual void update(const Tick& tick) = 0;
  /// The latest reading (its layout is documented by each sensor type); zeros before the
  /// first update.
  virtual VecX signal() const = 0;
  /// The latest reading for the debugger's plots, obtained without side effects (no new
  /// sample is taken); nullopt when there is none yet.
  virtual std::optional<VecX> latest_reading() const { return signal(); }
};

/// A controller the pipeline runs before each step (at its rate).
class ControllerComponent : public Component {
 public:
  bool takes_part_in_pipeline() const override { return true; }
  /// Writes commands for the DOFs it controls into `out` (sized to the articulation's DOFs and
  /// cleared before the call). Between runs the pipeline holds its last commands.
  virtual void compute(const Tick& tick, DofCommands& out) = 0;
};

/// An actuator the pipeline runs before each step (at its rate): it drives the single DOF of
/// its link's joint (FORMATS.md: "an actuator's DOF is the DOF of its link's joint").
class ActuatorComponent : public Component {
 public:
  bool takes_part_in_pipeline() const override { return true; }
  /// The generalized force (N m or N) on its DOF for this command. Between runs the pipeline
  /// holds its last effort.
  virtual real compute_effort(const Tick& tick, const DofCommand& command) = 0;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
