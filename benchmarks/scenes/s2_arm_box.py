"""Scene 2: the seed's 2-DOF arm pressing on a rigid box (instead of the soft duck), in SuperDex,
MuJoCo and PyBullet, from one description (scenes/arm.py), at the seed's 250 Hz.

Variants
- control: the seed's law (circle tracking, force control on contact, PI servos) in Python every
  step, reading and writing each simulator through its Python API (the same per-step work). The
  law's calls are timed apart inside the loop (perf_counter around them): the rest of the step,
  the simulator's part (its API calls and its step), is what the simulators are compared on.
- physics: no control, the joints' efforts held at zero: the arm folds under gravity onto the
  box; only the simulator's step is timed (PyBullet still needs its torques given every step).
- law alone: the control variant's Python law (controller and servos) with no simulator, on
  fixed inputs near the circle: the part of a control step that is the same in every simulator.
"""

from __future__ import annotations

import time

import numpy as np

from benchmarks.harness import Timer, median_of_episodes
from benchmarks.scenes import arm

NUMBER = 2
TITLE = "2-DOF arm on a rigid box (250 Hz)"
SIMS = ("superdex", "mujoco", "pybullet")


def cases(opts):
    seconds = 0.1 if opts.quick else 6.0
    # the physics variant's loop lasts some 15 ms: the median of several episodes in the process
    episodes = 1 if opts.quick else 9
    return [{"label": f"{variant} / {sim}", "sim": sim, "variant": variant, "seconds": seconds, "episodes": episodes}
            for variant in ("control", "physics") for sim in SIMS] + \
        [{"label": "law alone", "sim": "none", "variant": "law alone", "seconds": seconds, "episodes": episodes}]


def run_case(case):
    return median_of_episodes(case, run_episode)


def run_law(case):
    """The control law alone, on inputs near the circle (a fixed Jacobian and joint velocities,
    the end effector 1 mm from its target, no contact force)."""
    controller = arm.Controller()
    servos = [arm.Servo(**params) for params in arm.arm_description()["servos"]]
    J = np.array([[0.12, 0.05], [0.0, 0.0], [-0.18, -0.09]])
    qd = np.array([0.1, -0.2])
    steps = int(round(case["seconds"] / arm.DT))
    with Timer() as timer:
        for k in range(steps):
            x = arm.trajectory_target(k * arm.DT)[0] - 0.001
            q_dot_des = controller.compute(x, J, 0.0, k * arm.DT)
            [s.effort(w, qd[i], arm.DT) for i, (s, w) in enumerate(zip(servos, q_dot_des))]
    return timer.wall, {"steps": steps, "sim_time": steps * arm.DT, "checks": {}}


def run_episode(case):
    """One episode on a freshly built simulation: (wall of its stepping loop, result)."""
    if case["sim"] == "none":
        return run_law(case)
    desc = arm.scene_description(with_box=True)
    sim = arm.ADAPTERS[case["sim"]](desc)
    steps = int(round(case["seconds"] / arm.DT))
    control = case["variant"] == "control"
    controller = arm.Controller()
    servos = [arm.Servo(**params) for params in arm.arm_description()["servos"]]
    f = np.zeros(3)
    fz_tail = []
    law = 0.0  # s in the law's calls
    clock = time.perf_counter
    with Timer() as timer:
        for k in range(steps):
            if control:
                x, J, qd = sim.observe()
                t0 = clock()
                q_dot_des = controller.compute(x, J, f[2], k * arm.DT)
                efforts = [s.effort(w, qd[i], arm.DT) for i, (s, w) in enumerate(zip(servos, q_dot_des))]
                law += clock() - t0
                sim.apply(efforts)
                sim.step()
                f = sim.contact_force()
                if k >= steps - int(1.0 / arm.DT):
                    fz_tail.append(f[2])
            else:
                sim.step()
    x, _, _ = sim.observe()
    checks = {"ball_x": float(x[0]), "ball_z": float(x[2]), "box_dx_mm": 1e3 * float(sim.box_position()[0] + 0.3)}
    if control:
        checks["fz_last_1s_N"] = float(np.mean(fz_tail)) if fz_tail else 0.0
        checks["force_mode_frac"] = controller.force_steps / steps
    result = {"steps": steps, "sim_time": steps * arm.DT, "checks": checks}
    if control:
        result.update(law_wall=law, simulator_wall=timer.wall - law)
    sim.close()
    return timer.wall, result
