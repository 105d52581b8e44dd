// The params structs of the built-in components that have one: plain values with keyword
// construction, equality and JSON files (load_from_file / save_to_file).

#include <nanobind/stl/array.h>
#include <nanobind/stl/string.h>

#include "bind_container.h"
#include "bind_robotics_types.h"
#include "struct_binder.h"
#include "superdex/robotics/controller_basic_jsc_pd.h"
#include "superdex/robotics/controller_mochi_articulated_pose.h"
#include "superdex/robotics/sensor_camera.h"

namespace superdex::python {

using robotics::CameraSensorParams;
using robotics::ControllerBasicJscPdParams;
using robotics::ControllerMochiArticulatedPoseObsv;
using robotics::ControllerMochiArticulatedPoseParams;
using robotics::ControllerMochiArticulatedPoseTarget;

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

  StructBinder<ControllerMochiArticulatedPoseParams>(m, "ControllerMochiArticulatedPoseParams",
                                                    "Gains of MOCHI_ARTICULATED_POSE: the engine pose controller's PoseControllerParams.")
      .field("pose_controller_params", &ControllerMochiArticulatedPoseParams::pose_controller_params)
      .done()
      .def_static("load_from_file", &ControllerMochiArticulatedPoseParams::load_from_file, "path"_a, "Reads a .superdex_controller JSON file.")
      .def("save_to_file", &ControllerMochiArticulatedPoseParams::save_to_file, "path"_a, "Writes a .superdex_controller JSON file.");
  nb::class_<ControllerMochiArticulatedPoseObsv>(m, "ControllerMochiArticulatedPoseObsv",
                                                 "What MOCHI_ARTICULATED_POSE observes: nothing (its target aims it).")
      .def(nb::init<>());
  StructBinder<ControllerMochiArticulatedPoseTarget>(
      m, "ControllerMochiArticulatedPoseTarget",
      "The pose MOCHI_ARTICULATED_POSE holds: world_from_root with exactly one of local_to_parent_transforms (one per link,\n"
      "each link in its parent's frame) and pose_dofs (the DOFs below the root: rad, m).")
      .field("world_from_root", &ControllerMochiArticulatedPoseTarget::world_from_root)
      .field("local_to_parent_transforms", &ControllerMochiArticulatedPoseTarget::local_to_parent_transforms)
      .field("pose_dofs", &ControllerMochiArticulatedPoseTarget::pose_dofs)
      .done(false);

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
