// Constraints: ConstraintType, the constraint params, the Constraint class (a scene and a
// handle), and the Scene's methods that create, find and destroy them.

#include <nanobind/stl/function.h>
#include <nanobind/stl/optional.h>

#include "bind_common.h"
#include "bind_container.h"
#include "struct_binder.h"

namespace superdex::python {

void export_constraints(nb::module_& m) {
  nb::enum_<ConstraintType>(m, "ConstraintType", "The kind of a constraint.")
      .value("RIGID_SPHERICAL_JOINT", ConstraintType::RigidSphericalJoint)
      .value("RIGID_PRISMATIC_JOINT", ConstraintType::RigidPrismaticJoint)
      .value("JOINT_ROTATION_RANGE", ConstraintType::JointRotationRange)
      .value("JOINT_ROTATION_TRACKING", ConstraintType::JointRotationTracking)
      .value("ROD_ELEMENT_ROTATION_TO_RIGID", ConstraintType::RodElementRotationToRigid)
      .value("RIGID_PIVOT_POSITION", ConstraintType::RigidPivotPosition)
      .value("RIGID_PIVOT_TO_RIGID_TARGET", ConstraintType::RigidPivotToRigidTarget)
      .value("RIGID_PIVOT_ROTATION", ConstraintType::RigidPivotRotation)
      .value("DEFORMABLE_NODE_POSITION", ConstraintType::DeformableNodePosition)
      .value("ARTICULATED_SINGLE_DOF_TARGET", ConstraintType::ArticulatedSingleDofTarget)
      .value("ARTICULATED_3D_ROTATION_TARGET", ConstraintType::Articulated3dRotationTarget)
      .value("ARTICULATED_SINGLE_DOF_RANGE", ConstraintType::ArticulatedSingleDofRange)
      .value("DEFORMABLE_NODE_TO_RIGID", ConstraintType::DeformableNodeToRigid)
      .value("DEFORMABLE_NODE_TO_DEFORMABLE_NODE", ConstraintType::DeformableNodeToDeformableNode);

  StructBinder<ConstraintParams>(m, "ConstraintParams",
                                 "An implicit spring-damper on a constraint's deviation, per component: stiffness (N/m or N m/rad),\n"
                                 "damping (N s/m or N m s/rad), saturation (the force cap, N or N m; negative: none; never 0).")
      .field("stiffness", &ConstraintParams::stiffness)
      .field("damping", &ConstraintParams::damping)
      .field("saturation", &ConstraintParams::saturation)
      .done();
  StructBinder<RigidSphericalJointConstraintParams, ConstraintParams>(
      m, "RigidSphericalJointConstraintParams", "A ball joint: the point local_pos_a of actor_a on the point local_pos_b of actor_b (m, actor frames).")
      .field("local_pos_a", &RigidSphericalJointConstraintParams::local_pos_a)
      .field("local_pos_b", &RigidSphericalJointConstraintParams::local_pos_b)
      .field("actor_a", &RigidSphericalJointConstraintParams::actor_a)
      .field("actor_b", &RigidSphericalJointConstraintParams::actor_b)
      .done(false);
  StructBinder<RigidPrismaticJointConstraintParams, ConstraintParams>(
      m, "RigidPrismaticJointConstraintParams",
      "actor_b's origin moves relative to actor_a only along free_axis (world at creation, then fixed in actor_a), between min\n"
      "and max (m) when given; actor_b's rotation is free.")
      .field("free_axis", &RigidPrismaticJointConstraintParams::free_axis)
      .field("actor_a", &RigidPrismaticJointConstraintParams::actor_a)
      .field("actor_b", &RigidPrismaticJointConstraintParams::actor_b)
      .field("max", &RigidPrismaticJointConstraintParams::max)
      .field("min", &RigidPrismaticJointConstraintParams::min)
      .done(false);
  StructBinder<JointRotationRangeConstraintParams, ConstraintParams>(
      m, "JointRotationRangeConstraintParams",
      "Bounds (rad, per axis of the joint frame ref_frame_rot_vec: world at creation, then fixed in actor_a) on the rotation of\n"
      "actor_b relative to actor_a, measured from their relative rotation at creation when range_around_rest.")
      .field("ref_frame_rot_vec", &JointRotationRangeConstraintParams::ref_frame_rot_vec)
      .field("angle_range_x", &JointRotationRangeConstraintParams::angle_range_x)
      .field("angle_range_y", &JointRotationRangeConstraintParams::angle_range_y)
      .field("angle_range_z", &JointRotationRangeConstraintParams::angle_range_z)
      .field("actor_a", &JointRotationRangeConstraintParams::actor_a)
      .field("actor_b", &JointRotationRangeConstraintParams::actor_b)
      .field("range_around_rest", &JointRotationRangeConstraintParams::range_around_rest)
      .done(false);
  StructBinder<JointRotationTrackingConstraintParams, ConstraintParams>(
      m, "JointRotationTrackingConstraintParams",
      "Drives actor_b's rotation relative to actor_a towards a target (at creation, the relative rotation then).")
      .field("ref_frame_rot_vec", &JointRotationTrackingConstraintParams::ref_frame_rot_vec)
      .field("actor_a", &JointRotationTrackingConstraintParams::actor_a)
      .field("actor_b", &JointRotationTrackingConstraintParams::actor_b)
      .done(false);
  StructBinder<RodElementRotationToRigidConstraintParams, ConstraintParams>(
      m, "RodElementRotationToRigidConstraintParams",
      "Holds the material frame of element element_index of rod_actor at its rotation relative to rigid_actor at creation,\n"
      "turned by ref_frame_rot_vec (rad, element frame). Its force is the torque on the element (N m, world).")
      .field("ref_frame_rot_vec", &RodElementRotationToRigidConstraintParams::ref_frame_rot_vec)
      .field("rigid_actor", &RodElementRotationToRigidConstraintParams::rigid_actor)
      .field("rod_actor", &RodElementRotationToRigidConstraintParams::rod_actor)
      .field("element_index", &RodElementRotationToRigidConstraintParams::element_index)
      .done(false);
  StructBinder<RigidPivotPositionConstraintParams, ConstraintParams>(
      m, "RigidPivotPositionConstraintParams", "Pulls the point local_position (m, actor frame) of actor to target_position (m, world).")
      .field("target_position", &RigidPivotPositionConstraintParams::target_position)
      .field("local_position", &RigidPivotPositionConstraintParams::local_position)
      .field("actor", &RigidPivotPositionConstraintParams::actor)
      .done(false);
  StructBinder<RigidPivotToRigidTargetConstraintParams, ConstraintParams>(
      m, "RigidPivotToRigidTargetConstraintParams",
      "Pulls the point local_position (m, actor frame) of actor to where it would be with the actor frame at target_transform.")
      .field("target_transform", &RigidPivotToRigidTargetConstraintParams::target_transform)
      .field("local_position", &RigidPivotToRigidTargetConstraintParams::local_position)
      .field("actor", &RigidPivotToRigidTargetConstraintParams::actor)
      .done(false);
  StructBinder<RigidPivotRotationConstraintParams, ConstraintParams>(
      m, "RigidPivotRotationConstraintParams",
      "Turns actor so that its frame rotated by local_rotation has the world rotation target_rotation (rotation vectors, rad).")
      .field("target_rotation", &RigidPivotRotationConstraintParams::target_rotation)
      .field("local_rotation", &RigidPivotRotationConstraintParams::local_rotation)
      .field("actor", &RigidPivotRotationConstraintParams::actor)
      .done(false);
  StructBinder<DeformableNodePositionConstraintParams, ConstraintParams>(
      m, "DeformableNodePositionConstraintParams", "Pulls node node_index of a soft actor to position (m, world).")
      .field("node_index", &DeformableNodePositionConstraintParams::node_index)
      .field("position", &DeformableNodePositionConstraintParams::position)
      .field("actor", &DeformableNodePositionConstraintParams::actor)
      .done(false);
  StructBinder<DeformableNodeToRigidConstraintParams, ConstraintParams>(
      m, "DeformableNodeToRigidConstraintParams",
      "Ties node deformable_node_index of a soft actor to a point of a rigid actor: where the node is at creation\n"
      "(fix_to_deformable_pos), else rigid_local_pos (m, rigid actor frame); find_closest: the surface node nearest that point.")
      .field("rigid_local_pos", &DeformableNodeToRigidConstraintParams::rigid_local_pos)
      .field("deformable_node_index", &DeformableNodeToRigidConstraintParams::deformable_node_index)
      .field("rigid_actor", &DeformableNodeToRigidConstraintParams::rigid_actor)
      .field("deformable_actor", &DeformableNodeToRigidConstraintParams::deformable_actor)
      .field("find_closest", &DeformableNodeToRigidConstraintParams::find_closest)
      .field("fix_to_deformable_pos", &DeformableNodeToRigidConstraintParams::fix_to_deformable_pos)
      .done(false);
  StructBinder<DeformableNodeToDeformableNodeConstraintParams, ConstraintParams>(
      m, "DeformableNodeToDeformableNodeConstraintParams",
      "Holds node node_index_a of soft actor actor_a and node node_index_b of soft actor actor_b together (m, world);\n"
      "find_closest: each actor's surface node nearest the midpoint of the two actors' origins instead.")
      .field("node_index_a", &DeformableNodeToDeformableNodeConstraintParams::node_index_a)
      .field("node_index_b", &DeformableNodeToDeformableNodeConstraintParams::node_index_b)
      .field("actor_a", &DeformableNodeToDeformableNodeConstraintParams::actor_a)
      .field("actor_b", &DeformableNodeToDeformableNodeConstraintParams::actor_b)
      .field("find_closest", &DeformableNodeToDeformableNodeConstraintParams::find_closest)
      .done(false);
  StructBinder<ArticulatedSingleDofTargetConstraintParams, ConstraintParams>(
      m, "ArticulatedSingleDofTargetConstraintParams",
      "Pulls DOF dof_index (0) of joint joint_index (a revolute or prismatic joint) of an articulated actor to target_value\n"
      "(rad or m).")
      .field("actor", &ArticulatedSingleDofTargetConstraintParams::actor)
      .field("joint_index", &ArticulatedSingleDofTargetConstraintParams::joint_index)
      .field("dof_index", &ArticulatedSingleDofTargetConstraintParams::dof_index)
      .field("target_value", &ArticulatedSingleDofTargetConstraintParams::target_value)
      .done(false);
  StructBinder<Articulated3dRotationTargetConstraintParams, ConstraintParams>(
      m, "Articulated3dRotationTargetConstraintParams",
      "Turns joint joint_index (a spherical or free joint) of an articulated actor to the rotation target (its child link in\n"
      "the joint frame).")
      .field("actor", &Articulated3dRotationTargetConstraintParams::actor)
      .field("joint_index", &Articulated3dRotationTargetConstraintParams::joint_index)
      .field("target", &Articulated3dRotationTargetConstraintParams::target)
      .done(false);

  nb::class_<Constraint>(m, "Constraint",
                         "A constraint of a scene, by handle. Methods that do not apply to its type raise superdex.physics.Error.")
      .def("get_type", [](const Constraint& c) { return c.scene.constraint_type(c.handle); })
      .def("get_handle", [](const Constraint& c) { return c.handle; })
      .def("get_stiffness", [](const Constraint& c) { return c.scene.constraint_params(c.handle).stiffness; })
      .def("set_stiffness", [](Constraint& c, real stiffness) {
             ConstraintParams p = c.scene.constraint_params(c.handle);
             p.stiffness = stiffness;
             c.scene.set_constraint_params(c.handle, p);
           }, "stiffness"_a)
      .def("get_damping", [](const Constraint& c) { return c.scene.constraint_params(c.handle).damping; })
      .def("set_damping", [](Constraint& c, real damping) {
             ConstraintParams p = c.scene.constraint_params(c.handle);
             p.damping = damping;
             c.scene.set_constraint_params(c.handle, p);
           }, "damping"_a)
      .def("get_saturation", [](const Constraint& c) { return c.scene.constraint_params(c.handle).saturation; })
      .def("set_saturation", [](Constraint& c, real saturation) {
             ConstraintParams p = c.scene.constraint_params(c.handle);
             p.saturation = saturation;
             c.scene.set_constraint_params(c.handle, p);
           }, "saturation"_a)
      .def("get_deviation", [](const Constraint& c) { return SpanOf<const real>::owning(c.scene.constraint_deviation(c.handle)); },
           "Target minus current per constrained component (m, rad), from the current state.")
      .def("get_force", [](const Constraint& c) { return SpanOf<const real>::owning(c.scene.constraint_force(c.handle)); },
           "The last step's generalized force on each actor's DOFs (get_dof_indices_for_actor), actor after actor: N, and N m\n"
           "about the centre of mass, world. Needs a CONSTRAINT_FORCE query registered before the step.")
      .def("get_num_actors", [](const Constraint& c) { return static_cast<int>(c.scene.constraint_actors(c.handle).size()); })
      .def("get_actor", [](const Constraint& c, int actor_index) {
             const std::vector<ActorHandle> actors = c.scene.constraint_actors(c.handle);
             if (actor_index < 0 || actor_index >= static_cast<int>(actors.size()))
               throw Error("get_actor: actor_index " + std::to_string(actor_index) + " out of range [0, " + std::to_string(actors.size()) + ")");
             return Actor{c.scene, actors[actor_index]};
           }, "actor_index"_a)
      .def("get_dof_indices_for_actor", [](const Constraint& c, int actor_index) {
             return SpanOf<const int>::owning(c.scene.constraint_dof_indices(c.handle, actor_index));
           }, "actor_index"_a, "0-2: translation, 3-5: rotation.")
      .def("set_target_position", [](Constraint& c, const Real3& position) { c.scene.set_constraint_target_position(c.handle, position); },
           "position"_a, "RIGID_PIVOT_POSITION, DEFORMABLE_NODE_POSITION and RIGID_PIVOT_TO_RIGID_TARGET (m, world).")
      .def("set_target_rotation", [](Constraint& c, const Quaternion& rotation) { c.scene.set_constraint_target_rotation(c.handle, rotation); },
           "rotation"_a, "RIGID_PIVOT_ROTATION, RIGID_PIVOT_TO_RIGID_TARGET (world), JOINT_ROTATION_TRACKING (B relative to A) and\n"
           "ARTICULATED_3D_ROTATION_TARGET (the joint's).")
      .def("set_target_dof", [](Constraint& c, real target) { c.scene.set_constraint_target_dof(c.handle, target); }, "target"_a,
           "ARTICULATED_SINGLE_DOF_TARGET: the joint value (rad or m).")
      .def("update_old_target", [](Constraint& c) { c.scene.update_constraint_old_target(c.handle); },
           "Forgets the target's motion since the last step (after a jump of the target).")
      .def("set_ref_relative_rotation", [](Constraint& c, const Quaternion& a, const Quaternion& b) {
             c.scene.set_constraint_ref_relative_rotation(c.handle, a, b);
           }, "rotation_a"_a, "rotation_b"_a)
      .def("get_limit_min_values", [](const Constraint& c) { return SpanOf<const real>::owning(c.scene.constraint_limit_min_values(c.handle)); })
      .def("get_limit_max_values", [](const Constraint& c) { return SpanOf<const real>::owning(c.scene.constraint_limit_max_values(c.handle)); })
      .def("register_query", [](Constraint& c, QueryType type) { return c.scene.register_constraint_query(c.handle, type); }, "type"_a)
      .def("cancel_query", [](Constraint& c, QueryHandle q) { c.scene.cancel_constraint_query(c.handle, q); }, "handle"_a)
      .def("is_query_supported", [](const Constraint& c, QueryType type) { return c.scene.is_constraint_query_supported(c.handle, type); },
           "type"_a)
      .def("__eq__", [](const Constraint& a, const Constraint& b) { return a.handle == b.handle && a.scene.handle() == b.scene.handle(); },
           nb::is_operator())
      .def("__hash__", [](const Constraint& c) { return static_cast<std::int64_t>(c.handle); });
}

namespace {

template <class P>
void add_create(nb::class_<Scene>& scene, const char* name, const char* params_name, ConstraintHandle (Scene::*create)(const P&)) {
  scene.def(name, [create](Scene& s, const P& p) { return Constraint{s, (s.*create)(p)}; }, "params"_a);
  scene.def(name, [create, params_name](Scene& s, nb::kwargs kwargs) {
    nb::object params = nb::module_::import_("superdex.physics").attr(params_name)(**kwargs);
    return Constraint{s, (s.*create)(nb::cast<const P&>(params))};
  });
}

}  // namespace

void add_constraint_methods(nb::class_<Scene>& scene) {
  add_create(scene, "create_rigid_spherical_joint_constraint", "RigidSphericalJointConstraintParams", &Scene::create_rigid_spherical_joint_constraint);
  add_create(scene, "create_rigid_prismatic_joint_constraint", "RigidPrismaticJointConstraintParams", &Scene::create_rigid_prismatic_joint_constraint);
  add_create(scene, "create_joint_rotation_range_constraint", "JointRotationRangeConstraintParams", &Scene::create_joint_rotation_range_constraint);
  add_create(scene, "create_joint_rotation_tracking_constraint", "JointRotationTrackingConstraintParams",
             &Scene::create_joint_rotation_tracking_constraint);
  add_create(scene, "create_rod_element_rotation_to_rigid_constraint", "RodElementRotationToRigidConstraintParams",
             &Scene::create_rod_element_rotation_to_rigid_constraint);
  add_create(scene, "create_rigid_pivot_position_constraint", "RigidPivotPositionConstraintParams", &Scene::create_rigid_pivot_position_constraint);
  add_create(scene, "create_rigid_pivot_to_rigid_target_constraint", "RigidPivotToRigidTargetConstraintParams",
             &Scene::create_rigid_pivot_to_rigid_target_constraint);
  add_create(scene, "create_rigid_pivot_rotation_constraint", "RigidPivotRotationConstraintParams", &Scene::create_rigid_pivot_rotation_constraint);
  add_create(scene, "create_deformable_node_position_constraint", "DeformableNodePositionConstraintParams",
             &Scene::create_deformable_node_position_constraint);
  add_create(scene, "create_deformable_node_to_rigid_constraint", "DeformableNodeToRigidConstraintParams",
             &Scene::create_deformable_node_to_rigid_constraint);
  add_create(scene, "create_deformable_node_to_deformable_node_constraint", "DeformableNodeToDeformableNodeConstraintParams",
             &Scene::create_deformable_node_to_deformable_node_constraint);
  add_create(scene, "create_articulated_single_dof_target_constraint", "ArticulatedSingleDofTargetConstraintParams",
             &Scene::create_articulated_single_dof_target_constraint);
  add_create(scene, "create_articulated_3d_rotation_target_constraint", "Articulated3dRotationTargetConstraintParams",
             &Scene::create_articulated_3d_rotation_target_constraint);
  scene.def("destroy_constraint", [](Scene& s, const Constraint& c) { s.destroy_constraint(c.handle); }, "constraint"_a)
      .def("get_constraint", [](Scene& s, ConstraintHandle h) -> std::optional<Constraint> {
             if (!s.has_constraint(h)) return std::nullopt;
             return Constraint{s, h};
           }, "handle"_a, "The constraint with this handle, or None.")
      .def("for_each_constraint", [](Scene& s, const std::function<void(Constraint)>& fn) {
             for (ConstraintHandle h : s.constraints()) fn(Constraint{s, h});
           }, "fn"_a, "Calls fn with each constraint, in creation order.")
      .def("get_num_constraints", [](const Scene& s) { return static_cast<int>(s.constraints().size()); });
}

}  // namespace superdex::python
