// The Actor class: one class for every actor kind; methods that do not apply raise Error.

#include <nanobind/stl/string.h>

#include <climits>

#include "bind_common.h"

namespace superdex::python {

namespace {

// Writes `values` into the out-parameter (or a new numpy array when it is None) and returns it.
nb::object fill_out(nb::handle out, const VecX& values, std::string_view arg) {
  if (out.is_none()) return nb::cast(numpy_copy(values));
  real* dst = out_buffer(out, arg, static_cast<size_t>(values.size()));
  std::copy(values.data(), values.data() + values.size(), dst);
  return nb::borrow(out);
}

// DOF indices from a list or tuple of ints or an array of integral numbers, into `out` (which
// keeps its storage).
void read_indices(nb::handle obj, std::string_view arg, std::vector<int>& out) {
  // a list or tuple of Python ints, without a conversion to numpy
  PyObject* o = obj.ptr();
  if (PyList_Check(o) || PyTuple_Check(o)) {
    const Py_ssize_t n = PySequence_Fast_GET_SIZE(o);
    PyObject** items = PySequence_Fast_ITEMS(o);
    out.resize(n);
    bool all_ints = true;
    for (Py_ssize_t i = 0; i < n && all_ints; ++i) {
      int overflow = 0;
      const long k = PyLong_Check(items[i]) ? PyLong_AsLongAndOverflow(items[i], &overflow) : 0;
      all_ints = PyLong_Check(items[i]) && !overflow && k >= INT_MIN && k <= INT_MAX;
      out[i] = static_cast<int>(k);
    }
    if (all_ints) return;
  }
  const VecX v = read_vector(obj, arg);
  out.resize(v.size());
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i]) || v[i] != std::floor(v[i]))
      throw Error(std::string(arg) + "[" + std::to_string(i) + "]: expected an integer DOF index");
    out[i] = static_cast<int>(v[i]);
  }
}

NumpyArray matrix_to_numpy(const MatX& M) {
  const MatXR R = M;
  return numpy_copy(R.data(), {static_cast<size_t>(R.rows()), static_cast<size_t>(R.cols())});
}

}  // namespace

