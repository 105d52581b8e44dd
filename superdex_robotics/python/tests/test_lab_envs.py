"""superdex.lab: the Gymnasium environments (Env contract, bitwise repeatable seeds), the batched
vector environment against the single environment, and the C++ batch's servo and drive against
independent Python references."""

import math

import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import superdex.physics as sdp
import superdex.robotics as sdr
from superdex.lab import PandaReachEnv, SeedTaskEnv, SuperDexVectorEnv
from superdex.lab.seed_task import load_prefab

np_real = np.float64 if sdp.uses_double_precision() else np.float32


@pytest.fixture
def engine():
    sdp.initialize(num_worker_threads=0)
    yield
    sdp.shutdown()


@pytest.fixture
def engine2():
    sdp.initialize(num_worker_threads=2)
    yield
    sdp.shutdown()


def rollout(env, seed, steps, action_seed):
    """(observations, rewards) of `steps` steps from reset(seed) under seeded random actions."""
    obs, _ = env.reset(seed=seed)
    rng = np.random.default_rng(action_seed)
    out, rewards = [obs], []
    for _ in range(steps):
        obs, r, terminated, truncated, _ = env.step(rng.uniform(-1, 1, env.action_space.shape).astype(np.float32))
        out.append(obs)
        rewards.append(r)
    return np.array(out), np.array(rewards)


ENVS = {
    "seed_box": (lambda **kw: SeedTaskEnv(prop="box", **kw), 40),
    "panda": (lambda **kw: PandaReachEnv(**kw), 40),
    "seed_duck": (lambda **kw: SeedTaskEnv(prop="duck", **kw), 3),  # ~40 ms per step
}


class PythonSeedTask(SeedTaskEnv):
    """The seed task with its target point, observation and reward written here in numpy from the
    task's definition (seed_task.py's docstring) instead of the batch's C++ task: the reference
    for the C++ task, and a task that runs through the Python hooks."""

    def batch_spec(self):
        spec = super().batch_spec()
        spec.task = sdr.BatchTask()  # no C++ task
        return spec

    def target(self, t, params):
        theta = 2 * math.pi / 3.0 * np.asarray(t) / 250.0 + params[:, 0]
        return np.stack([-0.3 + 0.08 * np.cos(theta), np.zeros_like(theta), 0.15 + 0.08 * np.sin(theta)], axis=1)

    def task_observation(self, raw, t, params):
        return np.concatenate([raw, self.target(t, params).astype(np_real)], axis=1)

    def task_reward(self, raw, t, params, actions):
        x = self.target(t, params)
        p, f = raw[:, 4:7].astype(np.float64), raw[:, 7:10].astype(np.float64)
        tracking = np.hypot(p[:, 0] - x[:, 0], p[:, 2] - x[:, 2]) / 0.08
        force = np.where(np.any(f != 0, axis=1), np.abs(f[:, 2] - 0.5) / 0.5, 0.0)
        return -tracking - self.force_weight * force, np.zeros(len(raw), dtype=bool)


def test_cxx_tasks_match_their_python_definitions(engine):
    """The built-in environments' C++ tasks against numpy written from their definitions: the seed
    task against the same environment run through the Python hooks (the ball pressing on the box
    for part of the run), the Panda's reward from its observations."""
    assert not PythonSeedTask(prop="box").task_in_cxx and SeedTaskEnv(prop="box").task_in_cxx
    actions = np.tile(np.array([[-1.0, 1.0]], dtype=np.float32), (150, 1))  # fold down onto the box
    actions[100:] = [0.6, -0.4]
    runs = []
    for cls in (SeedTaskEnv, PythonSeedTask):
        env = cls(prop="box", episode_steps=1000)
        obs, _ = env.reset(seed=5)
        out, rewards = [obs], []
        for a in actions:
            obs, r, *_ = env.step(a)
            out.append(obs), rewards.append(r)
        runs.append((np.array(out), np.array(rewards)))
        env.close()
    (obs_c, rew_c), (obs_py, rew_py) = runs
    touching = np.any(obs_c[1:, 7:10] != 0, axis=1)
    assert 10 < touching.sum() < len(touching), "the run has steps with and without contact"
    assert np.array_equal(obs_c[:, :10], obs_py[:, :10]), "the same physics"
    np.testing.assert_allclose(obs_c[:, 10:], obs_py[:, 10:], atol=1e-6)
    np.testing.assert_allclose(rew_c, rew_py, rtol=1e-6, atol=1e-6)

    env = PandaReachEnv()
    obs, _ = env.reset(seed=2)
    goal = env._params[0].copy()
    rng = np.random.default_rng(0)
    for _ in range(20):
        obs, r, *_ = env.step(rng.uniform(-1, 1, 7).astype(np.float32))
        o = obs.astype(np.float64)
        np.testing.assert_allclose(o[20:23], goal, rtol=1e-6)
        assert r == pytest.approx(-np.linalg.norm(o[14:17] - goal) - 0.01 * np.linalg.norm(o[17:20]), rel=1e-6, abs=1e-7)
    env.close()


