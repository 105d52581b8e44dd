"""Scene 10: the examples of the physics features users start from, run as users run them.

Each example module (superdex_physics/examples/) is imported and its run() called with its own
defaults, as `python <example>.py` does (engine initialized and shut down, the scene built, every
step with its Python-side work and its printed report, no debugger). The time is the whole call,
building included: what a user waits for. SuperDex only (the peers have no such examples).

- constraints_double_pendulum: two boxes hung by pivot and ball-joint constraints from a moving
  anchor, 10 s at 4 ms;
- articulations_pose_controller: the pose controller's hybrid, joint and link phases on an arm
  hanging from a cart, 9 s at 5 ms;
- double_pendulum_on_rail: the jointed double pendulum on its rail, 5 s at 1 ms;
- inverse_kinematics: the IK solver's eight targets on the five-link mixed-joint arm (no
  simulated time: reported per solve);
- skinned_double_pendulum: a double pendulum whose skin (328 skinned nodes) strikes a ball,
  4 s at 5 ms;
- soft_skinned_double_pendulum: a double pendulum carrying a soft finite-element bar tied to its
  tip, 4 s at 5 ms.
"""

from __future__ import annotations

import contextlib
import importlib.util
import inspect
import io

from benchmarks.harness import REPO, Timer, median_of_episodes

NUMBER = 10
TITLE = "Feature examples as users run them (constraints, pose control, IK, skins)"
# name: (run() keyword arguments for the full run, for --quick, the simulated seconds key or None)
EXAMPLES = {
    "constraints_double_pendulum": ({}, {"seconds": 0.1}),
    "articulations_pose_controller": ({}, {"seconds": 0.1}),
    "double_pendulum_on_rail": ({}, {"seconds": 0.05}),
    "inverse_kinematics": ({}, {"num_targets": 2}),
    "skinned_double_pendulum": ({}, {"seconds": 0.1}),
    "soft_skinned_double_pendulum": ({}, {"seconds": 0.1}),
}


def cases(opts):
    return [{"label": name, "example": name, "kwargs": EXAMPLES[name][1 if opts.quick else 0], "episodes": 1 if opts.quick else 3}
            for name in EXAMPLES]


def load(name: str):
    spec = importlib.util.spec_from_file_location(f"example_{name}", REPO / "superdex_physics" / "examples" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def run_case(case):
    return median_of_episodes(case, run_episode)


def run_episode(case):
    example = load(case["example"])
    # the printed report is part of the run; it goes to a buffer, not the parent's pipe
    with contextlib.redirect_stdout(io.StringIO()), Timer() as timer:
        result = example.run(**case["kwargs"])
    if case["example"] == "inverse_kinematics":
        solves = len(result)
        return timer.wall, {"solves": solves, "ms_per_solve": 1e3 * timer.wall / solves,
                            "checks": {"reached": sum(r["reached"] for r in result)}}
    defaults = inspect.signature(example.run).parameters
    seconds = case["kwargs"].get("seconds", defaults["seconds"].default)
    dt = case["kwargs"].get("dt", defaults["dt"].default)
    steps = int(round(seconds / dt))
    return timer.wall, {"steps": steps, "sim_time": steps * dt, "checks": {}}
