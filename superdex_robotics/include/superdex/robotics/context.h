#pragma once
/// @file context.h
/// The robotics context: registries of component types (C++ factories; the Python layer
/// registers Python classes through the same factories), every component and bot, all
/// addressed by handles drawn from the engine-wide counter and never reused.
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

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

using physics::ActorHandle;
using physics::Scene;
using ComponentHandle = std::int64_t;
using BotHandle = std::int64_t;

enum class ComponentKind { Controller, Sensor, Actuator };
const char* component_kind_name(ComponentKind kind);

/// A controller, sensor or actuator. Every component can be reset to its initial state.
class Component {
 public:
  virtual ~Component() = default;
  virtual void reset() = 0;
};

/// What a factory receives.
struct ComponentArgs {
  Scene scene{0};
  /// The actor the component is attached to: a link actor (sensors, actuators) or an
  /// articulation (controllers); 0 for an actor-less sensor.
  ActorHandle actor = 0;
  /// Parameters: inline JSON, an absolute path to a JSON file, or empty.
  std::string params;
  /// Controllers: the prefab of the bot it drives, when known.
  const BotPrefab* prefab = nullptr;
};

using ComponentFactory = std::function<std::unique_ptr<Component>(const ComponentArgs&)>;

struct ComponentRecord {
  ComponentKind kind;
  std::string type, name;
  Scene scene{0};
  ActorHandle actor = 0;
  BotHandle bot = 0;  ///< the bot that owns it, or 0
  std::unique_ptr<Component> impl;
};

struct BotRecord {
  BotHandle handle = 0;
  Scene scene{0};
  ActorHandle articulation = 0;
  BotPrefab prefab;
  std::vector<ComponentHandle> controllers, sensors, actuators;  ///< creation order
};

class Context {
 public:
  Context() = default;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  /// Registers (or replaces) a factory for `type_name`.
  void register_type(ComponentKind kind, const std::string& type_name, ComponentFactory factory);
  bool is_type_registered(ComponentKind kind, const std::string& type_name) const;

  /// Creates a component through its type's factory. Throws superdex::Error for an unknown
  /// type or a failing factory (with the factory's message).
  ComponentHandle create(ComponentKind kind, const std::string& type_name, const ComponentArgs& args,
                         const std::string& name, BotHandle bot = 0);
  void destroy(ComponentKind kind, ComponentHandle handle);
  const ComponentRecord& component(ComponentKind kind, ComponentHandle handle) const;
  std::vector<ComponentHandle> find_by_name(ComponentKind kind, const std::string& name) const;
  std::vector<ComponentHandle> find_by_type(ComponentKind kind, const std::string& type_name) const;
  /// Calls reset() on every component (of one bot when bot != 0).
  void reset_components(BotHandle bot = 0);

  /// Builds the articulation of `prefab` in `scene` and its declared sensors and actuators.
  /// Types nobody registered are skipped with a warning (appended to `warnings`); a failing
  /// factory destroys what was built and throws.
  BotHandle create_bot(Scene scene, const BotPrefab& prefab, std::vector<std::string>* warnings);
  /// Destroys the bot's components, then its articulation.
  void destroy_bot(BotHandle bot);
  const BotRecord& bot(BotHandle bot) const;
  BotRecord& bot(BotHandle bot);
  bool has_bot(BotHandle bot) const { return bots_.count(bot) > 0; }
  std::vector<BotHandle> bots() const;

 private:
  std::map<std::string, ComponentFactory> factories_[3];
  std::map<ComponentHandle, ComponentRecord> components_[3];
  std::map<BotHandle, BotRecord> bots_;
};

/// Resolves a component's `params` string: inline JSON and empty strings are returned as
/// they are; anything else is a JSON file path, made absolute against `base_dir` and checked
/// to exist (throws superdex::Error naming `where` otherwise).
std::string resolve_params(const std::string& params, const std::string& base_dir, const std::string& where);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
