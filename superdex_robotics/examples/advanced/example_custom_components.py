"""Custom components: a sensing-control-actuation loop written in Python.

A 2-DOF planar arm (assets/bots/fun/example_bot_2dof) follows a circle in the X-Z plane and switches
its vertical axis to force control when its ball presses on the soft duck-lamp prop:

- MyContactForceSensor: the total contact force on the end-effector link, world frame (N).
- MyVelocityForceController: task-space velocity control, v = x_dot_target + k_p (x_target - x);
  in force mode the Z row becomes the admittance law v_z = k_f (f_z - f_z_target).
- MyVelocityServoActuator: a velocity-mode PI servo with a trajectory ramp, clamped to its effort
  limit (N m), applied as an external joint effort.

The sensor and actuators are declared in the bot file by type name; registering the Python
classes under those names lets create_bot() instantiate them. The controller is created in code.

Run it with

    uv run python superdex_robotics/examples/advanced/example_custom_components.py

It opens the scene debugger and loops while the page is attached. Without a display, set
SUPERDEX_DEBUGGER_RECORD=run.sdrec.jsonl and SUPERDEX_DEBUGGER_DURATION=12 to record 12 simulated
seconds to a file instead (see superdex.physics.debugger).
"""

import json
import math
from pathlib import Path

import numpy as np

import superdex.physics as physics
import superdex.robotics as robotics

np_real = np.float64 if physics.uses_double_precision() else np.float32

END_EFFECTOR_LINK_INDEX = 3
SENSOR_NAME = "force_sensor"
ACTUATOR_NAMES = ("servo_1", "servo_2")
BOT_ASSET = "bots/fun/example_bot_2dof/example_bot_2dof.superdex_bot"
DUCK_LAMP_ASSET = "prefabs/duck_lamp/duck_lamp_recumbent.mochi_prefab"
CONTROL_RATE_HZ = 250.0


def get_default_bot_path() -> str:
    return str(physics.paths.resolve_asset(BOT_ASSET))


def get_link_actor(actor, link_index: int):
    """The link actor of an articulation by link index."""
    return actor.get_scene().get_actor(actor.get_nested_link_actors()[link_index])


def resolve_link_dof(link_actor):
    """(articulation actor, DOF index) of the joint that moves a one-DOF link."""
    scene = link_actor.get_scene()
    bot_actor = scene.get_actor(link_actor.get_articulated_actor())
    info = bot_actor.get_articulated_shape_info()
    dof = info.dof_info[link_actor.get_link_index()]
    if dof.get_size() != 1:
        raise RuntimeError(f"link {link_actor.get_link_index()} is not moved by a one-DOF joint")
    return bot_actor, dof.offset


class MyVelocityForceController:
    def __init__(self, actor):
        self.actor = actor
        self.k_p: float = 5.0  # 1/s
        self.k_f: float = 0.05  # (m/s)/N
        self.f_z_target: float = 0.5  # N
        self.exit_margin: float = 0.005  # m
        self.force_mode: bool = False

    def reset(self) -> None:
        self.force_mode = False

    def get_current_observations(self) -> dict[str, np.ndarray]:
        if self.actor is None:
            return None
        link_actor = get_link_actor(self.actor, END_EFFECTOR_LINK_INDEX)
        xforms = physics.DynamicArrayTransformRT(4)
        self.actor.get_articulated_link_transforms(xforms)
        x = np.array(xforms[END_EFFECTOR_LINK_INDEX].translation, dtype=np_real)
        num_dofs = self.actor.get_num_dofs()
        jacobian = np.array(link_actor.get_articulated_jacobian(), dtype=np_real)
        J_pos = jacobian.reshape(6, num_dofs)[0:3, :]
        return {"x": x, "J_pos": J_pos}

    def compute_output(self, obsv: dict, target: dict) -> np.ndarray:
        x_target = np.asarray(target["x"], dtype=np.float64)
        x_dot_target = np.asarray(target.get("x_dot", np.zeros(3)), dtype=np.float64)
        x = np.asarray(obsv["x"], dtype=np.float64)
        J_pos = np.asarray(obsv["J_pos"], dtype=np.float64)
        v_des = x_dot_target + self.k_p * (x_target - x)
        f_z = float(np.asarray(obsv["f_contact"])[2])
        self._update_mode(f_z, float(x_target[2]), float(x[2]))
        if self.force_mode:
            v_des[2] = self.k_f * (f_z - self.f_z_target)
        J_eff = J_pos[[0, 2], :]
        q_dot_des = np.linalg.pinv(J_eff) @ v_des[[0, 2]]
        return np.asarray(q_dot_des).reshape(-1)

    def _update_mode(self, f_z: float, x_target_z: float, x_z: float) -> None:
        if not self.force_mode:
            self.force_mode = f_z > self.f_z_target
        elif x_target_z > x_z + self.exit_margin or f_z <= 0.0:
            self.force_mode = False


class MyContactForceSensor:
    def __init__(self, actor, param_args: str):
        self.actor = actor
        if actor is not None:
            actor.register_query(physics.QueryType.TOTAL_CONTACT_FORCE)

    def reset(self) -> None:
        pass

    def compute_signal(self) -> np.ndarray:
        """World-frame contact force [N]. Call only after scene.step()."""
        return np.array(self.actor.get_contact_force_world(), dtype=np_real)


