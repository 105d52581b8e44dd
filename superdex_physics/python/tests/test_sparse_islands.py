"""Large islands are solved with sparse linear algebra: a 20-box stack (one island of 120 DOFs)
stands, carries 20 m g on the ground, and gives the same result as the dense solve."""

import numpy as np
import pytest

import superdex.physics as sdp
from contact_helpers import G, add_box, add_ground, position


def stack(scene, n=20):
    ground = add_ground(scene)
    return ground, [add_box(scene, f"b{k}", [0, 0, 0.1 + 0.2 * k + 0.0005 * k], half=0.1, mass=1.0) for k in range(n)]


def run(dense_max_dofs):
    sdp.initialize(0)
    scene = sdp.create_scene("stack")
    scene.set_gravity([0, 0, -G])
    p = scene.get_solver_params()
    p.implicit_step.dense_island_max_dofs = dense_max_dofs
    scene.set_solver_params(p)
    ground, boxes = stack(scene)
    boxes[0].register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    for _ in range(100):
        scene.step(0.01)
    stats = scene.get_solver_stats()
    result = (np.array([position(b) for b in boxes]), boxes[0].get_contact_force_from_actor_world(ground), stats.num_islands)
    sdp.shutdown()
    return result


def test_sparse_and_dense_islands_agree():
    sparse_pos, sparse_force, islands = run(dense_max_dofs=96)
    dense_pos, dense_force, _ = run(dense_max_dofs=10_000)
    assert islands == 1
    np.testing.assert_allclose(sparse_pos, dense_pos, atol=2e-5)
    np.testing.assert_allclose(sparse_pos[:, :2], 0, atol=1e-3)
    assert sparse_force[2] == pytest.approx(20 * G, rel=0.01)
