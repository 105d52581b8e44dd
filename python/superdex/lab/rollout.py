"""Distributed rollouts with Ray: rollout workers, each a batched SuperDexVectorEnv, spread over a
Ray cluster; the driver gathers their trajectories, shows progress bars (tqdm) and saves a plot of
episode returns (PNG, matplotlib's Agg backend).

    uv run python -m superdex.lab.rollout --env seed --prop box --workers 2 --envs-per-worker 16 \\
        --steps 2000 --seed 0 --out build/lab_rollout

starts a local Ray instance (or joins a running cluster with `--address auto` / `--address
HOST:PORT`), runs the workers and writes `returns.png` and `trajectories.npz` to --out. The policy
is a seeded uniform random policy (the point is the machinery: swap in your own in `Rollout.act`).

Worker w resets its sub-environments with seeds `seed + w * envs_per_worker + i` and draws its
actions from `seed + w`, so a rollout is reproducible: `Rollout` run in this process with the same
arguments gives bitwise the same trajectory as the Ray worker (tested).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import numpy as np
from tqdm import tqdm

# Ray workers run this interpreter and environment as they are. Without this, a driver started by
# `uv run` makes Ray package the working directory and `uv run` (rebuild) it for every worker.
# Ray reads it when it is first imported: import this module before ray.
os.environ.setdefault("RAY_ENABLE_UV_RUN_RUNTIME_ENV", "0")


class Rollout:
    """One rollout worker: a SuperDexVectorEnv stepped by a seeded random policy. Ray runs it as an
    actor (`ray.remote(Rollout)`); it works the same in-process."""

    def __init__(self, env: str, num_envs: int, num_worker_threads: int = 0, env_kwargs: dict | None = None):
        from superdex.lab import ENVIRONMENTS, SuperDexVectorEnv

        if env not in ENVIRONMENTS:
            raise ValueError(f"env must be one of {sorted(ENVIRONMENTS)}, got {env!r}")
        self.vec = SuperDexVectorEnv(ENVIRONMENTS[env], num_envs, num_worker_threads=num_worker_threads, **(env_kwargs or {}))
        self.obs = None
        self.rng = None

    def start(self, env_seed: int, policy_seed: int) -> None:
        self.obs, _ = self.vec.reset(seed=env_seed)
        self.rng = np.random.default_rng(policy_seed)

    def act(self, obs: np.ndarray) -> np.ndarray:
        return self.rng.uniform(-1.0, 1.0, size=self.vec.action_space.shape)

    def advance(self, steps: int) -> dict:
        """Steps every sub-environment `steps` times; returns arrays over (steps, num_envs, ...)."""
        out = {"obs": [], "actions": [], "rewards": [], "terminated": [], "truncated": []}
        for _ in range(steps):
            actions = self.act(self.obs)
            out["obs"].append(self.obs)
            out["actions"].append(actions)
            self.obs, reward, terminated, truncated, _ = self.vec.step(actions)
            out["rewards"].append(reward)
            out["terminated"].append(terminated)
            out["truncated"].append(truncated)
        return {k: np.asarray(v) for k, v in out.items()}


def concatenate(chunks: list[dict]) -> dict:
    return {k: np.concatenate([c[k] for c in chunks]) for k in chunks[0]}


def episode_returns(trajectory: dict) -> np.ndarray:
    """Returns of the episodes that ended within a trajectory (NEXT_STEP autoreset: the step after
    an end belongs to no episode), in order of their ends."""
    rewards, done = trajectory["rewards"], trajectory["terminated"] | trajectory["truncated"]
    running = np.zeros(rewards.shape[1])
    after_end = np.zeros(rewards.shape[1], dtype=bool)
    returns = []
    for t in range(len(rewards)):
        running = np.where(after_end, 0.0, running + rewards[t])
        returns.extend(running[done[t]].tolist())
        after_end = done[t]
    return np.asarray(returns)


def plot_returns(returns: np.ndarray, path, title: str = "episode returns") -> Path:
    """Saves the returns (in order of episode ends) as a PNG, headless."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6, 3.5), dpi=100)
    ax = fig.add_subplot()
    ax.plot(np.arange(1, len(returns) + 1), returns, ".", ms=4)
    if len(returns) >= 20:
        k = len(returns) // 10
        ax.plot(np.arange(k, len(returns) + 1), np.convolve(returns, np.ones(k) / k, mode="valid"), "-", label=f"mean of {k}")
        ax.legend()
    ax.set_xlabel("episode")
    ax.set_ylabel("return")
    ax.set_title(title)
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    return path


