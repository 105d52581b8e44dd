"""The physics API surface of API.md: lifecycle, scenes, value types, rigid and articulated actors."""

import threading
import time

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import real_dtype, two_link_arm


def test_lifecycle(engine):
    assert sdp.is_initialized()
    with pytest.raises(sdp.Error, match="already been initialized"):
        sdp.initialize(0)
    sdp.shutdown()
    assert not sdp.is_initialized()
    with pytest.raises(sdp.Error, match="not initialized"):
        sdp.create_scene("x")
    sdp.initialize(num_worker_threads=2)
    assert sdp.is_initialized()


def test_precision_matches_environment(engine):
    import os

    wanted = os.environ.get("SUPERDEX_PRECISION", "float") == "double"
    assert sdp.uses_double_precision() == wanted
    arm = two_link_arm(sdp.create_scene("s"))
    assert arm.get_articulated_joint_velocities().dtype == real_dtype()


def test_error_is_runtime_error():
    assert issubclass(sdp.Error, RuntimeError)


def test_gravity_and_time(scene):
    scene.set_gravity([0, 0, -3.0])
    np.testing.assert_allclose(scene.get_gravity(), [0, 0, -3.0])
    for _ in range(10):
        scene.step(0.01)
    assert scene.get_total_simulation_time() == pytest.approx(0.1)


def test_destroyed_scene_raises(engine):
    s = sdp.create_scene("gone")
    sdp.destroy_scene(s)
    with pytest.raises(sdp.Error, match="does not exist"):
        s.step(0.01)
    assert not sdp.is_valid_scene(s)
    sdp.destroy_scene(s)  # SuperDex: destroying a destroyed scene (or None) has no effect
    sdp.destroy_scene(None)
    with pytest.raises(sdp.Error, match="does not exist"):
        s.step(0.01)


def test_shutdown_invalidates_scenes():
    sdp.initialize(0)
    s = sdp.create_scene("s")
    sdp.shutdown()
    with pytest.raises(sdp.Error, match="shut down"):
        s.get_total_simulation_time()


def test_value_types():
    q = sdp.Quaternion.from_axis_angle([0, 0, 1], np.pi / 2)
    np.testing.assert_allclose(np.array(q), [0, 0, np.sqrt(0.5), np.sqrt(0.5)], atol=1e-6)
    assert len(q) == 4 and q[3] == pytest.approx(np.sqrt(0.5))
    t = sdp.TransformRT(rotation=q, translation=[1, 2, 3])
    np.testing.assert_allclose(np.array(t.translation), [1, 2, 3])
    np.testing.assert_allclose(np.array(t.rotation), np.array(q))
    assert np.array(sdp.TransformRT().rotation).tolist() == [0, 0, 0, 1]

    arr = sdp.DynamicArrayReal(3)
    view = np.asarray(arr)
    view[:] = [1, 2, 3]
    assert arr[2] == 3 and len(arr) == 3 and view.dtype == real_dtype()
    xs = sdp.DynamicArrayTransformRT(2)
    assert len(xs) == 2
    with pytest.raises(IndexError):
        xs[2]


def test_rigid_actor_static_and_dynamic(scene):
    box = sdp.create_box_shape([0.1, 0.2, 0.3])
    dyn = scene.create_rigid_actor(name="box", shape=box, density=500.0)
    assert dyn.get_type() == sdp.ActorType.RIGID
    assert dyn.get_mass() == pytest.approx(500.0 * 0.2 * 0.4 * 0.6, rel=1e-5)
    assert dyn.get_num_dofs() == 6
    heavy = scene.create_rigid_actor(sdp.RigidActorParams(name="heavy", shape=box, mass=3.0))
    assert heavy.get_mass() == pytest.approx(3.0)
    # SuperDex: given both, the mass takes precedence over the density
    both = scene.create_rigid_actor(name="both", shape=box, mass=2.0, density=500.0)
    assert both.get_mass() == pytest.approx(2.0)
    ground = scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    assert ground.get_num_dofs() == 0
    assert scene.get_actor(dyn.get_handle()) == dyn
    names = []
    scene.for_each_actor(lambda a: names.append(a.get_name()))
    assert names == ["box", "heavy", "both", "ground"]


def test_free_body_velocity_round_trip(scene):
    ball = scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1),
                                    world_from_local=sdp.TransformRT(sdp.Quaternion.from_axis_angle([1, 0, 0], 0.7), [0, 0, 1]))
    ball.set_velocity([1, 2, 3], [0.1, -0.2, 0.3])
    np.testing.assert_allclose(ball.get_linear_velocity(), [1, 2, 3], rtol=1e-5)
    np.testing.assert_allclose(ball.get_angular_velocity(), [0.1, -0.2, 0.3], rtol=1e-5)
    ball.set_root_transform(sdp.TransformRT(translation=[4, 5, 6]))
    np.testing.assert_allclose(np.array(ball.get_root_transform().translation), [4, 5, 6], rtol=1e-6)