class MyVelocityServoActuator:
    def __init__(self, actor, param_args: str):
        assert actor is not None, "MyVelocityServoActuator requires a link actor"
        self.actor = actor
        self.bot_actor, self.dof_index = resolve_link_dof(actor)
        text = param_args.strip()
        if not text:
            params = {}
        else:
            source = text if text.startswith("{") else Path(text).read_text()
            params = json.loads(source)
        self.k_p: float = float(params.get("k_p", 1.0))  # N*m/(rad/s)
        self.k_i: float = float(params.get("k_i", 0.3))  # N*m/rad
        self.effort_limit: float = float(params.get("effort_limit", 1.0))  # N*m
        self.profile_accel: float = float(params.get("profile_accel", 0.0))  # rad/s^2
        self._integral: float = 0.0
        self._w_traj: float = 0.0

    def reset(self) -> None:
        self._integral = 0.0
        self._w_traj = 0.0

    def get_current_observations(self) -> dict[str, float]:
        num_dofs = self.bot_actor.get_num_dofs()
        q_dot = np.zeros(num_dofs, dtype=np_real)
        self.bot_actor.get_articulated_joint_velocities(out_velocities=q_dot)
        return {"w_present": float(q_dot[self.dof_index]), "w_traj": float(self._w_traj)}

    def compute_effort(self, obsv: dict, w_goal: float, dt: float) -> float:
        w_present = float(obsv["w_present"])
        self._w_traj = self._ramp_toward(float(w_goal), dt)
        e = self._w_traj - w_present
        integral_next = self._integral + e * dt
        effort_unsat = self.k_p * e + self.k_i * integral_next
        effort = float(np.clip(effort_unsat, -self.effort_limit, self.effort_limit))
        if effort == effort_unsat or e * effort_unsat < 0:
            self._integral = integral_next
        return effort

    def _ramp_toward(self, goal: float, dt: float) -> float:
        if self.profile_accel <= 0:
            return goal
        max_step = self.profile_accel * dt
        return self._w_traj + float(np.clip(goal - self._w_traj, -max_step, max_step))


def compute_trajectory_target(t: float) -> dict[str, np.ndarray]:
    center = np.array([-0.3, 0.0, 0.15])
    radius = 0.08
    omega = 2 * math.pi / 3.0
    theta = omega * t
    return {
        "x": center + radius * np.array([math.cos(theta), 0.0, math.sin(theta)]),
        "x_dot": radius * omega * np.array([-math.sin(theta), 0.0, math.cos(theta)]),
    }


def register_component_types(robotics_context) -> None:
    robotics.register_python_controller(robotics_context, "MY_VELOCITY_FORCE_CONTROLLER", MyVelocityForceController)
    robotics.register_python_sensor(robotics_context, "MY_CONTACT_FORCE_SENSOR", MyContactForceSensor)
    robotics.register_python_actuator(robotics_context, "MY_VELOCITY_SERVO_ACTUATOR", MyVelocityServoActuator)


def _one_handle(handles, name: str):
    if len(handles) != 1:
        raise RuntimeError(f"expected exactly one component named {name!r}, found {len(handles)}")
    return handles[0]


def main() -> None:
    physics.initialize(num_worker_threads=0)

    scene = physics.create_scene("Custom Components Example")
    scene.set_gravity([0, 0, -9.81])

    bot_prefab = robotics.load_bot_prefab_from_file(get_default_bot_path())

    robotics_context = robotics.create_context()
    register_component_types(robotics_context)
    bot = robotics.create_bot(scene, bot_prefab, robotics_context)
    bot_actor = bot.get_articulated_actor()

    plane_shape = physics.create_plane_shape(normal=[0, 0, 1], distance=0)
    scene.create_rigid_actor(name="ground", shape=plane_shape, is_static=True)

    physics.prefab.add_to_scene(
        prefab_path=str(physics.paths.resolve_asset(DUCK_LAMP_ASSET)),
        root_path=str(physics.paths.get_assets_root()),
        scene=scene,
        params=physics.prefab.PrefabParams(name="duck_lamp"),
    )

    handle = robotics_context.create_controller("MY_VELOCITY_FORCE_CONTROLLER", None, bot_actor, "my_controller")
    controller = robotics.get_python_controller(robotics_context, handle)

    sensor = robotics.get_python_sensor(robotics_context, _one_handle(bot.find_sensors_by_name(SENSOR_NAME), SENSOR_NAME))
    actuators = [
        robotics.get_python_actuator(robotics_context, _one_handle(bot.find_actuators_by_name(name), name))
        for name in ACTUATOR_NAMES
    ]
    dof_indices = [actuator.dof_index for actuator in actuators]
    time_step = 1.0 / CONTROL_RATE_HZ
    contact_force = np.zeros(3, dtype=np_real)

    if physics.debugger.attach():
        while physics.debugger.is_attached():
            t = scene.get_total_simulation_time()

            obsv = controller.get_current_observations()
            obsv["f_contact"] = contact_force
            q_dot_des = controller.compute_output(obsv, compute_trajectory_target(t))

            efforts = np.array(
                [
                    actuator.compute_effort(actuator.get_current_observations(), w_goal, dt=time_step)
                    for actuator, w_goal in zip(actuators, q_dot_des)
                ],
                dtype=np_real,
            )

            bot_actor.set_external_forces_on_dofs(dof_indices=dof_indices, force_values=efforts)
            scene.step(time_step)

            # Valid only after the step has completed.
            contact_force = sensor.compute_signal()

    robotics.destroy_bot(scene, bot)
    physics.shutdown()


if __name__ == "__main__":
    main()
