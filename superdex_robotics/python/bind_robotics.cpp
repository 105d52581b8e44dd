// superdex.robotics: the context and its registries, Python components held by a C++ adapter
// (python_component.h), typed component handles, bots and their pipelines, the bot loaders.

#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "python_component.h"
#include "superdex/robotics/context.h"

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

// A component handle tagged with its kind, so that a sensor handle cannot be used as an actuator's.
template <ComponentKind K>
struct TypedHandle {
  ComponentHandle value = 0;
};
using ControllerHandle = TypedHandle<ComponentKind::Controller>;
using SensorHandle = TypedHandle<ComponentKind::Sensor>;
using ActuatorHandle = TypedHandle<ComponentKind::Actuator>;

// The Python-side context: the C++ context plus nothing else; components keep Python objects.
struct PyContext {
  Context ctx;
};

// A bot as seen from Python: its context (kept alive) and handle.
struct PyBot {
  nb::object context;  // PyContext
  BotHandle handle = 0;
  Context& ctx() const { return nb::cast<PyContext&>(context).ctx; }
};

const char* kind_title(ComponentKind k) {
  switch (k) {
    case ComponentKind::Controller: return "controller";
    case ComponentKind::Sensor: return "sensor";
    case ComponentKind::Actuator: return "actuator";
  }
  return "?";
}

template <ComponentKind K>
void bind_handle(nb::module_& m, const char* name) {
  using H = TypedHandle<K>;
  nb::class_<H>(m, name)
      .def_ro("value", &H::value)
      .def("__int__", [](const H& h) { return h.value; })
      .def("__index__", [](const H& h) { return h.value; })
      .def("__eq__", [](const H& a, const H& b) { return a.value == b.value; })
      .def("__hash__", [](const H& h) { return h.value; })
      .def("__repr__", [name](const H& h) { return std::string(name) + "(" + std::to_string(h.value) + ")"; });
}

// The handle of kind K from a typed handle or an int; a handle of another kind is refused.
template <ComponentKind K>
ComponentHandle handle_of(nb::handle obj, const char* what) {
  if (nb::isinstance<TypedHandle<K>>(obj)) return nb::cast<TypedHandle<K>&>(obj).value;
  for (bool other : {nb::isinstance<ControllerHandle>(obj), nb::isinstance<SensorHandle>(obj), nb::isinstance<ActuatorHandle>(obj)})
    if (other) throw Error(std::string(what) + ": expected a " + kind_title(K) + " handle, got " + nb::inst_name(obj).c_str());
  ComponentHandle h;
  if (!nb::try_cast(obj, h)) throw Error(std::string(what) + ": expected a " + kind_title(K) + " handle");
  return h;
}

// Handle lists are Python lists of typed handles (no std::vector caster here: the physics
// bindings bind vectors of their element types as DynamicArrays).
template <ComponentKind K>
nb::list typed(const std::vector<ComponentHandle>& hs) {
  nb::list out;
  for (ComponentHandle h : hs) out.append(nb::cast(TypedHandle<K>{h}));
  return out;
}

void emit(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1);
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

// Params given to create_*: a dict (written as JSON) or a string (inline JSON or a file path,
// relative to `base_dir`).
std::string creation_params(nb::handle params, const std::string& base_dir, const std::string& where) {
  if (params.is_none()) return "";
  if (nb::isinstance<nb::str>(params)) return robotics::resolve_params(nb::cast<std::string>(params), base_dir, where);
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
  m.def(("get_python_" + k).c_str(), [](PyContext& c, nb::handle h) {
        return python_object(c.ctx, K, handle_of<K>(h, ("get_python_" + std::string(kind_title(K))).c_str()));
      }, "ctx"_a, "handle"_a, "The live Python object of a Python component, or None for a C++ one.");
  ctx_cls.def(("destroy_" + k).c_str(), [](PyContext& c, nb::handle h) { c.ctx.destroy(K, handle_of<K>(h, "destroy")); }, "handle"_a)
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
      .def(("find_" + k + "s_by_type").c_str(), [](const PyBot& b, const std::string& t) { return bot_find<K>(b, t, true); });
}

