"""SuperDexEnv: the Gymnasium environment base class of the lab, over one scene.

A subclass says how a scene is built and what its task is (the hooks below); the base class
gives the Gymnasium contract:

- control frequency `control_hz` (Hz) and simulation frequency `sim_multiple * control_hz`: each
  `step` applies the action and runs `sim_multiple` physics steps of 1 / (sim_multiple * control_hz) s;
- episodes of `episode_steps` control steps (then `truncated` is True);
- `reset(seed=...)` restores the scene's captured initial state exactly (Scene.capture_state /
  restore_state, bitwise), then places the robot at a pose drawn from the environment's
  generator, so the same seed gives bitwise the same trajectory;
- `render_mode`: None, "rgb_array" (a schematic side view, superdex.lab.render) or "human" (the
  scene debugger, `superdex.physics.debugger.attach()`, streams every step).

The stepping itself is a superdex.robotics.SceneBatch of one scene: the same C++ code that
SuperDexVectorEnv runs over many scenes (actions become joint efforts or drive targets in C++;
no Python runs inside the physics step).

Hooks (rows: arrays have one row per scene, so the same code serves the vector environment)
    build_scene(scene) -> BuiltScene          the robot, props and contact actor of one scene
    batch_spec() -> SceneBatchSpec            action DOFs, action mode, observed link, and
                                              optionally a C++ task (spec.task: BatchTask)
    sample_episode(rng) -> (q0, params)       start pose of the action DOFs, task parameters
and, for a task written in Python (a spec without a C++ task):
    task_observation(raw, t, params) -> obs   observation rows from raw SceneBatch rows
    task_reward(raw, t, params, actions) -> (reward, terminated)
    task_step(raw, t, params, actions) -> (reward, terminated, obs)
                                              both after a control step; by default the two
                                              hooks above, overridden where they share work
with t the control steps taken since each row's reset, and attributes `action_size`,
`obs_size`, `params_size`. With a C++ task (the built-in environments), the batch writes the
observation rows and rewards itself, per scene on the worker threads, and never terminates.
"""

from __future__ import annotations

import numpy as np
import gymnasium as gym
from gymnasium import spaces

import superdex.physics as sdp
import superdex.robotics as sdr
from superdex.lab.task import BuiltScene, ensure_engine, make_batch, np_real


