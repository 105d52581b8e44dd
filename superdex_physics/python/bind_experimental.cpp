// superdex.physics.experimental: per-element soft materials and run-time transmissions with their
// actuators (SuperDex's experimental functions that this engine implements).

#include "bind_common.h"
#include "bind_container.h"
#include "struct_binder.h"

namespace superdex::python {

void export_ik_solver(nb::module_& e);  // bind_ik_solver.cpp
void export_rod(nb::module_& m, nb::module_& e);  // bind_rod.cpp

void export_experimental(nb::module_& m) {
  nb::module_ e = m.def_submodule("experimental", "Functions whose form may still change.");
  export_ik_solver(e);
  export_rod(m, e);
  e.def("set_soft_material_params_field", [](Actor& actor, const SoftMaterialParams& params, int element_index) {
          actor.scene.set_soft_material_params_field(actor.handle, params, element_index);
        }, "actor"_a, "params"_a, "element_index"_a,
        "The material of one tetrahedron of a soft actor (its index in get_mesh()): elastic model, moduli and density\n"
        "(the node masses follow). Validated as set_soft_material_params; set_soft_material_params resets every element.");
  e.def("get_soft_material_params_field", [](const Actor& actor, int element_index) {
          return actor.scene.soft_material_params_field(actor.handle, element_index);
        }, "actor"_a, "element_index"_a, "The material of one tetrahedron of a soft actor.");

  StructBinder<LinearTransmissionParams>(e, "LinearTransmissionParams",
                                         "Displacement d = sum_k c_k q_k over single-DOF joints of an articulated actor.")
      .field("joint_indices", &LinearTransmissionParams::joint_indices, "indices into the actor's joints")
      .field("joint_coefficients", &LinearTransmissionParams::joint_coefficients, "c_k per joint (m of displacement per unit of joint motion)")
      .done();
  StructBinder<DisplacementControlActuatorParams>(e, "DisplacementControlActuatorParams",
                                                  "An implicit spring-damper driving the displacement to a target; pulls only unless "
                                                  "allow_compressive_force.")
      .field("target_displacement", &DisplacementControlActuatorParams::target_displacement, "m (the state variable)")
      .field("stiffness", &DisplacementControlActuatorParams::stiffness, "N/m")
      .field("damping", &DisplacementControlActuatorParams::damping, "N s/m")
      .field("allow_compressive_force", &DisplacementControlActuatorParams::allow_compressive_force, "the transmission can push")
      .done();
  StructBinder<ForceControlActuatorParams>(e, "ForceControlActuatorParams", "A given tension along the transmission.")
      .field("force", &ForceControlActuatorParams::force, "N (the state variable); >= 0 unless allow_compressive_force")
      .field("allow_compressive_force", &ForceControlActuatorParams::allow_compressive_force, "the transmission can push")
      .done();

  StructBinder<McKibbenActuatorParams>(e, "McKibbenActuatorParams",
                                       "A McKibben pneumatic muscle pulling along the transmission (Chou and Hannaford's model).")
      .field("pressure", &McKibbenActuatorParams::pressure, "Pa (the state variable)")
      .field("minimum_pressure", &McKibbenActuatorParams::minimum_pressure, "Pa: the inner tube presses on the braid above it")
      .field("thread_length", &McKibbenActuatorParams::thread_length, "m, > 0")
      .field("number_of_wraps", &McKibbenActuatorParams::number_of_wraps, "> 0")
      .field("deflated_stiffness", &McKibbenActuatorParams::deflated_stiffness, "N/m, > 0")
      .field("deflated_equilibrium_length", &McKibbenActuatorParams::deflated_equilibrium_length, "m, > 0: the length at zero displacement")
      .done();

  nb::enum_<RoutingElementType>(m, "RoutingElementType", "What a spatial tendon's routing element is.")
      .value("WAYPOINT", RoutingElementType::Waypoint)
      .value("LINEAR_JOINT", RoutingElementType::LinearJoint);
  StructBinder<RoutingElement>(m, "RoutingElement",
                               "One element of a spatial tendon's route, in order: a WAYPOINT (index: a link; local_position in its\n"
                               "frame, m) or a LINEAR_JOINT (index: a single-DOF joint; coefficient, m per unit of joint motion). A\n"
                               "segment joins adjacent waypoints only.")
      .field("type", &RoutingElement::type)
      .field("index", &RoutingElement::index)
      .field("local_position", &RoutingElement::local_position, "m, link frame (waypoints)")
      .field("coefficient", &RoutingElement::coefficient, "m per unit of joint motion (linear-joint elements)")
      .done();
  bind_dynamic_array<RoutingElement>(m, "DynamicArrayRoutingElement");
  StructBinder<SpatialTendonParams>(e, "SpatialTendonParams",
                                    "A spatial tendon: displacement = its segments' length less their length with the joints at zero, plus\n"
                                    "its linear-joint terms (m).")
      .field("routing_elements", &SpatialTendonParams::routing_elements)
      .done();
  e.def("add_spatial_tendon", [](Actor& actor, const SpatialTendonParams& params) { return actor.scene.add_spatial_tendon(actor.handle, params); },
        "actor"_a, "params"_a, "Adds a spatial tendon to an articulated actor; returns its transmission index.");
  e.def("add_linear_transmission", [](Actor& actor, const LinearTransmissionParams& params) {
          return actor.scene.add_linear_transmission(actor.handle, params);
        }, "actor"_a, "params"_a, "Adds a linear transmission to an articulated actor; returns its index.");
  e.def("get_transmission_displacement", [](const Actor& actor, int transmission_index) {
          return actor.scene.transmission_displacement(actor.handle, transmission_index);
        }, "actor"_a, "transmission_index"_a, "The displacement at the current pose (m).");
  e.def("get_transmission_displacement_jacobian", [](const Actor& actor, int transmission_index, nb::handle out_jacobian) {
          const VecX J = actor.scene.transmission_displacement_jacobian(actor.handle, transmission_index);
          write_out(out_jacobian, std::span<const real>(J.data(), static_cast<size_t>(J.size())), "get_transmission_displacement_jacobian: out_jacobian");
        }, "actor"_a, "transmission_index"_a, "out_jacobian"_a, "Writes dd/dv, one entry per DOF (get_num_dofs()).");
  e.def("attach_displacement_control_actuator", [](Actor& actor, int transmission_index, const DisplacementControlActuatorParams& params) {
          actor.scene.attach_displacement_control_actuator(actor.handle, transmission_index, params);
        }, "actor"_a, "transmission_index"_a, "params"_a, "Attaches (replacing any) a displacement-control actuator.");
  e.def("attach_force_control_actuator", [](Actor& actor, int transmission_index, const ForceControlActuatorParams& params) {
          actor.scene.attach_force_control_actuator(actor.handle, transmission_index, params);
        }, "actor"_a, "transmission_index"_a, "params"_a, "Attaches (replacing any) a force-control actuator.");
  e.def("attach_mc_kibben_actuator", [](Actor& actor, int transmission_index, const McKibbenActuatorParams& params) {
          actor.scene.attach_mc_kibben_actuator(actor.handle, transmission_index, params);
        }, "actor"_a, "transmission_index"_a, "params"_a, "Attaches (replacing any) a McKibben muscle; its state variable is the pressure.");
  e.def("get_num_transmission_actuator_state_variables", [](const Actor& actor, int transmission_index) {
          return actor.scene.num_transmission_actuator_state_variables(actor.handle, transmission_index);
        }, "actor"_a, "transmission_index"_a, "1 (the target displacement, the force or the pressure); an error when no actuator is attached.");
  e.def("get_transmission_actuator_state_variables", [](const Actor& actor, int transmission_index, nb::handle out_state_variables) {
          write_out(out_state_variables, actor.scene.transmission_actuator_state_variables(actor.handle, transmission_index),
                    "get_transmission_actuator_state_variables: out_state_variables");
        }, "actor"_a, "transmission_index"_a, "out_state_variables"_a, "Writes the attached actuator's state variables.");
  e.def("set_transmission_actuator_state_variables", [](Actor& actor, int transmission_index, nb::handle state_variables) {
          const VecX v = read_vector(state_variables, "set_transmission_actuator_state_variables: state_variables");
          actor.scene.set_transmission_actuator_state_variables(actor.handle, transmission_index, std::span<const real>(v.data(), static_cast<size_t>(v.size())));
        }, "actor"_a, "transmission_index"_a, "state_variables"_a, "Sets the target displacement, or the force.");
}

}  // namespace superdex::python
