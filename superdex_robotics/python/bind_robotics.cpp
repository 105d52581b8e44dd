// superdex.robotics: the context and its registries, Python components held by a C++ adapter,
// typed component handles, bots, and the bot loaders.

#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include "bind_common.h"
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

// A Python component owned by C++: the adapter holds the object and forwards reset().
class PythonComponent : public Component {
 public:
  explicit PythonComponent(nb::object obj) : obj_(std::move(obj)) {}
  ~PythonComponent() override {
    nb::gil_scoped_acquire gil;
    obj_.reset();
  }
  void reset() override {
    nb::gil_scoped_acquire gil;
    obj_.attr("reset")();
  }
  const nb::object& object() const { return obj_; }

 private:
  nb::object obj_;
};

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

std::string python_error_text(const nb::python_error& e) { return e.what(); }

nb::object actor_object(const ComponentArgs& args) {
  if (args.actor == 0) return nb::none();
  return nb::cast(Actor{args.scene, args.actor});
}

// Wraps a Python class or callable as a factory of the given kind (signatures of API.md).
robotics::ComponentFactory python_factory(ComponentKind kind, const std::string& type_name, nb::object factory) {
  return [kind, type_name, factory](const ComponentArgs& args) -> std::unique_ptr<Component> {
    nb::gil_scoped_acquire gil;
    nb::object obj;
    try {
      if (kind == ComponentKind::Controller) obj = factory(actor_object(args));
      else obj = factory(actor_object(args), args.params);
    } catch (nb::python_error& e) {
      throw Error("the factory of " + std::string(kind_title(kind)) + " type '" + type_name + "' raised " +
                  python_error_text(e));
    }
    nb::object reset = nb::getattr(obj, "reset", nb::none());
    if (reset.is_none() || !PyCallable_Check(reset.ptr())) {
      const std::string cls = nb::cast<std::string>(nb::handle(reinterpret_cast<PyObject*>(Py_TYPE(obj.ptr()))).attr("__name__"));
      throw Error("class '" + cls + "' (" + kind_title(kind) + " type '" + type_name +
                  "') has no reset() method: every component must define reset()");
    }
    return std::make_unique<PythonComponent>(std::move(obj));
  };
}

nb::object python_object(Context& ctx, ComponentKind kind, ComponentHandle h) {
  const auto& rec = ctx.component(kind, h);
  if (auto* p = dynamic_cast<PythonComponent*>(rec.impl.get())) return p->object();
  return nb::none();
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

template <ComponentKind K>
std::vector<TypedHandle<K>> typed(const std::vector<ComponentHandle>& hs) {
  std::vector<TypedHandle<K>> out;
  for (ComponentHandle h : hs) out.push_back({h});
  return out;
}

void emit(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1);
}

ActorHandle actor_or_zero(nb::handle a, const char* what) { return a.is_none() ? 0 : actor_handle_of(a, what); }

// Bot component lists filtered by name or type.
template <ComponentKind K>
std::vector<TypedHandle<K>> bot_find(const PyBot& b, const std::string& value, bool by_type) {
  Context& ctx = b.ctx();
  const auto& rec = ctx.bot(b.handle);
  const auto& list = K == ComponentKind::Controller ? rec.controllers : K == ComponentKind::Sensor ? rec.sensors : rec.actuators;
  std::vector<TypedHandle<K>> out;
  for (ComponentHandle h : list) {
    const auto& c = ctx.component(K, h);
    if ((by_type ? c.type : c.name) == value) out.push_back({h});
  }
  return out;
}

template <ComponentKind K>
void def_kind(nb::module_& m, nb::class_<PyContext>& ctx_cls, nb::class_<PyBot>& bot_cls, const std::string& k) {
  m.def(("register_python_" + k).c_str(), [](PyContext& c, const std::string& type_name, nb::object factory) {
        if (!PyCallable_Check(factory.ptr()))
          throw Error("register_python_" + std::string(kind_title(K)) + ": the factory for '" + type_name + "' is not callable");
        c.ctx.register_type(K, type_name, python_factory(K, type_name, factory));
      }, "ctx"_a, "type_name"_a, "factory"_a);
  m.def(("get_python_" + k).c_str(), [](PyContext& c, nb::handle h) {
        return python_object(c.ctx, K, handle_of<K>(h, ("get_python_" + std::string(kind_title(K))).c_str()));
      }, "ctx"_a, "handle"_a, "The live Python object of a Python component, or None for a C++ one.");
  ctx_cls.def(("destroy_" + k).c_str(), [](PyContext& c, nb::handle h) { c.ctx.destroy(K, handle_of<K>(h, "destroy")); }, "handle"_a)
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

}  // namespace

