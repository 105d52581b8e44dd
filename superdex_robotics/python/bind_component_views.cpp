// ComponentBase and its subclasses: Python views of live components (bind_robotics_types.h).
// Every call resolves the component through its context, so a destroyed component's view
// answers is_valid() == False and raises superdex.physics.Error on other calls.

#include <nanobind/stl/string.h>

#include "bind_container.h"
#include "bind_robotics_types.h"
#include "superdex/physics/engine.h"
#include "superdex/robotics/controller_basic_jsc_pd.h"
#include "superdex/robotics/controller_mochi_articulated_pose.h"
#include "superdex/robotics/sensor_camera.h"

namespace superdex::python {

using robotics::CameraSensor;
using robotics::CameraSensorParams;
using robotics::ControllerBasicJscPd;
using robotics::ControllerBasicJscPdParams;
using robotics::ControllerMochiArticulatedPose;
using robotics::ControllerMochiArticulatedPoseObsv;
using robotics::ControllerMochiArticulatedPoseParams;
using robotics::ControllerMochiArticulatedPoseTarget;

const robotics::ComponentRecord& ComponentView::record() const {
  if (!is_valid())
    throw Error(std::string(robotics::component_kind_name(kind)) + " " + std::to_string(handle) +
                " no longer exists (it was destroyed, or its bot was)");
  return ctx().component(kind, handle);
}

nb::object component_view(nb::object context, ComponentKind kind, ComponentHandle handle) {
  Context& ctx = nb::cast<PyContext&>(context).ctx;
  if (!ctx.has_component(kind, handle)) return nb::none();
  const robotics::Component* impl = ctx.component(kind, handle).impl.get();
  // the most specific view for the component's C++ type
  switch (kind) {
    case ComponentKind::Controller:
      if (dynamic_cast<const ControllerBasicJscPd*>(impl)) return nb::cast(JscPdControllerView{{{context, kind, handle}}});
      if (dynamic_cast<const ControllerMochiArticulatedPose*>(impl))
        return nb::cast(MochiArticulatedPoseControllerView{{{context, kind, handle}}});
      return nb::cast(ControllerView{{context, kind, handle}});
    case ComponentKind::Sensor:
      if (dynamic_cast<const CameraSensor*>(impl)) return nb::cast(CameraSensorView{{{context, kind, handle}}});
      return nb::cast(SensorView{{context, kind, handle}});
    case ComponentKind::Actuator:
      return nb::cast(ActuatorView{{context, kind, handle}});
  }
  return nb::none();
}

namespace {

// The component's C++ object as T, or superdex::Error naming `what`.
template <class T>
T& impl_as(const ComponentView& v, const char* what) {
  auto* p = dynamic_cast<T*>(v.record().impl.get());
  if (!p) throw Error(std::string(what) + ": component '" + v.record().name + "' is not a " + T::kTypeName);
  return *p;
}

nb::object actor_of(const ComponentView& v) {
  const auto& rec = v.record();
  if (rec.actor == 0 || !physics::scene_exists(rec.scene.handle()) || !rec.scene.has_actor(rec.actor)) return nb::none();
  return nb::cast(Actor{rec.scene, rec.actor});
}

nb::object owning_bot(const ComponentView& v) {
  const auto& rec = v.record();
  // the bot it was created through, else the bot its actor belongs to
  const BotHandle b = rec.bot != 0 ? rec.bot : rec.attached_bot;
  if (b == 0 || !v.ctx().has_bot(b)) return nb::none();
  return nb::cast(PyBot{v.context, b});
}

}  // namespace

void export_component_views(nb::module_& m) {
  nb::class_<ComponentView>(m, "ComponentBase", "A controller, sensor or actuator owned by a RoboticsContext.")
      .def("is_valid", &ComponentView::is_valid, "False once the context destroyed the component.")
      .def("get_actor", &actor_of, "The live actor it is bound to, or None (none given, or destroyed since).")
      .def("get_owning_bot", &owning_bot,
           "The bot it was created on, or whose articulation or link its actor is; None otherwise.")
      .def("get_name", [](const ComponentView& v) { return v.record().name; }, "Instance name; empty if unnamed.")
      .def("get_type_name", [](const ComponentView& v) { return v.record().type; }, "Registered type name.")
      .def("reset", [](const ComponentView& v) { v.record().impl->reset(); },
           "Returns the component to its initial state; parameters are kept.")
      .def("__repr__", [](const ComponentView& v) {
        const std::string kind = robotics::component_kind_name(v.kind);
        if (!v.is_valid()) return kind + "(destroyed)";
        return kind + "('" + v.record().name + "', type " + v.record().type + ")";
      });

  nb::class_<ControllerView, ComponentView>(m, "ControllerBase", "A controller.")
      .def("configure_from_scene_entry", [](const ControllerView& v, const std::string& param_args, const std::string& init_args) {
             v.record();  // raises for a destroyed controller
             v.ctx().configure_from_scene_entry(v.kind, v.handle, param_args, init_args);
           }, "param_args"_a, "init_args"_a,
           "Configures it as a scene file's entry does: param_args and init_args are inline JSON or JSON\n"
           "file paths; empty strings mean the defaults.");

  nb::class_<SensorView, ComponentView>(m, "SensorBase", "A sensor.")
      .def("get_parent_from_sensor", [](const SensorView& v) { return v.record().parent_from_sensor; },
           "The sensor frame in its parent frame: its actor's, or the world for an actor-less sensor.")
      .def("set_parent_from_sensor", [](const SensorView& v, nb::handle pose) {
             v.record();
             v.ctx().set_parent_from_sensor(v.handle, read_transform(pose, "set_parent_from_sensor: parent_from_sensor"));
           }, "parent_from_sensor"_a.none())
      .def("get_world_transform", [](const SensorView& v) {
             v.record();
             return v.ctx().sensor_world_transform(v.handle);
           }, "World-from-sensor: the actor's world pose times parent_from_sensor (parent_from_sensor alone\n"
              "without an actor).");

  nb::class_<ActuatorView, ComponentView>(m, "ActuatorBase", "An actuator.");

  nb::class_<JscPdControllerView, ControllerView>(m, "ControllerBasicJscPd", "BASIC_JSC_PD: joint-space PD efforts.")
      .def_static("type_name", [] { return std::string(ControllerBasicJscPd::kTypeName); })
      .def("get_params", [](const JscPdControllerView& v) { return impl_as<ControllerBasicJscPd>(v, "get_params").params(); },
           "The gains in use, one value per joint DOF.")
      .def("set_params", [](const JscPdControllerView& v, nb::handle p) {
             impl_as<ControllerBasicJscPd>(v, "set_params")
                 .set_params(object_of<ControllerBasicJscPdParams>(p, "set_params: params", "a ControllerBasicJscPdParams"));
           }, "params"_a.none(), "Replaces the gains (empty: defaults, one value: every joint DOF).");

  nb::class_<MochiArticulatedPoseControllerView, ControllerView>(
      m, "ControllerMochiArticulatedPose", "MOCHI_ARTICULATED_POSE: the engine's pose controller, aimed by compute_output.")
      .def_static("type_name", [] { return std::string(ControllerMochiArticulatedPose::kTypeName); })
      .def("get_params", [](const MochiArticulatedPoseControllerView& v) { return impl_as<ControllerMochiArticulatedPose>(v, "get_params").params(); })
      .def("set_params", [](const MochiArticulatedPoseControllerView& v, const ControllerMochiArticulatedPoseParams& p) {
             impl_as<ControllerMochiArticulatedPose>(v, "set_params").set_params(p);
           }, "params"_a, "Keeps the params; once initialized, also sets the engine controller's gains.")
      .def("initialize", [](const MochiArticulatedPoseControllerView& v, bool remove_existing) {
             impl_as<ControllerMochiArticulatedPose>(v, "initialize").initialize(remove_existing);
           }, "remove_existing"_a = false,
           "Adds the engine pose controller to the articulation (replacing one when remove_existing, else an error).")
      .def("compute_output", [](const MochiArticulatedPoseControllerView& v, const ControllerMochiArticulatedPoseObsv& obsv,
                                const ControllerMochiArticulatedPoseTarget& target) {
             impl_as<ControllerMochiArticulatedPose>(v, "compute_output").compute_output(obsv, target);
             return SpanOf<const real>::owning({});
           }, "obsv"_a, "target"_a, "Aims the engine controller at the target; returns no efforts (the constraints act inside the step).");

  nb::class_<CameraSensorView, SensorView>(m, "CameraSensor", "SENSOR_CAMERA: intrinsics and mounting for renderers.")
      .def_static("type_name", [] { return std::string(CameraSensor::kTypeName); })
      .def("get_params", [](const CameraSensorView& v) { return impl_as<CameraSensor>(v, "get_params").params(); })
      .def("set_params", [](const CameraSensorView& v, nb::handle p) {
             impl_as<CameraSensor>(v, "set_params").set_params(object_of<CameraSensorParams>(p, "set_params: params", "a CameraSensorParams"));
           }, "params"_a.none(), "Validates, then replaces the params (Error names the field).");
}

}  // namespace superdex::python
