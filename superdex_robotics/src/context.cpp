// Registries, components and bots of the robotics context.

#include "superdex/robotics/context.h"

#include <filesystem>

#include "bot_pipeline.h"
#include "builtin_support.h"
#include "superdex/robotics/builtin_components.h"

#include "superdex/physics/error.h"
#include "superdex/physics/file_path.h"
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

// Inline JSON and empty params name no file.
bool names_a_file(const std::string& params) {
  const auto first = params.find_first_not_of(" \t\r\n");
  return first != std::string::npos && params[first] != '{';
}
}  // namespace

std::string params_relative_to(const std::string& params, const std::string& base_dir) {
  if (!names_a_file(params)) return params;
  fs::path p(params.substr(params.find_first_not_of(" \t\r\n")));
  if (p.is_relative() && !base_dir.empty()) p = fs::path(base_dir) / p;
  return p.string();
}

std::string resolve_params(const std::string& params, const std::string& base_dir, const std::string& where) {
  if (!names_a_file(params)) return params;
  const fs::path p = params_relative_to(params, base_dir);
  if (!is_existing_file(p)) throw Error(where + ": params file '" + p.string() + "' does not exist");
  return fs::absolute(p).lexically_normal().string();
}

Context::Context(bool register_builtins) {
  if (register_builtins) register_builtin_components(*this);
}

Context::~Context() {
  // the scene may outlive the context: no callback may point into it afterwards
  for (auto& [h, b] : bots_) {
    if (b.pipeline) stop_pipeline(b, true);
    remove_signal_source(b);
  }
}

void Context::remove_signal_source(BotRecord& b) {
  if (b.signal_source && physics::scene_exists(b.scene.handle())) b.scene.remove_signal_source(b.signal_source);
  b.signal_source = 0;
}

void Context::append_bot_signals(BotHandle handle, std::vector<physics::NamedSignal>& out) const {
  const auto it = bots_.find(handle);
  if (it == bots_.end()) return;
  const BotRecord& b = it->second;
  const std::string bot_name = b.prefab.name();
  // each sensor's reading, by the sensor's name
  for (ComponentHandle h : b.sensors) {
    const ComponentRecord& rec = component(ComponentKind::Sensor, h);
    const auto* sensor = dynamic_cast<const SensorComponent*>(rec.impl.get());
    if (!sensor) continue;
    std::optional<VecX> reading;
    try {
      reading = sensor->latest_reading();
    } catch (const std::exception&) {
      continue;  // a sensor that cannot report now is left out of this frame, not the user's step
    }
    if (!reading) continue;
    out.push_back({bot_name + "." + rec.name, std::vector<double>(reading->data(), reading->data() + reading->size()), "sensor"});
  }
  // each actuator's effort: the generalized force on its link's DOF (N m or N)
  const VecX tau = b.scene.external_forces(b.articulation);
  for (ComponentHandle h : b.actuators) {
    const ComponentRecord& rec = component(ComponentKind::Actuator, h);
    if (!b.scene.has_actor(rec.actor)) continue;
    const physics::ArticulatedDofInfo dofs = joint_dofs_of_link(b.scene, rec.actor, rec.name);
    if (dofs.size() != 1 || dofs.offset >= tau.size()) continue;
    out.push_back({bot_name + "." + rec.name + ".effort", {static_cast<double>(tau[dofs.offset])}, "actuator"});
  }
}

void Context::register_type(ComponentKind kind, const std::string& type_name, ComponentFactory factory,
                            ArmatureContribution armature) {
  if (type_name.empty()) throw Error(std::string("register_") + component_kind_name(kind) + ": the type name must not be empty");
  if (!factory) throw Error(std::string("register_") + component_kind_name(kind) + ": no factory given for '" + type_name + "'");
  factories_[index(kind)][type_name] = ComponentType{std::move(factory), std::move(armature)};
}

bool Context::is_type_registered(ComponentKind kind, const std::string& type_name) const {
  return factories_[index(kind)].count(type_name) > 0;
}

