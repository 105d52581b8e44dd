"""Compliant contact with a user stiffness, and many bodies through the broad phase.

- A box on four corner contacts, each a spring of the box's contact stiffness k (the ground
  is rigid, so the pair keeps k): at rest it sinks by m g / (4 k), and the contact force is m g.
- With dissipation, a dropped compliant ball settles (no lasting oscillation).
- 200 spheres on a grid, dropped onto the ground with gaps between them: every one lands
  and rests at its radius (the sweep-and-prune broad phase finds every ground pair and no
  false pair disturbs them).
"""

import numpy as np
import pytest

import superdex.physics as sdp
from contact_helpers import G, add_ground, position, step_for


def test_compliant_box_sinks_by_weight_over_stiffness(scene):
    add_ground(scene)
    m, k, half = 2.0, 2.0e4, 0.1
    box = scene.create_rigid_actor(
        name="box", shape=sdp.create_box_shape([half] * 3), mass=m,
        world_from_local=sdp.TransformRT(translation=[0, 0, half]),
        contact=sdp.ContactParams(coulomb_friction_coefficient=0.5, contact_stiffness=k, dissipation_time_scale=0.05))
    box.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    step_for(scene, 0.005, 3.0)
    sink = half - position(box)[2]
    assert sink == pytest.approx(m * G / (4 * k), rel=0.02)
    assert box.get_contact_force_world()[2] == pytest.approx(m * G, rel=0.005)


def test_compliant_ball_with_dissipation_settles(scene):
    add_ground(scene)
    m, k, r = 1.0, 1.0e4, 0.05
    ball = scene.create_rigid_actor(
        name="ball", shape=sdp.create_sphere_shape([0, 0, 0], r), mass=m,
        world_from_local=sdp.TransformRT(translation=[0, 0, 0.3]),
        contact=sdp.ContactParams(contact_stiffness=k, dissipation_time_scale=0.02))
    step_for(scene, 0.002, 2.0)
    assert position(ball)[2] == pytest.approx(r - m * G / k, abs=2e-4)
    assert abs(ball.get_linear_velocity()[2]) < 1e-3


def test_two_hundred_spheres_land_on_the_ground(scene):
    add_ground(scene)
    r = 0.04
    balls = []
    for i in range(20):
        for j in range(10):
            balls.append(scene.create_rigid_actor(
                name=f"s{i}_{j}", shape=sdp.create_sphere_shape([0, 0, 0], r), mass=0.1,
                world_from_local=sdp.TransformRT(translation=[0.1 * i, 0.1 * j, 0.2 + 0.01 * ((i + j) % 5)])))
    step_for(scene, 0.01, 1.0)
    z = np.array([position(b)[2] for b in balls])
    np.testing.assert_allclose(z, r, atol=2e-4)
    xy = np.array([position(b)[:2] for b in balls])
    expected = np.array([[0.1 * i, 0.1 * j] for i in range(20) for j in range(10)])
    np.testing.assert_allclose(xy, expected, atol=1e-4)
    assert scene.get_solver_stats().num_islands == 200
