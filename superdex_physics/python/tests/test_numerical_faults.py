"""Numerical faults in scene.step: a non-finite result or a diverged solve is detected (a solve
stopped by its iteration limit is not a fault: its status is STOPPED).
Under NumericalFaultPolicy.RAISE (the default) step raises superdex.physics.Error naming the actor
and the quantity, and the whole scene keeps its last good state, bitwise; under WARN_AND_CLAMP the
step goes on, the faulty island's bodies stay where they were with zero velocity, the others move,
and each fault is a RuntimeWarning."""

import warnings

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import real_dtype, two_link_arm


def state_bytes(scene):
    out = bytearray()
    scene.capture_state_to_bytes(out)
    return bytes(out)


def overflowing_arm(scene):
    """The two-link arm with velocities whose Coriolis forces overflow the scalar type."""
    arm = two_link_arm(scene)
    arm.set_articulated_pose_from_joints([0.2, 0.1])
    huge = float(np.finfo(real_dtype()).max)
    arm.set_articulated_joint_velocities([huge, -huge])
    return arm


def falling_ball(scene):
    return scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1), mass=1.0,
                                    world_from_local=sdp.TransformRT(translation=[5, 0, 2]))


def ball_on_ground(scene):
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    return scene.create_rigid_actor(name="box", shape=sdp.create_box_shape([0.1, 0.1, 0.1]), mass=1.0,
                                    world_from_local=sdp.TransformRT(translation=[0, 0, 0.095]))


def test_default_policy_is_raise(scene):
    assert scene.get_numerical_fault_policy() == sdp.NumericalFaultPolicy.RAISE


def test_raise_names_actor_and_quantity_and_keeps_the_last_good_state(scene):
    ball = falling_ball(scene)
    scene.step(0.01)
    arm = overflowing_arm(scene)
    before = state_bytes(scene)
    t = scene.get_total_simulation_time()
    with pytest.raises(sdp.Error, match=r"scene 'test', actor 'arm' \(handle \d+\): velocities became non-finite .*last good state"):
        scene.step(0.01)
    assert state_bytes(scene) == before, "nothing of the failed step was committed, the ball included"
    assert scene.get_total_simulation_time() == t
    # the engine stays usable: calm the arm down and step again
    arm.set_articulated_joint_velocities([0.0, 0.0])
    z = ball.get_root_transform().translation[2]
    scene.step(0.01)
    assert ball.get_root_transform().translation[2] < z
    assert scene.get_last_numerical_faults() == []


def test_huge_external_force_on_a_rigid_body(scene):
    ball = falling_ball(scene)
    big = float(np.finfo(real_dtype()).max)
    ball.set_external_forces_on_dofs([0, 1, 2], [big, big, big])
    with pytest.raises(sdp.Error, match=r"actor 'ball' .*: (velocities|positions) became non-finite"):
        for _ in range(3):
            scene.step(0.01)


def test_warn_and_clamp_stops_the_faulty_actor_and_steps_the_others(scene):
    scene.set_numerical_fault_policy(sdp.NumericalFaultPolicy.WARN_AND_CLAMP)
    assert scene.get_numerical_fault_policy() == sdp.NumericalFaultPolicy.WARN_AND_CLAMP
    ball = falling_ball(scene)
    arm = overflowing_arm(scene)
    pose = arm.get_articulated_pose().copy()
    z = ball.get_root_transform().translation[2]
    with pytest.warns(RuntimeWarning, match=r"actor 'arm' .*velocities became non-finite .*last good positions with zero velocity"):
        scene.step(0.01)
    np.testing.assert_array_equal(arm.get_articulated_pose(), pose)
    np.testing.assert_array_equal(arm.get_articulated_joint_velocities(), [0.0, 0.0])
    assert ball.get_root_transform().translation[2] < z, "the ball's island stepped"
    assert scene.get_total_simulation_time() == pytest.approx(0.01)
    (fault,) = scene.get_last_numerical_faults()
    assert fault.actor == arm.get_handle() and fault.quantity == "velocities"
    # the next step is clean: no warning, no fault
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        scene.step(0.01)
    assert scene.get_last_numerical_faults() == []
    assert np.all(np.isfinite(arm.get_articulated_pose()))


def test_iteration_limit_is_not_a_fault(scene):
    """A solve stopped by max_iter keeps its unconverged but finite result, silently (SuperDex's
    STOPPED status), under either policy."""
    box = ball_on_ground(scene)
    box.set_velocity([1.0, 0.0, -0.5], [0.0, 0.0, 2.0])
    params = scene.get_solver_params()
    params.non_linear_solver.max_iter = 1
    scene.set_solver_params(params)
    start = state_bytes(scene)
    for policy in (sdp.NumericalFaultPolicy.RAISE, sdp.NumericalFaultPolicy.WARN_AND_CLAMP):
        scene.restore_state_from_bytes(start)
        scene.set_numerical_fault_policy(policy)
        t = scene.get_total_simulation_time()
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            scene.step(0.01)
        assert scene.get_total_simulation_time() == pytest.approx(t + 0.01)
        stats = scene.get_solver_stats()
        assert stats.convergence_status == sdp.ConvergenceStatus.STOPPED and stats.max_non_linear_iters == 1
        assert box.get_convergence_status() == sdp.ConvergenceStatus.STOPPED
        assert scene.get_last_numerical_faults() == []


