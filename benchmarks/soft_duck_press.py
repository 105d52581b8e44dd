"""Time per step of the seed's soft prop: the duck-lamp prefab settling on the ground, then pressed
by a ball on a vertical slider (as the seed's arm presses it), at the seed's 250 Hz.

    uv run python benchmarks/soft_duck_press.py [--threads N] [--steps N] [--reduced-modes R]

With --reduced-modes R the duck's material gets reducedModes = R (a reduced soft body: R
vibration modes plus the static correction) instead of the full finite-element model.

Prints milliseconds per step and Newton iterations per step for both phases."""

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import superdex.physics as sdp

if __package__ in (None, ""):  # run as a script: the repository's root on the path for benchmarks.models
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from benchmarks.models import node_positions_world, superdex_articulation  # noqa: E402

DUCK = Path(__file__).resolve().parents[1] / "assets" / "prefabs" / "duck_lamp" / "duck_lamp_recumbent_full.mochi_prefab"


def duck_prefab(reduced_modes, folder):
    """The duck prefab, with its material's reducedModes set when reduced_modes > 0 (a copy in
    `folder`, beside a link to the original mesh)."""
    if reduced_modes <= 0:
        return DUCK
    prefab = json.loads(DUCK.read_text())
    soft = prefab["actors"]["soft"][0]
    soft["material"]["reducedModes"] = reduced_modes
    mesh = DUCK.parent / soft["shape"]
    (Path(folder) / mesh.name).symlink_to(mesh.resolve())
    path = Path(folder) / DUCK.name
    path.write_text(json.dumps(prefab))
    return path


def run(threads, steps, reduced_modes=0, dt=0.004):
    sdp.initialize(num_worker_threads=threads)
    scene = sdp.create_scene("bench")
    scene.set_gravity([0, 0, -9.81])
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    with tempfile.TemporaryDirectory() as folder:
        start = time.perf_counter()
        duck = sdp.prefab.add_to_scene(str(duck_prefab(reduced_modes, folder)), "/duck", scene).actors[0]
        print(f"    load: {1e3 * (time.perf_counter() - start):7.1f} ms")
    duck.register_query(sdp.QueryType.NODE_POSITIONS)

    def phase(name):
        iterations, start = [], time.perf_counter()
        for _ in range(steps):
            scene.step(dt)
            iterations.append(scene.get_solver_stats().total_non_linear_iters)
        ms = 1e3 * (time.perf_counter() - start) / steps
        print(f"{name:>8}: {ms:7.1f} ms/step, {np.mean(iterations):5.1f} Newton iterations/step")

    phase("settle")
    top = node_positions_world(duck)[:, 2].max()
    links = [{"name": "base", "mass": 1.0, "momentOfInertia": [1e-3, 0, 0, 1e-3, 0, 1e-3]},
             {"name": "ball", "parentLink": 0, "mass": 0.05, "momentOfInertia": [1e-6, 0, 0, 1e-6, 0, 1e-6],
              "shape": {"sphere": {"radius": 0.015, "center": [0, 0, 0]}}}]
    joints = [{"name": "weld", "type": "Hard", "parentLinkFromJoint": {"translation": [-0.30, 0, top + 0.016]}},
              {"name": "slide", "type": "Prismatic", "axis": [0, 0, 1]}]
    slider = superdex_articulation(scene, sdp, "slider", links, joints)
    slider.set_external_forces_on_dofs([0], [-0.5])
    phase("press")
    sdp.shutdown()


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--steps", type=int, default=100)
    parser.add_argument("--reduced-modes", type=int, default=0)
    args = parser.parse_args()
    print(f"precision: {'double' if sdp.uses_double_precision() else 'float'}, worker threads: {args.threads}, "
          f"reduced modes: {args.reduced_modes or 'none (full model)'}")
    run(args.threads, args.steps, args.reduced_modes)
