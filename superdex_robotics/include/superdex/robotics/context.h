#pragma once
/// @file context.h
/// The robotics context: registries of component types (C++ factories; the Python layer
/// registers Python classes through the same factories), every component and bot, all
/// addressed by handles drawn from the engine-wide counter and never reused. Every new
/// context has the built-in component types registered (builtin_components.h).
///
/// The bot pipeline. A bot whose components take part in the pipeline (component.h) runs
/// them inside `Scene::step`, with no loop in the user's script:
///   1. pre-step callback (priority 1000, after user pre-step callbacks of default priority):
///      each due controller computes its commands (creation order; positions and velocities
///      of later controllers replace earlier ones, efforts add); each due actuator turns the
///      command of its DOF into an effort; DOFs without an actuator take the commanded effort
///      directly; the resulting generalized forces (all DOFs, zero where nothing was
///      commanded) are applied with `Scene::set_external_forces_on_dofs`;
///   2. the physics step;
///   3. post-step callback (priority -1000, before user post-step callbacks): each due sensor
///      updates.
/// Components run at their rate (Component::rate, Hz; 0: every step) and hold their last
/// output in between. A bot's pipeline is active by default as soon as it has a component
/// that takes part (PipelineMode::Automatic), or is forced on or off (set_pipeline_mode).
/// While a pipeline with a controller or an actuator is active it OWNS its articulation's
/// external generalized forces: it replaces them every step, and clears them when it stops.
/// Components attached to the bot are those created by create_bot or through the bot, and
/// those created on the context whose actor is the bot's articulation or one of its links; all
/// of them belong to the bot (listed among its components, destroyed with it).
///
/// Lifetimes: the pipeline's scene callbacks are cancelled when the pipeline stops, when the
/// bot is destroyed and when the context is destroyed (if the scene still exists); a scene
/// destroyed first takes its callbacks with it. A pipeline refuses to let its own components
/// or bot be destroyed while it runs them.
///
/// Not thread-safe: use a context from one thread.

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "superdex/physics/scene.h"
#include "superdex/robotics/bot_prefab.h"
#include "superdex/robotics/component.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::ActorHandle;
using physics::Scene;
using ComponentHandle = std::int64_t;
using BotHandle = std::int64_t;

enum class ComponentKind { Controller, Sensor, Actuator };
const char* component_kind_name(ComponentKind kind);

/// What a factory receives.
struct ComponentArgs {
  Scene scene{0};
  /// The actor the component is attached to: a link actor (sensors, actuators) or an
  /// articulation (controllers); 0 for an actor-less sensor.
  ActorHandle actor = 0;
  /// Parameters: inline JSON, a path to a JSON file (bot files: made absolute against the bot
  /// file's folder; a relative path is read from the working directory), or empty.
  std::string params;
  /// The prefab of the bot the component belongs to, when known (create_bot, the bot's
  /// create_* methods, or a context-level component whose actor belongs to a bot).
  const BotPrefab* prefab = nullptr;
  /// Sensors: the sensor frame S in the link frame (parentFromSensor of the bot file).
  Transform parent_from_sensor;
};

using ComponentFactory = std::function<std::unique_ptr<Component>(const ComponentArgs&)>;
/// For actuator types that model a rotor: the armature (reflected rotor inertia, kg m^2 or
/// kg) the actuator adds to its joint, from its params (resolved as in ComponentArgs). Applied
/// by create_bot to the actuators declared in the bot file, before the articulation is built.
using ArmatureContribution = std::function<real(const std::string& params)>;

/// How a bot decides whether its pipeline runs.
enum class PipelineMode {
  Automatic,  ///< active when at least one attached component takes part (default)
  Enabled,    ///< always active
  Disabled,   ///< never active: the user's loop drives the components
};

class BotPipeline;  // src/bot_pipeline.h

struct ComponentRecord {
  ComponentKind kind;
  std::string type, name;
  Scene scene{0};
  ActorHandle actor = 0;
  BotHandle bot = 0;           ///< the bot that owns it (created through it or on its actors), or 0
  std::unique_ptr<Component> impl;
  BotHandle attached_bot = 0;  ///< the bot whose pipeline runs it (owner, or by actor), or 0
  int dof = -1;                ///< pipeline actuators: the DOF of its link's joint
  /// Sensors: the sensor frame S in its parent frame (the actor's frame, or the world for an
  /// actor-less sensor).
  Transform parent_from_sensor;
};

struct BotRecord {
  BotHandle handle = 0;
  Scene scene{0};
  ActorHandle articulation = 0;
  BotPrefab prefab;
  std::vector<ComponentHandle> controllers, sensors, actuators;  ///< creation order
  PipelineMode pipeline_mode = PipelineMode::Automatic;
  std::shared_ptr<BotPipeline> pipeline;  ///< set while the pipeline is active
  int signal_source = 0;  ///< the scene's signal source of its sensors and actuators (debugger plots)
};

class Context {
 public:
  /// A context with the built-in component types registered (unless told otherwise).
  explicit Context(bool register_builtins = true);
  /// Stops every pipeline (cancelling its scene callbacks if the scene still exists).
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  /// Registers (or replaces) a factory for `type_name`.
  void register_type(ComponentKind kind, const std::string& type_name, ComponentFactory factory,
                     ArmatureContribution armature = {});
  bool is_type_registered(ComponentKind kind, const std::string& type_name) const;

