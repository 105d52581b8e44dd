// Registration of the built-in component types in a context.

#include "superdex/robotics/builtin_components.h"

#include "builtins.h"
#include "superdex/robotics/controller_basic_jsc_pd.h"
#include "superdex/robotics/controller_mochi_articulated_pose.h"
#include "superdex/robotics/sensor_camera.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

void register_builtin_components(Context& ctx) {
  using K = ComponentKind;
  ctx.register_type(K::Controller, "JOINT_COMMAND", make_joint_command_controller);
  ctx.register_type(K::Controller, ControllerBasicJscPd::kTypeName, make_joint_pd_controller);
  ctx.register_type(K::Controller, "BASIC_OSC_PD", make_osc_pd_controller);
  ctx.register_type(K::Controller, "ARTICULATED_POSE", make_articulated_pose_controller);
  ctx.register_type(K::Controller, ControllerMochiArticulatedPose::kTypeName, make_mochi_articulated_pose_controller);
  ctx.register_type(K::Controller, "HYBRID_FORCE_VELOCITY", make_hybrid_force_velocity_controller);
  ctx.register_type(K::Actuator, "IDEAL_PD", make_ideal_pd_actuator);
  ctx.register_type(K::Actuator, "DC_MOTOR", make_dc_motor_actuator, dc_motor_armature);
  ctx.register_type(K::Actuator, "VELOCITY_SERVO", make_velocity_servo_actuator);
  // DELAYED builds its inner actuator through the registry of the context it lives in
  const Context* context = &ctx;
  ctx.register_type(K::Actuator, "DELAYED", [context](const ComponentArgs& args) { return make_delayed_actuator(*context, args); });
  ctx.register_type(K::Sensor, "CONTACT_FORCE", make_contact_force_sensor);
  ctx.register_type(K::Sensor, "JOINT_STATE", make_joint_state_sensor);
  ctx.register_type(K::Sensor, "FORCE_TORQUE", make_force_torque_sensor);
  ctx.register_type(K::Sensor, "IMU", make_imu_sensor);
  ctx.register_type(K::Sensor, CameraSensor::kTypeName, make_camera_sensor);
  ctx.register_type(K::Sensor, "TACTILE_PAD", make_tactile_pad_sensor);
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
