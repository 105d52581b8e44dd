"""PandaReachEnv: the 7-DOF Franka Panda (the URDF of the example-robot-data package, loaded by
superdex.robotics) reaching goal points just above a table, at 50 Hz control and 250 Hz physics.

- The robot: the URDF as imported (link meshes as collision shapes, the two finger DOFs held
  open by stiff joint drives); its links collide with the table but not with each other.
- The table: a static 30 x 60 x 4 cm box in front of the robot, its top at z = 0.40 m.
- action (7,): in [-1, 1], joint velocity commands scaled by `max_joint_speed` (rad/s), tracked by
  implicit joint drives (target position integrated from the command; stiffness and damping per
  joint, clamped to the URDF's effort limits), run in C++ inside the step.
- observation (23,): joint positions (rad, 7), joint velocities (rad/s, 7), the TCP position p_WE
  (m, world, 3), the contact force on the table f_W (N, world, 3) in the last step, the goal (m,
  world, 3).
- reward: -|p_WE - goal| (m) - force_weight * |f_W| (N): reach the goal without pushing on the table
  (the batch's C++ task, BatchTaskKind.GOAL_REACH, computed per scene on its worker thread).
- episode: `episode_steps` control steps (default 100: 2 s); start pose: the "ready" pose plus
  uniform noise of +-0.1 rad; goal: uniform in a box whose bottom is the table top.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

import superdex.physics as sdp
import superdex.robotics as sdr
from superdex.lab.env import SuperDexEnv
from superdex.lab.task import BuiltScene, np_real
from superdex.robot_files import PANDA_URDF, example_robot_data_file

READY = np.array([0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785])  # rad
# joint drive gains (N m/rad, N m s/rad) of the velocity commands
STIFFNESS = [600.0, 600.0, 600.0, 600.0, 250.0, 150.0, 50.0]
DAMPING = [30.0, 30.0, 30.0, 30.0, 10.0, 10.0, 5.0]
TCP_LINK = "panda_hand_tcp"
FINGER_OPENING = 0.02  # m per finger
ROBOT_LAYER = "panda"  # the robot's contact layer: its links touch the table, not each other
TABLE_HALF_EXTENTS = [0.15, 0.3, 0.02]  # m
TABLE_CENTER = [0.45, 0.0, 0.38]  # m, world: top at 0.40
GOAL_LOW = np.array([0.35, -0.2, 0.40])  # m, world
GOAL_HIGH = np.array([0.55, 0.2, 0.50])


def urdf_path() -> Path:
    """The Panda URDF shipped by the example-robot-data package."""
    try:
        return example_robot_data_file(PANDA_URDF)
    except FileNotFoundError as e:
        raise sdp.Error(str(e)) from None


class PandaReachEnv(SuperDexEnv):
    action_size = 7
    obs_size = 23
    params_size = 3  # the goal (m, world)

    def __init__(self, control_hz: float = 50.0, sim_multiple: int = 5, episode_steps: int = 100, max_joint_speed: float = 1.0,
                 force_weight: float = 0.01, render_mode: str | None = None, num_worker_threads: int = 0):
        self.max_joint_speed = self.action_scale = float(max_joint_speed)
        self.force_weight = float(force_weight)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the URDF's extra collision elements and mimic joints
            self._prefab = sdr.load_bot_prefab_from_urdf_file(str(urdf_path()), fixed_base=True)
        self._link_names = [link.name for link in self._prefab.links]
        self._efforts = [j.effort_limit for j in self._prefab.joints if j.name.startswith("panda_joint") and j.effort_limit > 0]
        super().__init__(control_hz, sim_multiple, episode_steps, render_mode, num_worker_threads)

    def build_scene(self, scene) -> BuiltScene:
        scene.set_gravity([0, 0, -9.81])
        scene.enable_layer_contact_symmetric(ROBOT_LAYER, ROBOT_LAYER, False)
        ctx = sdr.create_context()
        bot = sdr.create_bot(scene, self._prefab, ctx)
        arm = bot.get_articulated_actor()
        arm.set_contact_layer(ROBOT_LAYER)  # every link's
        pose = np.zeros(arm.get_num_dofs(), dtype=np_real)
        pose[:7] = READY
        pose[7:] = FINGER_OPENING
        arm.set_articulated_pose_from_joints(pose)
        for dof in range(7, arm.get_num_dofs()):  # fingers held open
            arm.set_joint_drive(dof, stiffness=200.0, damping=5.0, target_position=FINGER_OPENING, target_velocity=0.0, max_effort=20.0)
        table = scene.create_rigid_actor(name="table", shape=sdp.create_box_shape(TABLE_HALF_EXTENTS), is_static=True,
                                         world_from_local=sdp.TransformRT(translation=TABLE_CENTER))
        return BuiltScene(scene, arm, table, [ctx, bot])

    def batch_spec(self) -> sdr.SceneBatchSpec:
        spec = sdr.SceneBatchSpec()
        spec.mode = sdr.BatchActionMode.VELOCITY_DRIVE
        spec.action_dofs = list(range(7))
        spec.action_low = [-self.max_joint_speed] * 7
        spec.action_high = [self.max_joint_speed] * 7
        spec.drive_stiffness = STIFFNESS
        spec.drive_damping = DAMPING
        spec.drive_max_effort = self._efforts
        spec.observed_link = self._link_names.index(TCP_LINK)
        # the observation's goal columns and the reward in C++, per scene on its worker thread
        spec.task.kind = sdr.BatchTaskKind.GOAL_REACH
        spec.task.force_weight = self.force_weight
        return spec

    def sample_episode(self, rng):
        q0 = READY + rng.uniform(-0.1, 0.1, size=7)
        return q0, rng.uniform(GOAL_LOW, GOAL_HIGH)

    def render_targets(self):
        return self._params[:, :3]
