// Registries, components and bots of the robotics context.

#include "superdex/robotics/context.h"

#include <filesystem>

#include "superdex/physics/error.h"
#include "superdex/physics/engine.h"
#include "superdex/physics/handles.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace fs = std::filesystem;

const char* component_kind_name(ComponentKind kind) {
  switch (kind) {
    case ComponentKind::Controller: return "controller";
    case ComponentKind::Sensor: return "sensor";
    case ComponentKind::Actuator: return "actuator";
  }
  return "?";
}

namespace {
int index(ComponentKind k) { return static_cast<int>(k); }
}  // namespace

std::string resolve_params(const std::string& params, const std::string& base_dir, const std::string& where) {
  const auto first = params.find_first_not_of(" \t\r\n");
  if (first == std::string::npos || params[first] == '{') return params;
  fs::path p(params.substr(first));
  if (p.is_relative() && !base_dir.empty()) p = fs::path(base_dir) / p;
  if (!fs::is_regular_file(p)) throw Error(where + ": params file '" + p.string() + "' does not exist");
  return fs::absolute(p).lexically_normal().string();
}

void Context::register_type(ComponentKind kind, const std::string& type_name, ComponentFactory factory) {
  if (type_name.empty()) throw Error(std::string("register_") + component_kind_name(kind) + ": the type name must not be empty");
  if (!factory) throw Error(std::string("register_") + component_kind_name(kind) + ": no factory given for '" + type_name + "'");
  factories_[index(kind)][type_name] = std::move(factory);
}

bool Context::is_type_registered(ComponentKind kind, const std::string& type_name) const {
  return factories_[index(kind)].count(type_name) > 0;
}

ComponentHandle Context::create(ComponentKind kind, const std::string& type_name, const ComponentArgs& args,
                                const std::string& name, BotHandle bot) {
  const std::string what = std::string("create_") + component_kind_name(kind) + "('" + type_name + "', name '" + name + "')";
  auto it = factories_[index(kind)].find(type_name);
  if (it == factories_[index(kind)].end())
    throw Error(what + ": no " + component_kind_name(kind) + " type '" + type_name + "' is registered");
  if (kind == ComponentKind::Actuator && args.actor == 0) throw Error(what + ": an actuator needs an actor (a link)");
  if (args.actor != 0 && !args.scene.has_actor(args.actor))
    throw Error(what + ": actor " + std::to_string(args.actor) + " does not exist");
  std::unique_ptr<Component> impl;
  try {
    impl = it->second(args);
  } catch (const Error& e) {
    throw Error(what + ": " + e.what());
  } catch (const std::exception& e) {
    throw Error(what + ": the factory failed: " + e.what());
  }
  if (!impl) throw Error(what + ": the factory returned nothing");
  const ComponentHandle h = physics::next_handle();
  components_[index(kind)].emplace(h, ComponentRecord{kind, type_name, name, args.scene, args.actor, bot, std::move(impl)});
  return h;
}

void Context::destroy(ComponentKind kind, ComponentHandle handle) {
  auto& map = components_[index(kind)];
  auto it = map.find(handle);
  if (it == map.end())
    throw Error(std::string("destroy_") + component_kind_name(kind) + ": " + component_kind_name(kind) + " " +
                std::to_string(handle) + " does not exist (destroyed, or not a " + component_kind_name(kind) + ")");
  if (it->second.bot != 0 && bots_.count(it->second.bot)) {
    BotRecord& b = bots_.at(it->second.bot);
    for (auto* list : {&b.controllers, &b.sensors, &b.actuators}) std::erase(*list, handle);
  }
  map.erase(it);
}

const ComponentRecord& Context::component(ComponentKind kind, ComponentHandle handle) const {
  auto& map = components_[index(kind)];
  auto it = map.find(handle);
  if (it == map.end())
    throw Error(std::string(component_kind_name(kind)) + " " + std::to_string(handle) +
                " does not exist (destroyed, or the handle is of another kind)");
  return it->second;
}

