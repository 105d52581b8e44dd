"""Scene 4: 50 boxes (10 cm cubes, 1 kg, friction 0.5) dropped in two staggered layers of 5 x 5
with small random tilts onto the ground, where they settle into a pile; 250 Hz.

The timed run covers `seconds` of simulated time. Then, untimed, the simulation goes on for
0.5 s and every box's speed (finite difference of its position over one step) is recorded: the
largest one is the jitter measure (the target: every box at rest within 1 mm/s). The pile's
mean and top heights are the equivalence check between simulators.
"""

from __future__ import annotations

import numpy as np

from benchmarks.harness import Timer
from benchmarks.models import build_pybullet, build_superdex, to_mjcf

NUMBER = 4
TITLE = "50 boxes falling into a pile (250 Hz)"
SIMS = ("superdex", "mujoco", "pybullet")
DT = 0.004
HALF = 0.05
WINDOW = 0.5  # s of untimed stepping in which the jitter is measured


def scene_description(n=50, side=5):
    """n boxes in layers of side x side; the pile's centre is at the origin."""
    rng = np.random.default_rng(0)
    bodies = []
    for k in range(n):
        layer, i = divmod(k, side * side)
        r, c = divmod(i, side)
        shift = 0.5 * layer * 0.12  # the upper layer straddles the lower one's gaps
        axis = rng.normal(size=3)
        angle = rng.uniform(0, 0.3)
        q = np.append(np.sin(angle / 2) * axis / np.linalg.norm(axis), np.cos(angle / 2))
        bodies.append({"name": f"box{k}", "shape": {"box": {"halfExtents": [HALF] * 3}}, "mass": 1.0, "friction": 0.5,
                       "position": [(c - (side - 1) / 2) * 0.12 + shift, (r - (side - 1) / 2) * 0.12 + shift, 0.1 + 0.15 * layer],
                       "rotation": q.tolist()})
    return {"name": "pile", "dt": DT, "gravity": [0, 0, -9.81], "ground": {"friction": 0.5}, "bodies": bodies,
            "articulations": []}


def cases(opts):
    seconds = 0.04 if opts.quick else 4.0
    n = 6 if opts.quick else 50
    return [{"label": sim, "sim": sim, "seconds": seconds, "n": n, "window": 0.02 if opts.quick else WINDOW} for sim in SIMS]


def make_sim(name, desc):
    """(step(), positions() -> n x 3) for one simulator."""
    names = [b["name"] for b in desc["bodies"]]
    if name == "superdex":
        import superdex.physics as sdp

        sdp.initialize(num_worker_threads=0)
        scene, actors = build_superdex(desc, sdp)
        boxes = [actors[n] for n in names]
        return (lambda: scene.step(DT),
                lambda: np.array([b.get_root_transform().translation for b in boxes], dtype=np.float64),
                sdp.shutdown)
    if name == "mujoco":
        import mujoco

        model = mujoco.MjModel.from_xml_string(to_mjcf(desc))
        data = mujoco.MjData(model)
        ids = [model.body(n).id for n in names]
        return (lambda: mujoco.mj_step(model, data), lambda: data.xpos[ids].copy(), lambda: None)
    import pybullet as p

    c = p.connect(p.DIRECT)
    ids = build_pybullet(desc, p, c)
    bodies = [ids[n] for n in names]
    return (lambda: p.stepSimulation(physicsClientId=c),
            lambda: np.array([p.getBasePositionAndOrientation(b, physicsClientId=c)[0] for b in bodies]),
            lambda: p.disconnect(c))


def run_case(case):
    desc = scene_description(case["n"])
    step, positions, close = make_sim(case["sim"], desc)
    steps = int(round(case["seconds"] / DT))
    with Timer() as timer:
        for _ in range(steps):
            step()
    # untimed: the speeds of the settled pile
    x = positions()
    max_speed = 0.0
    for _ in range(int(round(case["window"] / DT))):
        step()
        x_next = positions()
        max_speed = max(max_speed, float(np.max(np.linalg.norm(x_next - x, axis=1))) / DT)
        x = x_next
    z = x[:, 2]
    close()
    return {"wall": timer.wall, "steps": steps, "sim_time": steps * DT,
            "checks": {"max_speed_mm_s": 1e3 * max_speed, "mean_z": float(np.mean(z)), "top_z": float(np.max(z)),
                       "lowest_z": float(np.min(z))}}
