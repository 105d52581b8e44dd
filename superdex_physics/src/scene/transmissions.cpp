// Scene API: linear transmissions added to articulated actors at run time, and their actuators
// (the step's terms are in multibody/articulation_step.cpp).

#include <cmath>
#include <string>

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

}  // namespace

int Scene::add_linear_transmission(ActorHandle h, const LinearTransmissionParams& p) {
  const char* what = "add_linear_transmission";
  Articulation& a = articulated(scene_data(handle_), h, what);
  if (p.joint_indices.size() != p.joint_coefficients.size())
    throw Error(std::string(what) + ": params.joint_indices has " + std::to_string(p.joint_indices.size()) +
                " entries and params.joint_coefficients " + std::to_string(p.joint_coefficients.size()) + "; one coefficient per joint");
  ArticulationModel::Tendon path;
  for (size_t k = 0; k < p.joint_indices.size(); ++k) {
    const int j = p.joint_indices[k];
    const std::string field = std::string(what) + ": params.joint_indices[" + std::to_string(k) + "]";
    if (j < 0 || j >= static_cast<int>(a.model.joints.size()))
      throw Error(field + ": expected the index of a joint (0 to " + std::to_string(a.model.joints.size()) + " - 1), got " + std::to_string(j));
    const JointModel& joint = a.model.joints[j];
    if (joint.nv != 1) throw Error(field + ": joint " + std::to_string(j) + " has " + std::to_string(joint.nv) + " DOFs; transmissions run over single-DOF joints");
    if (!std::isfinite(p.joint_coefficients[k]))
      throw Error(std::string(what) + ": params.joint_coefficients[" + std::to_string(k) + "] must be finite");
    path.dofs.push_back(joint.v_offset);
    path.q.push_back(joint.q_offset);
    path.coefficients.push_back(p.joint_coefficients[k]);
  }
  a.model.transmissions.push_back(std::move(path));
  a.state.transmission_actuators.resize(a.model.transmissions.size());
  return static_cast<int>(a.model.transmissions.size()) - 1;
}

real Scene::transmission_displacement(ActorHandle h, int transmission) const {
  const char* what = "get_transmission_displacement";
  const Articulation& a = articulated(scene_data(handle_), h, what);
  check_index(a, transmission, what);
  return a.model.transmissions[transmission].length(a.state.q);
}

VecX Scene::transmission_displacement_jacobian(ActorHandle h, int transmission) const {
  const char* what = "get_transmission_displacement_jacobian";
  const Articulation& a = articulated(scene_data(handle_), h, what);
  check_index(a, transmission, what);
  return a.model.transmissions[transmission].jacobian(a.model.nv);
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
