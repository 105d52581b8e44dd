#pragma once
// Factories of the built-in component types (one source file each), registered by
// register_builtin_components (builtin_components.cpp).

#include <memory>
#include <string>

#include "superdex/robotics/context.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

// controllers
std::unique_ptr<Component> make_joint_command_controller(const ComponentArgs& args);
std::unique_ptr<Component> make_joint_pd_controller(const ComponentArgs& args);
std::unique_ptr<Component> make_osc_pd_controller(const ComponentArgs& args);
std::unique_ptr<Component> make_articulated_pose_controller(const ComponentArgs& args);
std::unique_ptr<Component> make_mochi_articulated_pose_controller(const ComponentArgs& args);
std::unique_ptr<Component> make_hybrid_force_velocity_controller(const ComponentArgs& args);
// actuators
std::unique_ptr<Component> make_ideal_pd_actuator(const ComponentArgs& args);
std::unique_ptr<Component> make_dc_motor_actuator(const ComponentArgs& args);
real dc_motor_armature(const std::string& params);
std::unique_ptr<Component> make_velocity_servo_actuator(const ComponentArgs& args);
std::unique_ptr<Component> make_delayed_actuator(const Context& context, const ComponentArgs& args);
// sensors
std::unique_ptr<Component> make_contact_force_sensor(const ComponentArgs& args);
std::unique_ptr<Component> make_joint_state_sensor(const ComponentArgs& args);
std::unique_ptr<Component> make_force_torque_sensor(const ComponentArgs& args);
std::unique_ptr<Component> make_imu_sensor(const ComponentArgs& args);
std::unique_ptr<Component> make_camera_sensor(const ComponentArgs& args);
std::unique_ptr<Component> make_tactile_pad_sensor(const ComponentArgs& args);

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
