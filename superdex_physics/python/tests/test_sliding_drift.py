"""Coulomb friction without the cone model's drift (SolverParams.implicit_step.drift_correction_iterations).

In the convex cone model a contact sliding at speed s moves apart at mu s: a box pushed along
the ground rises, and boxes sliding on each other separate. The Newton solve corrects each
contact's normal target for that drift during its first iterations, so that a sliding contact
stays closed while its friction is mu times its normal force. The references are Coulomb's law
for boxes pushed past their friction bound (their accelerations in closed form) and the ground
they must stay on; 0 correction iterations (the pure cone model) shows the drift each test would
otherwise see.
"""

import numpy as np
import pytest

import superdex.physics as sdp
from contact_helpers import G, add_box, add_ground, position, vec

DT = 0.004
HALF = 0.05


def make_scene(name, correction_iterations=None):
    scene = sdp.create_scene(name)
    scene.set_gravity([0, 0, -G])
    if correction_iterations is not None:
        params = scene.get_solver_params()
        params.implicit_step.drift_correction_iterations = correction_iterations
        scene.set_solver_params(params)
    add_ground(scene, mu=0.5)
    return scene


def pushed_box(force, correction_iterations=None, steps=50):
    """A 1 kg box resting on the ground (mu 0.5), then pushed along x by `force` (N) for `steps`
    steps. Returns the box's displacement (m) and its mean acceleration along x (m/s^2), from its
    velocity."""
    scene = make_scene(f"pushed_{force}_{correction_iterations}", correction_iterations)
    box = add_box(scene, "box", [0, 0, HALF], half=HALF, mass=1.0, mu=0.5)
    for _ in range(50):
        scene.step(DT)
    start = position(box)
    box.set_external_forces_on_dofs([0], [force])
    for _ in range(steps):
        scene.step(DT)
    return position(box) - start, vec(box.get_linear_velocity())[0] / (steps * DT)


def test_a_sliding_box_stays_on_the_ground(engine):
    bound = 0.5 * G
    moved, a = pushed_box(2 * bound)
    # Coulomb: (F - mu m g) / m, and no motion off the ground
    assert a == pytest.approx(2 * bound - bound, rel=0.01)
    assert abs(moved[2]) < 1e-7 and abs(moved[1]) < 1e-7
    # the pure cone model lifts it by mu times its slip each step
    moved_cone, _ = pushed_box(2 * bound, correction_iterations=0)
    assert moved_cone[2] > 1e-5


def test_the_first_correction_comes_from_the_last_steps_slip(engine):
    """With one correction iteration, only the one made at the start of each solve acts: at the
    box's velocities of the last step, where it slid at nearly the same speed. It removes most of
    the cone model's rise; it would be none if it waited for the solve's first iterate."""
    bound = 0.5 * G
    moved_cone, _ = pushed_box(2 * bound, correction_iterations=0)
    moved_once, a = pushed_box(2 * bound, correction_iterations=1)
    assert a == pytest.approx(2 * bound - bound, rel=0.01)
    assert 0 <= moved_once[2] < 0.05 * moved_cone[2]


def test_a_box_pushed_below_its_bound_only_creeps(engine):
    bound = 0.5 * G
    moved, _ = pushed_box(bound - 0.01)
    assert 0 <= moved[0] < 1e-4
    assert abs(moved[2]) < 1e-7


def sliding_stack(correction_iterations=None, steps=50):
    """A 1 kg box on top of a 2 kg box on the ground, all contacts mu 0.5; the bottom box is
    pushed along x by 30 N, harder than the top one's friction can follow. Returns both boxes'
    displacements (m) and mean accelerations along x (m/s^2) over `steps` steps after the push."""
    scene = make_scene(f"stack_{correction_iterations}", correction_iterations)
    bottom = add_box(scene, "bottom", [0, 0, HALF], half=HALF, mass=2.0, mu=0.5)
    top = add_box(scene, "top", [0, 0, 3 * HALF], half=HALF, mass=1.0, mu=0.5)
    for _ in range(50):
        scene.step(DT)
    start = [position(bottom), position(top)]
    bottom.set_external_forces_on_dofs([0], [30.0])
    for _ in range(steps):
        scene.step(DT)
    accelerations = [vec(b.get_linear_velocity())[0] / (steps * DT) for b in (bottom, top)]
    return position(bottom) - start[0], position(top) - start[1], accelerations


def test_boxes_sliding_on_each_other_stay_in_contact(engine):
    moved_bottom, moved_top, (a_bottom_measured, a_top_measured) = sliding_stack()
    # Coulomb on both sliding contacts: the top box is dragged at mu g, the bottom one pushed by
    # 30 N against the ground's mu (m1 + m2) g and the top box's mu m2 g
    a_top = 0.5 * G
    a_bottom = (30.0 - 0.5 * 3.0 * G - 0.5 * 1.0 * G) / 2.0
    assert a_top_measured == pytest.approx(a_top, rel=0.01)
    assert a_bottom_measured == pytest.approx(a_bottom, rel=0.01)
    assert abs(moved_bottom[2]) < 1e-6 and abs(moved_top[2]) < 1e-6
    # the pure cone model separates both contacts
    cone_bottom, cone_top, _ = sliding_stack(correction_iterations=0)
    assert cone_bottom[2] > 1e-5 and cone_top[2] - cone_bottom[2] > 1e-5


def test_a_settled_pile_is_at_rest(engine):
    """Two staggered layers of 3 x 3 tilted 10 cm cubes dropped on the ground: after 1.4 s every
    box moves slower than 0.1 mm/s (the corrections of the landing's sliding contacts leave no
    jitter behind)."""
    scene = make_scene("pile")
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
    for _ in range(350):
        scene.step(DT)
    before = np.array([position(b) for b in boxes])
    for _ in range(25):
        scene.step(DT)
    speed = np.linalg.norm(np.array([position(b) for b in boxes]) - before, axis=1) / (25 * DT)
    assert np.max(speed) < 1e-4, speed
    assert scene.get_solver_stats().convergence_status == sdp.ConvergenceStatus.CONVERGED


def test_correction_iterations_must_not_be_negative(scene):
    params = scene.get_solver_params()
    params.implicit_step.drift_correction_iterations = -1
    with pytest.raises(sdp.Error, match="implicit_step.drift_correction_iterations"):
        scene.set_solver_params(params)
