// superdex.robotics: the context and its registries, Python components held by a C++ adapter
// (python_component.h), typed component handles, bots and their pipelines, the bot loaders.

#include <algorithm>

#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include "bind_common.h"
#include "bind_robotics_types.h"
#include "python_component.h"
#include "superdex/physics/engine.h"
#include "superdex/robotics/context.h"
#include "superdex/robotics/mjcf_import.h"

namespace superdex::python {

using robotics::BotHandle;
using robotics::BotPrefab;
using robotics::Component;
using robotics::ComponentArgs;
using robotics::ComponentHandle;
using robotics::ComponentKind;
using robotics::Context;

void export_prefab(nb::module_& m);

namespace {

const char* kind_title(ComponentKind k) {
  switch (k) {
    case ComponentKind::Controller: return "controller";
    case ComponentKind::Sensor: return "sensor";
    case ComponentKind::Actuator: return "actuator";
  }
  return "?";
}

// Handle lists are Python lists of typed handles (no std::vector caster here: the physics
// bindings bind vectors of their element types as DynamicArrays).
template <ComponentKind K>
nb::list typed(const std::vector<ComponentHandle>& hs) {
  nb::list out;
  for (ComponentHandle h : hs) out.append(nb::cast(TypedHandle<K>(h)));
  return out;
}

void emit(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1);
}

// A bot handle from a BotHandle or an int; other handles are refused.
BotHandle bot_handle_of(nb::handle obj, const char* what) {
  if (nb::isinstance<BotHandleValue>(obj)) return nb::cast<RoboticsHandle&>(obj).value;
  BotHandle h;
  if (nb::isinstance<RoboticsHandle>(obj) || nb::isinstance<nb::bool_>(obj) || !nb::try_cast(obj, h))
    throw Error(std::string(what) + ": expected a BotHandle, got " + nb::inst_name(obj).c_str());
  return h;
}

ActorHandle actor_or_zero(nb::handle a, const char* what) { return a.is_none() ? ActorHandle() : actor_handle_of(a, what); }

// Bot component lists filtered by name or type.
template <ComponentKind K>
nb::list bot_find(const PyBot& b, const std::string& value, bool by_type) {
  Context& ctx = b.ctx();
  const auto& rec = ctx.bot(b.handle);
  const auto& list = K == ComponentKind::Controller ? rec.controllers : K == ComponentKind::Sensor ? rec.sensors : rec.actuators;
  std::vector<ComponentHandle> found;
  for (ComponentHandle h : list) {
    const auto& c = ctx.component(K, h);
    if ((by_type ? c.type : c.name) == value) found.push_back(h);
  }
  return typed<K>(found);
}

// Run-time parameters: a Python component's configure(dict), or a C++ component's JSON.
void configure_component(Context& ctx, ComponentKind kind, ComponentHandle h, nb::handle params) {
  nb::object obj = python_object(ctx, kind, h);
  const std::string where = std::string("configure_") + kind_title(kind) + ": params";
  if (obj.is_none()) {
    ctx.configure(kind, h, params_text(params, where));
    return;
  }
  nb::object fn = nb::getattr(obj, "configure", nb::none());
  if (fn.is_none()) {
    const std::string cls = nb::cast<std::string>(nb::handle(reinterpret_cast<PyObject*>(Py_TYPE(obj.ptr()))).attr("__name__"));
    throw Error(std::string("configure_") + kind_title(kind) + ": class '" + cls + "' has no configure(params) method");
  }
  fn(nb::isinstance<nb::str>(params) ? nb::module_::import_("json").attr("loads")(params) : nb::borrow(params));
}

// Params given to a bot's create_*: a dict (written as JSON) or a string (inline JSON or a file
// path, relative to `base_dir`, the bot file's folder).
std::string creation_params(nb::handle params, const std::string& base_dir, const std::string& where) {
  if (params.is_none()) return "";
  if (nb::isinstance<nb::str>(params)) return robotics::resolve_params(nb::cast<std::string>(params), base_dir, where);
  return params_text(params, where);
}

// Params given to the context's create_*: a dict (written as JSON) or a string handed to the
// factory verbatim (a Python component's own configuration channel; a C++ built-in reads inline
// JSON or a file path relative to the working directory).
std::string verbatim_params(nb::handle params, const std::string& where) {
  if (params.is_none()) return "";
  if (nb::isinstance<nb::str>(params)) return nb::cast<std::string>(params);
  return params_text(params, where);
}

// None: automatic (the default), True: always on, False: off.
robotics::PipelineMode pipeline_mode(nb::handle enabled) {
  if (enabled.is_none()) return robotics::PipelineMode::Automatic;
  return nb::cast<bool>(enabled) ? robotics::PipelineMode::Enabled : robotics::PipelineMode::Disabled;
}

const char* pipeline_doc =
    "Runs the bot's pipeline inside scene.step (True), never (False), or when one of its\n"
    "components takes part (None, the default). While active with a controller or an actuator,\n"
    "the pipeline owns the articulation's external forces: it replaces them every step and\n"
    "clears them when it stops.";

// The factory contract and the pipeline protocol of each kind (python_component.h).
const char* register_doc(ComponentKind kind) {
  switch (kind) {
    case ComponentKind::Controller:
      return "Registers a Python controller type: factory(actor) -> object with reset().\n"
             "Pipeline (optional): compute(t, dt) -> {'position'|'velocity'|'effort': one value per DOF,\n"
             "NaN: not commanded} or None, called before each step (t: scene time at its start, dt: time\n"
             "since its last run); 'rate' attribute (Hz, 0: every step); configure(params: dict).";
    case ComponentKind::Sensor:
      return "Registers a Python sensor type: factory(actor_or_None, param_args: str) -> object with reset().\n"
             "Pipeline (optional): update(t, dt) after each step; signal() or compute_signal() is what\n"
             "Context.get_sensor_signal returns; 'rate' attribute (Hz); configure(params: dict).";
    case ComponentKind::Actuator:
      return "Registers a Python actuator type: factory(actor, param_args: str) -> object with reset().\n"
             "Pipeline (optional): compute_pipeline_effort(commands, dt) -> float, before each step, with\n"
             "commands {'position', 'velocity', 'effort'} of its link's joint DOF (floats or None); the\n"
             "result is that DOF's force; 'rate' attribute (Hz); configure(params: dict).";
  }
  return "";
}

template <ComponentKind K>
void def_kind(nb::module_& m, nb::class_<PyContext>& ctx_cls, nb::class_<PyBot>& bot_cls, const std::string& k) {
  m.def(("register_python_" + k).c_str(), [](PyContext& c, const std::string& type_name, nb::object factory) {
        if (!PyCallable_Check(factory.ptr()))
          throw Error("register_python_" + std::string(kind_title(K)) + ": the factory for '" + type_name + "' is not callable");
        c.ctx.register_type(K, type_name, python_factory(K, type_name, factory));
      }, "ctx"_a, "type_name"_a, "factory"_a, register_doc(K));
  m.def(("get_python_" + k).c_str(), [](PyContext& c, nb::handle h) -> nb::object {
        const ComponentHandle handle = handle_of<K>(h, ("get_python_" + std::string(kind_title(K))).c_str());
        // the invalid handle names no Python object (a stale one raises, naming it)
        if (handle == 0) return nb::none();
        return python_object(c.ctx, K, handle);
      }, "ctx"_a, "handle"_a, "The live Python object of a Python component; None for a C++ one or the invalid handle.\n"
      "Raises superdex.physics.Error for a destroyed component.");
  ctx_cls.def(("get_" + k).c_str(), [](nb::handle self, nb::handle h) {
             return component_view(nb::borrow(self), K, handle_of<K>(h, ("get_" + std::string(kind_title(K))).c_str()));
           }, "handle"_a, "The live component's view (ComponentBase subclass), or None for an invalid or stale handle.")
      .def(("is_valid_" + k).c_str(), [](const PyContext& c, nb::handle h) {
             return c.ctx.has_component(K, handle_of<K>(h, ("is_valid_" + std::string(kind_title(K))).c_str()));
           }, "handle"_a, "True while the handle names a live component of this kind.")
      .def(("destroy_" + k).c_str(), [](PyContext& c, nb::handle h) { c.ctx.destroy(K, handle_of<K>(h, "destroy")); }, "handle"_a)
      .def(("configure_" + k).c_str(), [](PyContext& c, nb::handle h, nb::handle params) {
             configure_component(c.ctx, K, handle_of<K>(h, ("configure_" + std::string(kind_title(K))).c_str()), params);
           }, "handle"_a, "params"_a,
           "Changes the component's parameters at run time: a dict or a JSON object string. A Python\n"
           "component receives the dict in its configure(params) method.")
      .def(("is_" + k + "_type_registered").c_str(), [](const PyContext& c, const std::string& t) { return c.ctx.is_type_registered(K, t); })
      .def(("find_" + k + "s_by_name").c_str(), [](const PyContext& c, const std::string& n) { return typed<K>(c.ctx.find_by_name(K, n)); })
      .def(("find_" + k + "s_by_type").c_str(), [](const PyContext& c, const std::string& t) { return typed<K>(c.ctx.find_by_type(K, t)); });
  bot_cls.def(("get_" + k + "_handles").c_str(), [](const PyBot& b) {
           const auto& rec = b.ctx().bot(b.handle);
           return typed<K>(K == ComponentKind::Controller ? rec.controllers : K == ComponentKind::Sensor ? rec.sensors : rec.actuators);
         })
      .def(("find_" + k + "s_by_name").c_str(), [](const PyBot& b, const std::string& n) { return bot_find<K>(b, n, false); })
      .def(("find_" + k + "s_by_type").c_str(), [](const PyBot& b, const std::string& t) { return bot_find<K>(b, t, true); })
      .def(("get_" + k).c_str(), [](const PyBot& b, nb::handle h) {
             const std::string what = "Bot.get_" + std::string(kind_title(K));
             const ComponentHandle handle = handle_of<K>(h, what.c_str());
             const auto& rec = b.ctx().bot(b.handle);
             const auto& list = K == ComponentKind::Controller ? rec.controllers : K == ComponentKind::Sensor ? rec.sensors : rec.actuators;
             // only this bot's components: a handle of another bot is a mistake worth reporting
             if (std::find(list.begin(), list.end(), handle) == list.end() && b.ctx().has_component(K, handle) &&
                 b.ctx().component(K, handle).attached_bot != b.handle)
               throw Error(what + ": " + kind_title(K) + " " + std::to_string(handle) + " does not belong to bot '" + rec.prefab.name() + "'");
             return component_view(b.context, K, handle);
           }, "handle"_a, "The view of one of this bot's components, or None for an invalid or stale handle.");
}

// The link actor of the bot's link named `link` (Error naming the bot's links otherwise).
ActorHandle link_actor_by_name(const robotics::BotRecord& rec, const std::string& link, const std::string& where) {
  const auto& links = rec.prefab.articulation.links;
  for (size_t i = 0; i < links.size(); ++i)
    if (links[i].name == link) return rec.scene.nested_link_actors(rec.articulation)[i];
  std::string names;
  for (const auto& l : links) names += (names.empty() ? "" : ", ") + l.name;
  throw Error(where + ": bot '" + rec.prefab.name() + "' has no link '" + link + "' (links: " + names + ")");
}

// The name of the bot link a component is attached to, or None (no actor, or not one of its links).
nb::object link_name_of(const PyBot& b, ComponentKind kind, ComponentHandle h) {
  const auto& rec = b.ctx().bot(b.handle);
  const ActorHandle actor = b.ctx().component(kind, h).actor;
  const auto links = rec.scene.nested_link_actors(rec.articulation);
  for (size_t i = 0; i < links.size(); ++i)
    if (links[i] == actor) return nb::str(rec.prefab.articulation.links[i].name.c_str());
  return nb::none();
}

// A component created through a bot: attached to `actor` (the bot's articulation for a
// controller), params resolved against the bot file's folder, listed among the bot's components.
ComponentHandle bot_create(PyBot& b, ComponentKind kind, const std::string& type_name, nb::handle actor,
                           const std::string& name, nb::handle params) {
  Context& ctx = b.ctx();
  auto& rec = ctx.bot(b.handle);
  const std::string what = std::string("create_") + kind_title(kind) + "('" + name + "')";
  const ActorHandle target = kind == ComponentKind::Controller ? rec.articulation
                             : nb::isinstance<nb::str>(actor)    ? link_actor_by_name(rec, nb::cast<std::string>(actor), what + ": link")
                                                                 : actor_or_zero(actor, (what + ": actor").c_str());
  ComponentArgs args{rec.scene, target, creation_params(params, rec.prefab.base_dir, what + ": params"), &rec.prefab};
  const ComponentHandle h = ctx.create(kind, type_name, args, name, b.handle);
  auto& bot = ctx.bot(b.handle);
  (kind == ComponentKind::Controller ? bot.controllers : kind == ComponentKind::Sensor ? bot.sensors : bot.actuators).push_back(h);
  return h;
}

}  // namespace

