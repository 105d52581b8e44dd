"""Inverse kinematics (superdex.physics.experimental IK solver) against independent references: a
planar two-link arm against its closed-form solution, the UR5 of example-robot-data reaching a
pose that Pinocchio's own forward kinematics (of the same URDF) checks within 1e-4 m and 1e-3 rad,
a joint limit that holds against an unreachable target; and the solver's API."""

import math

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import articulation, joint, link

L1, L2 = 0.4, 0.3
DOUBLE = sdp.uses_double_precision()


def planar_arm(scene, elbow_limits=None):
    """A welded base, a shoulder and an elbow about Y; the tip link's origin sits L2 along X from
    the elbow (a third link on a Hard joint marks it)."""
    inertia = [1e-3, 0, 0, 1e-3, 0, 1e-3]
    elbow = {}
    if elbow_limits is not None:
        elbow = {"min_limit": [0, elbow_limits[0], 0], "max_limit": [0, elbow_limits[1], 0]}
    links = [link("base", mass=1.0, moment_of_inertia=inertia),
             link("upper", parent=0, mass=1.0, center_of_mass=[L1 / 2, 0, 0], moment_of_inertia=inertia),
             link("lower", parent=1, mass=1.0, center_of_mass=[L2 / 2, 0, 0], moment_of_inertia=inertia),
             link("tip", parent=2, mass=0.1, moment_of_inertia=inertia)]
    joints = [joint("weld", "hard"), joint("shoulder", "revolute", axis=[0, 1, 0]),
              joint("elbow", "revolute", at=[L1, 0, 0], axis=[0, 1, 0], **elbow), joint("tip", "hard", at=[L2, 0, 0])]
    return articulation(scene, "arm", links, joints)


def tip_position(arm):
    return np.asarray(arm.get_articulated_link_transforms()[3].translation, dtype=float)


@pytest.fixture
def ik_scene(engine):
    scene = sdp.create_scene("ik")
    yield scene
    sdp.destroy_scene(scene)


def test_a_planar_arm_reaches_the_closed_form_solution(ik_scene):
    arm = planar_arm(ik_scene)
    arm.set_articulated_pose_from_joints(np.array([-0.3, 0.6]))  # start on the elbow-down branch
    solver = sdp.experimental.create_ik_solver(ik_scene)
    solver.set_solver_params(sdp.experimental.IKSolverParams(max_iter=100, abs_tol=1e-9, position_error_thres=1e-4))
    # about +Y a positive angle turns X towards -Z: the tip at (x, -z) for angles a, b is
    # x = L1 cos a + L2 cos(a + b), z = -(L1 sin a + L2 sin(a + b))
    x, z = 0.5, -0.2
    tip = arm.get_nested_link_actors()[3]
    target = solver.create_position_target(tip, [0, 0, 0], [x, 0, z], 1e4)
    assert solver.solve_ik()
    c = (x * x + z * z - L1 * L1 - L2 * L2) / (2 * L1 * L2)
    b = math.acos(c)  # elbow down (b > 0)
    a = math.atan2(-z, x) - math.atan2(L2 * math.sin(b), L1 + L2 * math.cos(b))
    np.testing.assert_allclose(arm.get_articulated_pose(), [a, b], atol=1e-6 if DOUBLE else 1e-3)
    np.testing.assert_allclose(tip_position(arm), [x, 0, z], atol=1e-4)
    np.testing.assert_allclose(arm.get_articulated_joint_velocities(), 0, atol=0)
    # the target moves with its constraint; the next solve follows
    target.set_target_position([0.3, 0, -0.45])
    assert solver.solve_ik()
    np.testing.assert_allclose(tip_position(arm), [0.3, 0, -0.45], atol=1e-4)


def test_a_joint_limit_holds_against_an_unreachable_target(ik_scene):
    arm = planar_arm(ik_scene, elbow_limits=(0.0, 0.5))
    arm.set_articulated_pose_from_joints(np.array([0.0, 0.2]))
    solver = sdp.experimental.create_ik_solver(ik_scene)
    solver.set_solver_params(sdp.experimental.IKSolverParams(max_iter=100, abs_tol=1e-9))
    # 0.25 m from the shoulder needs the elbow at 2.0 rad: it stops at its limit, short of it
    tip = arm.get_nested_link_actors()[3]
    solver.create_position_target(tip, [0, 0, 0], [0.25, 0, 0], 1e4)
    assert not solver.solve_ik()
    elbow = float(arm.get_articulated_pose()[1])
    assert elbow == pytest.approx(0.5, abs=1e-9 if DOUBLE else 1e-6)
    # the closest the limited arm gets: the tip's circle of radius |elbow-to-tip chord| about the shoulder
    reach = math.hypot(L1 + L2 * math.cos(0.5), L2 * math.sin(0.5))
    assert float(np.linalg.norm(tip_position(arm))) == pytest.approx(reach, abs=1e-6 if DOUBLE else 1e-4)


