// RoboticsHandle and its kinds (BotHandle, ControllerHandle, SensorHandle, ActuatorHandle):
// default-constructible values, 0 being invalid; handles of different kinds never compare equal.

#include <nanobind/stl/string.h>

#include "bind_robotics_types.h"

namespace superdex::python {

namespace {

const char* kind_title(ComponentKind k) { return robotics::component_kind_name(k); }

std::string py_type_name(nb::handle obj) {
  return nb::cast<std::string>(nb::handle(reinterpret_cast<PyObject*>(Py_TYPE(obj.ptr()))).attr("__name__"));
}

template <class H>
void bind_kind(nb::module_& m, const char* name, const char* doc) {
  nb::class_<H, RoboticsHandle>(m, name, doc)
      .def(nb::init<>(), "The invalid handle.")
      .def(nb::init<std::int64_t>(), "value"_a);
}

}  // namespace

ComponentHandle component_handle_of(ComponentKind kind, nb::handle obj, const char* what) {
  const bool same = (kind == ComponentKind::Controller && nb::isinstance<ControllerHandle>(obj)) ||
                    (kind == ComponentKind::Sensor && nb::isinstance<SensorHandle>(obj)) ||
                    (kind == ComponentKind::Actuator && nb::isinstance<ActuatorHandle>(obj));
  if (same) return nb::cast<RoboticsHandle&>(obj).value;
  if (nb::isinstance<RoboticsHandle>(obj))
    throw Error(std::string(what) + ": expected a " + kind_title(kind) + " handle, got a " + py_type_name(obj));
  ComponentHandle h;
  if (nb::isinstance<nb::bool_>(obj) || !nb::try_cast(obj, h))
    throw Error(std::string(what) + ": expected a " + kind_title(kind) + " handle, got " + nb::inst_name(obj).c_str());
  return h;
}

void export_robotics_handles(nb::module_& m) {
  nb::class_<RoboticsHandle>(m, "RoboticsHandle",
                             "Base of the bot and component handles: an integer value, 0 for the invalid handle.\n"
                             "Handles of different kinds never compare equal.")
      .def(nb::init<>(), "The invalid handle.")
      .def(nb::init<std::int64_t>(), "value"_a)
      .def_rw("value", &RoboticsHandle::value)
      .def("is_valid", &RoboticsHandle::is_valid, "True unless this is the invalid (0) handle; says nothing about liveness.")
      .def("__int__", [](const RoboticsHandle& h) { return h.value; })
      .def("__index__", [](const RoboticsHandle& h) { return h.value; })
      // equal when of the same kind (Python type) and value
      .def("__eq__", [](nb::handle a, nb::handle b) {
             return nb::isinstance<RoboticsHandle>(b) && a.type().is(b.type()) &&
                    nb::cast<RoboticsHandle&>(a).value == nb::cast<RoboticsHandle&>(b).value;
           }, nb::is_operator())
      .def("__ne__", [](nb::handle a, nb::handle b) { return !nb::cast<bool>(a.attr("__eq__")(b)); }, nb::is_operator())
      .def("__lt__", [](const RoboticsHandle& a, const RoboticsHandle& b) { return a.value < b.value; }, nb::is_operator())
      .def("__hash__", [](const RoboticsHandle& h) { return std::hash<std::int64_t>{}(h.value); })
      .def("__repr__", [](nb::handle h) -> std::string { return py_type_name(h) + "(" + std::to_string(nb::cast<RoboticsHandle&>(h).value) + ")"; });
  bind_kind<BotHandleValue>(m, "BotHandle", "Identifies a bot in its RoboticsContext.");
  bind_kind<ControllerHandle>(m, "ControllerHandle", "Identifies a controller in its RoboticsContext.");
  bind_kind<SensorHandle>(m, "SensorHandle", "Identifies a sensor in its RoboticsContext.");
  bind_kind<ActuatorHandle>(m, "ActuatorHandle", "Identifies an actuator in its RoboticsContext.");
}

}  // namespace superdex::python
