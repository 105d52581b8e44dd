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

/// A McKibben pneumatic muscle along the transmission (Chou and Hannaford's static model). Its
/// length is L = deflated_equilibrium_length + d; it pulls with tension
///   T = max(0, pressure - minimum_pressure) b^2 / (4 pi n^2) (3 L^2 / b^2 - 1) + deflated_stiffness d
/// (b the thread length, n the number of wraps), the derivative of its energy in d, and never
/// pushes (T < 0 acts as 0). Integrated implicitly (its stiffness dT/dd in the step's matrix).
/// State variable: the pressure (Pa; gauge pressures may be negative, as long as the minimum is
/// measured the same way). thread_length, number_of_wraps, deflated_stiffness and
/// deflated_equilibrium_length must be positive.
struct McKibbenActuatorParams {
  real pressure = 0;                     ///< Pa
  real minimum_pressure = 0;             ///< Pa: below it the inner tube does not press on the braid
  real thread_length = 0;                ///< m (b)
  real number_of_wraps = 0;              ///< turns of a thread around the muscle (n)
  real deflated_stiffness = 0;           ///< N/m
  real deflated_equilibrium_length = 0;  ///< m: the muscle's length at zero displacement
};

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::physics