def run_local(env, num_envs, steps, env_seed, policy_seed, num_worker_threads=0, env_kwargs=None, chunk=100, progress=True) -> dict:
    """One worker's rollout in this process, with a progress bar."""
    worker = Rollout(env, num_envs, num_worker_threads, env_kwargs)
    worker.start(env_seed, policy_seed)
    chunks = []
    with tqdm(total=steps * num_envs, unit="step", disable=not progress, desc=f"{env} x{num_envs}") as bar:
        for n in _chunk_sizes(steps, chunk):
            chunks.append(worker.advance(n))
            bar.update(n * num_envs)
    return concatenate(chunks)


def run_distributed(env, num_workers, envs_per_worker, steps, seed=0, num_worker_threads=0, env_kwargs=None, chunk=100,
                    progress=True) -> list[dict]:
    """Rollouts of `num_workers` Ray actors (each a batched vector env of `envs_per_worker` scenes,
    `steps` steps); ray must be initialized. Returns each worker's trajectory."""
    import ray

    actor = ray.remote(num_cpus=max(1, num_worker_threads))(Rollout)
    workers = [actor.remote(env, envs_per_worker, num_worker_threads, env_kwargs) for _ in range(num_workers)]
    ray.get([w.start.remote(seed + i * envs_per_worker, seed + i) for i, w in enumerate(workers)])
    sizes = _chunk_sizes(steps, chunk)
    chunks = [[] for _ in workers]
    pending = {w.advance.remote(sizes[0]): (i, 0) for i, w in enumerate(workers)}
    with tqdm(total=steps * envs_per_worker * num_workers, unit="step", disable=not progress, desc=f"{env} {num_workers} workers") as bar:
        while pending:
            done, _ = ray.wait(list(pending), num_returns=1)
            i, k = pending.pop(done[0])
            chunks[i].append(ray.get(done[0]))
            bar.update(sizes[k] * envs_per_worker)
            if k + 1 < len(sizes):
                pending[workers[i].advance.remote(sizes[k + 1])] = (i, k + 1)
    for w in workers:
        ray.kill(w)
    return [concatenate(c) for c in chunks]


def _chunk_sizes(steps, chunk):
    return [min(chunk, steps - s) for s in range(0, steps, chunk)]


def init_ray(address=None, num_cpus=None):
    """Starts (or joins, with an address) Ray."""
    import ray

    if address:
        ray.init(address=address, include_dashboard=False)
    else:
        ray.init(num_cpus=num_cpus, include_dashboard=False)
    return ray


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m superdex.lab.rollout", description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--env", choices=["seed", "panda"], default="seed")
    parser.add_argument("--prop", choices=["duck", "box"], default="box", help="seed task: soft duck or rigid box")
    parser.add_argument("--workers", type=int, default=2, help="Ray rollout workers")
    parser.add_argument("--envs-per-worker", type=int, default=16, help="scenes in each worker's batch")
    parser.add_argument("--threads", type=int, default=0, help="engine worker threads per rollout worker (0: one)")
    parser.add_argument("--steps", type=int, default=1000, help="vector steps per worker")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--address", default=None, help="a running Ray cluster ('auto' or HOST:PORT); default: start a local one")
    parser.add_argument("--num-cpus", type=int, default=None, help="CPUs of the local Ray instance")
    parser.add_argument("--out", default="build/lab_rollout", help="folder for returns.png and trajectories.npz")
    args = parser.parse_args(argv)
    env_kwargs = {"prop": args.prop} if args.env == "seed" else {}
    ray = init_ray(args.address, args.num_cpus)
    try:
        trajectories = run_distributed(args.env, args.workers, args.envs_per_worker, args.steps, args.seed, args.threads, env_kwargs)
    finally:
        ray.shutdown()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(out / "trajectories.npz", **{f"w{i}_{k}": v for i, t in enumerate(trajectories) for k, v in t.items()})
    returns = np.concatenate([episode_returns(t) for t in trajectories])
    png = plot_returns(returns, out / "returns.png", f"{args.env}: {len(returns)} episodes, {args.workers} workers")
    steps = sum(t["rewards"].size for t in trajectories)
    print(f"{steps} steps, {len(returns)} episodes (mean return {returns.mean() if len(returns) else float('nan'):.3f}); wrote {png}")


if __name__ == "__main__":
    main()
