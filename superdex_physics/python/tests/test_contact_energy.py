"""Contact never creates energy: a ball dropped on the ground, and a ball skidding and spinning on it.

The mechanical energy of a free ball (mass m, radius r, solid: I = 2/5 m r^2) is

    E = 1/2 m |v|^2 + 1/2 I |w|^2 + m g z.

Gravity conserves it; contact (inelastic, rigid by default) and friction can only remove it.
So, step after step, E must not grow beyond float rounding: we allow 1e-6 of the initial
energy in both precisions (E ~ 5 J; float32 rounding of positions near 0.1 m is ~1e-8 of E).

The skidding ball also has a classical answer: friction acts at the contact point, so the
angular momentum about that point is conserved, m r v + I w_y; the ball stops slipping when
v = w_y r, hence finishes rolling at v = (5 v0 + 2 r w0) / 7.
"""

import numpy as np
import pytest

import superdex.physics as sdp
from contact_helpers import G, add_ground, add_sphere, position, step_for, vec

M = 1.0
RADIUS = 0.1
INERTIA = 0.4 * M * RADIUS**2
REL_TOL = 1e-6


def energy(ball):
    v = vec(ball.get_linear_velocity())
    w = vec(ball.get_angular_velocity())
    return 0.5 * M * v @ v + 0.5 * INERTIA * w @ w + M * G * position(ball)[2]


def energy_history(scene, ball, dt, seconds):
    """Energy before the first step and after every step, and the index of the first step
    whose result shows contact (a non-zero contact force on the ball)."""
    ball.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    energies = [energy(ball)]
    first_contact = []

    def record(k):
        energies.append(energy(ball))
        if not first_contact and np.linalg.norm(vec(ball.get_contact_force_world())) > 0:
            first_contact.append(k)

    step_for(scene, dt, seconds, record)
    assert first_contact, "the ball never touched the ground"
    return np.array(energies), first_contact[0]


def assert_non_increasing(energies, start, label):
    tol = REL_TOL * abs(energies[0])
    increases = np.diff(energies[start:])
    worst = int(np.argmax(increases))
    assert increases[worst] <= tol, (
        f"{label}: energy grew by {increases[worst]:.3e} J (> {tol:.1e} J) at step {start + worst + 1}; "
        f"E went {energies[start + worst]:.9f} -> {energies[start + worst + 1]:.9f}")


@pytest.mark.parametrize("dt", [0.001, 0.004, 0.025])
def test_dropped_ball_never_gains_energy(scene, dt):
    """A ball released from 0.5 m: from the first contact on, E is non-increasing step by step,
    and the ball ends at rest on the ground (centre at r, within 1 mm)."""
    add_ground(scene)
    ball = add_sphere(scene, "ball", [0, 0, 0.5], radius=RADIUS, mass=M)
    energies, first = energy_history(scene, ball, dt, 2.0)
    assert_non_increasing(energies, first - 1, f"dt = {dt}")
    assert energies[-1] <= energies[0]
    assert position(ball)[2] == pytest.approx(RADIUS, abs=1e-3)
    assert np.linalg.norm(vec(ball.get_linear_velocity())) < 1e-2


@pytest.mark.parametrize("dt", [0.001, 0.004, 0.025])
def test_skidding_spinning_ball_never_gains_energy(scene, dt):
    """A ball on the ground thrown forward at 2 m/s with backspin w_y = -5 rad/s (and a spin
    w_z = 3 rad/s about the vertical): kinetic friction brakes the slip; E never increases.
    It ends rolling without slipping at v = (5 v0 + 2 r w0) / 7 = 1.286 m/s (2 %), w_y = v / r."""
    add_ground(scene, mu=0.5)
    ball = add_sphere(scene, "ball", [0, 0, RADIUS], radius=RADIUS, mass=M, mu=0.5)
    v0, w0 = 2.0, -5.0
    ball.set_velocity([v0, 0, 0], [0, w0, 3.0])
    energies, first = energy_history(scene, ball, dt, 1.0)
    assert_non_increasing(energies, max(first - 1, 0), f"dt = {dt}")
    assert energies[-1] < energies[0]
    v_roll = (5 * v0 + 2 * RADIUS * w0) / 7
    v = vec(ball.get_linear_velocity())
    w = vec(ball.get_angular_velocity())
    assert v[0] == pytest.approx(v_roll, rel=0.02)
    assert abs(v[1]) < 0.02 * v_roll
    assert w[1] * RADIUS == pytest.approx(v_roll, rel=0.02)
    assert position(ball)[2] == pytest.approx(RADIUS, abs=1e-3)
