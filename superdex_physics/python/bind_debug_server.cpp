// The scene debugger's server (superdex/physics/debug_server.h) and its coordinate space.

#include <nanobind/stl/string.h>

#include "bind_common.h"
#include "superdex/physics/debug_server.h"

namespace superdex::python {

namespace {

// The axes the debugger page draws with (API.md: CoordinateSpace(axes=CoordinateSpaceAxes.FLU)).
struct CoordinateSpace {
  physics::CoordinateAxes axes = physics::CoordinateAxes::FLU;
};

// The server as seen from Python: a view of the process's one server.
struct DebugServerView {};

physics::DebugServer& server() { return physics::get_debug_server(); }

}  // namespace

void export_debug_server(nb::module_& m) {
  nb::enum_<physics::CoordinateAxes>(m, "CoordinateSpaceAxes", "Which way is up in the debugger page.")
      .value("FLU", physics::CoordinateAxes::FLU, "x forward, y left, z up (the engine's frame)")
      .value("RUB", physics::CoordinateAxes::RUB, "x right, y up, z backward (Y up)");
  nb::class_<CoordinateSpace>(m, "CoordinateSpace", "The debugger page's coordinate convention.")
      .def(nb::init<physics::CoordinateAxes>(), "axes"_a = physics::CoordinateAxes::FLU)
      .def_rw("axes", &CoordinateSpace::axes)
      .def("__repr__", [](const CoordinateSpace& c) {
        return std::string("CoordinateSpace(axes=CoordinateSpaceAxes.") + (c.axes == physics::CoordinateAxes::FLU ? "FLU" : "RUB") + ")";
      });
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
      .def("set_coordinate_space", [](DebugServerView&, const CoordinateSpace& c) { server().set_coordinate_axes(c.axes); },
           "coordinate_space"_a, "The axes pages draw with (set before attach).")
      .def("get_coordinate_space", [](DebugServerView&) { return CoordinateSpace{server().coordinate_axes()}; })
      .def("set_ui_directory", [](DebugServerView&, const std::string& path) { server().set_ui_directory(path); }, "path"_a,
           "The folder of the built debugger page (before start).")
      .def("get_ui_directory", [](DebugServerView&) { return server().ui_directory(); })
      .def("is_paused", [](DebugServerView&) { return server().play_state().paused; }, "Whether a page holds the simulation paused.");
  m.def("get_debug_server", [] { return DebugServerView{}; }, "The scene debugger's server (one per process).");
}

}  // namespace superdex::python