def test_symmetric_mesh_body_reads_back_what_was_set(scene):
    """A cube meshed by five tetrahedra about its centre: its centre of mass is the centre to
    within a fiftieth of a rounding step of its size; velocities set at the identity
    orientation read back exactly, and so does a pose (the quaternion given, not one passed
    through a rotation matrix)."""
    nodes = np.array([[x, y, z] for z in (-0.1, 0.1) for y in (-0.1, 0.1) for x in (-0.1, 0.1)])
    tets = np.array([[0, 1, 2, 4], [6, 7, 4, 2], [5, 4, 7, 1], [3, 2, 1, 7], [1, 2, 4, 7]])
    box = scene.create_rigid_actor(name="box", shape=sdp.create_tet_mesh_shape(nodes, tets))
    eps = np.finfo(real_dtype()).eps
    assert np.all(np.abs(np.array(box.get_rigid_center_of_mass_local())) <= 0.02 * eps * 0.2)
    box.set_velocity(linear_vel=[1, 2, 3], angular_vel=[4, 5, 6])
    assert box.get_linear_velocity() == sdp.Real3(1, 2, 3)
    assert box.get_angular_velocity() == sdp.Real3(4, 5, 6)
    pose = sdp.TransformRT(rotation=sdp.normalize(sdp.Quaternion(0.1, 0.2, 0.3, 0.4)), translation=[1.0, 2.0, 3.0])
    box.set_root_transform(pose)
    assert box.get_root_transform() == pose


def test_articulation_api(scene):
    arm = two_link_arm(scene)
    assert arm.get_type() == sdp.ActorType.ARTICULATED
    assert arm.get_num_dofs() == 2
    links = arm.get_nested_link_actors()
    assert len(links) == 3
    link2 = scene.get_actor(links[2])
    # a link is a rigid actor nested in its articulation, named "<articulation>/<link>"
    assert link2.get_type() == sdp.ActorType.RIGID and link2.is_nested_link_actor()
    assert not arm.is_nested_link_actor()
    assert link2.get_articulated_actor() == arm.get_handle()
    assert link2.get_link_index() == 2
    assert link2.get_name() == "arm/l2"

    info = arm.get_articulated_shape_info()
    assert list(info.link_names) == ["base", "l1", "l2"]
    assert list(info.joint_names) == ["weld", "j1", "j2"]
    assert list(info.parents) == [-1, 0, 1]
    assert [d.offset for d in info.dof_info] == [0, 0, 1]
    assert [d.get_size() for d in info.dof_info] == [0, 1, 1]
    assert info.dof_info[1].rot_size == 1 and info.dof_info[1].trans_size == 0
    np.testing.assert_allclose(info.joint_axes[1], [0, 1, 0])

    arm.set_articulated_pose_from_joints([np.pi / 2, 0.0])
    pose = np.zeros(2, dtype=real_dtype())
    arm.get_articulated_pose(pose)
    np.testing.assert_allclose(pose, [np.pi / 2, 0], atol=1e-6)
    xforms = sdp.DynamicArrayTransformRT(3)
    arm.get_articulated_link_transforms(xforms)
    # rotating +90 deg about Y sends the arm's x axis to -z: the elbow is 0.5 m below the shoulder
    np.testing.assert_allclose(np.array(xforms[2].translation), [0, 0, 0.5], atol=1e-6)

    v = np.zeros(2, dtype=real_dtype())
    arm.set_articulated_joint_velocities([1.0, -2.0])
    out = arm.get_articulated_joint_velocities(out_velocities=v)
    assert out is v
    np.testing.assert_allclose(v, [1, -2])

    J = np.asarray(link2.get_articulated_jacobian())  # row-major 6 x num_dofs
    assert J.shape == (12,)
    J = J.reshape(6, 2)
    # shoulder column: w = (0, 1, 0), v = w x (p_elbow - p_shoulder); the elbow joint turns l2
    # about its own origin: angular only
    np.testing.assert_allclose(J[:, 0], [-0.5, 0, 0, 0, 1, 0], atol=1e-6)
    np.testing.assert_allclose(J[:, 1], [0, 0, 0, 0, 1, 0], atol=1e-6)
    # the same values into a caller-owned array, which is returned
    J_out = np.full(12, np.nan, dtype=real_dtype())
    assert link2.get_articulated_jacobian(out=J_out) is J_out
    np.testing.assert_array_equal(J_out, J.ravel())
    with pytest.raises(sdp.Error, match="get_articulated_jacobian: out"):
        link2.get_articulated_jacobian(out=np.zeros(6, dtype=real_dtype()))


