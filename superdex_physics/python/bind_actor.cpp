// The Actor class: what every actor has (identity, frame, velocity, mass properties, contact
// settings, bounds, DOFs and external forces); the soft, articulated and query methods are added
// by their own files (bind_actor.h). Methods that do not apply to an actor's kind raise
// superdex.physics.Error naming the call and the actor.

#include <nanobind/stl/string.h>

#include "bind_actor.h"
#include "bind_model_view.h"
#include "bind_container.h"

namespace superdex::python {

void export_actor(nb::module_& m) {
  export_query_results(m);
  bind_span<const ActorHandle>(m, "SpanConstActorHandle");
  bind_dynamic_array<ActorHandle>(m, "DynamicArrayActorHandle");

  ActorClass c(m, "Actor",
               "A simulated body of a scene (rigid, soft or articulated; an articulation's links are rigid actors nested in it),\n"
               "by handle. Not thread-safe: use an actor from the thread that uses its scene.");
  c.def("get_handle", [](const Actor& a) { return a.handle; }, "Safe to store; Scene.get_actor looks it up.")
      .def("get_scene", [](const Actor& a) { return a.scene; })
      .def("get_name", [](const Actor& a) { return a.scene.actor_name(a.handle); }, "Not necessarily unique.")
      .def("get_type", [](const Actor& a) { return a.scene.actor_type(a.handle); })
      .def("get_convergence_status", [](const Actor& a) { return a.scene.convergence_status(a.handle); },
           "How the last step's solve of the actor's island ended; NONE for static actors and before a step.")
      .def("is_static", [](const Actor& a) { return a.scene.is_static(a.handle); })
      .def("get_contact_params", [](const Actor& a) { return a.scene.contact_params(a.handle); })
      .def("set_contact_params", [](Actor& a, const ContactParams& p) { a.scene.set_contact_params(a.handle, p); }, "params"_a,
           "Validated; applies from the next step (to every link of an articulated actor).")
      .def("get_collider_type", [](const Actor& a) { return a.scene.collider_type(a.handle); }, "AUTO resolved.")
      .def("has_root_transform", [](const Actor& a) { return a.scene.has_actor(a.handle); }, "True: every actor of this engine has a frame.")
      .def("get_root_transform", [](const Actor& a) { return TransformRT(a.scene.root_transform(a.handle)); },
           "World-from-local transform X_WL: a rigid actor's frame, a link's frame, an articulation's root frame, or a soft\n"
           "actor's frame (which follows its rigid motion when recentering is on).")
      .def("set_root_transform", [](Actor& a, nb::handle world_from_local) {
             a.scene.set_root_transform(a.handle, read_transform(world_from_local, "set_root_transform: world_from_local"));
           }, "world_from_local"_a, "Moves the actor (velocities unchanged); not for link actors.")
      .def("get_rigid_center_of_mass_local", [](const Actor& a) { return a.scene.center_of_mass_local(a.handle); },
           "Centre of mass (m) in the actor frame: rigid actors, links and soft actors.")
      .def("get_center_of_mass_transform", [](const Actor& a) { return a.scene.center_of_mass_transform(a.handle); },
           "X_WC: the actor frame's rotation at the centre of mass (dynamic rigid actors and links).")
      .def("set_center_of_mass_transform", [](Actor& a, nb::handle world_from_com) {
             a.scene.set_center_of_mass_transform(a.handle, read_transform(world_from_com, "set_center_of_mass_transform: world_from_com"));
           }, "world_from_com"_a, "Moves a dynamic rigid actor so that its centre of mass frame is world_from_com.")
      .def("get_rigid_moment_of_inertia_local", [](const Actor& a) { return a.scene.moment_of_inertia_local(a.handle); },
           "[ixx, ixy, ixz, iyy, iyz, izz] (kg m^2) about the centre of mass in the actor frame's axes; off-diagonal entries\n"
           "are the tensor's (negative products of inertia).")
      .def("set_velocity", [](Actor& a, nb::handle linear_vel, nb::handle angular_vel) {
             a.scene.set_velocity(a.handle, read_vec3(linear_vel, "set_velocity: linear_vel"), read_vec3(angular_vel, "set_velocity: angular_vel"));
           }, "linear_vel"_a, "angular_vel"_a,
           "Velocity of the centre of mass (m/s) and angular velocity (rad/s), world frame. Rigid actors and soft actors\n"
           "(linear only: every node gets it).")
      .def("get_linear_velocity", [](const Actor& a) { return Real3(a.scene.velocity(a.handle).head<3>()); },
           "Velocity of the centre of mass (m/s), world frame.")
      .def("get_angular_velocity", [](const Actor& a) { return Real3(a.scene.velocity(a.handle).tail<3>()); }, "rad/s, world frame.")
      .def("get_mass", [](const Actor& a) { return a.scene.mass(a.handle); }, "kg")
      .def("get_density", [](const Actor& a) { return a.scene.density(a.handle); }, "kg/m^3")
      .def("set_density", [](Actor& a, real density) { a.scene.set_density(a.handle, density); }, "density"_a,
           "kg/m^3 (> 0): scales mass and inertia; the centre of mass stays.")
      .def("set_inertia_properties", [](Actor& a, real mass, const Real3& center_of_mass, const Real6& moment_of_inertia) {
             a.scene.set_inertia_properties(a.handle, mass, center_of_mass, moment_of_inertia);
           }, "mass"_a, "center_of_mass"_a, "moment_of_inertia"_a,
           "Mass (kg, > 0), centre of mass (m, actor frame) and inertia about it ([ixx, ixy, ixz, iyy, iyz, izz], kg m^2)\n"
           "of a dynamic rigid actor.")
      .def("get_reference_shape", [](const Actor& a) { return a.scene.reference_shape(a.handle); },
           "A new reference to the shape the actor was made from.")
      .def("get_mesh", [](const Actor& a) { return shared_view(a.scene.meshes(a.handle).mesh); },
           "The simulation mesh in the actor frame: a soft actor's tetrahedra, a rigid actor's compact triangle surface;\n"
           "empty for primitives. The view keeps the data alive.")
      .def("get_surface_mesh", [](const Actor& a) { return shared_view(a.scene.meshes(a.handle).surface); },
           "The compact triangle surface (only the nodes it uses, in increasing order of their mesh index).")
      .def("get_visual_mesh", [](const Actor& a) { return shared_view(a.scene.meshes(a.handle).visual); },
           "The model's visual mesh; empty when it has none.")
      .def("get_contact_layer", [](const Actor& a) { return a.scene.contact_layer(a.handle); }, "Empty for the default layer.")
      .def("set_contact_layer", [](Actor& a, const std::string& layer) { a.scene.set_contact_layer(a.handle, layer); }, "layer"_a)
      .def("get_num_dofs", [](const Actor& a) { return a.scene.num_dofs(a.handle); }, "0 for static actors.")
      .def("get_dof_values", [](const Actor& a, nb::handle dof_indices, nb::handle out_dof_values) {
             const std::vector<int> dofs = read_indices(dof_indices, "get_dof_values: dof_indices");
             const std::vector<real> values = a.scene.dof_values(a.handle, dofs);
             write_out(out_dof_values, values, "get_dof_values: out_dof_values");
           }, "dof_indices"_a, "out_dof_values"_a,
           "Writes the values of the DOFs (all of them for empty dof_indices): a rigid actor's centre of mass position (m)\n"
           "and rotation vector (rad), an articulation's joint positions, a soft actor's node displacements (m, actor frame).")
      .def("get_points_distance_to_surface", [](const Actor& a, nb::handle points_world, nb::handle out_distances) {
             const std::vector<Real3> p = read_real3s(points_world, "get_points_distance_to_surface: points_world");
             write_out(out_distances, a.scene.points_distance_to_surface(a.handle, p), "get_points_distance_to_surface: out_distances");
           }, "points_world"_a, "out_distances"_a, "Signed distances (m, negative inside) of world points to the actor's collider.")
      .def("get_aabb_local", [](const Actor& a) { return a.scene.aabb_local(a.handle); }, "m, actor frame.")
      .def("get_aabb_world", [](const Actor& a) { return a.scene.aabb_world(a.handle); }, "m, world frame.")
      .def("set_external_forces_on_dofs", [](Actor& a, nb::handle dof_indices, nb::handle force_values) {
             // kept across calls (the GIL is held), so that a control loop's call allocates nothing
             thread_local std::vector<int> dofs;
             thread_local VecX f;
             read_indices(dof_indices, "set_external_forces_on_dofs: dof_indices", dofs);
             read_vector(force_values, "set_external_forces_on_dofs: force_values", f);
             a.scene.set_external_forces_on_dofs(a.handle, dofs, std::span<const real>(f.data(), static_cast<size_t>(f.size())));
           }, "dof_indices"_a, "force_values"_a,
           "Replaces every external generalized force (N, N m) of the actor; held until replaced or cleared (empty clears).\n"
           "Rigid actors: force on the centre of mass (0-2) and torque (3-5), world frame; articulations: joint efforts.")
      .def("clear_external_forces", [](Actor& a) { a.scene.clear_external_forces(a.handle); })
      .def("get_external_forces", [](const Actor& a, nb::handle out_forces) -> nb::object {
             const VecX f = a.scene.external_forces(a.handle);
             if (out_forces.is_none()) return nb::cast(numpy_copy(f));
             write_out(out_forces, std::span<const real>(f.data(), static_cast<size_t>(f.size())), "get_external_forces: out_forces");
             return nb::borrow(out_forces);
           }, "out_forces"_a.none() = nb::none(), "Per DOF, zero where unset; into out_forces when given, else a new array.")
      .def("is_nested_link_actor", [](const Actor& a) { return a.scene.is_nested_link_actor(a.handle); })
      .def("is_nested_soft_actor", [](const Actor& a) { return a.scene.is_nested_soft_actor(a.handle); },
           "Whether this is a soft body of a soft-skinned actor.")
      .def("__eq__", [](const Actor& a, const Actor& b) { return a.handle == b.handle && a.scene.handle() == b.scene.handle(); }, nb::is_operator())
      .def("__ne__", [](const Actor& a, const Actor& b) { return !(a.handle == b.handle && a.scene.handle() == b.scene.handle()); }, nb::is_operator())
      .def("__hash__", [](const Actor& a) { return std::hash<std::int64_t>()(a.handle); })
      .def("__repr__", [](const Actor& a) { return "Actor(" + std::to_string(a.handle) + ")"; });
  add_query_methods(c);
  add_soft_methods(c);
  add_articulated_methods(c);
  add_pose_controller_methods(c);
}

}  // namespace superdex::python
