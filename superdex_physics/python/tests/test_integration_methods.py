"""SolverParams.integration_method: BACKWARD_EULER (the default) and BDF2, against the methods'
own recurrences written here and against their orders of convergence:

- a mass on an implicit spring (a prismatic joint's drive) follows, step for step, the backward
  Euler recurrence, or with BDF2 the BDF2 recurrence started by one backward Euler step;
- a soft block swinging under gravity converges at second order in the time step with BDF2
  (halving the step quarters the change), at first order with backward Euler, and BDF2 takes far
  less energy out of its swing;
- the first step after the state is set from outside is backward Euler again (no history to
  extrapolate from), and a step of another size too.
"""

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import node_positions_world, soft_actor, soft_material

MASS, STIFFNESS = 2.0, 50.0  # kg, N/m: omega = 5 rad/s


def set_method(scene, method):
    params = scene.get_solver_params()
    params.integration_method = method
    scene.set_solver_params(params)


def spring_slider(scene):
    """A box on a prismatic joint along x, no gravity, held by an implicit drive spring to q = 0."""
    scene.set_gravity([0, 0, 0])
    params = sdp.ArticulatedActorParams(name="slider")
    params.joints = [sdp.ArticulatedJointParams(type=sdp.ArticulatedJointType.PRISMATIC, axis=[1, 0, 0])]
    params.links = [sdp.ArticulatedLinkParams(parent_link=-1, shape=sdp.create_box_shape(half_extents=[0.05, 0.05, 0.05]), mass=MASS)]
    actor = scene.create_articulated_actor(params)
    actor.set_joint_drive(0, stiffness=STIFFNESS)
    return actor


def recurrence(q0, h, steps, bdf2):
    """The spring's m q'' = -k q by backward Euler, or by BDF2 after one backward Euler step: each
    step solves x+ = xs + c v+, v+ = vs - c w^2 x+ from the start (xs, vs) and step c (h; for
    BDF2, the extrapolation 4/3 x - 1/3 x- of the last two states and 2/3 h)."""
    w2 = STIFFNESS / MASS
    xs = [(q0, 0.0)]
    for n in range(steps):
        (x, v) = xs[-1]
        if bdf2 and n > 0:
            (xp, vp) = xs[-2]
            x, v, c = 4 / 3 * x - 1 / 3 * xp, 4 / 3 * v - 1 / 3 * vp, 2 * h / 3
        else:
            c = h
        v_next = (v - c * w2 * x) / (1 + c * c * w2)
        xs.append((x + c * v_next, v_next))
    return np.array([x for x, _ in xs[1:]])


@pytest.mark.parametrize("method", ["BACKWARD_EULER", "BDF2"])
def test_a_spring_follows_the_methods_recurrence(scene, method):
    set_method(scene, getattr(sdp.IntegrationMethod, method))
    actor = spring_slider(scene)
    actor.set_articulated_pose_from_joints(np.array([0.1]))
    h, steps = 0.02, 150
    got = []
    for _ in range(steps):
        scene.step(h)
        got.append(float(actor.get_articulated_pose()[0]))
    expected = recurrence(0.1, h, steps, bdf2=method == "BDF2")
    tol = 1e-9 if sdp.uses_double_precision() else 2e-5
    np.testing.assert_allclose(got, expected, atol=tol)
    # three periods (0.4 pi s) in: backward Euler has lost most of the swing, BDF2 little of it
    other = recurrence(0.1, h, steps, bdf2=method != "BDF2")
    assert np.abs(np.asarray(got) - other).max() > 1e-3


