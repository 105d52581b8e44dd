"""A body spawned inside another is pushed out at a bounded speed (1 m/s), not at
penetration / dt: a 0.2 m box created with 5 cm of it in the ground would otherwise leave at
10 m/s after one 5 ms step and fly 5 m up."""

from __future__ import annotations

import numpy as np
import pytest

import superdex.physics as sdp

DT = 0.005


@pytest.mark.parametrize("depth", [0.05, 0.09])
def test_a_box_spawned_in_the_ground_rises_out_slowly(scene, depth):
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    box = scene.create_rigid_actor(name="box", shape=sdp.create_box_shape([0.1, 0.1, 0.1]), density=500.0,
                                   world_from_local=sdp.TransformRT(translation=[0, 0, 0.1 - depth]))
    top_speed, top_height = 0.0, 0.0
    for _ in range(200):
        scene.step(DT)
        top_speed = max(top_speed, float(np.asarray(box.get_linear_velocity())[2]))
        top_height = max(top_height, float(np.asarray(box.get_root_transform().translation)[2]))
    # pushed out no faster than the bound (the last push, less gravity's pull within the step)
    assert 0.5 < top_speed <= 1.0 + 1e-6
    # so it barely overshoots its resting height (1 m/s carries it v^2 / 2g = 5 cm at most) ...
    assert top_height < 0.1 + 0.052
    # ... and comes to rest on the ground
    np.testing.assert_allclose(np.asarray(box.get_root_transform().translation), [0, 0, 0.1], atol=2e-3)
    assert np.abs(np.asarray(box.get_linear_velocity())).max() < 1e-2
