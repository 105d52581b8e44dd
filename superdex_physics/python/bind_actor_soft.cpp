// Soft actor methods: node displacements, positions and velocities (3 values per node, actor
// frame), material, recentering, deformation gradients, surface nodes, boundary conditions and
// elastic energy.

#include <variant>

#include "bind_actor.h"
#include "bind_container.h"

namespace superdex::python {

namespace {

using ConstReals = SpanOf<const real>;

std::span<const real> as_span(const VecX& v) { return {v.data(), static_cast<size_t>(v.size())}; }

// Adds boundary conditions by DOF or node from Python arguments.
void add_bcs(Actor& a, nb::handle indices, nb::handle values, bool nodes, bool permanent, const std::string& what) {
  const std::vector<int> idx = read_indices(indices, what + (nodes ? ": node_indices" : ": dof_indices"));
  const VecX v = read_vector(nb::module_::import_("numpy").attr("ravel")(values), what + (nodes ? ": node_positions_world" : ": dof_values_world"));
  if (nodes) a.scene.add_boundary_condition_nodes_world(a.handle, idx, as_span(v), permanent);
  else a.scene.add_boundary_condition_dofs_world(a.handle, idx, as_span(v), permanent);
}

}  // namespace

void add_soft_methods(ActorClass& c) {
  c.def("get_displacements", [](const Actor& a) { return ConstReals::owning(a.scene.displacements(a.handle)); },
        "Node displacements from the rest shape (m, actor frame), 3 per node.")
      .def("set_displacements", [](Actor& a, nb::handle displacements) {
             a.scene.set_displacements(a.handle, as_span(read_vector(displacements, "set_displacements: displacements")));
           }, "displacements"_a, "3 per node (m, actor frame); velocities unchanged.")
      .def("get_node_positions_local", [](const Actor& a) { return ConstReals::owning(a.scene.node_positions_local(a.handle)); },
           "Rest positions plus displacements (m, actor frame), 3 per node. Needs NODE_POSITIONS.")
      .def("set_node_positions_local", [](Actor& a, nb::handle positions_local) {
             a.scene.set_node_positions_local(a.handle, as_span(read_vector(positions_local, "set_node_positions_local: positions_local")));
           }, "positions_local"_a, "3 per node (m, actor frame); velocities unchanged.")
      .def("set_node_velocities_local", [](Actor& a, nb::handle velocities_local) {
             a.scene.set_node_velocities_local(a.handle, as_span(read_vector(velocities_local, "set_node_velocities_local: velocities_local")));
           }, "velocities_local"_a, "3 per node (m/s, actor frame axes).")
      .def("set_zero_displacements_and_velocities", [](Actor& a) { a.scene.set_zero_displacements_and_velocities(a.handle); },
           "Back to the rest shape at the actor frame, at rest.")
      .def("get_recentering_params", [](const Actor& a) { return a.scene.recentering_params(a.handle); },
           "Soft actors' settings; defaults with use_recentering False for other actors.")
      .def("set_recentering_params", [](Actor& a, const RecenteringParams& p) { a.scene.set_recentering_params(a.handle, p); }, "params"_a)
      .def("get_soft_material_params", [](const Actor& a) { return a.scene.soft_material_params(a.handle); })
      .def("set_soft_material_params", [](Actor& a, const SoftMaterialParams& p) { a.scene.set_soft_material_params(a.handle, p); },
           "params"_a, "Validated; applies from the next step.")
      .def("get_elements_deformation_gradient", [](const Actor& a) {
             return ConstReals::owning(a.scene.elements_deformation_gradient(a.handle));
           }, "Per tetrahedron, the row-major 3 x 3 deformation gradient (9 values). Needs ELEMENTS_DEFORMATION_GRADIENT.")
      .def("get_surface_mesh_node_positions_local", [](const Actor& a) {
             return ConstReals::owning(a.scene.surface_node_positions_local(a.handle));
           }, "3 per surface node (m, actor frame), in get_surface_mesh() order. Needs SURFACE_NODE_POSITIONS.")
      .def("get_surface_mesh_node_normals_local", [](const Actor& a) {
             return ConstReals::owning(a.scene.surface_node_normals_local(a.handle));
           }, "Area-weighted unit normals of the surface nodes (actor frame). Needs SURFACE_NODE_NORMALS.")
      .def("query_nodes_in_volume_local", [](const Actor& a, nb::handle volume, bool boundary_only, nb::callable callback) {
             std::variant<Aabb, Obb, Sphere> v;
             if (Aabb* b = nullptr; nb::try_cast(volume, b, false) && b) v = *b;
             else if (Obb* o = nullptr; nb::try_cast(volume, o, false) && o) v = *o;
             else if (Sphere* s = nullptr; nb::try_cast(volume, s, false) && s) v = *s;
             else throw Error("query_nodes_in_volume_local: volume: expected an Aabb, Obb or Sphere (actor frame)");
             for (const auto& [index, p] : a.scene.nodes_in_volume_local(a.handle, v, boundary_only)) callback(index, p);
           }, "volume"_a, "boundary_only"_a, "callback"_a,
           "Calls callback(index, local position) for each node inside volume (Aabb, Obb or Sphere, actor frame). boundary_only\n"
           "False: every node of a soft actor (needs NODE_POSITIONS); True: surface nodes of a soft actor (needs\n"
           "SURFACE_NODE_POSITIONS) or of a rigid mesh shape, indexed as get_mesh().")
      .def("get_elastic_energy", [](const Actor& a) { return a.scene.elastic_energy(a.handle); },
           "Elastic energy relative to the rest shape (J). Needs ELASTIC_ENERGY.")
      .def("get_boundary_condition_dof_indices", [](const Actor& a) {
             return SpanOf<const int>::owning(a.scene.boundary_condition_dof_indices(a.handle));
           }, "Every entry added (clearable and permanent) in insertion order, repeats included.")
      .def("get_boundary_condition_dof_values_world", [](const Actor& a) {
             return ConstReals::owning(a.scene.boundary_condition_dof_values_world(a.handle));
           }, "One per get_boundary_condition_dof_indices() entry (m, world).")
      .def("add_boundary_condition_dofs_world", [](Actor& a, nb::handle dof_indices, nb::handle dof_values_world) {
             add_bcs(a, dof_indices, dof_values_world, false, false, "add_boundary_condition_dofs_world");
           }, "dof_indices"_a, "dof_values_world"_a,
           "Holds DOFs at world values until clear_boundary_conditions(); a node's 3 DOFs (its world position, m) go together.\n"
           "The latest entry of a DOF wins.")
      .def("add_boundary_condition_dofs_world_permanent", [](Actor& a, nb::handle dof_indices, nb::handle dof_values_world) {
             add_bcs(a, dof_indices, dof_values_world, false, true, "add_boundary_condition_dofs_world_permanent");
           }, "dof_indices"_a, "dof_values_world"_a, "As add_boundary_condition_dofs_world, never cleared.")
      .def("add_boundary_condition_nodes_world", [](Actor& a, nb::handle node_indices, nb::handle node_positions_world) {
             add_bcs(a, node_indices, node_positions_world, true, false, "add_boundary_condition_nodes_world");
           }, "node_indices"_a, "node_positions_world"_a, "Holds nodes at world positions (m, 3 per node) until cleared.")
      .def("add_boundary_condition_nodes_world_permanent", [](Actor& a, nb::handle node_indices, nb::handle node_positions_world) {
             add_bcs(a, node_indices, node_positions_world, true, true, "add_boundary_condition_nodes_world_permanent");
           }, "node_indices"_a, "node_positions_world"_a, "As add_boundary_condition_nodes_world, never cleared.")
      .def("clear_boundary_conditions", [](Actor& a) { a.scene.clear_boundary_conditions(a.handle); },
           "Removes the clearable entries; permanent ones stay.");
}

}  // namespace superdex::python
