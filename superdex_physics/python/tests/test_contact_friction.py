"""Coulomb friction of a box on the ground: sticking and sliding on an incline, and under a push.

The incline is made by tilting gravity rather than the ground: with gravity
g (sin th, 0, -cos th) a box on the horizontal ground (normal +z) is in exactly the situation
of a box on a plane inclined by th, with "downhill" = +x. Coulomb's law with coefficient mu:
the box sticks while tan th <= mu, and otherwise slides with acceleration
a = g (sin th - mu cos th) along the slope. Pairs combine their coefficients by their
geometric mean sqrt(mu_a mu_b) (SuperDex's rule).

Boxes are 2 kg cubes of half extent 0.1 m, stepped at dt = 10 ms. A cube sliding or pushed at
its centre does not tip here: tipping needs the resultant to leave the base, i.e.
tan th > 1 on the incline or F > m g for the push.
"""

import numpy as np
import pytest

import superdex.physics as sdp
from contact_helpers import G, add_box, add_ground, position, quaternion, rotation_angle, step_for, vec

M = 2.0
HALF = 0.1
DT = 0.01


def tilted_gravity(scene, theta_deg):
    th = np.radians(theta_deg)
    scene.set_gravity([G * np.sin(th), 0.0, -G * np.cos(th)])
    return th


def combined_mu(a, b):
    return np.sqrt(a * b)


def sliding_acceleration(scene, box, settle=0.2, window=0.8):
    """Downhill (x) acceleration: least-squares slope of v_x(t) over `window` seconds after `settle`.
    Also checks the box stays on the ground, upright, without sideways motion."""
    step_for(scene, DT, settle)
    ts, vs = [], []

    def record(_):
        ts.append(scene.get_total_simulation_time())
        vs.append(vec(box.get_linear_velocity())[0])

    step_for(scene, DT, window, record)
    assert position(box)[2] == pytest.approx(HALF, abs=1e-3), "the box left the ground"
    assert abs(position(box)[1]) < 1e-3
    assert rotation_angle(quaternion(box), np.array([0, 0, 0, 1.0])) < 0.02, "the box tipped"
    slope, _ = np.polyfit(np.array(ts), np.array(vs), 1)
    return slope


def test_box_sticks_below_the_friction_angle(scene):
    """tan 20 deg = 0.364 < mu = 0.5: static friction holds the box; it moves less than 1 mm along
    the slope in 10 s. The friction force then balances the downhill weight component exactly:
    the contact force is (-m g sin th, 0, m g cos th), i.e. it cancels gravity (1 %)."""
    th = tilted_gravity(scene, 20.0)
    add_ground(scene, mu=0.5)
    box = add_box(scene, "box", [0, 0, HALF], half=HALF, mass=M, mu=0.5)
    box.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    start = position(box)
    step_for(scene, DT, 10.0)
    moved = position(box) - start
    assert abs(moved[0]) < 1e-3, f"the box crept {moved[0] * 1e3:.3f} mm down a 20 deg slope with mu = 0.5"
    assert abs(moved[1]) < 1e-3
    f = vec(box.get_contact_force_world())
    np.testing.assert_allclose(f, [-M * G * np.sin(th), 0, M * G * np.cos(th)], atol=0.01 * M * G)


def test_box_slides_above_the_friction_angle(scene):
    """tan 35 deg = 0.700 > mu = 0.5: the box slides with a = g (sin th - mu cos th) = 1.609 m/s^2
    (5 %); kinetic friction then equals mu times the normal force (2 %)."""
    th = tilted_gravity(scene, 35.0)
    add_ground(scene, mu=0.5)
    box = add_box(scene, "box", [0, 0, HALF], half=HALF, mass=M, mu=0.5)
    box.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    a = sliding_acceleration(scene, box)
    expected = G * (np.sin(th) - 0.5 * np.cos(th))
    assert a == pytest.approx(expected, rel=0.05)
    f = vec(box.get_contact_force_world())
    assert f[2] == pytest.approx(M * G * np.cos(th), rel=0.02)
    assert -f[0] == pytest.approx(0.5 * f[2], rel=0.02)


def test_friction_coefficients_combine_by_geometric_mean(scene):
    """Box mu = 0.3 on ground mu = 1.0: the pair's coefficient is sqrt(0.3 x 1.0) = 0.5477, so at
    35 deg (tan 35 deg = 0.700) the box slides with g (sin th - 0.5477 cos th) = 1.226 m/s^2 (5 %).
    (Other rules give clearly different motion: max sticks, the arithmetic mean 0.65 gives
    0.40, the harmonic mean 0.4615 gives 1.918, min gives 3.22 m/s^2.)"""
    th = tilted_gravity(scene, 35.0)
    add_ground(scene, mu=1.0)
    box = add_box(scene, "box", [0, 0, HALF], half=HALF, mass=M, mu=0.3)
    a = sliding_acceleration(scene, box)
    assert a == pytest.approx(G * (np.sin(th) - combined_mu(0.3, 1.0) * np.cos(th)), rel=0.05)


def push(box, force):
    # a dynamic rigid actor's external forces are the force on its centre of mass (DOFs 0-2) and
    # the torque (3-5), world frame: DOF 0 is world x
    box.set_external_forces_on_dofs([0], [force])


def test_push_below_static_friction_does_not_move_the_box(scene):
    """A horizontal push F = 0.8 mu m g at the centre of mass is held by static friction: the box
    moves less than 1 mm in 2 s and the friction force is exactly -F (1 %)."""
    add_ground(scene, mu=0.5)
    box = add_box(scene, "box", [0, 0, HALF], half=HALF, mass=M, mu=0.5)
    box.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    step_for(scene, DT, 0.2)
    start = position(box)
    force = 0.8 * 0.5 * M * G
    push(box, force)
    step_for(scene, DT, 2.0)
    assert np.linalg.norm((position(box) - start)[:2]) < 1e-3
    assert rotation_angle(quaternion(box), np.array([0, 0, 0, 1.0])) < 1e-3
    f = vec(box.get_contact_force_world())
    assert f[0] == pytest.approx(-force, rel=0.01)
    assert f[2] == pytest.approx(M * G, rel=0.01)


def test_push_above_kinetic_friction_accelerates_the_box(scene):
    """A horizontal push F = 1.5 mu m g exceeds friction: the box accelerates at
    (F - mu m g) / m = 0.5 mu g = 2.45 m/s^2 (5 %)."""
    add_ground(scene, mu=0.5)
    box = add_box(scene, "box", [0, 0, HALF], half=HALF, mass=M, mu=0.5)
    step_for(scene, DT, 0.2)
    force = 1.5 * 0.5 * M * G
    push(box, force)
    a = sliding_acceleration(scene, box, settle=0.1, window=0.8)
    assert a == pytest.approx((force - 0.5 * M * G) / M, rel=0.05)