std::unique_ptr<Component> Context::construct(ComponentKind kind, const std::string& type_name, const ComponentArgs& args,
                                              const std::string& what) const {
  auto it = factories_[index(kind)].find(type_name);
  if (it == factories_[index(kind)].end())
    throw Error(what + ": no " + component_kind_name(kind) + " type '" + type_name + "' is registered");
  if (kind == ComponentKind::Actuator && args.actor == 0) throw Error(what + ": an actuator needs an actor (a link)");
  if (args.actor != 0 && !args.scene.has_actor(args.actor))
    throw Error(what + ": actor " + std::to_string(args.actor) + " does not exist");
  std::unique_ptr<Component> impl;
  try {
    impl = it->second.factory(args);
  } catch (const Error& e) {
    throw Error(what + ": " + e.what());
  } catch (const std::exception& e) {
    throw Error(what + ": the factory failed: " + e.what());
  }
  if (!impl) throw Error(what + ": the factory returned nothing");
  return impl;
}

ComponentHandle Context::create(ComponentKind kind, const std::string& type_name, const ComponentArgs& args,
                                const std::string& name, BotHandle bot) {
  const std::string what = std::string("create_") + component_kind_name(kind) + "('" + type_name + "', name '" + name + "')";
  // the bot whose pipeline will run it: its owner, or the bot its actor belongs to
  const BotHandle attached = bot != 0 ? bot : bot_of_actor(args.scene, args.actor);
  ComponentArgs with_prefab = args;
  if (!with_prefab.prefab && attached != 0) with_prefab.prefab = &bots_.at(attached).prefab;
  std::unique_ptr<Component> impl = construct(kind, type_name, with_prefab, what);
  int dof = -1;
  if (kind == ComponentKind::Actuator && impl->takes_part_in_pipeline()) dof = single_dof_of_link(args.scene, args.actor, what);
  const ComponentHandle h = physics::next_handle();
  // a component created on one of a bot's actors belongs to that bot: listed with its
  // components and destroyed with it, however it was created
  const BotHandle owner = bot != 0 ? bot : attached;
  components_[index(kind)].emplace(
      h, ComponentRecord{kind, type_name, name, args.scene, args.actor, owner, std::move(impl), attached, dof, args.parent_from_sensor});
  if (bot == 0 && attached != 0) {
    BotRecord& b = bots_.at(attached);
    (kind == ComponentKind::Controller ? b.controllers : kind == ComponentKind::Sensor ? b.sensors : b.actuators).push_back(h);
  }
  if (attached != 0) sync_pipeline(attached);
  return h;
}

void Context::destroy(ComponentKind kind, ComponentHandle handle) {
  auto& map = components_[index(kind)];
  auto it = map.find(handle);
  if (it == map.end())
    throw Error(std::string("destroy_") + component_kind_name(kind) + ": " + component_kind_name(kind) + " " +
                std::to_string(handle) + " does not exist (destroyed, or not a " + component_kind_name(kind) + ")");
  const BotHandle attached = it->second.attached_bot;
  if (attached != 0 && bots_.count(attached) && bots_.at(attached).pipeline && bots_.at(attached).pipeline->running())
    throw Error(std::string("destroy_") + component_kind_name(kind) + ": '" + it->second.name +
                "' cannot be destroyed while its bot's pipeline is running (from inside scene.step)");
  if (it->second.bot != 0 && bots_.count(it->second.bot)) {
    BotRecord& b = bots_.at(it->second.bot);
    for (auto* list : {&b.controllers, &b.sensors, &b.actuators}) std::erase(*list, handle);
  }
  map.erase(it);
  if (attached != 0 && bots_.count(attached)) sync_pipeline(attached);
}

const ComponentRecord& Context::component(ComponentKind kind, ComponentHandle handle) const {
  auto& map = components_[index(kind)];
  auto it = map.find(handle);
  if (it == map.end())
    throw Error(std::string(component_kind_name(kind)) + " " + std::to_string(handle) +
                " does not exist (destroyed, or the handle is of another kind)");
  return it->second;
}

bool Context::has_component(ComponentKind kind, ComponentHandle handle) const {
  return components_[index(kind)].count(handle) > 0;
}

void Context::set_parent_from_sensor(ComponentHandle sensor, const Transform& parent_from_sensor) {
  component(ComponentKind::Sensor, sensor);  // throws for an unknown sensor
  components_[index(ComponentKind::Sensor)].at(sensor).parent_from_sensor = parent_from_sensor;
}

