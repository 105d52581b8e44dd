// Per-DOF commands and the defaults of the component base class.

#include "superdex/robotics/component.h"

#include <cmath>

#include "superdex/physics/error.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void DofCommands::clear(int num_dofs) {
  position.setZero(num_dofs);
  velocity.setZero(num_dofs);
  effort.setZero(num_dofs);
  has_position.assign(num_dofs, 0);
  has_velocity.assign(num_dofs, 0);
  has_effort.assign(num_dofs, 0);
}

namespace {
void set(VecX& values, std::vector<std::uint8_t>& has, int dof, real value, const char* what) {
  if (dof < 0 || dof >= values.size())
    throw Error(std::string("DofCommands::") + what + ": DOF " + std::to_string(dof) + " is out of range (" +
                std::to_string(values.size()) + " DOFs)");
  if (!std::isfinite(value)) throw Error(std::string("DofCommands::") + what + ": DOF " + std::to_string(dof) + ": the value is not finite");
  values[dof] = value;
  has[dof] = 1;
}
}  // namespace

void DofCommands::set_position(int dof, real value) { set(position, has_position, dof, value, "set_position"); }
void DofCommands::set_velocity(int dof, real value) { set(velocity, has_velocity, dof, value, "set_velocity"); }
void DofCommands::set_effort(int dof, real value) { set(effort, has_effort, dof, value, "set_effort"); }

DofCommand DofCommands::at(int dof) const {
  DofCommand c;
  if (has_position[dof]) c.position = position[dof];
  if (has_velocity[dof]) c.velocity = velocity[dof];
  if (has_effort[dof]) c.effort = effort[dof];
  return c;
}

void DofCommands::merge(const DofCommands& other) {
  for (int i = 0; i < std::min(size(), other.size()); ++i) {
    if (other.has_position[i]) position[i] = other.position[i], has_position[i] = 1;
    if (other.has_velocity[i]) velocity[i] = other.velocity[i], has_velocity[i] = 1;
    if (other.has_effort[i]) effort[i] += other.effort[i], has_effort[i] = 1;
  }
}

void Component::configure(const std::string&) {
  throw Error("this component has no run-time parameters (configure is not supported)");
}

void Component::configure_from_scene_entry(const std::string& params, const std::string& init_args) {
  for (const std::string* args : {&params, &init_args})
    if (args->find_first_not_of(" \t\r\n") != std::string::npos) configure(*args);
}

void Component::set_rate(double rate_hz) {
  if (!(rate_hz >= 0) || !std::isfinite(rate_hz))
    throw Error("rate must be a finite number of Hz >= 0 (0: every step), got " + std::to_string(rate_hz));
  rate_hz_ = rate_hz;
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
