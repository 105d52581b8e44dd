"""Soak test (not run by CI): the seed scene for a long stretch of simulated time, reporting memory
and step-time drift.

    uv run python tools/soak.py                      # one hour of simulated time (about 15 h of wall time at ~60 ms/step)
    uv run python tools/soak.py --seconds 60         # a shorter run
    uv run python tools/soak.py --seconds 600 --csv soak.csv --report-every 30

The scene and its loop are the seed example's (superdex_robotics/examples/advanced/
example_custom_components.py: the 2-DOF arm with Python sensor, controller and servo actuators
pressing on the soft duck lamp), imported from the example itself so that the two cannot drift
apart. Every `--report-every` simulated seconds it prints the process's resident memory (RSS), the
mean wall time per step over that window, and the arm's state. At the end it reports:

- memory drift: RSS at the end against RSS after the first window (the warm-up), in %;
- step-time drift: the last window's mean step time against the first window's, in %;
- whether every step stayed finite (under the default NumericalFaultPolicy.RAISE a numerical
  fault stops the run with the error).

Exit status 1 when the memory drift exceeds `--max-memory-drift` percent (default 5).
"""

import argparse
import csv
import importlib.util
import os
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
SEED = REPO / "superdex_robotics" / "examples" / "advanced" / "example_custom_components.py"


def load_seed():
    spec = importlib.util.spec_from_file_location("seed_example", SEED)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def rss_mib():
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    return float("nan")


def build(seed, physics, robotics):
    """The seed example's scene, components and handles, built as its main() builds them."""
    scene = physics.create_scene("Soak: custom components example")
    scene.set_gravity([0, 0, -9.81])
    ctx = robotics.create_context()
    seed.register_component_types(ctx)
    bot = robotics.create_bot(scene, robotics.load_bot_prefab_from_file(seed.get_default_bot_path()), ctx)
    arm = bot.get_articulated_actor()
    scene.create_rigid_actor(name="ground", shape=physics.create_plane_shape(normal=[0, 0, 1], distance=0), is_static=True)
    physics.prefab.add_to_scene(prefab_path=str(physics.paths.resolve_asset(seed.DUCK_LAMP_ASSET)),
                                root_path=str(physics.paths.get_assets_root()), scene=scene,
                                params=physics.prefab.PrefabParams(name="duck_lamp"))
    controller = robotics.get_python_controller(ctx, ctx.create_controller("MY_VELOCITY_FORCE_CONTROLLER", None, arm, "my_controller"))
    sensor = robotics.get_python_sensor(ctx, seed._one_handle(bot.find_sensors_by_name(seed.SENSOR_NAME), seed.SENSOR_NAME))
    actuators = [robotics.get_python_actuator(ctx, seed._one_handle(bot.find_actuators_by_name(n), n)) for n in seed.ACTUATOR_NAMES]
    return scene, ctx, bot, arm, controller, sensor, actuators


def main():
    parser = argparse.ArgumentParser(description="Soak test: the seed scene for a long simulated time; memory and step-time drift.")
    parser.add_argument("--seconds", type=float, default=3600.0, help="simulated seconds to run (default 3600)")
    parser.add_argument("--report-every", type=float, default=None, help="simulated seconds per report window (default: seconds / 20)")
    parser.add_argument("--csv", type=Path, help="write one row per window to this CSV file")
    parser.add_argument("--max-memory-drift", type=float, default=5.0, help="percent of RSS growth that fails the run (default 5)")
    args = parser.parse_args()
    window = args.report_every or max(args.seconds / 20, 1e-9)

    sys.path.insert(0, str(SEED.parent))
    os.environ.setdefault("SUPERDEX_DEBUGGER_BROWSER", "0")
    seed = load_seed()
    physics, robotics = seed.physics, seed.robotics
    physics.initialize(num_worker_threads=0)
    scene, ctx, bot, arm, controller, sensor, actuators = build(seed, physics, robotics)
    dt = 1.0 / seed.CONTROL_RATE_HZ
    dof_indices = [a.dof_index for a in actuators]
    contact_force = np.zeros(3, dtype=seed.np_real)

    rows = []
    steps_in_window, seconds_in_window, next_report = 0, 0.0, window
    started = time.perf_counter()
    print(f"soak: seed scene, {args.seconds:g} s simulated at dt = {dt:g} s ({int(round(args.seconds / dt))} steps), "
          f"{'double' if physics.uses_double_precision() else 'float'} build")
    print(f"{'sim s':>9} {'wall s':>9} {'RSS MiB':>9} {'ms/step':>9} {'|q| rad':>9} {'|f| N':>9}")
    while scene.get_total_simulation_time() < args.seconds - 0.5 * dt:
        t = scene.get_total_simulation_time()
        observations = controller.get_current_observations()
        observations["f_contact"] = contact_force
        q_dot_des = controller.compute_output(observations, seed.compute_trajectory_target(t))
        efforts = np.array([a.compute_effort(a.get_current_observations(), w, dt=dt) for a, w in zip(actuators, q_dot_des)],
                           dtype=seed.np_real)
        arm.set_external_forces_on_dofs(dof_indices=dof_indices, force_values=efforts)
        t0 = time.perf_counter()
        scene.step(dt)
        seconds_in_window += time.perf_counter() - t0
        steps_in_window += 1
        contact_force = sensor.compute_signal()
        if scene.get_total_simulation_time() >= next_report - 0.5 * dt:
            pose = arm.get_articulated_pose()
            if not (np.all(np.isfinite(pose)) and np.all(np.isfinite(contact_force))):
                print("soak: the state became non-finite", file=sys.stderr)
                return 1
            row = {"sim_s": scene.get_total_simulation_time(), "wall_s": time.perf_counter() - started, "rss_mib": rss_mib(),
                   "ms_per_step": 1000 * seconds_in_window / steps_in_window, "pose_norm": float(np.linalg.norm(pose)),
                   "contact_force_n": float(np.linalg.norm(contact_force))}
            rows.append(row)
            print(f"{row['sim_s']:9.1f} {row['wall_s']:9.1f} {row['rss_mib']:9.1f} {row['ms_per_step']:9.3f} "
                  f"{row['pose_norm']:9.4f} {row['contact_force_n']:9.3f}", flush=True)
            steps_in_window, seconds_in_window, next_report = 0, 0.0, next_report + window
    robotics.destroy_bot(scene, bot)
    physics.shutdown()

    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)
    if len(rows) < 2:
        print("soak: too short for drift (fewer than two report windows)")
        return 0
    first, last = rows[0], rows[-1]
    memory_drift = 100 * (last["rss_mib"] - first["rss_mib"]) / first["rss_mib"]
    time_drift = 100 * (last["ms_per_step"] - first["ms_per_step"]) / first["ms_per_step"]
    print(f"soak: memory drift {memory_drift:+.2f} % ({first['rss_mib']:.1f} -> {last['rss_mib']:.1f} MiB after the first window), "
          f"step-time drift {time_drift:+.1f} % ({first['ms_per_step']:.3f} -> {last['ms_per_step']:.3f} ms/step), "
          f"every step finite")
    return 1 if memory_drift > args.max_memory_drift else 0


if __name__ == "__main__":
    sys.exit(main())
