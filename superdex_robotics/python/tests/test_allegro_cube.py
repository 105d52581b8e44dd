"""The Allegro hand (example-robot-data) holds a 5 cm cube palm up for 5 s under joint PD
(superdex_robotics/examples/robots/example_allegro_cube.py): the fingers close on the cube, the
cube rests on the palm's face, and it slips less than 1 mm relative to the palm over the hold.
"""

import importlib.util
import warnings
from pathlib import Path

import numpy as np
import pytest

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "robots" / "example_allegro_cube.py"


def load_example():
    spec = importlib.util.spec_from_file_location("example_allegro_cube", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_allegro_holds_the_cube_without_slipping():
    example = load_example()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the importer's notes on the Allegro's inertias
        r = example.run(seconds=5.0, dt=0.002)
    path = r["cube_in_palm"]
    assert len(path) == 2500 and np.all(np.isfinite(path))
    # on the palm's face (palm x is its normal), within the palm's length and width
    assert path[-1][0] == pytest.approx(example.PALM_SURFACE + example.CUBE_HALF, abs=0.002)
    assert abs(path[-1][1]) < 0.03 and -0.095 < path[-1][2] < 0.0
    assert np.all(r["q"][[1, 5, 9]] > 0.3), "the fingers closed on the cube"
    slip = np.linalg.norm(path - path[0], axis=1).max()
    assert slip < 1e-3, f"slipped {slip * 1000:.3f} mm"