void export_actor(nb::module_& m) {
  nb::class_<DofInfo>(m, "DofInfo", "One joint's slice of the DOFs.")
      .def_ro("offset", &DofInfo::offset)
      .def_ro("trans_size", &DofInfo::trans_size)
      .def_ro("rot_size", &DofInfo::rot_size)
      .def("get_size", &DofInfo::size);

  nb::class_<ArticulatedShapeInfo>(m, "ArticulatedShapeInfo", "The structure of an articulation, in link order.")
      .def_ro("link_names", &ArticulatedShapeInfo::link_names)
      .def_ro("joint_names", &ArticulatedShapeInfo::joint_names)
      .def_ro("parents", &ArticulatedShapeInfo::parents)
      .def_ro("joint_types", &ArticulatedShapeInfo::joint_types)
      .def_prop_ro("joint_axes", [](const ArticulatedShapeInfo& s) {
        nb::list out;
        for (const Vec3& a : s.joint_axes) out.append(numpy_copy(a.data(), {3}));
        return out;
      })
      .def_ro("dof_info", &ArticulatedShapeInfo::dof_info);

  nb::enum_<QueryType>(m, "QueryType")
      .value("TOTAL_CONTACT_FORCE", QueryType::TotalContactForce)
      .value("CONTACT_POINTS", QueryType::ContactPoints)
      .value("NODE_POSITIONS", QueryType::NodePositions)
      .value("NODE_CONTACT_FORCES", QueryType::NodeContactForces)
      .value("CONSTRAINT_FORCE", QueryType::ConstraintForce)
      .value("ARTICULATED_CONTROLLER_FORCE", QueryType::ArticulatedControllerForce);

  nb::class_<ContactPointInfo>(m, "ContactPoint", "One contact of the last step, seen from actor_a.")
      .def_ro("actor_a", &ContactPointInfo::actor_a)
      .def_ro("actor_b", &ContactPointInfo::actor_b)
      .def_prop_ro("position", [](const ContactPointInfo& c) { return numpy_copy(c.position.data(), {3}); }, nb::rv_policy::automatic)
      .def_prop_ro("normal", [](const ContactPointInfo& c) { return numpy_copy(c.normal.data(), {3}); }, nb::rv_policy::automatic)
      .def_ro("distance", &ContactPointInfo::distance)
      .def_prop_ro("force", [](const ContactPointInfo& c) { return numpy_copy(c.force.data(), {3}); }, nb::rv_policy::automatic)
      .def("__repr__", [](const ContactPointInfo& c) {
        return "ContactPoint(actor_a=" + std::to_string(c.actor_a) + ", actor_b=" + std::to_string(c.actor_b) +
               ", distance=" + std::to_string(c.distance) + ")";
      });

  nb::class_<Actor>(m, "Actor", "A rigid body, an articulation, or one link of an articulation, by handle.")
      .def("get_handle", [](const Actor& a) { return a.handle; })
      .def("get_name", [](const Actor& a) { return a.scene.actor_name(a.handle); })
      .def("get_type", [](const Actor& a) { return a.scene.actor_type(a.handle); })
      .def("get_scene", [](const Actor& a) { return a.scene; })
      .def("get_root_transform", [](const Actor& a) { return a.scene.root_transform(a.handle); },
           "World-from-actor transform (a link's own pose for a link actor).")
      .def("set_root_transform", [](Actor& a, nb::handle t) {
             a.scene.set_root_transform(a.handle, read_transform(t, "set_root_transform: transform"));
           }, "transform"_a)
      .def("set_velocity", [](Actor& a, nb::handle linear, nb::handle angular) {
             a.scene.set_velocity(a.handle, read_vec3(linear, "set_velocity: linear"), read_vec3(angular, "set_velocity: angular"));
           }, "linear"_a, "angular"_a, "Velocity of the actor origin (m/s) and angular velocity (rad/s), world frame.")
      .def("get_linear_velocity", [](const Actor& a) { return Real3(a.scene.velocity(a.handle).head<3>()); },
           "Velocity of the actor origin (m/s), world frame.")
      .def("get_angular_velocity", [](const Actor& a) { return Real3(a.scene.velocity(a.handle).tail<3>()); },
           "Angular velocity (rad/s), world frame.")
      .def("get_mass", [](const Actor& a) { return a.scene.mass(a.handle); })
      .def("get_num_dofs", [](const Actor& a) { return a.scene.num_dofs(a.handle); })
      .def("set_external_forces_on_dofs", [](Actor& a, nb::handle dof_indices, nb::handle force_values) {
             // kept across calls (the GIL is held), so that a control loop's call allocates nothing
             thread_local std::vector<int> dofs;
             thread_local VecX f;
             read_indices(dof_indices, "set_external_forces_on_dofs: dof_indices", dofs);
             read_vector(force_values, "set_external_forces_on_dofs: force_values", f);
             a.scene.set_external_forces_on_dofs(a.handle, dofs, std::span<const real>(f.data(), static_cast<size_t>(f.size())));
           }, "dof_indices"_a, "force_values"_a,
           "Replaces the whole set of external generalized forces (N, N m); held until replaced or cleared.")
      .def("clear_external_forces", [](Actor& a) { a.scene.clear_external_forces(a.handle); })
      .def("get_external_forces", [](const Actor& a) { return numpy_copy(a.scene.external_forces(a.handle)); })
      .def("get_nested_link_actors", [](const Actor& a) { return a.scene.nested_link_actors(a.handle); },
           "Handles of the link actors, in link order.")
      .def("get_articulated_actor", [](const Actor& a) { return a.scene.articulated_actor_of_link(a.handle); },
           "Handle of the articulation this link belongs to.")
      .def("get_link_index", [](const Actor& a) { return a.scene.link_index(a.handle); })
      .def("get_articulated_shape_info", [](const Actor& a) { return a.scene.articulated_shape_info(a.handle); })
      .def("get_articulated_link_transforms", [](const Actor& a, nb::handle out) -> nb::object {
             const std::vector<Transform> X = a.scene.link_transforms(a.handle);
             if (out.is_none()) return nb::cast(X);
             std::vector<TransformRT>* arr = nullptr;
             if (!nb::try_cast(out, arr) || !arr) throw Error("get_articulated_link_transforms: out must be a DynamicArrayTransformRT");
             if (arr->size() != X.size())
               throw Error("get_articulated_link_transforms: out must have one entry per link (" + std::to_string(X.size()) +
                           "), got " + std::to_string(arr->size()));
             for (size_t i = 0; i < X.size(); ++i) (*arr)[i] = X[i];
             return nb::borrow(out);
           }, "out"_a.none() = nb::none(), "Fills `out` with world-from-link transforms in link order.")
      .def("get_articulated_pose", [](const Actor& a, nb::handle out) { return fill_out(out, a.scene.pose(a.handle), "get_articulated_pose: out"); },
           "out"_a.none() = nb::none(), "Generalized positions, one per DOF (rotation vectors for spherical and free rotations).")
      .def("set_articulated_pose_from_joints", [](Actor& a, nb::handle pose) {
             a.scene.set_pose(a.handle, read_vector(pose, "set_articulated_pose_from_joints: pose"));
           }, "pose"_a)
      .def("get_articulated_joint_velocities", [](const Actor& a, nb::handle out) {
             return fill_out(out, a.scene.joint_velocities(a.handle), "get_articulated_joint_velocities: out_velocities");
           }, "out_velocities"_a.none() = nb::none(),
           "Generalized velocities (rad/s, m/s); a Free root's are (linear, angular) in its link frame.")
      .def("set_articulated_joint_velocities", [](Actor& a, nb::handle v) {
             a.scene.set_joint_velocities(a.handle, read_vector(v, "set_articulated_joint_velocities: velocities"));
           }, "velocities"_a)
      .def("get_articulated_jacobian", [](const Actor& a, nb::handle out) -> nb::object {
             // one buffer per thread: no allocation per call once it has the articulation's size
             thread_local MatXR J_WL;
             a.scene.link_jacobian(a.handle, J_WL);
             if (out.is_none()) return nb::cast(numpy_copy(J_WL.data(), {static_cast<size_t>(J_WL.size())}));
             real* dst = out_buffer(out, "get_articulated_jacobian: out", static_cast<size_t>(J_WL.size()));
             std::copy(J_WL.data(), J_WL.data() + J_WL.size(), dst);
             return nb::borrow(out);
           }, "out"_a.none() = nb::none(),
           "Flat row-major 6 x num_dofs Jacobian of this link: rows 0-2 velocity of the link origin, rows 3-5 angular velocity,\n"
           "world frame. Filled into `out` (a contiguous array of 6 * num_dofs reals) when given, else a new array.")
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
           "An implicit spring-damper on a revolute or prismatic DOF, solved inside the step (stable for any\n"
           "stiffness): effort = stiffness (target_position - q) + damping (target_velocity - v) at the end of the\n"
           "step, clamped to max_effort when >= 0. Stiffness and damping 0 turn it off.")
      .def("clear_joint_drives", [](Actor& a) { a.scene.clear_joint_drives(a.handle); },
           "Removes every joint and link drive of the articulation.")
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
           "Called on a LINK actor: an implicit spring-damper towards a world pose (TransformRT), solved inside\n"
           "the step; per-axis limits when >= 0; all gains 0 remove it.")
      .def("get_joint_drive_efforts", [](const Actor& a) { return numpy_copy(a.scene.joint_drive_efforts(a.handle)); },
           "Efforts (N m or N) the joint drives applied in the last step, per DOF.")
      .def("get_node_positions_world", [](const Actor& a) {
             const std::vector<Vec3> x = a.scene.node_positions(a.handle);
             std::vector<real> flat;
             for (const Vec3& p : x) flat.insert(flat.end(), p.data(), p.data() + 3);
             return numpy_copy(flat.data(), {x.size(), 3});
           }, "Soft actors: node positions (m), world frame, N x 3.")
      .def("get_node_contact_forces_world", [](const Actor& a) {
             const std::vector<Vec3> f = a.scene.node_contact_forces(a.handle);
             std::vector<real> flat;
             for (const Vec3& p : f) flat.insert(flat.end(), p.data(), p.data() + 3);
             return numpy_copy(flat.data(), {f.size(), 3});
           }, "Soft actors: contact force on each node in the last step (N, world), N x 3. Needs NODE_CONTACT_FORCES.")
      .def("get_elastic_energy", [](const Actor& a) { return a.scene.elastic_energy(a.handle); },
           "Soft actors: elastic energy at the current positions (J).")
      .def("add_boundary_condition_nodes_world", [](Actor& a, nb::handle node_indices, nb::handle positions) {
             const char* what = "add_boundary_condition_nodes_world";
             const VecX idx = read_vector(node_indices, std::string(what) + ": node_indices");
             const nb::object flat_positions = nb::module_::import_("numpy").attr("ravel")(positions);
             const VecX flat = read_vector(flat_positions, std::string(what) + ": positions (K x 3)", 3 * idx.size());
             std::vector<int> nodes;
             std::vector<Vec3> targets;
             for (Eigen::Index k = 0; k < idx.size(); ++k) {
               nodes.push_back(static_cast<int>(idx[k]));
               targets.push_back(flat.segment<3>(3 * k));
             }
             a.scene.set_boundary_nodes(a.handle, nodes, targets);
           }, "node_indices"_a, "positions"_a,
           "Soft actors: pins nodes at world positions (m, K x 3); the next step moves them there. Call again to\n"
           "move them along a path.")
      .def("remove_boundary_condition_nodes", [](Actor& a, nb::handle node_indices) {
             const VecX idx = read_vector(node_indices, "remove_boundary_condition_nodes: node_indices");
             std::vector<int> nodes;
             for (Eigen::Index k = 0; k < idx.size(); ++k) nodes.push_back(static_cast<int>(idx[k]));
             a.scene.release_boundary_nodes(a.handle, nodes);
           }, "node_indices"_a, "Soft actors: releases pinned nodes.")
      .def("get_boundary_condition_nodes", [](const Actor& a) {
             const std::vector<int> nodes = a.scene.boundary_nodes(a.handle);
             nb::object np = nb::module_::import_("numpy");
             return np.attr("array")(nb::cast(nodes), "dtype"_a = np.attr("int64"));
           }, "Soft actors: the indices of the pinned nodes (a prefab's fixedNodes or fixedRegion, and those set\n"
              "by add_boundary_condition_nodes_world), increasing.")
      .def("register_query", [](Actor& a, nb::handle query_type) {
             QueryType type;
             if (!nb::try_cast(query_type, type))
               throw Error(std::string("register_query: query_type: expected a superdex.physics.QueryType, got ") + nb::inst_name(query_type).c_str());
             return a.scene.register_query(a.handle, type);
           }, "query_type"_a,
           "Registers a query; its results are valid after the next scene.step(). Returns the query handle.")
      .def("cancel_query", [](Actor& a, std::int64_t q) { a.scene.cancel_query(a.handle, q); }, "query_handle"_a)
      .def("get_contact_force_world", [](const Actor& a) { return a.scene.contact_force(a.handle); },
           "Total contact force applied TO this actor by everything touching it (N, world). Needs TOTAL_CONTACT_FORCE.")
      .def("get_contact_torque_world", [](const Actor& a) { return a.scene.contact_torque(a.handle); },
           "Total contact torque about the actor's origin (N m, world). Needs TOTAL_CONTACT_FORCE.")
      .def("get_contact_force_from_actor_world", [](const Actor& a, nb::handle other) {
             const Vec3 f = a.scene.contact_force_from(a.handle, actor_handle_of(other, "get_contact_force_from_actor_world: other"));
             return numpy_copy(f.data(), {3});
           }, "other"_a, "Contact force applied to this actor by `other` (N, world). Needs TOTAL_CONTACT_FORCE.")
      .def("get_contact_points_world", [](const Actor& a) { return a.scene.contact_points(a.handle); },
           "This actor's contacts of the last step (position, normal, distance, force on this actor). Needs CONTACT_POINTS.")
      .def("__eq__", [](const Actor& a, const Actor& b) { return a.handle == b.handle && a.scene.handle() == b.scene.handle(); })
      .def("__hash__", [](const Actor& a) { return a.handle; })
      .def("__repr__", [](const Actor& a) { return "Actor(" + std::to_string(a.handle) + ")"; });
}

}  // namespace superdex::python