  /// Runs the factory of a registered type without registering the result (a component that
  /// wraps another, such as DELAYED). Throws superdex::Error like create().
  std::unique_ptr<Component> construct(ComponentKind kind, const std::string& type_name, const ComponentArgs& args,
                                       const std::string& what) const;
  /// Creates a component through its type's factory. Throws superdex::Error for an unknown
  /// type or a failing factory (with the factory's message), and for a pipeline actuator
  /// whose link's joint does not have exactly one DOF.
  ComponentHandle create(ComponentKind kind, const std::string& type_name, const ComponentArgs& args,
                         const std::string& name, BotHandle bot = 0);
  void destroy(ComponentKind kind, ComponentHandle handle);
  const ComponentRecord& component(ComponentKind kind, ComponentHandle handle) const;
  /// True while `handle` names a live component of `kind` (false for 0, stale or other kinds).
  bool has_component(ComponentKind kind, ComponentHandle handle) const;
  /// A sensor's pose in its parent frame (see ComponentRecord::parent_from_sensor).
  void set_parent_from_sensor(ComponentHandle sensor, const Transform& parent_from_sensor);
  /// World-from-sensor: the actor's world pose times parent_from_sensor, or parent_from_sensor
  /// itself for an actor-less sensor (the scene root is the world). Throws superdex::Error when
  /// the sensor's actor or scene no longer exists.
  Transform sensor_world_transform(ComponentHandle sensor) const;
  /// Applies a scene file's entry to a component (Component::configure_from_scene_entry);
  /// `params` and `init_args` are resolved like ComponentArgs::params against `base_dir`.
  void configure_from_scene_entry(ComponentKind kind, ComponentHandle handle, const std::string& params,
                                  const std::string& init_args, const std::string& base_dir = "");
  std::vector<ComponentHandle> find_by_name(ComponentKind kind, const std::string& name) const;
  std::vector<ComponentHandle> find_by_type(ComponentKind kind, const std::string& type_name) const;
  /// Components of `kind` run by `bot`'s pipeline, in creation order.
  std::vector<ComponentHandle> attached_components(ComponentKind kind, BotHandle bot) const;
  /// Calls reset() on every component (of one bot when bot != 0) and restarts the pipelines'
  /// timing and held outputs.
  void reset_components(BotHandle bot = 0);
  /// Changes a component's parameters at run time (JSON object text); see Component::configure.
  void configure(ComponentKind kind, ComponentHandle handle, const std::string& json_params);
  /// The latest reading of a sensor (SensorComponent::signal).
  VecX sensor_signal(ComponentHandle sensor) const;

  /// Builds the articulation of `prefab` in `scene` and its declared sensors and actuators.
  /// Types nobody registered are skipped with a warning (appended to `warnings`); a failing
  /// factory destroys what was built and throws.
  BotHandle create_bot(Scene scene, const BotPrefab& prefab, std::vector<std::string>* warnings);
  /// Stops the bot's pipeline, destroys its components, then its articulation.
  void destroy_bot(BotHandle bot);
  const BotRecord& bot(BotHandle bot) const;
  BotRecord& bot(BotHandle bot);
  bool has_bot(BotHandle bot) const { return bots_.count(bot) > 0; }
  std::vector<BotHandle> bots() const;
  /// Bots whose prefab name is `name`, in creation order.
  std::vector<BotHandle> find_bots_by_name(const std::string& name) const;
  /// The bot whose articulation is `actor` or owns the link `actor`, or 0 (also for actor 0).
  BotHandle bot_of_actor(const Scene& scene, ActorHandle actor) const;

  /// Sets how the bot's pipeline is switched on (see PipelineMode) and applies it now.
  void set_pipeline_mode(BotHandle bot, PipelineMode mode);
  PipelineMode pipeline_mode(BotHandle bot) const { return this->bot(bot).pipeline_mode; }
  /// True while the bot's pipeline runs inside its scene's steps.
  bool is_pipeline_active(BotHandle bot) const { return this->bot(bot).pipeline != nullptr; }

 private:
  struct ComponentType {
    ComponentFactory factory;
    ArmatureContribution armature;
  };
  // starts or stops the bot's pipeline as its mode and components ask; refreshes its members
  void sync_pipeline(BotHandle bot);
  void stop_pipeline(BotRecord& bot, bool clear_forces);

  std::map<std::string, ComponentType> factories_[3];
  std::map<ComponentHandle, ComponentRecord> components_[3];
  // the debugger's signals of a bot: sensor readings and actuator efforts
  void append_bot_signals(BotHandle handle, std::vector<physics::NamedSignal>& out) const;
  void remove_signal_source(BotRecord& b);
  std::map<BotHandle, BotRecord> bots_;
};

/// Resolves a component's `params` string: inline JSON and empty strings are returned as
/// they are; anything else is a JSON file path, made absolute against `base_dir` and checked
/// to exist (throws superdex::Error naming `where` otherwise).
std::string resolve_params(const std::string& params, const std::string& base_dir, const std::string& where);

/// `params` with a relative file path joined to `base_dir`, unchecked (inline JSON, empty strings
/// and absolute paths as they are): the file resolve_params checks for.
std::string params_relative_to(const std::string& params, const std::string& base_dir);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