Transform Context::sensor_world_transform(ComponentHandle sensor) const {
  const ComponentRecord& rec = component(ComponentKind::Sensor, sensor);
  // no actor: the scene root is the parent and stands at the world origin
  if (rec.actor == 0) return rec.parent_from_sensor;
  if (!physics::scene_exists(rec.scene.handle()) || !rec.scene.has_actor(rec.actor))
    throw Error("sensor '" + rec.name + "': its actor " + std::to_string(rec.actor) + " no longer exists");
  return rec.scene.root_transform(rec.actor) * rec.parent_from_sensor;
}

void Context::configure_from_scene_entry(ComponentKind kind, ComponentHandle handle, const std::string& params,
                                         const std::string& init_args, const std::string& base_dir) {
  const ComponentRecord& rec = component(kind, handle);
  const std::string what = std::string("configure_from_scene_entry(") + component_kind_name(kind) + " '" + rec.name + "', type " + rec.type + ")";
  const std::string p = resolve_params(params, base_dir, what + ": param_args");
  const std::string i = resolve_params(init_args, base_dir, what + ": init_args");
  try {
    rec.impl->configure_from_scene_entry(p, i);
  } catch (const Error& e) {
    throw Error(what + ": " + e.what());
  }
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

std::vector<ComponentHandle> Context::attached_components(ComponentKind kind, BotHandle bot) const {
  std::vector<ComponentHandle> out;
  for (const auto& [h, c] : components_[index(kind)])
    if (c.attached_bot == bot) out.push_back(h);
  return out;
}

void Context::reset_components(BotHandle bot) {
  for (auto& map : components_)
    for (auto& [h, c] : map)
      if (bot == 0 || c.bot == bot || c.attached_bot == bot) c.impl->reset();
  for (auto& [h, b] : bots_)
    if ((bot == 0 || h == bot) && b.pipeline) b.pipeline->reset_timing();
}

void Context::configure(ComponentKind kind, ComponentHandle handle, const std::string& json_params) {
  const ComponentRecord& rec = component(kind, handle);
  try {
    rec.impl->configure(json_params);
  } catch (const Error& e) {
    throw Error(std::string("configure_") + component_kind_name(kind) + "('" + rec.name + "', type " + rec.type + "): " + e.what());
  }
}

VecX Context::sensor_signal(ComponentHandle sensor) const {
  const ComponentRecord& rec = component(ComponentKind::Sensor, sensor);
  const auto* s = dynamic_cast<const SensorComponent*>(rec.impl.get());
  if (!s) throw Error("get_sensor_signal: sensor '" + rec.name + "' (type " + rec.type + ") provides no signal");
  return s->signal();
}

BotHandle Context::create_bot(Scene scene, const BotPrefab& prefab, std::vector<std::string>* warnings) {
  const std::string source = prefab.source.empty() ? "bot '" + prefab.name() + "'" : prefab.source;
  if (prefab.sensors.size() != prefab.articulation.links.size() || prefab.actuators.size() != prefab.articulation.links.size())
    throw Error(source + ": sensors and actuators must have one list per link");
  BotRecord rec;
  rec.handle = physics::next_handle();
  rec.scene = scene;
  rec.prefab = prefab;
  // actuator types that model a rotor add its reflected inertia to their joint's armature
  physics::ArticulationDesc desc = prefab.articulation;
  for (size_t i = 0; i < prefab.actuators.size(); ++i)
    for (size_t k = 0; k < prefab.actuators[i].size(); ++k) {
      const ComponentDecl& d = prefab.actuators[i][k];
      auto it = factories_[index(ComponentKind::Actuator)].find(d.type);
      if (it == factories_[index(ComponentKind::Actuator)].end() || !it->second.armature) continue;
      const std::string where = source + ": links[" + std::to_string(i) + "].actuators[" + std::to_string(k) + "]";
      try {
        desc.joints[i].armature += it->second.armature(resolve_params(d.params, prefab.base_dir, where + ".params"));
      } catch (const Error& e) {
        throw Error(where + " ('" + d.name + "', type " + d.type + "): " + e.what());
      }
    }
  rec.articulation = scene.create_articulated_actor(desc, source);
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
          ComponentArgs args{scene, links[i], resolve_params(d.params, prefab.base_dir, where + ".params"), &b.prefab,
                             d.parent_from_sensor};
          ComponentHandle h = 0;
          try {
            h = create(kind, d.type, args, d.name, b.handle);
          } catch (const Error& e) {
            // say which declaration in which file made the component fail
            throw Error(where + " ('" + d.name + "'): " + e.what());
          }
          (kind == ComponentKind::Sensor ? b.sensors : b.actuators).push_back(h);
        }
    }
  } catch (...) {
    destroy_bot(b.handle);
    throw;
  }
  b.signal_source = scene.add_signal_source([this, handle](std::vector<physics::NamedSignal>& out) { append_bot_signals(handle, out); });
  return b.handle;
}