def test_diverged_solve_raises_or_warns(scene):
    """A solve whose residual passes the divergence tolerances is a fault (here the tolerances are
    made tiny, so that the first residual passes them): RAISE keeps the last good state, and
    WARN_AND_CLAMP stops the island, reporting quantity "convergence" and status DIVERGED."""
    box = ball_on_ground(scene)
    box.set_velocity([1.0, 0.0, -0.5], [0.0, 0.0, 2.0])
    params = scene.get_solver_params()
    params.non_linear_solver.explosion_control = True
    params.non_linear_solver.abs_div_tol = 1e-12
    params.non_linear_solver.rel_div_tol = 1e-12
    scene.set_solver_params(params)
    before = state_bytes(scene)
    with pytest.raises(sdp.Error, match=r"actor 'box' .*the solver diverged \(scaled residual .* Newton iterations, beyond the divergence tolerances\)"):
        scene.step(0.01)
    assert state_bytes(scene) == before
    assert scene.get_total_simulation_time() == 0
    scene.set_numerical_fault_policy(sdp.NumericalFaultPolicy.WARN_AND_CLAMP)
    pose = box.get_root_transform()
    with pytest.warns(RuntimeWarning, match="actor 'box' .*diverged.*last good positions with zero velocity"):
        scene.step(0.01)
    assert scene.get_total_simulation_time() == pytest.approx(0.01)
    assert [f.quantity for f in scene.get_last_numerical_faults()] == ["convergence"]
    assert scene.get_last_numerical_faults()[0].actor == box.get_handle()
    assert scene.get_solver_stats().convergence_status == sdp.ConvergenceStatus.DIVERGED
    assert box.get_convergence_status() == sdp.ConvergenceStatus.DIVERGED
    assert box.get_root_transform() == pose
    np.testing.assert_array_equal(box.get_linear_velocity(), [0, 0, 0])
    np.testing.assert_array_equal(box.get_angular_velocity(), [0, 0, 0])


def test_warnings_can_be_made_errors(scene):
    # a script that wants the warning to stop it can say so with the warnings module
    scene.set_numerical_fault_policy(sdp.NumericalFaultPolicy.WARN_AND_CLAMP)
    overflowing_arm(scene)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(RuntimeWarning, match="actor 'arm'"):
            scene.step(0.01)


def test_policy_argument_is_checked(scene):
    # a TypeError (as SuperDex's bindings raise for a mistyped argument) naming the argument, the
    # type it takes and the type it got
    with pytest.raises(TypeError, match=r"set_numerical_fault_policy\(self, policy: [\w.]*NumericalFaultPolicy\)(.|\n)*"
                                        r"Invoked with types: [\w.]*Scene, str"):
        scene.set_numerical_fault_policy("raise")


def test_soft_body_fault_names_node_velocities(scene):
    nodes = np.array([[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]], dtype=float)
    soft = scene.create_soft_actor(name="jelly", shape=sdp.create_tet_mesh_shape(nodes, np.array([[0, 1, 2, 3]])))
    # the actor frame stays put (no recentering), so that unchanged world positions read as
    # bitwise unchanged local ones
    soft.set_recentering_params(sdp.RecenteringParams(use_recentering=False))
    soft.register_query_and_compute(sdp.QueryType.NODE_POSITIONS)
    frame = soft.get_root_transform()

    def positions():
        assert soft.get_root_transform() == frame
        return np.array(soft.get_node_positions_local())

    # a pinned node sent to the largest finite coordinate: its velocity overflows
    soft.add_boundary_condition_nodes_world([0], [[float(np.finfo(real_dtype()).max), 0, 0]])
    before = positions()
    with pytest.raises(sdp.Error, match=r"^step: scene 'test', actor 'jelly' \(handle \d+\): node velocities became non-finite[^\n]*$"):
        scene.step(0.01)
    np.testing.assert_array_equal(positions(), before)
    scene.set_numerical_fault_policy(sdp.NumericalFaultPolicy.WARN_AND_CLAMP)
    with pytest.warns(RuntimeWarning, match="actor 'jelly'.*node velocities"):
        scene.step(0.01)
    np.testing.assert_array_equal(positions(), before)
    assert [f.quantity for f in scene.get_last_numerical_faults()] == ["node velocities"]
