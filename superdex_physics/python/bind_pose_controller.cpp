// The pose controller of articulated actors: PoseTrackingParams, PoseControllerParams,
// PoseConstraintType and PoseConstraintInfo, and the Actor methods that add, tune and aim it
// and read the force it applied.

#include "bind_actor.h"
#include "bind_container.h"
#include "struct_binder.h"

namespace superdex::python {

namespace {

// One array of `out` (pre-sized to one entry per link, as an out-parameter) set from `values`.
void fill_tracking(std::vector<PoseTrackingParams>& out, const std::vector<PoseTrackingParams>& values, const char* field) {
  if (out.size() != values.size())
    throw Error(std::string("get_articulated_pose_controller_params: out_params.") + field + " must hold one entry per link (" +
                std::to_string(values.size()) + "), got " + std::to_string(out.size()) + "; PoseControllerParams(num_links) makes one");
  out = values;
}

}  // namespace

void export_pose_controller(nb::module_& m) {
  StructBinder<PoseTrackingParams>(m, "PoseTrackingParams",
                                   "One spring-damper of a pose controller: stiffness (N/m, or N m/rad on rotations), damping (N s/m, or\n"
                                   "N m s/rad) and saturation (the per-component force cap, N or N m; negative: none; never 0).")
      .field("stiffness", &PoseTrackingParams::stiffness)
      .field("damping", &PoseTrackingParams::damping)
      .field("saturation", &PoseTrackingParams::saturation)
      .done();
  bind_dynamic_array<PoseTrackingParams>(m, "DynamicArrayPoseTrackingParams");
  StructBinder<PoseControllerParams> params(
      m, "PoseControllerParams",
      "A pose controller's gains, each array indexed by link (entry i: link i's centre of mass, its rotation, its inbound\n"
      "joint). An array holds one entry per link, one entry (for every link) or none (zero gains).");
  params.field("link_pos_tracking", &PoseControllerParams::link_pos_tracking)
      .field("link_rot_tracking", &PoseControllerParams::link_rot_tracking)
      .field("joint_tracking", &PoseControllerParams::joint_tracking)
      .done()
      .def("__init__", [](PoseControllerParams* self, int num_links) {
             if (num_links < 0) throw Error("PoseControllerParams: num_links must be >= 0, got " + std::to_string(num_links));
             new (self) PoseControllerParams(num_links);
           }, "num_links"_a, "All three arrays with num_links zero-gain entries.");

  nb::enum_<PoseConstraintType>(m, "PoseConstraintType", "What one of a pose controller's constraints tracks.")
      .value("JOINT", PoseConstraintType::Joint)
      .value("LINK_TRANSLATION", PoseConstraintType::LinkTranslation)
      .value("LINK_ROTATION", PoseConstraintType::LinkRotation)
      .value("INVALID", PoseConstraintType::Invalid);
  StructBinder<PoseConstraintInfo>(m, "PoseConstraintInfo",
                                   "One of a pose controller's constraints: its handle, what it tracks, its link (a joint's: the link the\n"
                                   "joint attaches) and that link's parent (-1: the root).")
      .field("handle", &PoseConstraintInfo::handle)
      .field("type", &PoseConstraintInfo::type)
      .field("link", &PoseConstraintInfo::link)
      .field("parent", &PoseConstraintInfo::parent)
      .done();
  bind_dynamic_array<PoseConstraintInfo>(m, "DynamicArrayPoseConstraintInfo");
  bind_span<const PoseConstraintInfo>(m, "SpanConstPoseConstraintInfo");
}

void add_pose_controller_methods(ActorClass& c) {
  c.def("has_articulated_pose_controller", [](const Actor& a) { return a.scene.has_pose_controller(a.handle); })
      .def("add_articulated_pose_controller", [](Actor& a, const PoseControllerParams& params) { a.scene.add_pose_controller(a.handle, params); },
           "params"_a,
           "Adds the pose controller: per link, spring-dampers pulling its centre of mass and its rotation to their targets, and its\n"
           "inbound joint to its target values. The target starts at the pose now, moving with the joints' velocities now.")
      .def("remove_articulated_pose_controller", [](Actor& a) { a.scene.remove_pose_controller(a.handle); })
      .def("get_articulated_pose_controller_params", [](const Actor& a, PoseControllerParams& out_params) {
             const PoseControllerParams p = a.scene.pose_controller_params(a.handle);
             fill_tracking(out_params.link_pos_tracking, p.link_pos_tracking, "link_pos_tracking");
             fill_tracking(out_params.link_rot_tracking, p.link_rot_tracking, "link_rot_tracking");
             fill_tracking(out_params.joint_tracking, p.joint_tracking, "joint_tracking");
           }, "out_params"_a, "Into out_params (PoseControllerParams(num_links)); zero gains for joints without a controller.")
      .def("set_articulated_pose_controller_params", [](Actor& a, const PoseControllerParams& params) {
             a.scene.set_pose_controller_params(a.handle, params);
           }, "params"_a, "Each array: one entry per link, one for every link, or none (zero gains).")
      .def("get_articulated_pose_constraints", [](const Actor& a) {
             return SpanOf<const PoseConstraintInfo>::owning(a.scene.pose_constraints(a.handle));
           }, "Link translations (every link), link rotations (every link), then joints (all but Hard ones).")
      .def("set_articulated_target_pose", [](Actor& a, nb::handle pose) {
             a.scene.set_target_pose(a.handle, read_vector(pose, "set_articulated_target_pose: pose"));
           }, "pose"_a, "One value per DOF; the target moves there over the next step (the damping follows that motion).")
      .def("reset_articulated_target_pose", [](Actor& a, nb::handle pose) {
             a.scene.reset_target_pose(a.handle, read_vector(pose, "reset_articulated_target_pose: pose"));
           }, "pose"_a, "One value per DOF; the target jumps there and is at rest.")
      .def("set_articulated_target_link_transforms", [](Actor& a, const std::vector<TransformRT>& world_from_targets) {
             a.scene.set_target_link_transforms(a.handle, world_from_targets);
           }, "world_from_targets"_a, "One world-from-link transform per link; the joint target is their projection onto the joints.")
      .def("reset_articulated_target_link_transforms", [](Actor& a, const std::vector<TransformRT>& world_from_targets) {
             a.scene.reset_target_link_transforms(a.handle, world_from_targets);
           }, "world_from_targets"_a, "As set_articulated_target_link_transforms, the target at rest.")
      .def("set_articulated_target_velocity", [](Actor& a, nb::handle velocity) {
             a.scene.set_target_velocity(a.handle, read_vector(velocity, "set_articulated_target_velocity: velocity"));
           }, "velocity"_a, "One value per DOF: how the target moves over the next step (replacing its inferred motion).")
      .def("get_articulated_target_pose", [](const Actor& a, nb::handle out_pose) {
             return fill_out(out_pose, a.scene.target_pose(a.handle), "get_articulated_target_pose: out_pose");
           }, "out_pose"_a.none() = nb::none())
      .def("get_articulated_target_link_transforms", [](const Actor& a, nb::handle out_world_from_targets) -> nb::object {
             const std::vector<Transform> X = a.scene.target_link_transforms(a.handle);
             if (out_world_from_targets.is_none()) return nb::cast(X);
             write_out(out_world_from_targets, X, "get_articulated_target_link_transforms: out_world_from_targets");
             return nb::borrow(out_world_from_targets);
           }, "out_world_from_targets"_a.none() = nb::none())
      .def("get_articulated_controller_force", [](const Actor& a) {
             const VecX f = a.scene.controller_force(a.handle);
             return SpanOf<const real>::owning(std::vector<real>(f.data(), f.data() + f.size()));
           }, "The generalized force (N or N m per DOF) the pose controller applied in the last step; needs an\n"
              "ARTICULATED_CONTROLLER_FORCE query registered before it.");
}

}  // namespace superdex::python
