// The adapters that hold Python components and run them in the bot pipeline.

#include "python_component.h"

#include <cmath>

#include <nanobind/stl/string.h>
#include <nlohmann/json.hpp>

namespace superdex::python {

using robotics::ComponentArgs;
using robotics::ComponentKind;
using robotics::DofCommand;
using robotics::DofCommands;
using robotics::Tick;

namespace {

const char* kind_title(ComponentKind k) { return robotics::component_kind_name(k); }

// The object's attribute `name` when it is callable, else None.
nb::object method(const nb::object& obj, const char* name) {
  nb::object m = nb::getattr(obj, name, nb::none());
  return !m.is_none() && PyCallable_Check(m.ptr()) ? m : nb::none();
}

std::string class_name(const nb::object& obj) {
  return nb::cast<std::string>(nb::handle(reinterpret_cast<PyObject*>(Py_TYPE(obj.ptr()))).attr("__name__"));
}

// The shared part of the three adapters: reset, configure, rate, pipeline participation.
template <class Base>
class PythonAdapter : public Base, public PythonHeld {
 public:
  PythonAdapter(nb::object obj, const char* pipeline_method) : PythonHeld(std::move(obj)) {
    takes_part_ = !method(obj_, pipeline_method).is_none();
    // the rate only means something to the pipeline: other classes may use the name freely
    nb::object rate = takes_part_ ? nb::getattr(obj_, "rate", nb::none()) : nb::none();
    if (!rate.is_none()) {
      double hz;
      if (!nb::try_cast(rate, hz)) throw Error("class '" + class_name(obj_) + "': attribute 'rate' must be a number of Hz");
      this->set_rate(hz);
    }
  }
  void reset() override {
    nb::gil_scoped_acquire gil;
    obj_.attr("reset")();
  }
  void configure(const std::string& json_params) override {
    nb::gil_scoped_acquire gil;
    nb::object fn = method(obj_, "configure");
    if (fn.is_none()) throw Error("class '" + class_name(obj_) + "' has no configure(params) method");
    fn(nb::module_::import_("json").attr("loads")(json_params.empty() ? std::string("{}") : json_params));
  }
  bool takes_part_in_pipeline() const override { return takes_part_; }

 protected:
  bool takes_part_ = false;
};

class PythonSensor final : public PythonAdapter<robotics::SensorComponent> {
 public:
  explicit PythonSensor(nb::object obj) : PythonAdapter(std::move(obj), "update") {}
  void update(const Tick& tick) override {
    nb::gil_scoped_acquire gil;
    obj_.attr("update")(tick.time, tick.dt);
  }
  VecX signal() const override {
    nb::gil_scoped_acquire gil;
    nb::object fn = method(obj_, "signal");
    if (fn.is_none()) fn = method(obj_, "compute_signal");
    if (fn.is_none()) throw Error("sensor class '" + class_name(obj_) + "' has neither signal() nor compute_signal()");
    return read_vector(fn(), class_name(obj_) + ".signal()");
  }
  // the reading the user's code last obtained (kept by superdex.robotics' registration wrapper)
  std::optional<VecX> latest_reading() const override {
    nb::gil_scoped_acquire gil;
    nb::object kept = nb::getattr(obj_, "_superdex_latest_reading", nb::none());
    if (kept.is_none()) return std::nullopt;
    try {
      return read_vector(kept, class_name(obj_) + " reading");
    } catch (const Error&) {
      return std::nullopt;
    }
  }
};

class PythonController final : public PythonAdapter<robotics::ControllerComponent> {
 public:
  explicit PythonController(nb::object obj) : PythonAdapter(std::move(obj), "compute") {}
  void compute(const Tick& tick, DofCommands& out) override {
    nb::gil_scoped_acquire gil;
    nb::object result = obj_.attr("compute")(tick.time, tick.dt);
    if (result.is_none()) return;
    const std::string where = class_name(obj_) + ".compute()";
    if (!nb::isinstance<nb::dict>(result))
      throw Error(where + ": expected a dict {\"position\", \"velocity\", \"effort\"} or None, got " + nb::inst_name(result).c_str());
    for (auto [key, value] : nb::cast<nb::dict>(result)) {
      const std::string k = nb::isinstance<nb::str>(key) ? nb::cast<std::string>(key) : std::string("?");
      if (k != "position" && k != "velocity" && k != "effort")
        throw Error(where + ": unknown key '" + k + "' (expected \"position\", \"velocity\", \"effort\")");
      const VecX values = read_vector(value, where + "[\"" + k + "\"]", out.size());
      for (int d = 0; d < out.size(); ++d) {
        if (std::isnan(values[d])) continue;
        if (k == "position") out.set_position(d, values[d]);
        else if (k == "velocity") out.set_velocity(d, values[d]);
        else out.set_effort(d, values[d]);
      }
    }
  }
};

class PythonActuator final : public PythonAdapter<robotics::ActuatorComponent> {
 public:
  explicit PythonActuator(nb::object obj) : PythonAdapter(std::move(obj), "compute_pipeline_effort") {}
  real compute_effort(const Tick& tick, const DofCommand& command) override {
    nb::gil_scoped_acquire gil;
    auto value = [](const std::optional<real>& x) { return x ? nb::object(nb::float_(double(*x))) : nb::none(); };
    nb::dict commands;
    commands["position"] = value(command.position);
    commands["velocity"] = value(command.velocity);
    commands["effort"] = value(command.effort);
    nb::object result = obj_.attr("compute_pipeline_effort")(commands, tick.dt);
    double effort;
    if (!nb::try_cast(result, effort))
      throw Error(class_name(obj_) + ".compute_pipeline_effort(): expected a number, got " + nb::inst_name(result).c_str());
    return static_cast<real>(effort);
  }
};

nb::object actor_object(const ComponentArgs& args) {
  if (args.actor == 0) return nb::none();
  return nb::cast(Actor{args.scene, args.actor});
}


}  // namespace

robotics::ComponentFactory python_factory(ComponentKind kind, const std::string& type_name, nb::object factory) {
  return [kind, type_name, factory](const ComponentArgs& args) -> std::unique_ptr<robotics::Component> {
    nb::gil_scoped_acquire gil;
    nb::object obj;
    try {
      if (kind == ComponentKind::Controller) obj = factory(actor_object(args));
      else obj = factory(actor_object(args), args.params);
    } catch (nb::python_error& e) {
      throw Error("the factory of " + std::string(kind_title(kind)) + " type '" + type_name + "' raised " + e.what());
    }
    if (method(obj, "reset").is_none())
      throw Error("class '" + class_name(obj) + "' (" + kind_title(kind) + " type '" + type_name +
                  "') has no reset() method: every component must define reset()");
    switch (kind) {
      case ComponentKind::Sensor: return std::make_unique<PythonSensor>(std::move(obj));
      case ComponentKind::Controller: return std::make_unique<PythonController>(std::move(obj));
      case ComponentKind::Actuator: return std::make_unique<PythonActuator>(std::move(obj));
    }
    return nullptr;
  };
}

nb::object python_object(const robotics::Context& ctx, ComponentKind kind, robotics::ComponentHandle h) {
  const auto& rec = ctx.component(kind, h);
  if (auto* p = dynamic_cast<const PythonHeld*>(rec.impl.get())) return p->object();
  return nb::none();
}

std::string params_text(nb::handle params, const std::string& where) {
  if (params.is_none()) return "";
  if (nb::isinstance<nb::str>(params)) return nb::cast<std::string>(params);
  return to_json(params, where).dump();
}

}  // namespace superdex::python
