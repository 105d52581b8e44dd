#pragma once
// The Python-side objects of superdex.robotics shared by its binding files: the context, bots,
// handles and component views. Python never holds a C++ component pointer: a view is the
// context plus a handle, resolved on every call, so a stale view reports is_valid() == False
// instead of dangling.

#include <cstdint>

#include "bind_common.h"
#include "superdex/robotics/context.h"

namespace superdex::python {

using robotics::BotHandle;
using robotics::ComponentHandle;
using robotics::ComponentKind;
using robotics::Context;

// The value shared by every robotics handle; 0 is the invalid handle.
struct RoboticsHandle {
  std::int64_t value = 0;
  RoboticsHandle() = default;
  explicit RoboticsHandle(std::int64_t v) : value(v) {}
  bool is_valid() const { return value != 0; }
};

// A component handle tagged with its kind, so that a sensor handle cannot be used as an actuator's.
template <ComponentKind K>
struct TypedHandle : RoboticsHandle {
  using RoboticsHandle::RoboticsHandle;
};
using ControllerHandle = TypedHandle<ComponentKind::Controller>;
using SensorHandle = TypedHandle<ComponentKind::Sensor>;
using ActuatorHandle = TypedHandle<ComponentKind::Actuator>;

// Python's BotHandle.
struct BotHandleValue : RoboticsHandle {
  using RoboticsHandle::RoboticsHandle;
};

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

// A component as seen from Python (ComponentBase and its subclasses).
struct ComponentView {
  nb::object context;  // PyContext
  ComponentKind kind = ComponentKind::Sensor;
  ComponentHandle handle = 0;
  Context& ctx() const { return nb::cast<PyContext&>(context).ctx; }
  bool is_valid() const { return ctx().has_component(kind, handle); }
  // the live record; superdex::Error once the component was destroyed
  const robotics::ComponentRecord& record() const;
};
struct ControllerView : ComponentView {};
struct SensorView : ComponentView {};
struct ActuatorView : ComponentView {};
struct CameraSensorView : SensorView {};
struct JscPdControllerView : ControllerView {};
struct MochiArticulatedPoseControllerView : ControllerView {};

// The handle of kind K from a typed handle or an int; a handle of another kind is refused
// (superdex::Error naming `what`).
ComponentHandle component_handle_of(ComponentKind kind, nb::handle obj, const char* what);
template <ComponentKind K>
ComponentHandle handle_of(nb::handle obj, const char* what) {
  return component_handle_of(K, obj, what);
}

// The view of a live component (the most specific Python class for its C++ type), or None.
nb::object component_view(nb::object context, ComponentKind kind, ComponentHandle handle);

void export_robotics_handles(nb::module_& m);
void export_component_views(nb::module_& m);
void export_component_params(nb::module_& m);

}  // namespace superdex::python
