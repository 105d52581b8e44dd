// Scene API: linear transmissions added to articulated actors at run time, and their actuators
// (the step's terms are in multibody/articulation_step.cpp).

#include <cmath>
#include <string>

#include "multibody/kinematics.h"
#include "multibody/transmission_path.h"
#include "scene/actor_lookup.h"
#include "scene/scene_data.h"
#include "superdex/physics/error.h"
#include "superdex/physics/scene.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

namespace {

// The transmission's index checked against the articulation's transmissions.
void check_index(const Articulation& a, int transmission, const char* what) {
  const int n = static_cast<int>(a.model.transmissions.size());
  if (transmission < 0 || transmission >= n)
    throw Error(std::string(what) + ": transmission_index " + std::to_string(transmission) + " is out of range: the actor has " +
                std::to_string(n) + " transmission" + (n == 1 ? "" : "s"));
}

// The attached actuator of a transmission; an error when there is none.
TransmissionActuator& attached(Articulation& a, int transmission, const char* what) {
  check_index(a, transmission, what);
  TransmissionActuator& act = a.state.transmission_actuators[transmission];
  if (act.kind == TransmissionActuator::Kind::None)
    throw Error(std::string(what) + ": transmission " + std::to_string(transmission) + " has no actuator attached");
  return act;
}

void attach(Articulation& a, int transmission, const TransmissionActuator& act, const char* what) {
  check_index(a, transmission, what);
  a.state.transmission_actuators[transmission] = act;
}

// Adds c q_j to a transmission's linear sum; `field` names the joint index's argument.
void add_joint_term(const Articulation& a, ArticulationModel::Transmission& path, int j, real c, const std::string& field,
                    const std::string& coefficient_field) {
  if (j < 0 || j >= static_cast<int>(a.model.joints.size()))
    throw Error(field + ": expected the index of a joint (0 to " + std::to_string(a.model.joints.size()) + " - 1), got " + std::to_string(j));
  const JointModel& joint = a.model.joints[j];
  if (joint.nv != 1) throw Error(field + ": joint " + std::to_string(j) + " has " + std::to_string(joint.nv) + " DOFs; transmissions run over single-DOF joints");
  if (!std::isfinite(c)) throw Error(coefficient_field + " must be finite");
  path.dofs.push_back(joint.v_offset);
  path.q.push_back(joint.q_offset);
  path.coefficients.push_back(c);
}

int add_transmission(Articulation& a, ArticulationModel::Transmission path) {
  a.model.transmissions.push_back(std::move(path));
  a.state.transmission_actuators.resize(a.model.transmissions.size());
  return static_cast<int>(a.model.transmissions.size()) - 1;
}

}  // namespace

int Scene::add_linear_transmission(ActorHandle h, const LinearTransmissionParams& p) {
  const char* what = "add_linear_transmission";
  Articulation& a = articulated(scene_data(handle_), h, what);
  if (p.joint_indices.size() != p.joint_coefficients.size())
    throw Error(std::string(what) + ": params.joint_indices has " + std::to_string(p.joint_indices.size()) +
                " entries and params.joint_coefficients " + std::to_string(p.joint_coefficients.size()) + "; one coefficient per joint");
  ArticulationModel::Transmission path;
  for (size_t k = 0; k < p.joint_indices.size(); ++k)
    add_joint_term(a, path, p.joint_indices[k], p.joint_coefficients[k], std::string(what) + ": params.joint_indices[" + std::to_string(k) + "]",
                   std::string(what) + ": params.joint_coefficients[" + std::to_string(k) + "]");
  return add_transmission(a, std::move(path));
}

int Scene::add_spatial_tendon(ActorHandle h, const SpatialTendonParams& p) {
  const char* what = "add_spatial_tendon";
  Articulation& a = articulated(scene_data(handle_), h, what);
  ArticulationModel::Transmission path;
  bool last_was_waypoint = false;
  for (size_t k = 0; k < p.routing_elements.size(); ++k) {
    const RoutingElement& e = p.routing_elements[k];
    const std::string field = std::string(what) + ": params.routing_elements[" + std::to_string(k) + "]";
    if (e.type == RoutingElementType::LinearJoint) {
      add_joint_term(a, path, e.index, e.coefficient, field + ".index", field + ".coefficient");
      last_was_waypoint = false;
      continue;
    }
    if (e.index < 0 || e.index >= a.model.num_links)
      throw Error(field + ".index: expected the index of a link (0 to " + std::to_string(a.model.num_links) + " - 1), got " + std::to_string(e.index));
    if (!e.local_position.allFinite()) throw Error(field + ".local_position must be finite");
    // a segment joins it to the previous element when that was a waypoint too
    if (last_was_waypoint) path.waypoints.back().to_next = true;
    path.waypoints.push_back({e.index, e.local_position, false});
    last_was_waypoint = true;
  }
  if (path.waypoints.empty() && path.dofs.empty()) throw Error(std::string(what) + ": params.routing_elements is empty");
  // the segments' length with every joint at zero (the base where it is: lengths do not depend on it)
  ArticulationKinematics rest;
  VecX q = a.state.q;
  const VecX zero_pose = VecX::Zero(a.model.nv);
  q_from_pose(a.model, zero_pose.data(), false, q);
  update_kinematics(a.model, q, VecX::Zero(a.model.nv), a.state.X_W_base, rest);
  path.rest_length = segments_length(path, rest.X_WL);
  return add_transmission(a, std::move(path));
}