void export_robotics(nb::module_& parent) {
  nb::module_ m = parent.def_submodule("robotics", "SuperDex robotics SDK");
  export_prefab(m);
  export_scene_batch(m);
  export_robotics_handles(m);
  export_component_params(m);
  export_component_views(m);
  // BotJointPrefab.effort_limit below zero: no bound on the joint's effort
  m.attr("EFFORT_UNBOUNDED") = -1.0;

  nb::class_<PyContext> ctx_cls(m, "RoboticsContext", "Registries of component types, and every bot and component.");
  ctx_cls
      .def("create_controller", [](PyContext& c, const std::string& type_name, nb::handle prefab, nb::handle actor, const std::string& name,
                                   nb::handle params) {
             ComponentArgs args;
             args.actor = actor_or_zero(actor, "create_controller: actor");
             if (!actor.is_none()) args.scene = nb::cast<Actor&>(actor).scene;
             if (!prefab.is_none()) args.prefab = &nb::cast<BotPrefab&>(prefab);
             args.params = verbatim_params(params, "create_controller('" + name + "'): params");
             return ControllerHandle{c.ctx.create(ComponentKind::Controller, type_name, args, name)};
           }, "type_name"_a, "prefab"_a.none(), "actor"_a.none(), "name"_a = "", "params"_a.none() = "",
           "Creates a controller; params (C++ built-ins): a dict, inline JSON or a JSON file path.")
      .def("create_sensor", [](PyContext& c, const std::string& type_name, nb::handle actor, const std::string& name, nb::handle params) {
             ComponentArgs args;
             args.actor = actor_or_zero(actor, "create_sensor: actor");
             if (!actor.is_none()) args.scene = nb::cast<Actor&>(actor).scene;
             args.params = verbatim_params(params, "create_sensor('" + name + "'): params");
             return SensorHandle{c.ctx.create(ComponentKind::Sensor, type_name, args, name)};
           }, "type_name"_a, "actor"_a.none(), "name"_a = "", "param_args"_a.none() = "")
      .def("create_actuator", [](PyContext& c, const std::string& type_name, nb::handle actor, const std::string& name, nb::handle params) {
             if (actor.is_none()) throw Error("create_actuator('" + name + "'): an actuator needs an actor (a link)");
             ComponentArgs args;
             args.actor = actor_handle_of(actor, "create_actuator: actor");
             args.scene = nb::cast<Actor&>(actor).scene;
             args.params = verbatim_params(params, "create_actuator('" + name + "'): params");
             return ActuatorHandle{c.ctx.create(ComponentKind::Actuator, type_name, args, name)};
           }, "type_name"_a, "actor"_a.none(), "name"_a = "", "param_args"_a.none() = "")
      .def("reset_components", [](PyContext& c) { c.ctx.reset_components(); },
           "Calls reset() on every component and restarts the pipelines' timing.")
      .def("get_sensor_signal", [](const PyContext& c, nb::handle h) {
             return numpy_copy(c.ctx.sensor_signal(handle_of<ComponentKind::Sensor>(h, "get_sensor_signal")));
           }, "handle"_a,
           "The sensor's latest reading as a numpy array of the build's dtype (layout: the sensor type's\n"
           "documentation). A Python sensor's signal() or compute_signal() is called.")
      .def("set_pipeline_enabled", [](PyContext& c, const PyBot& b, nb::handle enabled) {
             c.ctx.set_pipeline_mode(b.handle, pipeline_mode(enabled));
           }, "bot"_a, "enabled"_a.none(), pipeline_doc)
      .def("is_pipeline_active", [](const PyContext& c, const PyBot& b) { return c.ctx.is_pipeline_active(b.handle); }, "bot"_a)
      .def("get_bot", [](nb::handle self, nb::handle h) -> nb::object {
             const BotHandle b = bot_handle_of(h, "get_bot: handle");
             if (!nb::cast<PyContext&>(self).ctx.has_bot(b)) return nb::none();
             return nb::cast(PyBot{nb::borrow(self), b});
           }, "handle"_a, "The bot, or None for an invalid handle or a destroyed bot.")
      .def("is_valid_bot", [](const PyContext& c, nb::handle h) { return c.ctx.has_bot(bot_handle_of(h, "is_valid_bot: handle")); },
           "handle"_a)
      .def("get_bot_containing_actor", [](nb::handle self, nb::handle actor) -> nb::object {
             if (actor.is_none()) return nb::none();
             const Actor& a = object_of<Actor>(actor, "get_bot_containing_actor: actor", "a superdex.physics.Actor or None");
             const BotHandle b = nb::cast<PyContext&>(self).ctx.bot_of_actor(a.scene, a.handle);
             if (b == 0) return nb::none();
             return nb::cast(PyBot{nb::borrow(self), b});
           }, "actor"_a.none(), "The bot whose articulation is `actor` or owns the link `actor`; None otherwise.")
      .def("find_bots_by_name", [](const PyContext& c, const std::string& name) {
             nb::list out;
             for (BotHandle b : c.ctx.find_bots_by_name(name)) out.append(nb::cast(BotHandleValue(b)));
             return out;
           }, "name"_a, "Handles of the live bots named `name`, in creation order.");

  nb::class_<PyBot> bot_cls(m, "Bot", "A robot built by create_bot: its articulation and components.");
  bot_cls
      .def("get_articulated_actor", [](const PyBot& b) {
             const auto& rec = b.ctx().bot(b.handle);
             return Actor{rec.scene, rec.articulation};
           })
      .def("get_name", [](const PyBot& b) { return b.ctx().bot(b.handle).prefab.name(); })
      .def("get_handle", [](const PyBot& b) { return BotHandleValue(b.handle); })
      .def("get_scene", [](const PyBot& b) -> nb::object {
             const Scene& scene = b.ctx().bot(b.handle).scene;
             if (!physics::scene_exists(scene.handle())) return nb::none();
             return nb::cast(scene);
           }, "The scene the bot lives in, or None once it was destroyed.")
      .def("get_bot_prefab", [](const PyBot& b) { return b.ctx().bot(b.handle).prefab; }, "A copy of the prefab it was built from.")
      .def("create_controller", [](PyBot& b, const std::string& type_name, const std::string& name, nb::handle params) {
             return ControllerHandle{bot_create(b, ComponentKind::Controller, type_name, nb::none(), name, params)};
           }, "type_name"_a, "name"_a = "", "params"_a.none() = "")
      .def("create_sensor", [](PyBot& b, const std::string& type_name, nb::handle actor, const std::string& name, nb::handle params) {
             return SensorHandle{bot_create(b, ComponentKind::Sensor, type_name, actor, name, params)};
           }, "type_name"_a, "actor"_a.none(), "name"_a = "", "params"_a.none() = "",
           "Creates a sensor on one of the bot's links: `actor` is the link actor or the link's name.")
      .def("create_actuator", [](PyBot& b, const std::string& type_name, nb::handle actor, const std::string& name, nb::handle params) {
             return ActuatorHandle{bot_create(b, ComponentKind::Actuator, type_name, actor, name, params)};
           }, "type_name"_a, "actor"_a.none(), "name"_a = "", "params"_a.none() = "",
           "Creates a actuator on one of the bot's links: `actor` is the link actor or the link's name.")
      .def("get_sensor_link_name", [](const PyBot& b, nb::handle h) {
             return link_name_of(b, ComponentKind::Sensor, handle_of<ComponentKind::Sensor>(h, "get_sensor_link_name"));
           }, "handle"_a, "The name of the link the sensor is attached to, or None.")
      .def("get_actuator_link_name", [](const PyBot& b, nb::handle h) {
             return link_name_of(b, ComponentKind::Actuator, handle_of<ComponentKind::Actuator>(h, "get_actuator_link_name"));
           }, "handle"_a, "The name of the link the actuator is attached to, or None.")
      .def("reset", [](PyBot& b) { b.ctx().reset_components(b.handle); },
           "Calls reset() on the bot's components and restarts its pipeline's timing.")
      .def("set_pipeline_enabled", [](PyBot& b, nb::handle enabled) { b.ctx().set_pipeline_mode(b.handle, pipeline_mode(enabled)); },
           "enabled"_a.none(), pipeline_doc)
      .def("is_pipeline_active", [](const PyBot& b) { return b.ctx().is_pipeline_active(b.handle); },
           "True while the bot's pipeline runs inside its scene's steps.")
      .def("__repr__", [](const PyBot& b) { return "Bot(" + std::to_string(b.handle) + ")"; });

  def_kind<ComponentKind::Controller>(m, ctx_cls, bot_cls, "controller");
  def_kind<ComponentKind::Sensor>(m, ctx_cls, bot_cls, "sensor");
  def_kind<ComponentKind::Actuator>(m, ctx_cls, bot_cls, "actuator");

  m.def("create_context", [] { return new PyContext(); }, nb::rv_policy::take_ownership,
        "A new robotics context. Not thread-safe: a context, its bots and components are used by one\n"
        "thread at a time (give each thread that steps its own scene its own context).");
  m.def("load_bot_prefab_from_file", [](nb::handle path_arg) {
        std::vector<std::string> warnings;
        const std::string path = nb::cast<std::string>(nb::module_::import_("os").attr("fspath")(path_arg));
        BotPrefab p = robotics::load_bot_prefab(path, &warnings);
        emit(warnings);
        return p;
      }, "path"_a, "Reads a .superdex_bot file.");
  m.def("load_bot_prefab_from_urdf_file", [](nb::handle path_arg, bool fixed_base, bool exclude_overlapping_links,
                                              const std::string& mesh_collision) {
        std::vector<std::string> warnings;
        const std::string path = nb::cast<std::string>(nb::module_::import_("os").attr("fspath")(path_arg));
        robotics::UrdfImportOptions options;
        options.fixed_base = fixed_base;
        options.exclude_overlapping_links = exclude_overlapping_links;
        if (mesh_collision == "mesh") options.mesh_collision = robotics::MeshCollision::Mesh;
        else if (mesh_collision != "convex_hull")
          throw Error("load_bot_prefab_from_urdf_file: mesh_collision must be 'convex_hull' or 'mesh', got '" + mesh_collision + "'");
        BotPrefab p = robotics::load_bot_prefab_from_urdf(path, &warnings, options);
        emit(warnings);
        return p;
      }, "path"_a, nb::kw_only(), "fixed_base"_a = false, "exclude_overlapping_links"_a = true, "mesh_collision"_a = "convex_hull",
      "Imports a URDF file. The root link hangs on a free joint named 'world_joint' (a floating base), or on a "
      "fixed one with fixed_base=True; a root attached to a 'world' link keeps that joint. Links whose collision "
      "shapes already overlap with every joint at zero do not collide with each other (one warning names them) "
      "unless exclude_overlapping_links=False. Mesh colliders are the meshes' convex hulls (mesh_collision='convex_hull'), "
      "or the triangle meshes themselves with mesh_collision='mesh'.");
  m.def("save_to_urdf_string", [](const BotPrefab& prefab) {
        std::vector<std::string> warnings;
        std::string xml = robotics::save_to_urdf_string(prefab, &warnings);
        emit(warnings);
        return xml;
      }, "bot_prefab"_a,
      "The bot as URDF XML: links with inertials and primitive collision shapes, joints with frames, axes, limits, "
      "friction and <mimic> couplings; the root joint is left out. Mesh shapes and rotor inertias are left out (a "
      "warning names them).");
  m.def("save_to_urdf_file", [](const BotPrefab& prefab, nb::handle path) {
        std::vector<std::string> warnings;
        robotics::save_to_urdf_file(prefab, nb::cast<std::string>(nb::module_::import_("os").attr("fspath")(path)), &warnings);
        emit(warnings);
      }, "bot_prefab"_a, "path"_a,
      "Writes the bot as a URDF file (save_to_urdf_string), its mesh collision shapes as OBJ files in <stem>_meshes/ "
      "beside it.");
  nb::class_<robotics::MjcfModel>(m, "MjcfModel", "An MJCF model as bots (load_mjcf_file).")
      .def_ro("name", &robotics::MjcfModel::name, "<mujoco model>, else the file's stem.")
      .def_ro("bots", &robotics::MjcfModel::bots,
              "The bots, in order: the world (a welded root link 'world' with the worldbody's geoms and every tree not on a "
              "free joint; left out when empty), then one per tree on a free joint.")
      .def_prop_ro("gravity", [](const robotics::MjcfModel& mm) { return std::vector<real>{mm.gravity.x(), mm.gravity.y(), mm.gravity.z()}; },
                   "<option gravity> (m/s^2, world frame, z up): give it to the scene with scene.set_gravity.")
      .def_ro("timestep", &robotics::MjcfModel::timestep, "<option timestep> (s).");
  m.def("load_mjcf_file", [](nb::handle path, const std::string& mesh_collision) {
        std::vector<std::string> warnings;
        robotics::MjcfImportOptions options;
        if (mesh_collision == "mesh") options.mesh_collision = robotics::MeshCollision::Mesh;
        else if (mesh_collision != "convex_hull")
          throw Error("load_mjcf_file: mesh_collision must be 'convex_hull' or 'mesh', got '" + mesh_collision + "'");
        const std::string p = nb::cast<std::string>(nb::module_::import_("os").attr("fspath")(path));
        robotics::MjcfModel model = robotics::load_mjcf(p, &warnings, options);
        emit(warnings);
        return model;
      }, "path"_a, nb::kw_only(), "mesh_collision"_a = "convex_hull",
      "Imports an MJCF (MuJoCo XML) file as bots with MuJoCo's kinematics and mass properties: create each of "
      "model.bots with create_bot. What is not imported (actuators, tendons, equality constraints, ...) is named in "
      "warnings. Mesh geoms collide as their convex hulls (MuJoCo's choice), or as triangles with mesh_collision='mesh'.");
  m.def("create_bot", [](nb::handle scene_arg, nb::handle prefab_arg, nb::object ctx) {
        const Scene& scene = object_of<Scene>(scene_arg, "create_bot: scene", "a superdex.physics.Scene");
        const BotPrefab& prefab = object_of<BotPrefab>(prefab_arg, "create_bot: prefab", "a BotPrefab (load_bot_prefab_from_file)");
        std::vector<std::string> warnings;
        Context& c = object_of<PyContext>(ctx, "create_bot: ctx", "a robotics context (create_context())").ctx;
        const BotHandle h = c.create_bot(scene, prefab, &warnings);
        emit(warnings);
        return PyBot{ctx, h};
      }, "scene"_a.none(), "prefab"_a.none(), "ctx"_a.none(),
      "Builds the articulation and the sensors and actuators declared on its links.");
  m.def("destroy_bot", [](const Scene& scene, PyBot& bot) {
        Context& c = bot.ctx();
        if (c.has_bot(bot.handle) && c.bot(bot.handle).scene.handle() != scene.handle())
          throw Error("destroy_bot: bot " + std::to_string(bot.handle) + " does not belong to this scene");
        c.destroy_bot(bot.handle);
      }, "scene"_a, "bot"_a, "Destroys the bot's components, then its articulation.");
}

}  // namespace superdex::python