@pytest.mark.parametrize("name", ["seed_box", "panda", "seed_duck"])
def test_check_env_passes(engine, name):
    make, _ = ENVS[name]
    env = make(episode_steps=5)
    check_env(env, skip_render_check=True)
    env.close()


@pytest.mark.parametrize("name", ["seed_box", "panda", "seed_duck"])
def test_same_seed_gives_bitwise_the_same_trajectory(engine, name):
    make, steps = ENVS[name]
    env = make()
    obs_a, rew_a = rollout(env, seed=11, steps=steps, action_seed=5)
    obs_other, _ = rollout(env, seed=12, steps=steps, action_seed=5)  # the scene moved on in between
    obs_b, rew_b = rollout(env, seed=11, steps=steps, action_seed=5)
    assert obs_a.dtype == np_real
    assert np.array_equal(obs_a, obs_b) and np.array_equal(rew_a, rew_b)
    assert not np.array_equal(obs_a, obs_other), "another seed starts elsewhere"
    assert np.abs(obs_a[-1] - obs_a[0]).max() > 1e-3, "the robot moved"
    env.close()


def test_rgb_array_render_shows_the_arm(engine):
    env = SeedTaskEnv(prop="box", render_mode="rgb_array")
    env.reset(seed=0)
    image = env.render()
    assert image.shape == (240, 320, 3) and image.dtype == np.uint8
    blue = (image[:, :, 2] > 150) & (image[:, :, 0] < 100)
    assert blue.sum() > 50, "the arm's links are drawn"
    env.close()


def test_vector_env_rows_equal_single_envs_across_autoreset(engine2):
    """Sub-environment i of the batch (stepped on 2 worker threads) is the single environment
    reset with seed + i, bitwise, through an autoreset (episodes of 6 steps, 15 steps)."""
    n, steps, episode = 4, 15, 6
    vec = SuperDexVectorEnv(SeedTaskEnv, n, prop="box", episode_steps=episode)
    rng = np.random.default_rng(3)
    actions = rng.uniform(-1, 1, (steps, n, 2)).astype(np.float32)
    obs, _ = vec.reset(seed=100)
    vec_obs, vec_rew, vec_done = [obs], [], []
    for t in range(steps):
        obs, r, term, trunc, _ = vec.step(actions[t])
        vec_obs.append(obs), vec_rew.append(r), vec_done.append(trunc)
    vec_obs, vec_rew, vec_done = np.array(vec_obs), np.array(vec_rew), np.array(vec_done)
    assert vec_done[episode - 1].all() and not vec_done[episode].any() and vec_done[2 * episode].all()
    for i in range(n):
        env = SeedTaskEnv(prop="box", episode_steps=episode)
        obs, _ = env.reset(seed=100 + i)
        single_obs, single_rew = [obs], []
        done = False
        for t in range(steps):
            if done:  # NEXT_STEP autoreset: this step only resets
                obs, _ = env.reset()
                r, done = 0.0, False
            else:
                obs, r, term, trunc, _ = env.step(actions[t, i].astype(np.float32))
                done = term or trunc
            single_obs.append(obs), single_rew.append(r)
        diff = np.argwhere(np.array(single_obs) != vec_obs[:, i])
        assert len(diff) == 0, f"row {i}: {diff[:5]}"
        assert np.array_equal(np.array(single_rew), vec_rew[:, i]), f"row {i}"
        env.close()
    vec.close()