class SuperDexEnv(gym.Env):
    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 30}

    action_size: int = 0
    #: an action in [-1, 1] times this is the batch's action (rad/s for velocity commands)
    action_scale: float = 1.0
    obs_size: int = 0
    params_size: int = 0

    def __init__(self, control_hz: float, sim_multiple: int = 1, episode_steps: int = 100, render_mode: str | None = None,
                 num_worker_threads: int = 0):
        if not control_hz > 0:
            raise sdp.Error(f"control_hz must be positive (Hz), got {control_hz}")
        if int(sim_multiple) != sim_multiple or sim_multiple < 1:
            raise sdp.Error(f"sim_multiple must be a positive integer, got {sim_multiple}")
        if int(episode_steps) != episode_steps or episode_steps < 1:
            raise sdp.Error(f"episode_steps must be a positive integer, got {episode_steps}")
        if render_mode not in (None, *self.metadata["render_modes"]):
            raise sdp.Error(f"render_mode must be None, 'rgb_array' or 'human', got {render_mode!r}")
        self.control_hz = float(control_hz)
        self.sim_multiple = int(sim_multiple)
        self.episode_steps = int(episode_steps)
        self.render_mode = render_mode
        self.num_worker_threads = num_worker_threads
        self.metadata = {**self.metadata, "render_fps": int(round(min(self.control_hz, 30)))}
        self.action_space = spaces.Box(-1.0, 1.0, shape=(self.action_size,), dtype=np.float32)
        self.observation_space = spaces.Box(-np.inf, np.inf, shape=(self.obs_size,), dtype=np_real)
        self._built: BuiltScene | None = None
        self._batch = None
        self._raw = None
        self._t = np.zeros(1, dtype=np.int64)
        self._params = np.zeros((1, self.params_size))
        self._needs_reset = True
        self._debugger_attached = False
        #: the spec's task is computed by the C++ batch (observation rows and rewards), not by the hooks
        self.task_in_cxx = self.batch_spec().task.kind != sdr.BatchTaskKind.NONE

    # ------------------------------------------------------------------ hooks
    def build_scene(self, scene) -> BuiltScene:
        raise NotImplementedError

    def batch_spec(self) -> sdr.SceneBatchSpec:
        raise NotImplementedError

    def sample_episode(self, rng: np.random.Generator):
        raise NotImplementedError

    def task_observation(self, raw, t, params):
        raise NotImplementedError

    def task_reward(self, raw, t, params, actions):
        raise NotImplementedError

    def task_step(self, raw, t, params, actions):
        """Reward, terminated and observation rows after a control step (what task_reward and
        task_observation give; a task overrides it to compute what the two share once)."""
        reward, terminated = self.task_reward(raw, t, params, actions)
        return reward, terminated, self.task_observation(raw, t, params)

    def observation_rows(self, raw, t, params):
        """Observation rows after a reset: the batch's rows for a C++ task, else task_observation."""
        return raw.copy() if self.task_in_cxx else self.task_observation(raw, t, params)

    def step_rows(self, raw, reward, t, params, actions):
        """(reward, terminated, obs) rows after a control step: the batch's rows and rewards
        (`reward`, written by the batch's step) for a C++ task, else task_step."""
        if self.task_in_cxx:
            return reward.copy(), np.zeros(len(raw), dtype=bool), raw.copy()
        return self.task_step(raw, t, params, actions)

    def batch_params(self, params):
        """The task parameter rows the batch's reset takes: float64 rows for a C++ task, else None."""
        return np.ascontiguousarray(params, dtype=np.float64) if self.task_in_cxx else None

    # ------------------------------------------------------------------ timing
    @property
    def control_dt(self) -> float:
        """Seconds per control step."""
        return 1.0 / self.control_hz

    @property
    def sim_dt(self) -> float:
        """Seconds per physics step."""
        return 1.0 / (self.control_hz * self.sim_multiple)

    def full_spec(self) -> sdr.SceneBatchSpec:
        """batch_spec() with the physics step and substeps of this environment's frequencies."""
        spec = self.batch_spec()
        spec.dt = self.sim_dt
        spec.substeps = self.sim_multiple
        return spec

    # ------------------------------------------------------------------ Gymnasium
    def _build(self):
        ensure_engine(self.num_worker_threads)
        scene = sdp.create_scene(type(self).__name__)
        self._built = self.build_scene(scene)
        self._batch = make_batch(self.full_spec(), [self._built])
        self._raw = np.zeros((1, self._batch.obs_size), dtype=np_real)
        self._reward = np.zeros(1)

    @property
    def scene(self):
        """The environment's scene (built at the first reset)."""
        return None if self._built is None else self._built.scene

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        if self._batch is None:
            self._build()
        q0, params = self.sample_episode(self.np_random)
        self._params[0] = params
        self._t[0] = 0
        self._batch.reset([0], np.ascontiguousarray(np.reshape(q0, (1, -1)), dtype=np.float64), self._raw,
                          self.batch_params(self._params))
        self._needs_reset = False
        if self.render_mode == "human":
            self._attach_debugger()
        return self.observation_rows(self._raw, self._t, self._params)[0], {}

    def step(self, action):
        if self._needs_reset:
            raise sdp.Error("step: call reset() first (at the start and after an episode ends)")
        a = np.asarray(action, dtype=np.float64).reshape(1, -1)
        if a.shape != (1, self.action_size):
            raise sdp.Error(f"step: action must have shape ({self.action_size},), got {np.shape(action)}")
        a = np.ascontiguousarray(np.clip(a, -1.0, 1.0) * self.action_scale)
        self._batch.step(a, self._raw, self._reward)
        self._t += 1
        reward, terminated, obs = self.step_rows(self._raw, self._reward, self._t, self._params, a)
        truncated = bool(self._t[0] >= self.episode_steps)
        self._needs_reset = bool(terminated[0]) or truncated
        return obs[0], float(reward[0]), bool(terminated[0]), truncated, {}

    def render(self):
        if self.render_mode == "rgb_array":
            from superdex.lab.render import render_side_view

            if self._built is None:
                self.reset()
            return render_side_view(self._built, self.render_targets())
        if self.render_mode == "human":
            self._attach_debugger()
        return None

    def render_targets(self) -> np.ndarray:
        """World points (k x 3, m) drawn as targets by the rgb_array view; none by default."""
        return np.zeros((0, 3))

    def _attach_debugger(self):
        if not self._debugger_attached:
            self._debugger_attached = bool(sdp.debugger.attach())

    def close(self):
        if self._built is not None and sdp.is_initialized():
            sdp.destroy_scene(self._built.scene)
        self._built = None
        self._batch = None
