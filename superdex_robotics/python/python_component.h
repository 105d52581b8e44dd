#pragma once
// Python components held by C++ (DESIGN.md: C++ owns every component's life). The adapter of
// each kind holds the Python object and forwards reset(), configure() and, when the object
// defines them, the pipeline methods. The Python pipeline protocol (all optional):
//   sensor.update(t, dt)                   after each step at its rate; t: scene time after
//                                          the step (s), dt: time since its last update (s)
//   sensor.signal() or .compute_signal()   the reading returned by Context.get_sensor_signal
//   controller.compute(t, dt) -> dict|None before each step: {"position": [...],
//                                          "velocity": [...], "effort": [...]}, each one value
//                                          per articulation DOF (root DOFs first), NaN: not
//                                          commanded; a missing key commands nothing
//   actuator.compute_pipeline_effort(commands, dt) -> float
//                                          before each step: commands is {"position",
//                                          "velocity", "effort"} of its DOF, each a float or
//                                          None; returns the effort (N m or N)
//   obj.rate                               Hz, read at creation (0 or absent: every step)
//   obj.configure(params: dict)            for Context.configure_*
// The GIL is taken for each call (scene.step runs without it); a Python exception propagates
// out of scene.step as itself.

#include <memory>
#include <string>

#include "bind_common.h"
#include "superdex/robotics/context.h"

namespace superdex::python {

// Owns the Python object of a component; drops it with the GIL held.
class PythonHeld {
 public:
  explicit PythonHeld(nb::object obj) : obj_(std::move(obj)) {}
  virtual ~PythonHeld() {
    nb::gil_scoped_acquire gil;
    obj_.reset();
  }
  const nb::object& object() const { return obj_; }

 protected:
  nb::object obj_;
};

// A factory of Python components of `kind` (signatures of API.md), for Context::register_type.
robotics::ComponentFactory python_factory(robotics::ComponentKind kind, const std::string& type_name, nb::object factory);

// The live Python object of a component, or None for a C++ one.
nb::object python_object(const robotics::Context& ctx, robotics::ComponentKind kind, robotics::ComponentHandle h);

// A Python params value as JSON text: a str passes as it is, dicts/lists/numbers become JSON
// (non-finite numbers become null: not commanded).
std::string params_text(nb::handle params, const std::string& where);

}  // namespace superdex::python