real Scene::transmission_displacement(ActorHandle h, int transmission) const {
  const char* what = "get_transmission_displacement";
  const Articulation& a = articulated(scene_data(handle_), h, what);
  check_index(a, transmission, what);
  return physics::transmission_displacement(a.model, a.state, a.kin, a.model.transmissions[transmission]);
}

VecX Scene::transmission_displacement_jacobian(ActorHandle h, int transmission) const {
  const char* what = "get_transmission_displacement_jacobian";
  const Articulation& a = articulated(scene_data(handle_), h, what);
  check_index(a, transmission, what);
  return transmission_jacobian(a.model, a.kin, a.model.transmissions[transmission]);
}

void Scene::attach_displacement_control_actuator(ActorHandle h, int transmission, const DisplacementControlActuatorParams& p) {
  const char* what = "attach_displacement_control_actuator";
  Articulation& a = articulated(scene_data(handle_), h, what);
  if (!std::isfinite(p.target_displacement)) throw Error(std::string(what) + ": params.target_displacement must be finite");
  if (!std::isfinite(p.stiffness) || p.stiffness < 0) throw Error(std::string(what) + ": params.stiffness must be a finite number >= 0");
  if (!std::isfinite(p.damping) || p.damping < 0) throw Error(std::string(what) + ": params.damping must be a finite number >= 0");
  TransmissionActuator act;
  act.kind = TransmissionActuator::Kind::DisplacementControl;
  act.value = p.target_displacement;
  act.stiffness = p.stiffness;
  act.damping = p.damping;
  act.allow_compressive_force = p.allow_compressive_force;
  attach(a, transmission, act, what);
}

void Scene::attach_force_control_actuator(ActorHandle h, int transmission, const ForceControlActuatorParams& p) {
  const char* what = "attach_force_control_actuator";
  Articulation& a = articulated(scene_data(handle_), h, what);
  if (!std::isfinite(p.force)) throw Error(std::string(what) + ": params.force must be finite");
  if (p.force < 0 && !p.allow_compressive_force)
    throw Error(std::string(what) + ": params.force is " + std::to_string(p.force) +
                "; a rope-like transmission only pulls (set allow_compressive_force for one that can push)");
  TransmissionActuator act;
  act.kind = TransmissionActuator::Kind::ForceControl;
  act.value = p.force;
  act.allow_compressive_force = p.allow_compressive_force;
  attach(a, transmission, act, what);
}

void Scene::attach_mc_kibben_actuator(ActorHandle h, int transmission, const McKibbenActuatorParams& p) {
  const char* what = "attach_mc_kibben_actuator";
  Articulation& a = articulated(scene_data(handle_), h, what);
  auto positive = [&](real v, const char* field) {
    if (!std::isfinite(v) || v <= 0) throw Error(std::string(what) + ": params." + field + " must be a positive finite number, got " + std::to_string(v));
  };
  positive(p.deflated_equilibrium_length, "deflated_equilibrium_length");
  positive(p.deflated_stiffness, "deflated_stiffness");
  positive(p.number_of_wraps, "number_of_wraps");
  positive(p.thread_length, "thread_length");
  if (!std::isfinite(p.pressure)) throw Error(std::string(what) + ": params.pressure must be finite");
  if (!std::isfinite(p.minimum_pressure)) throw Error(std::string(what) + ": params.minimum_pressure must be finite");
  TransmissionActuator act;
  act.kind = TransmissionActuator::Kind::McKibben;
  act.value = p.pressure;
  act.stiffness = p.deflated_stiffness;
  act.minimum_pressure = p.minimum_pressure;
  act.thread_length = p.thread_length;
  act.wraps = p.number_of_wraps;
  act.deflated_length = p.deflated_equilibrium_length;
  attach(a, transmission, act, what);
}

int Scene::num_transmission_actuator_state_variables(ActorHandle h, int transmission) const {
  const char* what = "get_num_transmission_actuator_state_variables";
  attached(articulated(scene_data(handle_), h, what), transmission, what);
  return 1;
}

std::vector<real> Scene::transmission_actuator_state_variables(ActorHandle h, int transmission) const {
  const char* what = "get_transmission_actuator_state_variables";
  return {attached(articulated(scene_data(handle_), h, what), transmission, what).value};
}

void Scene::set_transmission_actuator_state_variables(ActorHandle h, int transmission, std::span<const real> values) {
  const char* what = "set_transmission_actuator_state_variables";
  TransmissionActuator& act = attached(articulated(scene_data(handle_), h, what), transmission, what);
  if (values.size() != 1)
    throw Error(std::string(what) + ": state_variables has " + std::to_string(values.size()) + " values; the actuator has 1");
  if (!std::isfinite(values[0])) throw Error(std::string(what) + ": state_variables[0] must be finite");
  if (act.kind == TransmissionActuator::Kind::ForceControl && values[0] < 0 && !act.allow_compressive_force)
    throw Error(std::string(what) + ": a negative force on a transmission that only pulls (allow_compressive_force is false)");
  act.value = values[0];
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
