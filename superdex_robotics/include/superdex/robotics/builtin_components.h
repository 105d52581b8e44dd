#pragma once
/// @file builtin_components.h
/// The built-in C++ component types, registered by type name in every new Context.
/// Each takes its parameters as a JSON object (inline, or a file), accepts the same keys at
/// run time through Context::configure, and takes part in its bot's pipeline. Every type
/// accepts "rate" (Hz, default 0: every step). Unknown keys are errors.
///
/// Vectors over "joint DOFs" are in bot DOF order EXCLUDING the root joint's DOFs (the order
/// of `defaultPose`); a scalar is broadcast to every joint DOF; `null` entries of a target are
/// not commanded.
///
/// Controllers (actor: the articulation, or any of its links)
///   JOINT_COMMAND     constant setpoints: "position", "velocity", "effort" (joint DOFs). It
///                     is how a script commands actuators at run time (configure).
///   BASIC_JSC_PD      joint-space PD writing efforts: tau = kp e + kd (v* - v), e = q* - q set
///                     to 0 where |e| < deadband, clamped to |tau| <= saturation (< 0: none);
///                     "kp", "kd", "saturation", "deadband", "target_pose" (default: the pose
///                     at creation), "target_velocity" (default 0), "gravity_compensation"
///                     (default false: adds the bias forces c(q, v), gravity and Coriolis).
///   BASIC_OSC_PD      operational-space PD of an end-effector link relative to a base link.
///   ARTICULATED_POSE  stiff joint pose tracking, implicit in the step's dt.
///   MOCHI_ARTICULATED_POSE  the physics engine's pose controller, aimed by the script through
///                     compute_output (no part in the pipeline: controller_mochi_articulated_pose.h).
///   HYBRID_FORCE_VELOCITY  resolved-rate velocity control of a link's origin along a Cartesian
///                     target or trajectory, with force regulation along one axis in contact;
///                     writes joint velocities (for velocity actuators).
/// Actuators (actor: a link whose joint has one DOF)
///   IDEAL_PD, DC_MOTOR, VELOCITY_SERVO, DELAYED
/// Sensors (actor: a link)
///   CONTACT_FORCE, JOINT_STATE, FORCE_TORQUE, IMU
/// Sensors (actor: any actor, or none)
///   SENSOR_CAMERA     intrinsics and mounting for renderers; no signal (sensor_camera.h)
/// The parameters and conventions of each are documented in its source file
/// (src/controller_*.cpp, src/actuator_*.cpp, src/sensor_*.cpp).

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

class Context;

/// Registers the built-in types above in `ctx` (replacing types of the same names).
void register_builtin_components(Context& ctx);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
