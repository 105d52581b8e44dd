"""A robot run entirely by built-in C++ components: controller, motors and sensors inside scene.step.

Every bot has a pipeline. Before each physics step it runs the bot's controllers and then its
actuators, which turn the controllers' commands into joint efforts. After the step it updates the
sensors. With only built-in (C++) components the whole sensing-control-actuation loop runs inside
scene.step, with no Python per step. This script only steps the scene in a loop and reads the
sensors at the end.

The robot is the bundled 4-DOF URDF arm (assets/bots/urdf/tabletop_arm_4dof). A URDF has no
syntax for components, so this script adds them to the loaded BotPrefab before create_bot builds
the bot, just as a .superdex_bot file declares them on its links:

- actuators DC_MOTOR on each moving link: a geared DC motor per joint (100:1). It delivers the
  torque it is asked for along its torque-speed line. The rotor inertia, reflected through the
  gearbox (gear_ratio^2 x armature), is added to the joint by create_bot.
- sensor FORCE_TORQUE on base_link: the wrench the world applies to the arm through its base.
- sensor IMU on the tool: specific force and angular velocity in the tool frame.

Two more components are created in code on the built bot:

- sensor JOINT_STATE on the articulation: every joint's position and velocity;
- controller BASIC_OSC_PD: operational-space PD from base_link to the tool, position only, with
  gravity compensation and null-space damping, and a target point for the tool. Its efforts go
  to the motors as their torque requests.

The arm starts with the tool pointing down in front of it. Within about 1.5 s it reaches over to
the target and holds it. At the end the sensors say where it is and what it carries.

Run it with

    uv run python superdex_robotics/examples/control/example_cpp_pipeline.py [--seconds 3]

Add --debugger to watch it in the scene debugger; without a display, also set
SUPERDEX_DEBUGGER_RECORD=pipeline.jsonl to record the run to a file (superdex.physics.debugger).
"""

import argparse
import json

import numpy as np

import superdex.physics as physics
import superdex.robotics as robotics

ARM_ASSET = "bots/urdf/tabletop_arm_4dof/tabletop_arm_4dof.urdf"
START_POSE = [0.0, 0.45, 1.24, 1.45]  # rad: base yaw, shoulder, elbow, wrist (tool down at (0.45, 0, 0.40) m)
TARGET = [0.30, 0.25, 0.30]  # m, the tool's target in the base frame (the base is at the world origin)
DT = 0.002  # s
# per moving link: DC motor parameters (motor side; gear 100:1), stall torque x 100 = the URDF's effort limit
MOTORS = {
    "turret": {"stall_torque": 0.4, "no_load_speed": 300.0, "gear_ratio": 100.0, "armature": 2e-6},
    "upper_arm": {"stall_torque": 0.4, "no_load_speed": 300.0, "gear_ratio": 100.0, "armature": 2e-6},
    "forearm": {"stall_torque": 0.2, "no_load_speed": 300.0, "gear_ratio": 100.0, "armature": 1e-6},
    "wrist_link": {"stall_torque": 0.1, "no_load_speed": 300.0, "gear_ratio": 100.0, "armature": 5e-7},
}
SENSORS = {"base_link": ("FORCE_TORQUE", "base_ft"), "tool": ("IMU", "tool_imu")}
OSC_PARAMS = {
    "base_link": "base_link", "end_effector_link": "tool", "control_orientation": False,
    "kp_p": 100.0, "kd_p": 20.0,  # per unit task-space inertia: 10 rad/s, critically damped
    "max_position_error": 0.05,  # m: far from the target the tool moves at about kp/kd x 5 cm = 0.25 m/s
    "gravity_compensation": True, "null_space_damping": 1.0, "target_position": TARGET,
}


def declare_components(prefab) -> None:
    """Adds the motors and sensors to the prefab's links, as a .superdex_bot file would declare them."""
    names = [link.name for link in prefab.links]
    for link, params in MOTORS.items():
        prefab.actuators[names.index(link)].append(robotics.ComponentDecl("DC_MOTOR", f"motor_{link}", json.dumps(params)))
    for link, (type_name, name) in SENSORS.items():
        prefab.sensors[names.index(link)].append(robotics.ComponentDecl(type_name, name, ""))


