// Rods (superdex.physics.experimental): their material and actor params, create_rod_actor and
// generate_tubular_rod_model_data.

#include "bind_common.h"
#include "bind_container.h"
#include "struct_binder.h"
#include "superdex/physics/rod_model_data.h"

namespace superdex::python {

namespace {

// An N x 3 array (or a sequence of N triples) as points; throws naming `what`.
std::vector<Real3> points_of(nb::handle h, const char* what) {
  nb::object a = nb::module_::import_("numpy").attr("asarray")(h, "dtype"_a = "float64");
  const size_t n = nb::cast<size_t>(a.attr("size"));
  if (n % 3 != 0 || (nb::cast<int>(a.attr("ndim")) == 2 && nb::cast<int>(a.attr("shape")[nb::int_(1)]) != 3))
    throw Error(std::string("generate_tubular_rod_model_data: ") + what + " must be N x 3 (or 3 N values), got " +
                nb::cast<std::string>(nb::str(a.attr("shape"))));
  std::vector<double> flat;
  for (nb::handle v : a.attr("reshape")(-1).attr("tolist")()) flat.push_back(nb::cast<double>(v));
  std::vector<Real3> out(n / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = Real3(real(flat[3 * i]), real(flat[3 * i + 1]), real(flat[3 * i + 2]));
  return out;
}

}  // namespace

void export_rod(nb::module_& m, nb::module_& e) {
  nb::enum_<ActorSegmentElementType>(m, "ActorSegmentElementType", "Quadrature along a rod's segments.")
      .value("P1Q1", ActorSegmentElementType::P1Q1).value("P1Q2", ActorSegmentElementType::P1Q2).value("P1Q3", ActorSegmentElementType::P1Q3);
  add_default_alias<ActorSegmentElementType>(m, "ActorSegmentElementType");
  StructBinder<RodMaterialParams>(e, "RodMaterialParams",
                                  "An elastic rod's material per unit of rest length: for a homogeneous circular rod of radius r,\n"
                                  "rho A, rho J, E A, G J and E I with A = pi r^2, I = pi r^4 / 4, J = pi r^4 / 2.")
      .field("linear_density", &RodMaterialParams::linear_density, "kg/m, > 0")
      .field("linear_rotational_inertia", &RodMaterialParams::linear_rotational_inertia, "kg m, >= 0: about the centreline")
      .field("axial_stiffness", &RodMaterialParams::axial_stiffness, "N, > 0")
      .field("torsional_stiffness", &RodMaterialParams::torsional_stiffness, "N m^2, >= 0")
      .field("flexural_stiffness", &RodMaterialParams::flexural_stiffness,
             "N m^2: about the element's frame axis, then about the axis normal to it and to the rod")
      .field("mass_damping_coefficient", &RodMaterialParams::mass_damping_coefficient, "1/s")
      .field("stiffness_damping_coefficient", &RodMaterialParams::stiffness_damping_coefficient, "s")
      .done();
  StructBinder<RodActorParams>(e, "RodActorParams",
                               "Creates a rod actor (experimental.create_rod_actor) from a polyline model shape with element_frame_axes.")
      .field("name", &RodActorParams::name)
      .field("layer", &RodActorParams::layer)
      .field("world_from_local", &RodActorParams::world_from_local)
      .field("shape", &RodActorParams::shape)
      .field("contact", &RodActorParams::contact)
      .field("contact_element_type", &RodActorParams::contact_element_type)
      .field("material", &RodActorParams::material)
      .field("has_gravity", &RodActorParams::has_gravity)
      .field("use_contact_skin", &RodActorParams::use_contact_skin, "refused: rods do not touch other actors yet")
      .field("contact_skin_element_type", &RodActorParams::contact_skin_element_type)
      .done();
  e.def("create_rod_actor", [](Scene& scene, const RodActorParams& p) { return Actor{scene, scene.create_rod_actor(p)}; }, "scene"_a,
        "params"_a,
        "An elastic rod (stretching, bending, twisting): a soft actor of type ROD whose nodes are the polyline's, in its\n"
        "island's implicit step with everything else. Node constraints take the polyline's node indices.");
  e.def("generate_tubular_rod_model_data",
        [](nb::handle nodes, nb::handle element_frame_axes, real radius, int num_cross_section_segments, bool is_closed_loop) {
          return generate_tubular_rod_model_data(points_of(nodes, "nodes"), points_of(element_frame_axes, "element_frame_axes"), radius,
                                                 num_cross_section_segments, is_closed_loop);
        },
        "nodes"_a, "element_frame_axes"_a, "radius"_a, "num_cross_section_segments"_a, "is_closed_loop"_a,
        "A rod's ModelData: the polyline of nodes (N x 3, m), one frame axis per element (made normal to it), and a tube of\n"
        "radius (m) around it with num_cross_section_segments vertices per ring as its visual mesh, skinned to the elements.");
}

}  // namespace superdex::python