def test_external_forces_replace_the_set(scene):
    arm = two_link_arm(scene)
    arm.set_external_forces_on_dofs([0, 1], [1.0, 2.0])
    np.testing.assert_allclose(arm.get_external_forces(), [1, 2])
    arm.set_external_forces_on_dofs(np.array([1]), np.array([5.0], dtype=np.float16))
    np.testing.assert_allclose(arm.get_external_forces(), [0, 5])
    arm.clear_external_forces()
    np.testing.assert_allclose(arm.get_external_forces(), [0, 0])


def test_gravity_compensation_holds_the_arm(scene):
    # tau = c(q, 0) exactly cancels gravity, so the arm stays where it is
    arm = two_link_arm(scene)
    arm.set_articulated_pose_from_joints([0.3, -0.6])
    for _ in range(200):
        arm.set_external_forces_on_dofs([0, 1], arm.get_articulated_bias_forces())
        scene.step(0.005)
    np.testing.assert_allclose(arm.get_articulated_pose(), [0.3, -0.6], atol=1e-3)


def test_step_releases_the_gil(engine):
    # a Python thread keeps running while other threads are inside step()
    scenes = [sdp.create_scene(f"s{i}") for i in range(2)]
    for s in scenes:
        for k in range(20):
            two_link_arm(s, name=f"arm{k}")
    ticks = []
    stop = threading.Event()

    def ticker():
        while not stop.is_set():
            ticks.append(1)

    def stepper(s):
        for _ in range(200):
            s.step(0.001)

    t = threading.Thread(target=ticker)
    t.start()
    workers = [threading.Thread(target=stepper, args=(s,)) for s in scenes]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    stop.set()
    t.join()
    assert len(ticks) > 0
    assert all(s.get_total_simulation_time() == pytest.approx(0.2) for s in scenes)


def test_solver_params_and_stats(scene):
    p = scene.get_solver_params()
    p.non_linear_solver.max_iter = 20
    scene.set_solver_params(p)
    assert scene.get_solver_params().non_linear_solver.max_iter == 20
    two_link_arm(scene, min_limit=[0, -0.1, 0], max_limit=[0, 0.1, 0])
    for _ in range(50):
        scene.step(0.01)
    stats = scene.get_solver_stats()
    assert stats.convergence_status == sdp.ConvergenceStatus.CONVERGED and stats.num_islands == 1
    assert stats.num_constraints >= 1  # the arm rests on its limits
    bad = sdp.SolverParams()
    bad.non_linear_solver.max_iter = 0
    with pytest.raises(sdp.Error, match="non_linear_solver.max_iter"):
        scene.set_solver_params(bad)


def test_step_times_lie_within_the_wall_time_around_the_steps(scene):
    """The step's own times (its time-stamp counter, calibrated against the steady clock over the
    process's first steps) add up to most of the wall time measured around the steps, never more,
    and each part of a single-threaded step lies within the step."""
    arms = [two_link_arm(scene, name=f"a{k}") for k in range(6)]
    for k, a in enumerate(arms):
        a.set_articulated_pose_from_joints([0.1 * k, 0.2])
    start = time.perf_counter()
    while time.perf_counter() - start < 0.1:  # past the counter's calibration
        scene.step(0.001)
    totals = 0.0
    wall = 0.0
    for _ in range(300):
        # the wall time around each step alone: reading the stats is no part of it
        t0 = time.perf_counter()
        scene.step(0.001)
        wall += time.perf_counter() - t0
        stats = scene.get_performance_stats()
        totals += stats.total_step_duration_sec
        for part in (stats.kinematics_duration_sec, stats.collision_duration_sec, stats.island_solve_duration_sec,
                     stats.solve_step_duration_sec):
            assert 0 <= part <= stats.total_step_duration_sec
    assert 0.25 * wall < totals <= wall


def test_threaded_engine_matches_single_threaded():
    results = []
    for threads in (0, 2):
        sdp.initialize(num_worker_threads=threads)
        s = sdp.create_scene("s")
        arms = [two_link_arm(s, name=f"a{k}") for k in range(4)]
        for k, a in enumerate(arms):
            a.set_articulated_pose_from_joints([0.1 * k, 0.2])
        for _ in range(100):
            s.step(0.01)
        results.append(np.concatenate([a.get_articulated_pose() for a in arms]))
        sdp.shutdown()
    np.testing.assert_array_equal(results[0], results[1])