def run(seconds: float = 3.0, debugger: bool = False) -> dict:
    """Builds the arm with its components and steps the scene for `seconds`, with no Python in the
    loop. Returns the final sensor signals, the joint efforts the motors applied in the last step,
    the tool's world pose, the total mass (from the prefab) and the tool-position history."""
    physics.initialize(num_worker_threads=0)
    try:
        scene = physics.create_scene("C++ pipeline")
        scene.set_gravity([0, 0, -9.81])
        prefab = robotics.load_bot_prefab_from_urdf_file(str(physics.paths.resolve_asset(ARM_ASSET)), fixed_base=True)
        prefab.default_pose = START_POSE
        declare_components(prefab)
        context = robotics.create_context()
        bot = robotics.create_bot(scene, prefab, context)
        try:
            arm = bot.get_articulated_actor()
            link_names = list(arm.get_articulated_shape_info().link_names)
            tool = scene.get_actor(arm.get_nested_link_actors()[link_names.index("tool")])
            joint_state = bot.create_sensor("JOINT_STATE", arm, "joint_state")
            bot.create_controller("BASIC_OSC_PD", "reach", OSC_PARAMS)
            assert bot.is_pipeline_active()

            tool_path = []
            if debugger:
                physics.debugger.attach()
            for k in range(int(round(seconds / DT))):
                scene.step(DT)  # controller, motors, physics, sensors: all in C++
                if k % 25 == 24:  # every 50 ms, for the summary only
                    tool_path.append((scene.get_total_simulation_time(), np.array(tool.get_root_transform().translation, dtype=np.float64)))

            def signal(name):
                (handle,) = bot.find_sensors_by_name(name)
                return np.array(context.get_sensor_signal(handle), dtype=np.float64)

            tool_pose = tool.get_root_transform()
            result = {
                "time": scene.get_total_simulation_time(),
                "num_dofs": arm.get_num_dofs(),
                "joint_state": np.array(context.get_sensor_signal(joint_state), dtype=np.float64),
                "base_ft": signal("base_ft"),
                "tool_imu": signal("tool_imu"),
                "efforts": np.array(arm.get_external_forces(), dtype=np.float64),
                "tool_position": np.array(tool_pose.translation, dtype=np.float64),
                "tool_rotation": np.array(tool_pose.rotation, dtype=np.float64),
                "total_mass": sum(link.mass for link in prefab.links),
                "tool_path": tool_path,
            }
        finally:
            robotics.destroy_bot(scene, bot)
        return result
    finally:
        if debugger:
            physics.debugger.detach()
        physics.shutdown()


def print_summary(result: dict) -> None:
    n = result["num_dofs"]
    q, v = result["joint_state"][:n], result["joint_state"][n:]
    print(f"after {result['time']:.2f} s, with the controller, {len(MOTORS)} motors and 3 sensors running in C++:")
    for t, p in result["tool_path"][3::6]:
        print(f"  t = {t:4.2f} s  tool at {np.array2string(p, precision=4, floatmode='fixed')} m, "
              f"{1e3 * np.linalg.norm(p - TARGET):7.2f} mm from the target")
    print(f"tool at {np.array2string(result['tool_position'], precision=4, floatmode='fixed')} m; target {TARGET} m; "
          f"error {1e3 * np.linalg.norm(result['tool_position'] - TARGET):.3f} mm")
    print(f"JOINT_STATE  q = {np.array2string(q, precision=4)} rad, v = {np.array2string(v, precision=1)} rad/s")
    print(f"DC_MOTOR efforts (joint side) = {np.array2string(result['efforts'], precision=4)} N m")
    f, t = result["base_ft"][:3], result["base_ft"][3:]
    print(f"FORCE_TORQUE at the base: F = {np.array2string(f, precision=3)} N (arm weight {result['total_mass'] * 9.81:.3f} N), "
          f"T = {np.array2string(t, precision=3)} N m")
    a, w = result["tool_imu"][:3], result["tool_imu"][3:]
    print(f"IMU on the tool: specific force {np.array2string(a, precision=3)} m/s^2 (|f| = {np.linalg.norm(a):.3f}), "
          f"angular velocity {np.array2string(w, precision=1)} rad/s")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=3.0, help="simulated time (s)")
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    print_summary(run(args.seconds, args.debugger))


if __name__ == "__main__":
    main()
