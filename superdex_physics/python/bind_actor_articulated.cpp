// Articulated actor methods: structure, poses and link transforms, joint velocities, pose
// arithmetic, joint friction, armature and limits, a link's Jacobian, the dynamics terms and the
// implicit joint and link drives (this engine's additions). Out-parameters are filled in place;
// where they are optional, a new array is returned without one.

#include <nanobind/stl/vector.h>

#include "bind_actor.h"
#include "bind_container.h"

namespace superdex::python {

namespace {

std::span<const real> as_span(const VecX& v) { return {v.data(), static_cast<size_t>(v.size())}; }

NumpyArray matrix_to_numpy(const MatX& M) {
  const MatXR R = M;
  return numpy_copy(R.data(), {static_cast<size_t>(R.rows()), static_cast<size_t>(R.cols())});
}

}  // namespace

void add_articulated_methods(ActorClass& c) {
  c.def("get_nested_link_actors", [](const Actor& a) { return SpanOf<const ActorHandle>::owning(a.scene.nested_link_actors(a.handle)); },
        "The link actors, in link order.")
      .def("get_nested_soft_actors", [](const Actor& a) { return SpanOf<const ActorHandle>::owning(a.scene.nested_soft_actors(a.handle)); },
           "A soft-skinned actor's soft actors (create_soft_skinned_actor), in soft_params order; empty for other articulations.")
      .def("get_articulated_actor", [](const Actor& a) { return a.scene.articulated_actor_of_link(a.handle); },
           "The articulated actor this link belongs to.")
      .def("get_link_index", [](const Actor& a) { return a.scene.link_index(a.handle); }, "This link's index in its articulation.")
      .def("get_articulated_shape_info", [](const Actor& a) { return a.scene.articulated_shape_info(a.handle); })
      .def("get_articulated_joint_friction_params", [](const Actor& a) {
             return SpanOf<const ArticulatedJointFrictionParams>::owning(a.scene.joint_friction_params(a.handle));
           }, "One per joint.")
      .def("set_articulated_joint_friction_params", [](Actor& a, const std::vector<ArticulatedJointFrictionParams>& friction) {
             a.scene.set_joint_friction_params(a.handle, friction);
           }, "friction"_a, "One per joint; finite, non-negative.")
      .def("get_articulated_joint_inertia_params", [](const Actor& a) {
             return SpanOf<const real>::owning(a.scene.joint_inertia_params(a.handle));
           }, "Armature per joint (kg or kg m^2).")
      .def("set_articulated_joint_inertia_params", [](Actor& a, nb::handle inertia) {
             a.scene.set_joint_inertia_params(a.handle, as_span(read_vector(inertia, "set_articulated_joint_inertia_params: inertia")));
           }, "inertia"_a, "One per joint; finite, >= 0.")
      .def("get_articulated_joint_limit_constraints", [](const Actor& a) {
             std::vector<Constraint> out;
             for (ConstraintHandle h : a.scene.joint_limit_constraints(a.handle)) out.push_back(Constraint{a.scene, h});
             return out;
           }, "The constraints standing for the joint limits (ARTICULATED_SINGLE_DOF_RANGE, one per limited revolute or\n"
              "prismatic joint): their limits, deviation beyond them, stiffness and damping (0: near rigid).")
      .def("get_articulated_dof_limits", [](const Actor& a, nb::handle out_dof_limits) {
             write_out(out_dof_limits, a.scene.dof_limits(a.handle), "get_articulated_dof_limits: out_dof_limits");
           }, "out_dof_limits"_a, "[min, max] per DOF (m or rad; -inf, +inf where unlimited).")
      .def("get_articulated_pose", [](const Actor& a, nb::handle out_pose) {
             thread_local VecX q;
             a.scene.pose(a.handle, q);
             return fill_out(out_pose, q, "get_articulated_pose: out_pose");
           }, "out_pose"_a.none() = nb::none(),
           "Joint positions, one per DOF (m, rad; rotation vectors for spherical and free rotations).")
      .def("set_articulated_pose_from_joints", [](Actor& a, nb::handle pose) {
             a.scene.set_pose(a.handle, read_vector(pose, "set_articulated_pose_from_joints: pose"));
           }, "pose"_a, "Velocities unchanged.")
      .def("get_articulated_link_transforms", [](const Actor& a, nb::handle out_world_from_links) -> nb::object {
             const std::vector<Transform> X = a.scene.link_transforms(a.handle);
             if (out_world_from_links.is_none()) return nb::cast(X);
             write_out(out_world_from_links, X, "get_articulated_link_transforms: out_world_from_links");
             return nb::borrow(out_world_from_links);
           }, "out_world_from_links"_a.none() = nb::none(), "World-from-link transforms in link order.")
      .def("set_articulated_pose_from_links", [](Actor& a, const std::vector<TransformRT>& world_from_links) {
             a.scene.set_pose_from_links(a.handle, world_from_links);
           }, "world_from_links"_a, "Poses the joints nearest to these link transforms (projected onto the joints).")
      .def("get_articulated_joint_velocities", [](const Actor& a, nb::handle out_velocities) {
             thread_local VecX v;
             a.scene.joint_velocities(a.handle, v);
             return fill_out(out_velocities, v, "get_articulated_joint_velocities: out_velocities");
           }, "out_velocities"_a.none() = nb::none(),
           "Generalized velocities (m/s, rad/s); a free root's are (linear, angular) in its link frame.")
      .def("set_articulated_joint_velocities", [](Actor& a, nb::handle velocities) {
             a.scene.set_joint_velocities(a.handle, read_vector(velocities, "set_articulated_joint_velocities: velocities"));
           }, "velocities"_a)
      .def("add_articulated_delta_to_pose", [](const Actor& a, nb::handle pose, nb::handle delta_dofs, nb::handle out_pose) {
             const VecX q = a.scene.add_delta_to_pose(a.handle, read_vector(pose, "add_articulated_delta_to_pose: pose"),
                                                      read_vector(delta_dofs, "add_articulated_delta_to_pose: delta_dofs"));
             write_out(out_pose, as_span(q), "add_articulated_delta_to_pose: out_pose");
           }, "pose"_a, "delta_dofs"_a, "out_pose"_a, "pose (+) delta, joint by joint (rotation deltas are rotation vectors).")
      .def("compute_articulated_pose_delta", [](const Actor& a, nb::handle pose_base, nb::handle pose_target, nb::handle out_delta_dofs) {
             const VecX d = a.scene.pose_delta(a.handle, read_vector(pose_base, "compute_articulated_pose_delta: pose_base"),
                                               read_vector(pose_target, "compute_articulated_pose_delta: pose_target"));
             write_out(out_delta_dofs, as_span(d), "compute_articulated_pose_delta: out_delta_dofs");
           }, "pose_base"_a, "pose_target"_a, "out_delta_dofs"_a, "The delta taking pose_base to pose_target.")
      .def("get_articulated_pose_distance", [](const Actor& a, nb::handle pose_a, nb::handle pose_b, nb::handle out_trans_distances,
                                               nb::handle out_rot_distances) {
             VecX t, r;
             a.scene.pose_distance(a.handle, read_vector(pose_a, "get_articulated_pose_distance: pose_a"),
                                   read_vector(pose_b, "get_articulated_pose_distance: pose_b"), t, r);
             write_out(out_trans_distances, as_span(t), "get_articulated_pose_distance: out_trans_distances");
             write_out(out_rot_distances, as_span(r), "get_articulated_pose_distance: out_rot_distances");
           }, "pose_a"_a, "pose_b"_a, "out_trans_distances"_a, "out_rot_distances"_a,
           "Per joint: the distance its translation moves (m) and the angle its rotation turns (rad).")
      .def("get_articulated_jacobian", [](const Actor& a, nb::handle out) -> nb::object {
             // one buffer per thread: no allocation per call once it has the articulation's size
             thread_local MatXR J_WL;
             a.scene.link_jacobian(a.handle, J_WL);
             const std::span<const real> values(J_WL.data(), static_cast<size_t>(J_WL.size()));
             if (out.is_none()) return nb::cast(SpanOf<const real>::owning({values.begin(), values.end()}));
             write_out(out, values, "get_articulated_jacobian: out");
             return nb::borrow(out);
           }, "out"_a.none() = nb::none(),
           "A link's Jacobian, world frame, row-major 6 x num_dofs of its articulation: rows 0-2 the velocity of the link\n"
           "origin, rows 3-5 its angular velocity. Into `out` (6 * num_dofs reals) when given, else a SpanConstReal.")
      .def("get_articulated_mass_matrix", [](const Actor& a) { return matrix_to_numpy(a.scene.mass_matrix(a.handle)); },
           "Joint-space mass matrix (num_dofs x num_dofs), armature included.")
      .def("get_articulated_bias_forces", [](const Actor& a) { return numpy_copy(a.scene.bias_forces(a.handle)); },
           "Bias forces c(q, v): Coriolis, centrifugal and gravity, so that M vdot + c = tau.")
      .def("compute_articulated_forward_dynamics", [](const Actor& a, nb::handle tau) {
             return numpy_copy(a.scene.forward_dynamics(a.handle, read_vector(tau, "compute_articulated_forward_dynamics: tau")));
           }, "tau"_a, "Joint accelerations M^-1 (tau - c) of the unconstrained articulation.")
      .def("set_joint_drive", [](Actor& a, int dof, real stiffness, real damping, real target_position, real target_velocity,
                                 real max_effort) {
             a.scene.set_joint_drive(a.handle, dof, JointDrive{stiffness, damping, target_position, target_velocity, max_effort});
           }, "dof"_a, "stiffness"_a = 0, "damping"_a = 0, "target_position"_a = 0, "target_velocity"_a = 0, "max_effort"_a = -1,
           "An implicit spring-damper on a revolute or prismatic DOF, solved inside the step (stable for any stiffness):\n"
           "effort = stiffness (target_position - q) + damping (target_velocity - v) at the end of the step, clamped to\n"
           "max_effort when >= 0. Stiffness and damping 0 turn it off.")
      .def("clear_joint_drives", [](Actor& a) { a.scene.clear_joint_drives(a.handle); }, "Removes every joint and link drive.")
      .def("set_link_drive", [](Actor& a, nb::handle target, real linear_stiffness, real linear_damping, real angular_stiffness,
                                real angular_damping, nb::handle target_linear_velocity, nb::handle target_angular_velocity,
                                real max_force, real max_torque) {
             LinkDrive d;
             d.target = read_transform(target, "set_link_drive: target");
             d.linear_stiffness = linear_stiffness, d.linear_damping = linear_damping;
             d.angular_stiffness = angular_stiffness, d.angular_damping = angular_damping;
             if (!target_linear_velocity.is_none()) d.target_linear_velocity = read_vec3(target_linear_velocity, "set_link_drive: target_linear_velocity");
             if (!target_angular_velocity.is_none()) d.target_angular_velocity = read_vec3(target_angular_velocity, "set_link_drive: target_angular_velocity");
             d.max_force = max_force, d.max_torque = max_torque;
             a.scene.set_link_drive(a.handle, d);
           }, "target"_a, "linear_stiffness"_a = 0, "linear_damping"_a = 0, "angular_stiffness"_a = 0, "angular_damping"_a = 0,
           "target_linear_velocity"_a.none() = nb::none(), "target_angular_velocity"_a.none() = nb::none(), "max_force"_a = -1,
           "max_torque"_a = -1,
           "On a link actor: an implicit spring-damper towards a world pose (TransformRT), solved inside the step;\n"
           "force and torque limits when >= 0; all gains 0 remove it.")
      .def("get_joint_drive_efforts", [](const Actor& a) { return numpy_copy(a.scene.joint_drive_efforts(a.handle)); },
           "Efforts (N m or N) the joint drives applied in the last step, per DOF.");
}

}  // namespace superdex::python
