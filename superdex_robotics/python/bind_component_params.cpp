// The params structs of the built-in components that have one: plain values with keyword
// construction, equality and JSON files (load_from_file / save_to_file).

#include <nanobind/stl/array.h>
#include <nanobind/stl/string.h>

#include "bind_container.h"
#include "bind_robotics_types.h"
#include "struct_binder.h"
#include "superdex/robotics/controller_basic_jsc_pd.h"
#include "superdex/robotics/sensor_camera.h"

namespace superdex::python {

using robotics::CameraSensorParams;
using robotics::ControllerBasicJscPdParams;

void export_component_params(nb::module_& m) {
  StructBinder<ControllerBasicJscPdParams>(m, "ControllerBasicJscPdParams",
                                           "Gains of BASIC_JSC_PD, one value per joint DOF (one value: every DOF;\n"
                                           "empty: the default).")
      .field("kp", &ControllerBasicJscPdParams::kp, "position gain, N m/rad (N/m); default 100")
      .field("kd", &ControllerBasicJscPdParams::kd, "damping gain, N m s/rad (N s/m); default 10")
      .field("saturation", &ControllerBasicJscPdParams::saturation, "|effort| bound, N m (N); < 0: none (default)")
      .field("deadband", &ControllerBasicJscPdParams::deadband, "position error removed before kp, rad (m); default 0")
      .done()
      .def_static("load_from_file", &ControllerBasicJscPdParams::load_from_file, "path"_a, "Reads a .superdex_controller JSON file.")
      .def("save_to_file", &ControllerBasicJscPdParams::save_to_file, "path"_a, "Writes a .superdex_controller JSON file.");

  StructBinder<CameraSensorParams>(m, "CameraSensorParams", "A camera's intrinsics and mounting; numeric 0 means the renderer's default.")
      .field("name", &CameraSensorParams::name, "the camera's name in the params (not the instance name)")
      .field("image_width", &CameraSensorParams::image_width, "px")
      .field("image_height", &CameraSensorParams::image_height, "px")
      .field("fov_vertical_deg", &CameraSensorParams::fov_vertical_deg, "vertical field of view, degrees")
      .field("near_clip", &CameraSensorParams::near_clip, "m")
      .field("far_clip", &CameraSensorParams::far_clip, "m")
      .field("look_at", &CameraSensorParams::look_at, "world point a fixed camera looks at (m)")
      .field("offset_local", &CameraSensorParams::offset_local, "wrist cameras: offset from the link origin (m)")
      .field("forward_axis", &CameraSensorParams::forward_axis, "wrist cameras: viewing direction, link frame")
      .field("up_axis_local", &CameraSensorParams::up_axis_local, "wrist cameras: image up direction, link frame")
      .field("look_distance", &CameraSensorParams::look_distance, "wrist cameras: distance to the look-at point (m)")
      .done()
      .def("validate", [](const CameraSensorParams& p) { p.validate("CameraSensorParams"); },
           "Raises superdex.physics.Error naming the first out-of-range field.")
      .def("get_pinhole_intrinsics", &CameraSensorParams::pinhole_intrinsics,
           "(fx, fy, cx, cy) in pixels for square pixels; needs image size and field of view.")
      .def_static("load_from_file", &CameraSensorParams::load_from_file, "path"_a, "Reads a .superdex_sensor JSON file.")
      .def("save_to_file", &CameraSensorParams::save_to_file, "path"_a, "Writes a .superdex_sensor JSON file.");
}

}  // namespace superdex::python
