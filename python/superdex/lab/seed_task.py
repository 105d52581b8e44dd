"""SeedTaskEnv: the seed's task (superdex_robotics/examples/advanced/example_custom_components.py)
as a Gymnasium environment.

The 2-DOF arm (assets/bots/fun/example_bot_2dof) at 250 Hz; its ball should follow a circle in the
X-Z plane (centre (-0.30, 0, 0.15) m, radius 8 cm, one turn in 3 s, starting at a random phase)
whose lower part lies inside the soft duck-lamp prop, where the ball should press on the duck with
0.5 N.

- action (2,): in [-1, 1], the velocity goals of the two joints' velocity servos, scaled by
  `max_joint_speed` (rad/s). The servos are the seed's (VELOCITY_SERVO law: PI with profile
  acceleration and anti-windup, with the gains declared in the bot file), run in C++ every step.
- observation (13,): joint positions (rad, 2), joint velocities (rad/s, 2), the ball's position
  p_WE (m, world, 3), the contact force on the ball f_W (N, world, 3) during the last step, the
  circle's target point x*(t) (m, world, 3).
- reward: -|p_xz - x*_xz| / radius (circle tracking) - force_weight * |f_z - 0.5 N| / 0.5 N while
  the ball touches something (force regulation on the duck).
The target point, the observation and the reward are the batch's C++ task (SceneBatchSpec.task,
BatchTaskKind.CIRCLE_TRACKING), computed per scene on its worker thread.

`prop="box"` swaps the soft duck (about 40 ms per step) for the rigid 12 x 12 x 9 cm box of the
benchmarks (benchmarks/scenes/arm.py: where the duck lies, its top at 9 cm), for fast runs and tests.
"""

from __future__ import annotations

import json
import math
import warnings

import numpy as np

import superdex.physics as sdp
import superdex.robotics as sdr
from superdex.physics.paths import get_assets_root, resolve_asset
from superdex.lab.env import SuperDexEnv
from superdex.lab.task import BuiltScene

BOT_ASSET = "bots/fun/example_bot_2dof/example_bot_2dof.superdex_bot"
DUCK_LAMP_ASSET = "prefabs/duck_lamp/duck_lamp_recumbent.mochi_prefab"
END_EFFECTOR_LINK = 3
CENTER = np.array([-0.3, 0.0, 0.15])  # m, world
RADIUS = 0.08  # m
OMEGA = 2 * math.pi / 3.0  # rad/s
FORCE_TARGET = 0.5  # N
BOX_HALF_EXTENTS = [0.06, 0.06, 0.045]  # m
FRICTION = 0.5


def load_prefab():
    """The bot prefab and its servo gains, from the bot file's actuator declarations."""
    prefab = sdr.load_bot_prefab_from_file(str(resolve_asset(BOT_ASSET)))
    servos = [json.loads(d.params) for decls in prefab.actuators for d in decls]
    return prefab, servos


class SeedTaskEnv(SuperDexEnv):
    action_size = 2
    obs_size = 13
    params_size = 1  # the circle's start phase (rad)

    def __init__(self, prop: str = "duck", control_hz: float = 250.0, sim_multiple: int = 1, episode_steps: int = 750,
                 max_joint_speed: float = 2.0, force_weight: float = 0.5, render_mode: str | None = None,
                 num_worker_threads: int = 0):
        if prop not in ("duck", "box"):
            raise sdp.Error(f"prop must be 'duck' (soft duck lamp) or 'box' (rigid box), got {prop!r}")
        self.prop = prop
        self.max_joint_speed = self.action_scale = float(max_joint_speed)
        self.force_weight = float(force_weight)
        self._prefab, self._servos = load_prefab()
        super().__init__(control_hz, sim_multiple, episode_steps, render_mode, num_worker_threads)

    def build_scene(self, scene) -> BuiltScene:
        scene.set_gravity([0, 0, -9.81])
        ctx = sdr.create_context()
        with warnings.catch_warnings():
            # the bot file declares the seed's Python sensor and servos; here the servos run in C++
            warnings.simplefilter("ignore")
            bot = sdr.create_bot(scene, self._prefab, ctx)
        arm = bot.get_articulated_actor()
        scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape(normal=[0, 0, 1], distance=0), is_static=True)
        keep = [ctx, bot]
        if self.prop == "duck":
            keep.append(sdp.prefab.add_to_scene(prefab_path=str(resolve_asset(DUCK_LAMP_ASSET)), root_path=str(get_assets_root()),
                                                scene=scene, params=sdp.prefab.PrefabParams(name="duck_lamp")))
        else:
            scene.create_rigid_actor(name="box", shape=sdp.create_box_shape(BOX_HALF_EXTENTS), mass=0.5,
                                     world_from_local=sdp.TransformRT(translation=[-0.3, 0.0, BOX_HALF_EXTENTS[2]]))
        ball = arm.get_nested_link_actors()[END_EFFECTOR_LINK]
        return BuiltScene(scene, arm, ball, keep)

    def batch_spec(self) -> sdr.SceneBatchSpec:
        spec = sdr.SceneBatchSpec()
        spec.mode = sdr.BatchActionMode.VELOCITY_SERVO
        spec.action_dofs = [0, 1]
        spec.action_low = [-self.max_joint_speed] * 2
        spec.action_high = [self.max_joint_speed] * 2
        spec.servo_k_p = [float(s.get("k_p", 1.0)) for s in self._servos]
        spec.servo_k_i = [float(s.get("k_i", 0.3)) for s in self._servos]
        spec.servo_effort_limit = [float(s.get("effort_limit", 1.0)) for s in self._servos]
        spec.servo_profile_accel = [float(s.get("profile_accel", 0.0)) for s in self._servos]
        spec.observed_link = END_EFFECTOR_LINK
        # the target point, observation and reward in C++, per scene on its worker thread
        spec.task.kind = sdr.BatchTaskKind.CIRCLE_TRACKING
        spec.task.center = CENTER.tolist()
        spec.task.radius = RADIUS
        spec.task.omega = OMEGA
        spec.task.force_target = FORCE_TARGET
        spec.task.force_weight = self.force_weight
        return spec

    def sample_episode(self, rng):
        q0 = np.asarray(self._prefab.default_pose, dtype=np.float64) + rng.uniform(-0.05, 0.05, size=2)
        return q0, np.array([rng.uniform(0.0, 2 * math.pi)])

    def render_targets(self):
        return self._raw[:, -3:].astype(np.float64)  # the task's target point x*(t)
