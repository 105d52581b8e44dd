// Queries of an actor (register, cancel, support) and the results they give: contact points,
// node contact forces, SDF distances and total contact forces and torques.

#include <nanobind/stl/string.h>

#include "bind_actor.h"
#include "bind_container.h"
#include "struct_binder.h"

namespace superdex::python {

namespace {

QueryType query_type_of(nb::handle type, const char* what) {
  QueryType t;
  if (nb::try_cast(type, t)) return t;
  int k = 0;
  if (nb::try_cast(type, k)) {
    if (k < 0 || k > static_cast<int>(QueryType::TotalContactForce))
      throw Error(std::string(what) + ": type: " + std::to_string(k) + " is not a QueryType");
    return static_cast<QueryType>(k);
  }
  throw Error(std::string(what) + ": type: expected a superdex.physics.QueryType or an int, got " + nb::inst_name(type).c_str());
}

}  // namespace

void export_query_results(nb::module_& m) {
  StructBinder<ContactPoint>(m, "ContactPoint", "One contact of the last step (Actor.get_contact_points_world; needs CONTACT_POINTS).")
      .field("actor_a", &ContactPoint::actor_a, "the colliding actor (the queried actor may be a or b; a == b for self-contact)")
      .field("actor_b", &ContactPoint::actor_b, "the collider actor")
      .field("distance", &ContactPoint::distance, "signed gap at the start of the step (m), negative when overlapping")
      .field("pos_a", &ContactPoint::pos_a, "the contact point on actor a (m, world)")
      .field("pos_b", &ContactPoint::pos_b, "pos_a - normal * distance (m, world)")
      .field("normal", &ContactPoint::normal, "unit, world, pointing away from actor b")
      .field("force", &ContactPoint::force, "on actor a from actor b (N, world)")
      .field("point_velocity_a", &ContactPoint::point_velocity_a, "velocity of actor a's material point at pos_a after the step (m/s)")
      .field("point_velocity_b", &ContactPoint::point_velocity_b, "velocity of actor b's material point at pos_b after the step (m/s)")
      .field("sample_index", &ContactPoint::sample_index, "the contact's index among actor a's contacts of the step")
      .field("int_weight", &ContactPoint::int_weight, "quadrature weight (m^2); 0 for a point contact")
      .field("element_index", &ContactPoint::element_index, "the surface triangle of a soft actor a (-1 for rigid actors)")
      .field("parametric_coords", &ContactPoint::parametric_coords, "barycentric coordinates of pos_a in that triangle")
      .done();
  StructBinder<NodeContactForce>(m, "NodeContactForce", "The contact force on one node of a soft actor (needs NODE_CONTACT_FORCES).")
      .field("index", &NodeContactForce::index, "the node (volume mesh order)")
      .field("force", &NodeContactForce::force, "N, world")
      .done();
  StructBinder<SdfDistances>(m, "SdfDistances", "A soft actor's contact samples of the last step (needs SDF_DISTANCES).")
      .span_field("sample_indices", &SdfDistances::sample_indices, "the node nearest each sample")
      .span_field("world_positions", &SdfDistances::world_positions, "m")
      .span_field("distances", &SdfDistances::distances, "m, negative: penetration")
      .span_field("distance_grads", &SdfDistances::distance_grads, "unit, world: the collider's outward normal")
      .field("max_sdf_far_distance_evaluation", &SdfDistances::max_sdf_far_distance_evaluation, "m")
      .done();
  bind_span<const ContactPoint>(m, "SpanConstContactPoint");
  bind_span<const NodeContactForce>(m, "SpanConstNodeContactForce");
}

void add_query_methods(ActorClass& c) {
  c.def("register_query", [](Actor& a, nb::handle type) { return a.scene.register_query(a.handle, query_type_of(type, "register_query")); },
        "type"_a, "Registers a query; its results are valid after the next step (even of 0 s). Counted: cancel each registration.")
      .def("register_query_and_compute", [](Actor& a, nb::handle type) {
             return a.scene.register_query(a.handle, query_type_of(type, "register_query_and_compute"), true);
           }, "type"_a, "Registers a query and, for those computed from the state, computes it now.")
      .def("cancel_query", [](Actor& a, QueryHandle handle) { a.scene.cancel_query(a.handle, handle); }, "handle"_a,
           "No effect for an invalid or cancelled handle.")
      .def("is_query_supported", [](const Actor& a, nb::handle type) {
             return a.scene.is_query_supported(a.handle, query_type_of(type, "is_query_supported"));
           }, "type"_a)
      .def("get_contact_points_world", [](const Actor& a) { return SpanOf<const ContactPoint>::owning(a.scene.contact_points(a.handle)); },
           "The actor's contacts of the last step. Needs CONTACT_POINTS.")
      .def("get_node_contact_forces_world", [](const Actor& a) {
             return SpanOf<const NodeContactForce>::owning(a.scene.node_contact_forces(a.handle));
           }, "Soft actors: the nodes with a contact force in the last step (N, world). Needs NODE_CONTACT_FORCES.")
      .def("get_contact_force_world", [](const Actor& a) { return Real3(a.scene.contact_force(a.handle)); },
           "Total contact force on the actor (N, world). Needs TOTAL_CONTACT_FORCE.")
      .def("get_contact_torque_world", [](const Actor& a) { return Real3(a.scene.contact_torque(a.handle)); },
           "Total contact torque about the centre of mass (N m, world); rigid actors and links. Needs TOTAL_CONTACT_FORCE.")
      .def("get_contact_force_from_actor_world", [](const Actor& a, nb::handle other) {
             return Real3(a.scene.contact_force_from(a.handle, actor_handle_of(other, "get_contact_force_from_actor_world: other")));
           }, "other"_a, "Contact force on the actor from `other` (N, world). Needs TOTAL_CONTACT_FORCE.")
      .def("get_sdf_distances", [](const Actor& a) { return a.scene.sdf_distances(a.handle); }, "Needs SDF_DISTANCES.");
}

}  // namespace superdex::python
