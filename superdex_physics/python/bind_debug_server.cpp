// The scene debugger's server (superdex/physics/debug_server.h) and coordinate spaces
// (superdex/physics/coordinate_space.h).

#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "bind_container.h"
#include "struct_binder.h"
#include "superdex/physics/coordinate_space.h"
#include "superdex/physics/debug_server.h"

namespace superdex::python {

namespace {

// The server as seen from Python: a view of the process's one server.
struct DebugServerView {};

physics::DebugServer& server() { return physics::get_debug_server(); }

// The page draws FLU or RUB axes: other conventions are refused.
physics::CoordinateAxes page_axes(const CoordinateSpace& c) {
  c.validate();
  if (c.axes == CoordinateSpaceAxes::FLU) return physics::CoordinateAxes::FLU;
  if (c.axes == CoordinateSpaceAxes::RUB) return physics::CoordinateAxes::RUB;
  throw Error(std::string("set_coordinate_space: the debugger page draws FLU or RUB axes, got ") + coordinate_space_axes_name(c.axes));
}

Real3 real3(const Eigen::Vector3d& v) { return v.cast<real>(); }

void bind_coordinate_space(nb::module_& m) {
  nb::enum_<CoordinateSpaceAxes> axes(m, "CoordinateSpaceAxes", nb::is_arithmetic(),
                                      "Where the x, y and z axes point: FLU is x forward, y left, z up (the engine's).");
  for (CoordinateSpaceAxes a : kAllCoordinateSpaceAxes) axes.value(coordinate_space_axes_name(a), a);
  add_default_alias<CoordinateSpaceAxes>(m, "CoordinateSpaceAxes");
  StructBinder<CoordinateSpace> c(m, "CoordinateSpace", "A coordinate convention: axis directions and length units per metre.");
  c.field("axes", &CoordinateSpace::axes).field("units_per_meter", &CoordinateSpace::units_per_meter, "> 0 finite; e.g. 100 for centimetres.");
  c.cls()
      .def("validate", &CoordinateSpace::validate, "Raises Error for incomplete axes or a units_per_meter that is not finite positive.")
      .def_static("default", &CoordinateSpace::engine_default, "X-forward, Y-left, Z-up, metres.")
      .def_static("unreal", &CoordinateSpace::unreal, "X-forward, Y-right, Z-up, centimetres.")
      .def_static("unity", &CoordinateSpace::unity, "X-right, Y-up, Z-forward, metres.")
      .def_static("open_gl", &CoordinateSpace::open_gl, "X-right, Y-up, Z-backward, metres.")
      .def_static("filament", &CoordinateSpace::filament, "X-right, Y-up, Z-backward, metres.")
      .def("get_right", [](const CoordinateSpace& s) { s.validate(); return real3(s.right()); }, "The unit vector pointing right, in this space.")
      .def("get_up", [](const CoordinateSpace& s) { s.validate(); return real3(s.up()); })
      .def("get_forward", [](const CoordinateSpace& s) { s.validate(); return real3(s.forward()); });
  c.done();
}

}  // namespace

void export_debug_server(nb::module_& m) {
  bind_coordinate_space(m);
  nb::class_<DebugServerView>(m, "DebugServer",
                              "The scene debugger's server: HTTP and WebSocket on 127.0.0.1 (docs/debugger_protocol.md).")
      .def("start", [](DebugServerView&, int port) { return server().start(port); }, "port"_a = 0,
           nb::call_guard<nb::gil_scoped_release>(), "Serves the debugger page on 127.0.0.1:port (0: a free port); returns the port.")
      .def("start_replay", [](DebugServerView&, const std::string& path, int port) { return server().start_replay(path, port); },
           "path"_a, "port"_a = 0, nb::call_guard<nb::gil_scoped_release>(),
           "Serves the page in replay mode for a recording (docs/recording_format.md); returns the port.")
      .def("stop", [](DebugServerView&) { server().stop(); }, nb::call_guard<nb::gil_scoped_release>(),
           "Closes every page's connection and stops serving; a paused simulation resumes.")
      .def("has_started", [](DebugServerView&) { return server().has_started(); })
      .def("has_connection", [](DebugServerView&) { return server().has_connection(); }, "Whether a page is connected.")
      .def("get_port", [](DebugServerView&) { return server().port(); }, "The listening port, 0 when not started.")
      .def("get_url", [](DebugServerView&) { return server().url(); }, "The page's URL with the session token ('' when not started).")
      .def("wait_for_connection", [](DebugServerView&, double timeout) { return server().wait_for_connection(timeout); },
           "timeout_seconds"_a, nb::call_guard<nb::gil_scoped_release>(), "Waits for a page to connect; True when one is.")
      .def("set_coordinate_space", [](DebugServerView&, const CoordinateSpace& c) { server().set_coordinate_axes(page_axes(c)); },
           "coordinate_space"_a, "The axes pages draw with (set before attach): FLU or RUB, in metres.")
      .def("get_coordinate_space", [](DebugServerView&) {
        return CoordinateSpace{server().coordinate_axes() == physics::CoordinateAxes::FLU ? CoordinateSpaceAxes::FLU : CoordinateSpaceAxes::RUB, 1.0};
      })
      .def("set_ui_directory", [](DebugServerView&, const std::string& path) { server().set_ui_directory(path); }, "path"_a,
           "The folder of the built debugger page (before start).")
      .def("get_ui_directory", [](DebugServerView&) { return server().ui_directory(); })
      .def("is_paused", [](DebugServerView&) { return server().play_state().paused; }, "Whether a page holds the simulation paused.");
  m.def("get_debug_server", [] { return DebugServerView{}; }, "The scene debugger's server (one per process).");
}

}  // namespace superdex::python
