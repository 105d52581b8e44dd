"""The G1 humanoid (example-robot-data) stands on its feet for 5 s at 2 ms steps under joint PD
(superdex_robotics/examples/robots/example_g1_standing.py): it never falls (the pelvis stays
within 2 cm of its start height), only its feet touch the ground, and once settled the contact
force under the feet equals its weight within 1 % at every step of the last second.
"""

import importlib.util
import warnings
from pathlib import Path

import numpy as np
import pytest

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "robots" / "example_g1_standing.py"


def load_example():
    spec = importlib.util.spec_from_file_location("example_g1_standing", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_g1_stands_with_its_weight_on_its_feet():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the G1's meshes have degenerate triangles: repaired, with warnings
        r = load_example().run(seconds=5.0, dt=0.002)
    pelvis, feet, total, weight = r["pelvis"], r["foot_force"], r["total_force"], r["weight"]
    assert len(pelvis) == 2500 and np.all(np.isfinite(pelvis))
    assert weight == pytest.approx(33.34 * 9.81, rel=0.01)  # the URDF's 33.34 kg
    assert np.all(pelvis[:, 2] > r["start_height"] - 0.02), "the pelvis never drops: it stands"
    np.testing.assert_allclose(total, feet, atol=1e-6 * weight)  # nothing but the feet touches
    last_second = feet[-500:]
    assert np.all(np.abs(last_second / weight - 1) < 0.01), (last_second.min(), last_second.max(), weight)