// A component created through a bot: attached to `actor` (the bot's articulation for a
// controller), params resolved against the bot file's folder, listed among the bot's components.
ComponentHandle bot_create(PyBot& b, ComponentKind kind, const std::string& type_name, nb::handle actor,
                           const std::string& name, nb::handle params) {
  Context& ctx = b.ctx();
  auto& rec = ctx.bot(b.handle);
  const std::string what = std::string("create_") + kind_title(kind) + "('" + name + "')";
  const ActorHandle target = kind == ComponentKind::Controller ? rec.articulation : actor_or_zero(actor, (what + ": actor").c_str());
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
  bind_handle<ComponentKind::Controller>(m, "ControllerHandle");
  bind_handle<ComponentKind::Sensor>(m, "SensorHandle");
  bind_handle<ComponentKind::Actuator>(m, "ActuatorHandle");
  m.attr("EFFORT_UNBOUNDED") = -1;

  nb::class_<PyContext> ctx_cls(m, "Context", "Registries of component types, and every bot and component.");
  ctx_cls
      .def("create_controller", [](PyContext& c, const std::string& type_name, nb::handle prefab, nb::handle actor, const std::string& name,
                                   nb::handle params) {
             ComponentArgs args;
             args.actor = actor_or_zero(actor, "create_controller: actor");
             if (!actor.is_none()) args.scene = nb::cast<Actor&>(actor).scene;
             if (!prefab.is_none()) args.prefab = &nb::cast<BotPrefab&>(prefab);
             args.params = creation_params(params, "", "create_controller('" + name + "'): params");
             return ControllerHandle{c.ctx.create(ComponentKind::Controller, type_name, args, name)};
           }, "type_name"_a, "prefab"_a.none(), "actor"_a.none(), "name"_a = "", "params"_a.none() = "",
           "Creates a controller; params (C++ built-ins): a dict, inline JSON or a JSON file path.")
      .def("create_sensor", [](PyContext& c, const std::string& type_name, nb::handle actor, const std::string& name, nb::handle params) {
             ComponentArgs args;
             args.actor = actor_or_zero(actor, "create_sensor: actor");
             if (!actor.is_none()) args.scene = nb::cast<Actor&>(actor).scene;
             args.params = creation_params(params, "", "create_sensor('" + name + "'): params");
             return SensorHandle{c.ctx.create(ComponentKind::Sensor, type_name, args, name)};
           }, "type_name"_a, "actor"_a.none(), "name"_a = "", "params"_a.none() = "")
      .def("create_actuator", [](PyContext& c, const std::string& type_name, nb::handle actor, const std::string& name, nb::handle params) {
             if (actor.is_none()) throw Error("create_actuator('" + name + "'): an actuator needs an actor (a link)");
             ComponentArgs args;
             args.actor = actor_handle_of(actor, "create_actuator: actor");
             args.scene = nb::cast<Actor&>(actor).scene;
             args.params = creation_params(params, "", "create_actuator('" + name + "'): params");
             return ActuatorHandle{c.ctx.create(ComponentKind::Actuator, type_name, args, name)};
           }, "type_name"_a, "actor"_a.none(), "name"_a = "", "params"_a.none() = "")
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
      .def("is_pipeline_active", [](const PyContext& c, const PyBot& b) { return c.ctx.is_pipeline_active(b.handle); }, "bot"_a);

  nb::class_<PyBot> bot_cls(m, "Bot", "A robot built by create_bot: its articulation and components.");
  bot_cls
      .def("get_articulated_actor", [](const PyBot& b) {
             const auto& rec = b.ctx().bot(b.handle);
             return Actor{rec.scene, rec.articulation};
           })
      .def("get_name", [](const PyBot& b) { return b.ctx().bot(b.handle).prefab.name(); })
      .def("get_handle", [](const PyBot& b) { return b.handle; })
      .def("get_bot_prefab", [](const PyBot& b) { return b.ctx().bot(b.handle).prefab; }, "A copy of the prefab it was built from.")
      .def("create_controller", [](PyBot& b, const std::string& type_name, const std::string& name, nb::handle params) {
             return ControllerHandle{bot_create(b, ComponentKind::Controller, type_name, nb::none(), name, params)};
           }, "type_name"_a, "name"_a = "", "params"_a.none() = "")
      .def("create_sensor", [](PyBot& b, const std::string& type_name, nb::handle actor, const std::string& name, nb::handle params) {
             return SensorHandle{bot_create(b, ComponentKind::Sensor, type_name, actor, name, params)};
           }, "type_name"_a, "actor"_a.none(), "name"_a = "", "params"_a.none() = "")
      .def("create_actuator", [](PyBot& b, const std::string& type_name, nb::handle actor, const std::string& name, nb::handle params) {
             return ActuatorHandle{bot_create(b, ComponentKind::Actuator, type_name, actor, name, params)};
           }, "type_name"_a, "actor"_a.none(), "name"_a = "", "params"_a.none() = "")
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
  m.def("load_bot_prefab_from_file", [](const std::string& path) {
        std::vector<std::string> warnings;
        BotPrefab p = robotics::load_bot_prefab(path, &warnings);
        emit(warnings);
        return p;
      }, "path"_a, "Reads a .superdex_bot file.");
  m.def("load_bot_prefab_from_urdf_file", [](const std::string& path) {
        std::vector<std::string> warnings;
        BotPrefab p = robotics::load_bot_prefab_from_urdf(path, &warnings);
        emit(warnings);
        return p;
      }, "path"_a, "Imports a URDF file.");
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