std::vector<ComponentHandle> Context::find_by_name(ComponentKind kind, const std::string& name) const {
  std::vector<ComponentHandle> out;
  for (const auto& [h, c] : components_[index(kind)])
    if (c.name == name) out.push_back(h);
  return out;
}

std::vector<ComponentHandle> Context::find_by_type(ComponentKind kind, const std::string& type_name) const {
  std::vector<ComponentHandle> out;
  for (const auto& [h, c] : components_[index(kind)])
    if (c.type == type_name) out.push_back(h);
  return out;
}

void Context::reset_components(BotHandle bot) {
  for (auto& map : components_)
    for (auto& [h, c] : map)
      if (bot == 0 || c.bot == bot) c.impl->reset();
}

BotHandle Context::create_bot(Scene scene, const BotPrefab& prefab, std::vector<std::string>* warnings) {
  const std::string source = prefab.source.empty() ? "bot '" + prefab.name() + "'" : prefab.source;
  if (prefab.sensors.size() != prefab.articulation.links.size() || prefab.actuators.size() != prefab.articulation.links.size())
    throw Error(source + ": sensors and actuators must have one list per link");
  BotRecord rec;
  rec.handle = physics::next_handle();
  rec.scene = scene;
  rec.prefab = prefab;
  rec.articulation = scene.create_articulated_actor(prefab.articulation, source);
  const std::vector<ActorHandle> links = scene.nested_link_actors(rec.articulation);
  const BotHandle handle = rec.handle;
  BotRecord& b = bots_.emplace(handle, std::move(rec)).first->second;
  try {
    for (ComponentKind kind : {ComponentKind::Sensor, ComponentKind::Actuator}) {
      const auto& decls = kind == ComponentKind::Sensor ? prefab.sensors : prefab.actuators;
      for (size_t i = 0; i < decls.size(); ++i)
        for (size_t k = 0; k < decls[i].size(); ++k) {
          const ComponentDecl& d = decls[i][k];
          const std::string where = source + ": links[" + std::to_string(i) + "]." +
                                    (kind == ComponentKind::Sensor ? "sensors[" : "actuators[") + std::to_string(k) + "]";
          if (!is_type_registered(kind, d.type)) {
            if (warnings)
              warnings->push_back(where + ": " + component_kind_name(kind) + " type '" + d.type + "' of '" + d.name +
                                  "' is not registered; the component is skipped");
            continue;
          }
          ComponentArgs args{scene, links[i], resolve_params(d.params, prefab.base_dir, where + ".params"), &b.prefab};
          const ComponentHandle h = create(kind, d.type, args, d.name, b.handle);
          (kind == ComponentKind::Sensor ? b.sensors : b.actuators).push_back(h);
        }
    }
  } catch (...) {
    destroy_bot(b.handle);
    throw;
  }
  return b.handle;
}

void Context::destroy_bot(BotHandle handle) {
  auto it = bots_.find(handle);
  if (it == bots_.end()) throw Error("destroy_bot: bot " + std::to_string(handle) + " does not exist (already destroyed?)");
  // components first (they may hold the actor), then the articulation
  for (auto& map : components_) std::erase_if(map, [&](const auto& kv) { return kv.second.bot == handle; });
  BotRecord& b = it->second;
  if (physics::scene_exists(b.scene.handle()) && b.scene.has_actor(b.articulation)) b.scene.destroy_actor(b.articulation);
  bots_.erase(it);
}

const BotRecord& Context::bot(BotHandle handle) const {
  auto it = bots_.find(handle);
  if (it == bots_.end()) throw Error("bot " + std::to_string(handle) + " does not exist (destroyed?)");
  return it->second;
}

BotRecord& Context::bot(BotHandle handle) {
  auto it = bots_.find(handle);
  if (it == bots_.end()) throw Error("bot " + std::to_string(handle) + " does not exist (destroyed?)");
  return it->second;
}

std::vector<BotHandle> Context::bots() const {
  std::vector<BotHandle> out;
  for (const auto& [h, b] : bots_) out.push_back(h);
  return out;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