void export_robotics(nb::module_& parent) {
  nb::module_ m = parent.def_submodule("robotics", "SuperDex robotics SDK");
  export_prefab(m);
  bind_handle<ComponentKind::Controller>(m, "ControllerHandle");
  bind_handle<ComponentKind::Sensor>(m, "SensorHandle");
  bind_handle<ComponentKind::Actuator>(m, "ActuatorHandle");
  m.attr("EFFORT_UNBOUNDED") = -1;

  nb::class_<PyContext> ctx_cls(m, "Context", "Registries of component types, and every bot and component.");
  ctx_cls
      .def("create_controller", [](PyContext& c, const std::string& type_name, nb::handle prefab, nb::handle actor, const std::string& name) {
             ComponentArgs args;
             args.actor = actor_or_zero(actor, "create_controller: actor");
             if (!actor.is_none()) args.scene = nb::cast<Actor&>(actor).scene;
             if (!prefab.is_none()) args.prefab = &nb::cast<BotPrefab&>(prefab);
             return ControllerHandle{c.ctx.create(ComponentKind::Controller, type_name, args, name)};
           }, "type_name"_a, "prefab"_a.none(), "actor"_a.none(), "name"_a = "")
      .def("create_sensor", [](PyContext& c, const std::string& type_name, nb::handle actor, const std::string& name, const std::string& params) {
             ComponentArgs args;
             args.actor = actor_or_zero(actor, "create_sensor: actor");
             if (!actor.is_none()) args.scene = nb::cast<Actor&>(actor).scene;
             args.params = robotics::resolve_params(params, "", "create_sensor('" + name + "'): params");
             return SensorHandle{c.ctx.create(ComponentKind::Sensor, type_name, args, name)};
           }, "type_name"_a, "actor"_a.none(), "name"_a = "", "params"_a = "")
      .def("create_actuator", [](PyContext& c, const std::string& type_name, nb::handle actor, const std::string& name, const std::string& params) {
             if (actor.is_none()) throw Error("create_actuator('" + name + "'): an actuator needs an actor (a link)");
             ComponentArgs args;
             args.actor = actor_handle_of(actor, "create_actuator: actor");
             args.scene = nb::cast<Actor&>(actor).scene;
             args.params = robotics::resolve_params(params, "", "create_actuator('" + name + "'): params");
             return ActuatorHandle{c.ctx.create(ComponentKind::Actuator, type_name, args, name)};
           }, "type_name"_a, "actor"_a.none(), "name"_a = "", "params"_a = "")
      .def("reset_components", [](PyContext& c) { c.ctx.reset_components(); }, "Calls reset() on every component.");

  nb::class_<PyBot> bot_cls(m, "Bot", "A robot built by create_bot: its articulation and components.");
  bot_cls
      .def("get_articulated_actor", [](const PyBot& b) {
             const auto& rec = b.ctx().bot(b.handle);
             return Actor{rec.scene, rec.articulation};
           })
      .def("get_name", [](const PyBot& b) { return b.ctx().bot(b.handle).prefab.name(); })
      .def("get_handle", [](const PyBot& b) { return b.handle; })
      .def("get_bot_prefab", [](const PyBot& b) { return b.ctx().bot(b.handle).prefab; }, "A copy of the prefab it was built from.")
      .def("create_controller", [](PyBot& b, const std::string& type_name, const std::string& name) {
             Context& ctx = b.ctx();
             auto& rec = ctx.bot(b.handle);
             ComponentArgs args{rec.scene, rec.articulation, "", &rec.prefab};
             const ComponentHandle h = ctx.create(ComponentKind::Controller, type_name, args, name, b.handle);
             ctx.bot(b.handle).controllers.push_back(h);
             return ControllerHandle{h};
           }, "type_name"_a, "name"_a = "")
      .def("create_sensor", [](PyBot& b, const std::string& type_name, nb::handle actor, const std::string& name, const std::string& params) {
             Context& ctx = b.ctx();
             auto& rec = ctx.bot(b.handle);
             ComponentArgs args{rec.scene, actor_or_zero(actor, "create_sensor: actor"),
                                robotics::resolve_params(params, rec.prefab.base_dir, "create_sensor('" + name + "'): params"), &rec.prefab};
             const ComponentHandle h = ctx.create(ComponentKind::Sensor, type_name, args, name, b.handle);
             ctx.bot(b.handle).sensors.push_back(h);
             return SensorHandle{h};
           }, "type_name"_a, "actor"_a.none(), "name"_a = "", "params"_a = "")
      .def("create_actuator", [](PyBot& b, const std::string& type_name, nb::handle actor, const std::string& name, const std::string& params) {
             Context& ctx = b.ctx();
             auto& rec = ctx.bot(b.handle);
             ComponentArgs args{rec.scene, actor_or_zero(actor, "create_actuator: actor"),
                                robotics::resolve_params(params, rec.prefab.base_dir, "create_actuator('" + name + "'): params"), &rec.prefab};
             const ComponentHandle h = ctx.create(ComponentKind::Actuator, type_name, args, name, b.handle);
             ctx.bot(b.handle).actuators.push_back(h);
             return ActuatorHandle{h};
           }, "type_name"_a, "actor"_a.none(), "name"_a = "", "params"_a = "")
      .def("reset", [](PyBot& b) { b.ctx().reset_components(b.handle); }, "Calls reset() on the bot's components.")
      .def("__repr__", [](const PyBot& b) { return "Bot(" + std::to_string(b.handle) + ")"; });

  def_kind<ComponentKind::Controller>(m, ctx_cls, bot_cls, "controller");
  def_kind<ComponentKind::Sensor>(m, ctx_cls, bot_cls, "sensor");
  def_kind<ComponentKind::Actuator>(m, ctx_cls, bot_cls, "actuator");

  m.def("create_context", [] { return new PyContext(); }, nb::rv_policy::take_ownership, "A new robotics context.");
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
  m.def("create_bot", [](const Scene& scene, const BotPrefab& prefab, nb::object ctx) {
        std::vector<std::string> warnings;
        Context& c = nb::cast<PyContext&>(ctx).ctx;
        const BotHandle h = c.create_bot(scene, prefab, &warnings);
        emit(warnings);
        return PyBot{ctx, h};
      }, "scene"_a, "prefab"_a, "ctx"_a,
      "Builds the articulation and the sensors and actuators declared on its links.");
  m.def("destroy_bot", [](const Scene& scene, PyBot& bot) {
        Context& c = bot.ctx();
        if (c.has_bot(bot.handle) && c.bot(bot.handle).scene.handle() != scene.handle())
          throw Error("destroy_bot: bot " + std::to_string(bot.handle) + " does not belong to this scene");
        c.destroy_bot(bot.handle);
      }, "scene"_a, "bot"_a, "Destroys the bot's components, then its articulation.");
}

}  // namespace superdex::python
