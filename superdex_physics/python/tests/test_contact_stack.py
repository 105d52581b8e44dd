"""A stack of five boxes stays standing, and each contact carries the weight above it.

Five 1 kg cubes of half extent 0.1 m are stacked on the ground, each released 1 mm above the
one below (box k, k = 0..4 from the bottom, starts at z = 0.1 + 0.2 k + 0.001 (k + 1)).
Resting, box k's centre is at 0.1 + 0.2 k; static equilibrium of the boxes above each contact
gives its load: the ground carries 5 m g, the contact under box k carries (5 - k) m g, and the
net contact force on every box is m g upwards. Checked after 10 s at dt = 10 ms and at the
coarse dt = 25 ms.
"""

import numpy as np
import pytest

import superdex.physics as sdp
from contact_helpers import G, add_box, add_ground, position, quaternion, rotation_angle, step_for, vec

N = 5
M = 1.0
HALF = 0.1
GAP = 1e-3


def build_stack(scene):
    ground = add_ground(scene, mu=0.5)
    boxes = [add_box(scene, f"box{k}", [0, 0, HALF + 2 * HALF * k + GAP * (k + 1)], half=HALF, mass=M, mu=0.5)
             for k in range(N)]
    return ground, boxes


@pytest.mark.parametrize("dt", [0.01, 0.025])
def test_stack_of_five_boxes_stands(scene, dt):
    """After 10 s each box is within 5 mm of its start in x, y and of its ideal resting height
    0.1 + 0.2 k, turned by less than 0.02 rad, and at rest (< 1 cm/s)."""
    ground, boxes = build_stack(scene)
    starts = [position(b) for b in boxes]
    step_for(scene, dt, 10.0)
    for k, b in enumerate(boxes):
        p = position(b)
        assert np.linalg.norm(p[:2] - starts[k][:2]) < 5e-3, f"box {k} slid to {p}"
        assert p[2] == pytest.approx(HALF + 2 * HALF * k, abs=5e-3), f"box {k} at height {p[2]:.4f}"
        assert rotation_angle(quaternion(b), np.array([0, 0, 0, 1.0])) < 0.02, f"box {k} turned"
        assert np.linalg.norm(vec(b.get_linear_velocity())) < 1e-2
    assert scene.get_solver_stats().convergence_status == sdp.ConvergenceStatus.CONVERGED


@pytest.mark.parametrize("dt", [0.01, 0.025])
def test_stack_contact_forces_carry_the_weight_above(scene, dt):
    """At rest (after 3 s): the ground pushes the bottom box with 5 m g; box k is pushed by box
    k - 1 with (5 - k) m g (1 %, no horizontal part beyond 1 % of m g); the net contact force on
    each box is m g upwards (1 % of m g)."""
    ground, boxes = build_stack(scene)
    for b in boxes:
        b.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    step_for(scene, dt, 3.0)
    w = M * G
    below = [ground] + boxes[:-1]
    for k, b in enumerate(boxes):
        f = vec(b.get_contact_force_from_actor_world(below[k]))
        assert f[2] == pytest.approx((N - k) * w, rel=0.01), f"box {k} from below"
        assert np.linalg.norm(f[:2]) < 0.01 * w
        total = vec(b.get_contact_force_world())
        np.testing.assert_allclose(total, [0, 0, w], atol=0.01 * w, err_msg=f"net contact force on box {k}")
