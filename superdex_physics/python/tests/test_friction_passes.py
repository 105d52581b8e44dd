"""Friction refinement passes run only for contacts that slip at a speed that matters.

After the convex (cone) solve, contacts at their friction bound are re-solved with the bound
fixed, because the cone model lets a slipping contact separate at mu times its slip speed. In a
resting pile, some contact points sit at their bound while creeping at micrometres per second:
there the separation is far below a micrometre per step, and SolverParams.friction_pass_min_slip
(m/s) skips the passes. A pile settled with the default must rest where it rests with the
threshold at 0 (every bound contact refined); a box pushed just below its friction bound creeps at
it without being refined in most steps, and moves as it does when refined; a box that really
slides is refined in every step and stays on the ground (also test_contact_friction.py)."""

import numpy as np
import pytest

import superdex.physics as sdp
from contact_helpers import add_box, add_ground, position

DT = 0.004
HALF = 0.05


def settled_pile(min_slip):
    """Two staggered layers of 3 x 3 tilted 10 cm cubes, settled for 1.4 s.
    Returns the boxes' positions."""
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
    for _ in range(100):
        scene.step(DT)
    return np.array([position(b) for b in boxes])


def test_a_resting_pile_rests_in_the_same_place(engine):
    at_rest_always = settled_pile(0.0)
    at_rest = settled_pile(1e-4)
    np.testing.assert_allclose(at_rest, at_rest_always, atol=1e-4)


def pushed_box(min_slip, force):
    """A 1 kg box resting on the ground (mu 0.5), then pushed sideways by `force` (N) for 0.2 s.
    Returns the friction passes of each pushed step and the box's displacement (m)."""
    scene = sdp.create_scene(f"pushed_{min_slip}")
    params = scene.get_solver_params()
    params.friction_pass_min_slip = min_slip
    scene.set_solver_params(params)
    add_ground(scene, mu=0.5)
    box = add_box(scene, "box", [0, 0, HALF], half=HALF, mass=1.0, mu=0.5)
    for _ in range(50):
        scene.step(DT)
    start = position(box)
    box.set_external_forces_on_dofs([0], [force])
    passes = []
    for _ in range(50):
        scene.step(DT)
        passes.append(scene.get_solver_stats().friction_passes)
    return np.array(passes), position(box) - start


def test_a_creeping_contact_skips_the_passes(engine):
    # at 99.8 % of the friction bound the regularised stiction creeps at under 1e-4 m/s, at the
    # bound: with the threshold at 0 every step refines the contacts, with the default few do
    bound = 0.5 * 9.81
    passes_always, moved_always = pushed_box(0.0, bound - 0.01)
    passes, moved = pushed_box(1e-4, bound - 0.01)
    assert np.all(passes_always > 0)
    assert np.count_nonzero(passes) < 0.25 * len(passes), passes
    assert 0 < moved_always[0] < 1e-4 and abs(moved[0] - moved_always[0]) < 1e-6
    # the cone model's separation of the slow slip stays below a tenth of a micrometre
    assert abs(moved[2]) < 1e-7 and abs(moved_always[2]) < 1e-7
    # a box pushed well past its bound slides, and is refined in every step with either threshold
    passes_sliding, moved_sliding = pushed_box(1e-4, 2 * bound)
    assert np.all(passes_sliding > 0) and moved_sliding[0] > 1e-2 and abs(moved_sliding[2]) < 1e-7


def test_min_slip_must_not_be_negative(scene):
    params = scene.get_solver_params()
    params.friction_pass_min_slip = -1.0
    with pytest.raises(sdp.Error, match="friction_pass_min_slip"):
        scene.set_solver_params(params)
