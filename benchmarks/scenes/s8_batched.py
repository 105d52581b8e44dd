"""Scene 8: the lab's batched vector environment (superdex.lab.SuperDexVectorEnv: one C++
SceneBatch stepped per call on the engine's worker threads, GIL released) with 64 scenes, on 1 and
2 worker threads (`initialize(num_worker_threads=1 or 2)`); throughput in scene-steps per second
(one scene-step: one control step of one scene, with its reward and observation) and its ratio.
SuperDex only.

Variants
- seed task, rigid box: the 2-DOF arm at 250 Hz with its velocity servos in C++, on the rigid box
  (SeedTaskEnv(prop="box")), one physics step per control step;
- Panda reach: the 7-DOF Panda with joint velocity drives, 50 Hz control, 5 physics steps each.
Actions: a fixed seeded random sequence; the first WARM_UP control steps are not timed. Checks: the observations after the run are the same with
1 and 2 threads (digest), and the process's CPU time over wall time (about 2 when both threads work).
"""

from __future__ import annotations

import hashlib
import time

import numpy as np

from benchmarks.harness import Timer

NUMBER = 8
TITLE = "Batched vector environment: 64 scenes, 1 and 2 worker threads"
TASKS = ("seed task, rigid box", "Panda reach")
WARM_UP = 10  # untimed control steps after the reset


def cases(opts):
    n = 4 if opts.quick else 64
    steps = 3 if opts.quick else {"seed task, rigid box": 2000, "Panda reach": 100}
    return [{"label": f"{task} / {threads}", "sim": "superdex", "task": task, "threads": threads, "n": n,
             "steps": steps if opts.quick else steps[task]} for task in TASKS for threads in (1, 2)]


def run_case(case):
    import superdex.physics as sdp
    from superdex.lab import PandaReachEnv, SeedTaskEnv, SuperDexVectorEnv

    sdp.initialize(num_worker_threads=case["threads"])
    if case["task"] == "Panda reach":
        vec = SuperDexVectorEnv(PandaReachEnv, case["n"], episode_steps=10**9)
    else:
        vec = SuperDexVectorEnv(SeedTaskEnv, case["n"], prop="box", episode_steps=10**9)
    steps = case["steps"]
    actions = np.random.default_rng(0).uniform(-1, 1, (WARM_UP + steps,) + vec.action_space.shape).astype(np.float32)
    vec.reset(seed=0)
    # untimed: the worker threads start, the first contacts form
    for t in range(WARM_UP):
        vec.step(actions[t])
    cpu = time.process_time()
    with Timer() as timer:
        for t in range(steps):
            obs, *_ = vec.step(actions[WARM_UP + t])
    cpu = time.process_time() - cpu
    digest = hashlib.sha256(np.ascontiguousarray(obs).tobytes()).hexdigest()[:12]
    sim_time = steps * vec.env.control_dt
    vec.close()
    sdp.shutdown()
    return {"wall": timer.wall, "steps": steps, "sim_time": sim_time, "scene_steps_per_s": case["n"] * steps / timer.wall,
            "cpu_over_wall": cpu / timer.wall, "checks": {"obs digest": digest}}