def test_the_history_restarts_after_the_state_is_set_or_the_step_changes(scene):
    """BDF2 extrapolates from the last two steps only while nothing else moved the state: a pose
    set between steps, or a different step size, makes the next step a backward Euler one."""
    set_method(scene, sdp.IntegrationMethod.BDF2)
    actor = spring_slider(scene)
    actor.set_articulated_pose_from_joints(np.array([0.1]))
    h = 0.02
    for _ in range(5):
        scene.step(h)
    # set the same pose again: bitwise unchanged, the history holds
    actor.set_articulated_pose_from_joints(np.asarray(actor.get_articulated_pose(), dtype=float))
    q, v = float(actor.get_articulated_pose()[0]), float(actor.get_articulated_joint_velocities()[0])
    scene.step(h)
    held = float(actor.get_articulated_pose()[0])
    # a new state: the same values through set_pose + set velocities rebuilt in another scene
    other = sdp.create_scene("restart")
    set_method(other, sdp.IntegrationMethod.BDF2)
    twin = spring_slider(other)
    twin.set_articulated_pose_from_joints(np.array([q]))
    twin.set_articulated_joint_velocities(np.array([v]))
    other.step(h)
    restarted = float(twin.get_articulated_pose()[0])
    w2 = STIFFNESS / MASS
    v_be = (v - h * w2 * q) / (1 + h * h * w2)
    assert restarted == pytest.approx(q + h * v_be, abs=1e-6)  # backward Euler from (q, v)
    assert abs(held - restarted) > 1e-5  # the held history stepped by BDF2
    sdp.destroy_scene(other)
    # a step of another size: backward Euler over it
    q, v = float(actor.get_articulated_pose()[0]), float(actor.get_articulated_joint_velocities()[0])
    scene.step(h / 2)
    v_be = (v - h / 2 * w2 * q) / (1 + (h / 2) ** 2 * w2)
    assert float(actor.get_articulated_pose()[0]) == pytest.approx(q + h / 2 * v_be, abs=1e-6)


def test_other_methods_are_refused_naming_the_field(scene):
    params = scene.get_solver_params()
    params.integration_method = sdp.IntegrationMethod.DIRK22
    with pytest.raises(sdp.Error, match="integration_method"):
        scene.set_solver_params(params)


def swinging_block(method, h, seconds):
    """A soft block (2 x 2 x 2 cells, 10 cm, E = 20 kPa) with its top face held, released
    undeformed under gravity: the position of its bottom corner after `seconds` (m), and the
    largest downward speed of that corner over the last half of the run (m/s)."""
    from test_soft_bodies import box_tet_mesh

    sdp.initialize(num_worker_threads=0)
    scene = sdp.create_scene("block")
    scene.set_gravity([0, 0, -9.81])
    set_method(scene, getattr(sdp.IntegrationMethod, method))
    params = scene.get_solver_params()
    params.non_linear_solver.abs_tol = 1e-12
    params.non_linear_solver.rel_tol = 1e-12
    scene.set_solver_params(params)
    nodes, tets = box_tet_mesh([0.1, 0.1, 0.1], [2, 2, 2])
    top = np.flatnonzero(np.isclose(nodes[:, 2], 0.1))
    block = soft_actor(scene, "block", sdp.create_tet_mesh_shape(nodes, tets),
                       material=soft_material(youngs_modulus=2e4, poisson_ratio=0.3, density=1000.0), fixed_nodes=top, recentering=False)
    corner = int(np.argmin(np.linalg.norm(nodes - [0.1, 0.1, 0.0], axis=1)))
    steps = int(round(seconds / h))
    speeds = []
    for k in range(steps):
        before = node_positions_world(block)[corner, 2]
        scene.step(h)
        if k >= steps // 2:
            speeds.append((before - node_positions_world(block)[corner, 2]) / h)
    x = node_positions_world(block)[corner].copy()
    sdp.shutdown()
    return x, max(speeds)


@pytest.mark.skipif(not sdp.uses_double_precision(), reason="convergence orders need the double build's solver tolerances")
def test_bdf2_converges_at_second_order_on_a_soft_body():
    """Halving the step (2, 1, 0.5 ms over 0.1 s): the change of the corner's position nearly
    quarters with BDF2 (ratio > 3, tending to 4) and only halves with backward Euler (ratio < 2.2,
    tending to 2); at a coarse step (8 ms) BDF2's swing keeps more of its speed."""
    results = {}
    for method in ("BACKWARD_EULER", "BDF2"):
        xs = [swinging_block(method, h, 0.1)[0] for h in (0.002, 0.001, 0.0005)]
        d1, d2 = np.linalg.norm(xs[0] - xs[1]), np.linalg.norm(xs[1] - xs[2])
        results[method] = d1 / d2
    assert results["BDF2"] > 3.0, results
    assert results["BACKWARD_EULER"] < 2.2, results
    assert swinging_block("BDF2", 0.008, 0.2)[1] > swinging_block("BACKWARD_EULER", 0.008, 0.2)[1]
