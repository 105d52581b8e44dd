"""Scene 7: N independent piles of 18 boxes (scene 4's generator: 3 x 3, two layers), 250 Hz,
stepped with 1 and with 2 threads; throughput (pile-steps per second) and its ratio. SuperDex only.
Each run first steps WARM_UP steps untimed (the worker threads start, the first contacts form),
then times 1 s of simulated time: the boxes landing, then resting in their piles.

Variants
- worker threads: the N piles, 3 m apart, in ONE scene (N islands), `initialize(num_worker_threads=
  1 or 2)`: the engine's own parallelism (islands solved in parallel).
- Python threads: N separate scenes, engine single-threaded (`num_worker_threads=0`), stepped by
  1 or 2 Python threads (scene.step releases the GIL), each thread stepping its share of scenes.
"""

from __future__ import annotations

import threading

from benchmarks.harness import Timer
from benchmarks.models import build_superdex
from benchmarks.scenes import s4_pile

NUMBER = 7
TITLE = "Threads: N independent scenes, 1 and 2 threads"
DT = 0.004
BOXES, SIDE = 18, 3
WARM_UP = 10  # untimed steps before the timed ones


def cases(opts):
    n = 2 if opts.quick else 8
    steps = 3 if opts.quick else 250
    return [{"label": f"{variant} / {threads}", "sim": "superdex", "variant": variant, "threads": threads, "n": n,
             "steps": steps} for variant in ("worker threads", "Python threads") for threads in (1, 2)]


def run_case(case):
    import superdex.physics as sdp

    desc = s4_pile.scene_description(BOXES, SIDE)
    n, steps, threads = case["n"], case["steps"], case["threads"]
    if case["variant"] == "worker threads":
        sdp.initialize(num_worker_threads=threads)
        scene = None
        for k in range(n):
            # the first copy brings the (infinite) ground; the others are offset along x
            scene, _ = build_superdex(desc, sdp, scene=scene, offset=(3.0 * k, 0.0, 0.0))
        for _ in range(WARM_UP):
            scene.step(DT)
        with Timer() as timer:
            for _ in range(steps):
                scene.step(DT)
        islands = scene.get_solver_stats().num_islands
    else:
        sdp.initialize(num_worker_threads=0)
        scenes = [build_superdex(desc, sdp, name=f"pile{k}")[0] for k in range(n)]
        for s in scenes:
            for _ in range(WARM_UP):
                s.step(DT)

        def work(mine):
            for _ in range(steps):
                for s in mine:
                    s.step(DT)

        shares = [scenes[t::threads] for t in range(threads)]
        pool = [threading.Thread(target=work, args=(share,)) for share in shares]
        with Timer() as timer:
            for t in pool:
                t.start()
            for t in pool:
                t.join()
        islands = sum(s.get_solver_stats().num_islands for s in scenes)
    sdp.shutdown()
    return {"wall": timer.wall, "steps": steps, "sim_time": steps * DT, "scene_steps_per_s": n * steps / timer.wall,
            "checks": {"islands": islands}}