void Context::destroy_bot(BotHandle handle) {
  auto it = bots_.find(handle);
  if (it == bots_.end()) throw Error("destroy_bot: bot " + std::to_string(handle) + " does not exist (already destroyed?)");
  BotRecord& b = it->second;
  if (b.pipeline && b.pipeline->running())
    throw Error("destroy_bot: bot " + std::to_string(handle) + " cannot be destroyed while its pipeline is running (from inside scene.step)");
  // the pipeline first (its callbacks point at the components), then the components (they
  // may hold the actor), then the articulation
  if (b.pipeline) stop_pipeline(b, false);
  remove_signal_source(b);
  for (auto& map : components_) {
    std::erase_if(map, [&](const auto& kv) { return kv.second.bot == handle; });
    for (auto& [h, c] : map)
      if (c.attached_bot == handle) c.attached_bot = 0;
  }
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

std::vector<BotHandle> Context::find_bots_by_name(const std::string& name) const {
  std::vector<BotHandle> out;
  for (const auto& [h, b] : bots_)
    if (b.prefab.name() == name) out.push_back(h);
  return out;
}

void Context::set_pipeline_mode(BotHandle handle, PipelineMode mode) {
  BotRecord& b = bot(handle);
  b.pipeline_mode = mode;
  sync_pipeline(handle);
}

BotHandle Context::bot_of_actor(const Scene& scene, ActorHandle actor) const {
  if (actor == 0 || !physics::scene_exists(scene.handle()) || !scene.has_actor(actor)) return 0;
  const ActorHandle articulation =
      scene.is_nested_link_actor(actor) ? scene.articulated_actor_of_link(actor) : actor;
  for (const auto& [h, b] : bots_)
    if (b.scene.handle() == scene.handle() && b.articulation == articulation) return h;
  return 0;
}

void Context::sync_pipeline(BotHandle handle) {
  BotRecord& b = bot(handle);
  bool takes_part = false;
  for (const auto& map : components_)
    for (const auto& [h, c] : map) takes_part = takes_part || (c.attached_bot == handle && c.impl->takes_part_in_pipeline());
  const bool want = b.pipeline_mode == PipelineMode::Enabled || (b.pipeline_mode == PipelineMode::Automatic && takes_part);
  if (want && !b.pipeline) {
    if (!physics::scene_exists(b.scene.handle())) return;
    // the callbacks share the pipeline, so that one being run never outlives it
    auto p = std::make_shared<BotPipeline>(*this, handle, b.scene, b.articulation);
    p->set_callbacks(
        b.scene.register_pre_step_callback(p->pre_name(), [p](const physics::StepInfo& info) { p->pre_step(static_cast<real>(info.time_step_sec)); }, 1000),
        b.scene.register_post_step_callback(p->post_name(), [p](const physics::StepInfo& info) { p->post_step(static_cast<real>(info.time_step_sec)); }, -1000));
    b.pipeline = std::move(p);
  } else if (!want && b.pipeline) {
    stop_pipeline(b, true);
  } else if (b.pipeline) {
    b.pipeline->invalidate();
  }
}

void Context::stop_pipeline(BotRecord& b, bool clear_forces) {
  std::shared_ptr<BotPipeline> p = std::move(b.pipeline);
  b.pipeline = nullptr;
  p->detach();
  if (!physics::scene_exists(b.scene.handle())) return;
  for (physics::CallbackHandle h : {p->pre_callback(), p->post_callback()}) b.scene.cancel_callback(h);
  // the forces it applied stop with it
  if (clear_forces && p->wrote_forces() && b.scene.has_actor(b.articulation)) b.scene.clear_external_forces(b.articulation);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
