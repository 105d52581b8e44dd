"""TACTILE_PAD: a rows x cols grid of taxels on a pad fixed to a link. A cube resting on the pad
loads it with its weight, on taxels under its footprint only (where the engine's contact points
are, at the cube's corners) and centred under the cube; a cube resting on the link beside the
pad leaves every taxel at zero while the link's contact force reads its weight. The pad frame
turns the grid. Bad params name the field.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from robotics_helpers import scene  # noqa: F401

HALF = 0.05  # the slab's half extent in x and y (m)
TOP = 0.01  # the slab's top face: z = TOP (half thickness 0.01 around z = 0)
PAD = {"rows": 4, "cols": 4, "size": [0.04, 0.04], "thickness": 0.003}


def slab_bot(tmp_path, pad_params):
    bot = {
        "name": "slab",
        "links": [{"name": "slab", "mass": 2.0, "momentOfInertia": [0.002, 0, 0, 0.002, 0, 0.003],
                   "shape": {"box": {"halfExtents": [HALF, HALF, TOP]}},
                   "sensors": [
                       {"type": "TACTILE_PAD", "name": "pad", "params": json.dumps(pad_params),
                        "parentFromSensor": {"translation": [0.0, 0.0, TOP]}},
                       {"type": "CONTACT_FORCE", "name": "total"}]}],
        "joints": [{"name": "weld", "type": "Hard"}],
    }
    path = tmp_path / "slab.superdex_bot"
    path.write_text(json.dumps(bot))
    return str(path)


def settle_cube(scene, tmp_path, at, pad_params=PAD):  # noqa: F811
    ctx = sdr.create_context()
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(slab_bot(tmp_path, pad_params)), ctx)
    mass, half = 0.1, 0.01
    scene.create_rigid_actor(name="cube", shape=sdp.create_box_shape(half_extents=[half] * 3), mass=mass,
                             world_from_local=sdp.TransformRT(translation=[at[0], at[1], TOP + half]))
    for _ in range(400):
        scene.step(0.0025)
    (pad,) = bot.find_sensors_by_name("pad")
    (total,) = bot.find_sensors_by_name("total")
    return np.asarray(ctx.get_sensor_signal(pad), float), np.asarray(ctx.get_sensor_signal(total), float), mass * 9.81


def test_the_taxels_under_a_resting_cube_carry_its_weight(scene, tmp_path):  # noqa: F811
    # the cube's footprint x, y in [-0.005, 0.015]: columns and rows 1 to 3 of the 1 cm cells
    taxels, total, weight = settle_cube(scene, tmp_path, (0.005, 0.005))
    grid = taxels.reshape(4, 4)
    assert taxels.sum() == pytest.approx(weight, rel=0.02)
    assert -total[2] == pytest.approx(weight, rel=0.02)  # the cube presses the slab down
    np.testing.assert_array_equal(grid[0, :], 0.0)  # row 0: y in [-0.02, -0.01)
    np.testing.assert_array_equal(grid[:, 0], 0.0)  # column 0: x in [-0.02, -0.01)
    # the load's centre over the cell centres is the cube's centre, within half a cell
    centres = -0.015 + 0.01 * np.arange(4)
    assert grid.sum(axis=0) @ centres / grid.sum() == pytest.approx(0.005, abs=0.005)
    assert grid.sum(axis=1) @ centres / grid.sum() == pytest.approx(0.005, abs=0.005)


def test_a_cube_beside_the_pad_leaves_it_unloaded(scene, tmp_path):  # noqa: F811
    taxels, total, weight = settle_cube(scene, tmp_path, (0.035, -0.035))
    assert -total[2] == pytest.approx(weight, rel=0.02)  # the cube presses the slab down
    np.testing.assert_array_equal(taxels, 0.0)


def test_the_pad_frame_moves_the_grid(scene, tmp_path):  # noqa: F811
    # turned half a turn about z, the pad's rows and columns run the other way
    turned = dict(PAD, pad_from_sensor={"rotation": [0.0, 0.0, 1.0, 0.0], "translation": [0.0, 0.0, 0.0]})
    taxels, _, weight = settle_cube(scene, tmp_path, (0.005, 0.005), turned)
    grid = taxels.reshape(4, 4)
    assert taxels.sum() == pytest.approx(weight, rel=0.02)
    np.testing.assert_array_equal(grid[3, :], 0.0)
    np.testing.assert_array_equal(grid[:, 3], 0.0)


@pytest.mark.parametrize("params, message", [
    ({"rows": 0}, r"TACTILE_PAD: params.rows: expected a whole number from 1 to 1024"),
    ({"size": [0.01, -1.0]}, r"TACTILE_PAD: params.size: expected two positive lengths"),
    ({"thickness": 0}, r"TACTILE_PAD: params.thickness: expected a positive length"),
    ({"pad_from_sensor": {"spin": 1}}, r"pad_from_sensor"),
    ({"colour": "red"}, r"colour"),
])
def test_bad_params_name_the_field(scene, tmp_path, params, message):  # noqa: F811
    prefab = sdr.load_bot_prefab_from_file(slab_bot(tmp_path, params))
    with pytest.raises(sdp.Error, match=message):
        sdr.create_bot(scene, prefab, sdr.create_context())