def test_batch_servo_is_the_seed_servo(engine):
    """The batch's VELOCITY_SERVO path gives bitwise the trajectory of the seed's loop: its Python
    PI servo (written here again, from the seed example) applied with set_external_forces_on_dofs."""
    prefab, servos = load_prefab()

    def build():
        env = SeedTaskEnv(prop="box")
        return env, env.build_scene(sdp.create_scene("s"))

    env, built = build()
    spec = env.full_spec()
    batch = sdr.SceneBatch(spec, [built.scene], [built.articulation], [built.contact_actor])
    _, ref = build()
    arm = ref.articulation
    state = [{"integral": 0.0, "w_traj": 0.0} for _ in servos]

    def servo(k, goal, present, dt):
        p, s = servos[k], state[k]
        max_step = p["profile_accel"] * dt
        s["w_traj"] = s["w_traj"] + float(np.clip(goal - s["w_traj"], -max_step, max_step))
        e = s["w_traj"] - present
        integral_next = s["integral"] + e * dt
        unsat = p["k_p"] * e + p["k_i"] * integral_next
        effort = float(np.clip(unsat, -p["effort_limit"], p["effort_limit"]))
        if effort == unsat or e * unsat < 0:
            s["integral"] = integral_next
        return effort

    raw = np.zeros((1, batch.obs_size), dtype=np_real)
    batch.reset([0], None, raw)
    dt = spec.dt
    for t in range(60):
        goals = np.array([1.5 * math.sin(0.1 * t), -1.0 * math.cos(0.07 * t)])
        batch.step(goals.reshape(1, 2), raw)
        v = np.zeros(2, dtype=np_real)
        arm.get_articulated_joint_velocities(out_velocities=v)
        efforts = np.array([servo(k, goals[k], float(v[k]), dt) for k in range(2)], dtype=np_real)
        arm.set_external_forces_on_dofs(dof_indices=[0, 1], force_values=efforts)
        ref.scene.step(dt)
        q = np.asarray(arm.get_articulated_pose(), dtype=np_real)
        arm.get_articulated_joint_velocities(out_velocities=v)
        assert np.array_equal(raw[0, :2], q) and np.array_equal(raw[0, 2:4], v), f"step {t}"
    assert abs(raw[0, 0] - prefab.default_pose[0]) > 0.02, "the servos moved the arm"


def test_batch_velocity_drive_tracks_the_command(engine):
    """Panda joint 1 (vertical axis) commanded at 0.3 rad/s: after 0.5 s its velocity is the
    command and its angle grew by about command * time."""
    env = PandaReachEnv()
    obs, _ = env.reset(seed=0)
    q_start = float(obs[0])
    action = np.zeros(7, dtype=np.float32)
    action[0] = 0.3 / env.max_joint_speed
    for _ in range(25):
        obs, *_ = env.step(action)
    assert obs[7] == pytest.approx(0.3, abs=0.01)
    assert float(obs[0]) - q_start == pytest.approx(0.3 * 0.5, abs=0.02)
    env.close()


