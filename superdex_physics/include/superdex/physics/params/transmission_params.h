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

/// One element of a spatial tendon's route, in order: a waypoint (`index` a link, local_position
/// in that link's frame, m) or a linear-joint element (`index` a single-DOF joint, coefficient
/// m of displacement per unit of joint motion). A segment joins two waypoints only when they
/// are adjacent in the list: a linear-joint element between them leaves a gap.
enum class RoutingElementType { Waypoint, LinearJoint };
struct RoutingElement {
  RoutingElementType type = RoutingElementType::Waypoint;
  int index = 0;
  Real3 local_position = Real3::Zero();
  real coefficient = 0;
  bool operator==(const RoutingElement&) const = default;
};

/// A spatial tendon: displacement d = (the summed lengths of its segments) - (the same with every
/// joint at zero) + sum_k c_k q_k over its linear-joint elements (m). Driven like a linear
/// transmission (its index is a transmission index).
struct SpatialTendonParams {
  std::vector<RoutingElement> routing_elements;
  bool operator==(const SpatialTendonParams&) const = default;
};

/// Drives the displacement towards a target with an implicit spring-damper: tension
/// f = stiffness (d+ - target) + damping (d/dt)+ at the end of the step, which shortens the
/// transmission: joint efforts -f dd/dq. A rope pulls only (slack while d < target): f >= 0
/// unless allow_compressive_force. State variable: the target.
struct DisplacementControlActuatorParams {
  real target_displacement = 0;  ///< m (the transmission's unit)
  real stiffness = 1e9;          ///< N/m
  real damping = 0;              ///< N s/m
  bool allow_compressive_force = false;
};

/// Applies a given tension f along the transmission, shortening it (joint efforts -f dd/dq).
/// State variable: f, which must be >= 0 unless allow_compressive_force.
struct ForceControlActuatorParams {
  real force = 0;  ///< N (the transmission's generalized force)
  bool allow_compressive_force = false;
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