def test_parameters_targets_and_destruction(ik_scene):
    params = sdp.experimental.IKSolverParams()
    assert (params.max_iter, params.abs_tol, params.rel_tol) == (20, pytest.approx(1e-2), pytest.approx(1e-8))
    arm = planar_arm(ik_scene)
    solver = sdp.experimental.create_ik_solver(ik_scene)
    tip = arm.get_nested_link_actors()[3]
    with pytest.raises(sdp.Error, match="weight must be finite and > 0"):
        solver.create_position_target(tip, [0, 0, 0], [0.5, 0, 0], 0.0)
    with pytest.raises(sdp.Error, match="max_iter"):
        solver.set_solver_params(sdp.experimental.IKSolverParams(max_iter=-1))
    before = ik_scene.get_num_constraints()
    solver.create_position_target(tip, [0, 0, 0], [0.5, 0, 0], 1e3)
    solver.create_position_target(tip, [0, 0, 0], [0.6, 0, 0], 1e3)  # replaces the first
    rotation = solver.create_rotation_target(tip, [0, 0, 0], [0, 0.3, 0], 10.0)
    assert rotation.get_type() == sdp.ConstraintType.RIGID_PIVOT_ROTATION
    assert ik_scene.get_num_constraints() == before + 2
    solver.clear_position_target(tip)
    solver.clear_rotation_target(tip)
    assert ik_scene.get_num_constraints() == before
    assert sdp.experimental.is_valid_ik_solver(solver)
    sdp.experimental.destroy_ik_solver(solver)
    assert not sdp.experimental.is_valid_ik_solver(solver)
    assert not sdp.is_valid_scene(ik_scene)  # the solver's scene goes with it
    with pytest.raises(sdp.Error, match="destroyed"):
        solver.solve_ik()


@pytest.mark.skipif(not DOUBLE, reason="the Pinocchio check needs double precision")
def test_the_ur5_reaches_a_pose_that_pinocchio_confirms(ik_scene):
    pin = pytest.importorskip("pinocchio")
    import superdex.robotics as sdr
    from superdex.robot_files import example_robot_data_urdfs

    urdf = next(u for u in example_robot_data_urdfs() if u.as_posix().endswith("ur_description/urdf/ur5_robot.urdf"))
    bot = sdr.create_bot(ik_scene, sdr.load_bot_prefab_from_urdf_file(str(urdf), fixed_base=True), sdr.create_context())
    arm = bot.get_articulated_actor()
    info = arm.get_articulated_shape_info()
    names = list(info.link_names)
    model = pin.buildModelFromUrdf(str(urdf))
    data = model.createData()
    # DOFs by joint name
    perm = np.zeros(arm.get_num_dofs(), dtype=int)
    for i, joint_name in enumerate(info.joint_names):
        d = info.dof_info[i]
        if d.get_size() == 1:
            perm[d.offset] = model.idx_qs[model.getJointId(joint_name)]
    tool = "wrist_3_link"
    frame = model.getFrameId(tool, pin.FrameType.BODY)

    def pinocchio_pose(q_ours):
        q = np.zeros(model.nq)
        q[perm] = q_ours
        pin.framesForwardKinematics(model, data, q)
        return data.oMf[frame].translation.copy(), data.oMf[frame].rotation.copy()

    rng = np.random.default_rng(5)
    goal = rng.uniform(-1.2, 1.2, arm.get_num_dofs())
    p_goal, R_goal = pinocchio_pose(goal)
    arm.set_articulated_pose_from_joints(goal + rng.uniform(-0.3, 0.3, goal.size))
    solver = sdp.experimental.create_ik_solver(ik_scene)
    solver.set_solver_params(sdp.experimental.IKSolverParams(max_iter=100, abs_tol=1e-10, position_error_thres=1e-4,
                                                             rotation_error_thres=1e-3))
    handle = arm.get_nested_link_actors()[names.index(tool)]
    rotation_vector = pin.log3(R_goal)
    solver.create_position_target(handle, [0, 0, 0], p_goal.tolist(), 1e4)
    solver.create_rotation_target(handle, [0, 0, 0], rotation_vector.tolist(), 1e2)
    assert solver.solve_ik()
    p, R = pinocchio_pose(np.asarray(arm.get_articulated_pose(), dtype=float))
    assert float(np.linalg.norm(p - p_goal)) < 1e-4
    assert float(np.linalg.norm(pin.log3(R.T @ R_goal))) < 1e-3
