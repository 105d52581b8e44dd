"""Friction refinement passes run only for contacts that slip at a speed that matters.

After the convex (cone) solve, contacts at their friction bound are re-solved with the bound
fixed, because the cone model lets a slipping contact separate at mu times its slip speed. In a
resting pile, some contact points sit at their bound while creeping at micrometres per second:
there the separation is far below a micrometre per step, and SolverParams.friction_pass_min_slip
(m/s) skips the passes. A pile settled with the default must rest where it rests with the
threshold at 0 (every bound contact refined), and in float, whose resting contacts creep at their
bound, need fewer Newton iterations; a box that really slides is still refined and stays on the
ground (test_contact_friction.py)."""

import numpy as np
import pytest

import superdex.physics as sdp
from contact_helpers import add_box, add_ground, position

DT = 0.004
HALF = 0.05


def settled_pile(min_slip):
    """Two staggered layers of 3 x 3 tilted 10 cm cubes, settled for 1 s; then 0.4 s more.
    Returns the Newton iterations of those last 100 steps and the boxes' positions."""
    scene = sdp.create_scene(f"pile_{min_slip}")
    params = scene.get_solver_params()
    params.friction_pass_min_slip = min_slip
    scene.set_solver_params(params)
    add_ground(scene, mu=0.5)
    rng = np.random.default_rng(0)
    boxes = []
    for k in range(18):
        layer, i = divmod(k, 9)
        r, c = divmod(i, 3)
        shift = 0.06 * layer
        axis = rng.normal(size=3)
        angle = rng.uniform(0, 0.3)
        q = np.append(np.sin(angle / 2) * axis / np.linalg.norm(axis), np.cos(angle / 2))
        boxes.append(add_box(scene, f"box{k}", [(c - 1) * 0.12 + shift, (r - 1) * 0.12 + shift, 0.1 + 0.15 * layer],
                             half=HALF, mass=1.0, mu=0.5, rotation=sdp.Quaternion(*q)))
    for _ in range(250):
        scene.step(DT)
    iterations = 0
    for _ in range(100):
        scene.step(DT)
        iterations += scene.get_solver_stats().total_newton_iterations
    return iterations, np.array([position(b) for b in boxes])


def test_a_resting_pile_skips_the_passes_and_rests_in_the_same_place(engine):
    refined_always, at_rest_always = settled_pile(0.0)
    refined_if_slipping, at_rest = settled_pile(1e-4)
    np.testing.assert_allclose(at_rest, at_rest_always, atol=1e-4)
    assert refined_if_slipping <= refined_always
    if not sdp.uses_double_precision():
        # float's resting contacts creep at their bound (double's do not): the passes that ran
        # for them every step are skipped
        assert refined_if_slipping < 0.9 * refined_always, (refined_if_slipping, refined_always)


def test_min_slip_must_not_be_negative(scene):
    params = scene.get_solver_params()
    params.friction_pass_min_slip = -1.0
    with pytest.raises(sdp.Error, match="friction_pass_min_slip"):
        scene.set_solver_params(params)
