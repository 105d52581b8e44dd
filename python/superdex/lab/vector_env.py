"""SuperDexVectorEnv: many scenes of one lab environment stepped by one C++ call.

`SuperDexVectorEnv(SeedTaskEnv, num_envs=64, num_worker_threads=2, prop="box")` builds `num_envs`
scenes with the environment's `build_scene`, puts them in one superdex.robotics.SceneBatch and
steps them all per `step(actions)` on the engine's worker threads (the GIL released): actions and
observations are contiguous (num_envs x n) numpy arrays, and the task's observation and reward are
computed in C++ per scene (the built-in environments' C++ tasks) or on whole arrays (the
environment's row hooks), with no per-scene Python loop.

Sub-environment i behaves exactly as the single environment (same class and arguments) reset
with seed `seed + i`: same start, same physics, bitwise the same trajectory. Autoreset follows
Gymnasium's NEXT_STEP mode: the step after an episode ended resets that sub-environment (its
action is ignored, its reward is 0) and returns its first observation.
"""

from __future__ import annotations

import numpy as np
import gymnasium as gym
from gymnasium.utils import seeding
from gymnasium.vector.utils import batch_space

import superdex.physics as sdp
from superdex.lab.env import SuperDexEnv
from superdex.lab.task import ensure_engine, make_batch, np_real


class SuperDexVectorEnv(gym.vector.VectorEnv):
    metadata = {"autoreset_mode": gym.vector.AutoresetMode.NEXT_STEP}

    def __init__(self, env_class: type[SuperDexEnv], num_envs: int, num_worker_threads: int = 0, **env_kwargs):
        if int(num_envs) != num_envs or num_envs < 1:
            raise sdp.Error(f"num_envs must be a positive integer, got {num_envs}")
        if env_kwargs.get("render_mode") not in (None,):
            raise sdp.Error("render_mode: the vector environment does not render; render a single environment instead")
        ensure_engine(num_worker_threads)
        self.env = env_class(**env_kwargs)  # the task's hooks and spaces; it never builds a scene of its own
        self.num_envs = int(num_envs)
        self.single_action_space = self.env.action_space
        self.single_observation_space = self.env.observation_space
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.metadata = {**self.metadata, "render_fps": self.env.metadata["render_fps"]}
        self.render_mode = None
        self._built = [self.env.build_scene(sdp.create_scene(f"{env_class.__name__}[{k}]")) for k in range(self.num_envs)]
        self._batch = make_batch(self.env.full_spec(), self._built)
        self._raw = np.zeros((self.num_envs, self._batch.obs_size), dtype=np_real)
        self._reward = np.zeros(self.num_envs)
        self._t = np.zeros(self.num_envs, dtype=np.int64)
        self._params = np.zeros((self.num_envs, self.env.params_size))
        self._needs_reset = np.zeros(self.num_envs, dtype=bool)
        self._action_shape = (self.num_envs, self.env.action_size)
        self._rngs = [seeding.np_random(None)[0] for _ in range(self.num_envs)]

    @property
    def scenes(self):
        return [b.scene for b in self._built]

    def _reset_rows(self, rows):
        q0 = np.zeros((len(rows), self.env.action_size))
        for i, k in enumerate(rows):  # draws from each sub-environment's own generator (cheap, at resets only)
            q0[i], self._params[k] = self.env.sample_episode(self._rngs[k])
        self._t[rows] = 0
        self._batch.reset([int(k) for k in rows], np.ascontiguousarray(q0), self._raw, self.env.batch_params(self._params[rows]))
        self._needs_reset[rows] = False

    def reset(self, *, seed=None, options=None):
        if seed is not None:
            seeds = [seed + k for k in range(self.num_envs)] if isinstance(seed, int) else list(seed)
            if len(seeds) != self.num_envs:
                raise sdp.Error(f"seed: expected an int or {self.num_envs} seeds, got {len(seeds)}")
            self._rngs = [seeding.np_random(s)[0] for s in seeds]
        self._reset_rows(np.arange(self.num_envs))
        return self.env.observation_rows(self._raw, self._t, self._params), {}

    def step(self, actions):
        a = np.asarray(actions, dtype=np.float64)
        if a.shape != self._action_shape:
            raise sdp.Error(f"step: actions must have shape {self._action_shape}, got {a.shape}")
        a = np.clip(a, -1.0, 1.0) * self.env.action_scale  # a new C-contiguous array
        self._batch.step(a, self._raw, self._reward)
        self._t += 1
        reward, terminated, obs = self.env.step_rows(self._raw, self._reward, self._t, self._params, a)
        truncated = self._t >= self.env.episode_steps
        if self._needs_reset.any():  # NEXT_STEP autoreset: these rows start a new episode instead
            restart = np.flatnonzero(self._needs_reset)
            self._reset_rows(restart)
            reward[restart], terminated[restart], truncated[restart] = 0.0, False, False
            obs[restart] = self.env.observation_rows(self._raw[restart], self._t[restart], self._params[restart])
        self._needs_reset = terminated | truncated
        return obs, np.asarray(reward, dtype=np.float64), terminated, truncated, {}

    def close_extras(self, **kwargs):
        self._batch = None
        if sdp.is_initialized():
            for b in self._built:
                sdp.destroy_scene(b.scene)
        self._built = []


def make_SeedTaskEnv_vector(num_envs: int = 1, **kwargs) -> SuperDexVectorEnv:
    """gymnasium.make_vec's vector entry point of superdex/SeedTask-v0."""
    from superdex.lab.seed_task import SeedTaskEnv

    return SuperDexVectorEnv(SeedTaskEnv, num_envs, **kwargs)


def make_PandaReachEnv_vector(num_envs: int = 1, **kwargs) -> SuperDexVectorEnv:
    """gymnasium.make_vec's vector entry point of superdex/PandaReach-v0."""
    from superdex.lab.panda_reach import PandaReachEnv

    return SuperDexVectorEnv(PandaReachEnv, num_envs, **kwargs)