def test_bad_input_raises_error_naming_the_argument(engine):
    env = SeedTaskEnv(prop="box")
    built = env.build_scene(sdp.create_scene("s"))
    spec = env.full_spec()
    spec.action_dofs = [0, 5]
    with pytest.raises(sdp.Error, match=r"spec.action_dofs\[1\] = 5 is out of range"):
        sdr.SceneBatch(spec, [built.scene], [built.articulation], [built.contact_actor])
    spec = env.full_spec()
    spec.servo_k_i = [1.0]
    with pytest.raises(sdp.Error, match=r"spec.servo_k_i has 1 entries"):
        sdr.SceneBatch(spec, [built.scene], [built.articulation], [built.contact_actor])
    batch = sdr.SceneBatch(env.full_spec(), [built.scene], [built.articulation], [built.contact_actor])
    raw = np.zeros((1, batch.obs_size), dtype=np_real)
    with pytest.raises(sdp.Error, match=r"SceneBatch.step: actions: expected .*float64 and shape \(1, 2\), got shape \(1, 3\)"):
        batch.step(np.zeros((1, 3)), raw)
    with pytest.raises(sdp.Error, match=r"SceneBatch.step: obs_out: .*got a read-only array"):
        out = np.zeros((1, batch.obs_size), dtype=np_real)
        out.flags.writeable = False
        batch.step(np.zeros((1, 2)), out)
    with pytest.raises(sdp.Error, match=r"SceneBatch.step: reward_out: expected .*float64 and shape \(1,\), got shape \(2,\)"):
        batch.step(np.zeros((1, 2)), raw, np.zeros(2))
    with pytest.raises(sdp.Error, match=r"SceneBatch.reset: params: expected .*shape \(1, 1\), got shape \(1, 3\)"):
        batch.reset([0], None, raw, np.zeros((1, 3)))
    with pytest.raises(sdp.Error, match=r"spec.task.radius must be a positive length"):
        spec = env.full_spec()
        spec.task.radius = -0.1
        sdr.SceneBatch(spec, [built.scene], [built.articulation], [built.contact_actor])
    with pytest.raises(sdp.Error, match="prop must be"):
        SeedTaskEnv(prop="sponge")
    with pytest.raises(sdp.Error, match="step: action must have shape"):
        env.reset(seed=0)
        env.step(np.zeros(3))
    env.close()


def test_human_render_mode_attaches_the_debugger(engine, tmp_path, monkeypatch):
    """render_mode="human" attaches the scene debugger; headless, SUPERDEX_DEBUGGER_RECORD makes
    it record, and the recording holds the environment's scene and its stepped frames."""
    path = tmp_path / "lab.jsonl"
    monkeypatch.setenv("SUPERDEX_DEBUGGER_RECORD", str(path))
    monkeypatch.setenv("SUPERDEX_DEBUGGER_FRAME_INTERVAL", "0")
    env = SeedTaskEnv(prop="box", render_mode="human")
    env.reset(seed=0)
    for _ in range(5):
        env.step(np.ones(2, dtype=np.float32))
    assert sdp.debugger.is_attached()
    sdp.debugger.detach()
    text = path.read_text()
    assert "SeedTaskEnv" in text and text.count('"frame"') >= 5
    env.close()


def test_registered_with_gymnasium(engine):
    import gymnasium as gym

    env = gym.make("superdex/SeedTask-v0", prop="box")
    assert isinstance(env.unwrapped, SeedTaskEnv) and env.reset(seed=0)[0].shape == (13,)
    vec = gym.make_vec("superdex/PandaReach-v0", num_envs=3, vectorization_mode="vector_entry_point")
    assert isinstance(vec, SuperDexVectorEnv) and vec.reset(seed=0)[0].shape == (3, 23)
    env.close()
    vec.close()


def test_batch_step_releases_the_gil(engine):
    """Another Python thread runs while one SceneBatch.step call is inside C++ (with the GIL held
    it could not run at all during the call: a C call is never preempted by the interpreter)."""
    import threading
    import time

    vec = SuperDexVectorEnv(SeedTaskEnv, 16, prop="box", sim_multiple=500)  # one call: 8000 physics steps (50 ms or more)
    vec.reset(seed=0)
    actions = np.ascontiguousarray(np.full((16, 2), 0.5))
    ticks, span, stop = [], [], threading.Event()

    def ticker():
        while not stop.is_set():
            ticks.append(time.perf_counter())

    def stepper():
        start = time.perf_counter()
        vec._batch.step(actions, vec._raw)
        span.extend([start, time.perf_counter()])

    t = threading.Thread(target=ticker)
    t.start()
    s = threading.Thread(target=stepper)
    s.start()
    s.join()
    stop.set()
    t.join()
    start, end = span
    middle = [x for x in ticks if start + 0.3 * (end - start) < x < end - 0.3 * (end - start)]
    assert end - start > 0.02 and len(middle) > 100, (end - start, len(middle))
    vec.close()
