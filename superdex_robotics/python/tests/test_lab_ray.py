"""superdex.lab.rollout on a local Ray instance: 2 rollout workers (each a batched vector env of the
seed task on the rigid box) collect 10,016 steps; each worker's trajectory equals, bitwise, the
same rollout run in this process; episode returns and their PNG plot."""

import numpy as np
import pytest

import superdex.physics as sdp
from superdex.lab import rollout  # before ray: it keeps Ray from re-running `uv run` in each worker

ray = pytest.importorskip("ray")

ENVS_PER_WORKER, STEPS, EPISODE = 16, 313, 100  # 2 x 16 x 313 = 10,016 steps


@pytest.fixture(scope="module")
def trajectories():
    rollout.init_ray(num_cpus=2)
    try:
        yield rollout.run_distributed("seed", 2, ENVS_PER_WORKER, STEPS, seed=40, env_kwargs={"prop": "box", "episode_steps": EPISODE},
                                      progress=False)
    finally:
        ray.shutdown()


def test_two_ray_workers_equal_single_process_runs(trajectories):
    assert len(trajectories) == 2
    assert sum(t["rewards"].size for t in trajectories) >= 10_000
    sdp.initialize(num_worker_threads=0)
    try:
        for w, remote in enumerate(trajectories):
            local = rollout.run_local("seed", ENVS_PER_WORKER, STEPS, env_seed=40 + w * ENVS_PER_WORKER, policy_seed=40 + w,
                                      env_kwargs={"prop": "box", "episode_steps": EPISODE}, progress=False)
            assert local.keys() == remote.keys()
            for key in local:
                assert local[key].shape == remote[key].shape, key
                assert np.array_equal(local[key], remote[key]), f"worker {w}: {key}"
    finally:
        sdp.shutdown()
    assert not np.array_equal(trajectories[0]["obs"], trajectories[1]["obs"]), "the workers ran different seeds"


def test_episode_returns_and_plot(trajectories, tmp_path):
    t = trajectories[0]
    returns = rollout.episode_returns(t)
    # episodes of 100 steps, each followed by one autoreset step: ends at steps 99, 200, 301
    assert len(returns) == 3 * ENVS_PER_WORKER
    assert returns[0] == pytest.approx(t["rewards"][:EPISODE, 0].sum(), rel=1e-12)
    assert returns[-1] == pytest.approx(t["rewards"][202:302, -1].sum(), rel=1e-12)
    assert (t["rewards"][EPISODE] == 0).all(), "the autoreset step has no reward"
    png = rollout.plot_returns(returns, tmp_path / "returns.png")
    import matplotlib.image

    image = matplotlib.image.imread(png)
    assert image.shape[:2] == (350, 600)
