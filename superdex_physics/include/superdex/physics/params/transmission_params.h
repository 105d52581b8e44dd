#pragma once
/// @file transmission_params.h
/// Transmissions added to an articulated actor at run time (Scene::add_linear_transmission) and
/// the actuators that drive them (SuperDex's experimental transmission API; SI units).

#include <vector>

#include "superdex/physics/real.h"

namespace superdex::physics {
inline namespace SUPERDEX_REAL_NAMESPACE {

/// A linear transmission: displacement d = sum_k c_k q_{joint k} over single-DOF joints (a joint
/// may appear more than once: its coefficients add).
struct LinearTransmissionParams {
  std::vector<int> joint_indices;        ///< indices into the actor's joints
  std::vector<real> joint_coefficients;  ///< c_k: m (or rad) of displacement per unit of joint motion
};

/// Drives the displacement towards a target with an implicit spring-damper: tension
/// f = stiffness (target - d+) - damping (d/dt)+ at the end of the step, applied to the joints as
/// c_k f. A rope pulls only: f >= 0 unless allow_compressive_force. State variable: the target.
struct DisplacementControlActuatorParams {
  real target_displacement = 0;  ///< m (the transmission's unit)
  real stiffness = 1e9;          ///< N/m
  real damping = 0;              ///< N s/m
  bool allow_compressive_force = false;
};

/// Applies a given tension f along the transmission (joint efforts c_k f). State variable: f,
/// which must be >= 0 unless allow_compressive_force.
struct ForceControlActuatorParams {
  real force = 0;  ///< N (the transmission's generalized force)
  bool allow_compressive_force = false;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
