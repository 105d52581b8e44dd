"""The pose controller of articulated actors, against analytic references: a joint spring's sag
under gravity and the force it reports, its oscillation period, a ramp target followed without lag
(the damping follows the target's motion) or with the damping's lag D w / K (a reset target is at
rest), the damping alone towards a target velocity (one implicit step, exactly), a free body held
by its centre of mass (sag m g / K) and a pendulum held by its rotation (K theta = m g L cos theta);
targets in joint and link form agreeing; and its API (gains, broadcast, errors, ownership)."""

import math

import numpy as np
import pytest

import superdex.physics as sdp
from contact_helpers import rotation_matrix
from conftest import articulation, joint, link

M, L, ICOM = 1.0, 0.5, 1e-3
IPIVOT = ICOM + M * L * L  # the rod about its hinge (kg m^2)
G = 9.81
TIGHT = 1e-9 if sdp.uses_double_precision() else 2e-5


def arm(scene):
    """A welded base and a rod on a revolute joint about Y, its 1 kg at 0.5 m along X."""
    links = [
        link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
        link("rod", parent=0, mass=M, center_of_mass=[L, 0, 0], moment_of_inertia=[ICOM, 0, 0, ICOM, 0, ICOM]),
    ]
    return articulation(scene, "arm", links, [joint("weld", "hard"), joint("hinge", "revolute", axis=[0, 1, 0])])


def joint_gains(stiffness, damping=0.0, saturation=-1.0):
    """Joint tracking on the hinge only (the weld has no controller)."""
    params = sdp.PoseControllerParams(2)
    params.joint_tracking[1] = sdp.PoseTrackingParams(stiffness=stiffness, damping=damping, saturation=saturation)
    return params


def q_of(actor):
    return float(actor.get_articulated_pose()[0])


def test_joint_tracking_sags_by_the_gravity_torque_and_reports_it(scene):
    a = arm(scene)
    K = 200.0
    a.add_articulated_pose_controller(joint_gains(K, 5.0))
    a.register_query(sdp.QueryType.ARTICULATED_CONTROLLER_FORCE)
    for _ in range(2000):
        scene.step(0.005)
    q = q_of(a)
    # balance: K (0 - q) = -m g L cos q (gravity turns the horizontal rod by +q about +Y)
    assert -K * q + M * G * L * math.cos(q) == pytest.approx(0, abs=1e-3 * M * G * L)
    assert float(a.get_articulated_controller_force()[0]) == pytest.approx(-M * G * L * math.cos(q), rel=1e-3)


def test_joint_tracking_oscillates_with_the_spring_period(scene):
    scene.set_gravity([0, 0, 0])
    a = arm(scene)
    K, dt = 40.0, 1e-3
    a.add_articulated_pose_controller(joint_gains(K))
    a.set_articulated_pose_from_joints(np.array([0.1]))  # the target follows, to 0.1 at rest
    a.reset_articulated_target_pose(np.array([0.0]))
    qs = []
    for _ in range(3000):
        scene.step(dt)
        qs.append(q_of(a))
    qs = np.asarray(qs)
    crossings = [(i + 1 + qs[i] / (qs[i] - qs[i + 1])) * dt for i in range(len(qs) - 1) if qs[i] > 0 >= qs[i + 1]]
    assert len(crossings) >= 2
    assert float(np.mean(np.diff(crossings))) == pytest.approx(2 * math.pi * math.sqrt(IPIVOT / K), rel=1e-2)


@pytest.mark.parametrize("reset", [False, True])
def test_a_ramp_target_is_followed_without_lag_unless_reset_to_rest(scene, reset):
    """q* = w t set every step: the damping follows the target's motion, so the steady error is 0;
    reset each step, the target is at rest and the damping holds the rod back by D w / K."""
    scene.set_gravity([0, 0, 0])
    a = arm(scene)
    K, D, w, dt = 400.0, 20.0, 0.5, 0.005
    a.add_articulated_pose_controller(joint_gains(K, D))
    t = 0.0
    for _ in range(800):
        t += dt
        target = np.array([w * t])
        (a.reset_articulated_target_pose if reset else a.set_articulated_target_pose)(target)
        scene.step(dt)
    error = w * t - q_of(a)
    if reset:
        assert error == pytest.approx(D * w / K, rel=1e-3)
    else:
        assert abs(error) < 1e-4 * D * w / K
    assert float(a.get_articulated_joint_velocities()[0]) == pytest.approx(w, rel=1e-4)


def test_damping_alone_takes_the_target_velocity_in_one_implicit_step(scene):
    """K = 0: I (v+ - v) = dt D (v* - v+), so v+ = (I v + dt D v*) / (I + dt D); on the next step the
    target is at rest again (its velocity applies to one step) and v decays by I / (I + dt D)."""
    scene.set_gravity([0, 0, 0])
    a = arm(scene)
    D, dt, v_target = 0.5, 0.01, 0.8
    a.add_articulated_pose_controller(joint_gains(0.0, D))
    a.set_articulated_target_velocity(np.array([v_target]))
    scene.step(dt)
    v1 = float(a.get_articulated_joint_velocities()[0])
    assert v1 == pytest.approx(dt * D * v_target / (IPIVOT + dt * D), rel=1e-4)
    scene.step(dt)
    assert float(a.get_articulated_joint_velocities()[0]) == pytest.approx(v1 * IPIVOT / (IPIVOT + dt * D), rel=1e-4)


def free_body(scene, com=(0.0, 0.0, 0.0), at=(0.0, 0.0, 1.0)):
    links = [link("body", mass=2.0, center_of_mass=list(com), moment_of_inertia=[0.02, 0, 0, 0.02, 0, 0.02])]
    return articulation(scene, "body", links, [joint("free", "free")], world_from_root=sdp.TransformRT(translation=list(at)))


def test_link_position_tracking_holds_a_free_body_by_its_centre_of_mass(scene):
    body = free_body(scene, com=(0.1, 0.0, 0.0))
    K = 5e3
    params = sdp.PoseControllerParams(1)
    params.link_pos_tracking[0] = sdp.PoseTrackingParams(stiffness=K, damping=200.0)
    params.link_rot_tracking[0] = sdp.PoseTrackingParams(stiffness=50.0, damping=5.0)
    body.add_articulated_pose_controller(params)
    body.register_query(sdp.QueryType.ARTICULATED_CONTROLLER_FORCE)
    target_com = np.asarray(body.get_articulated_link_transforms()[0].translation, dtype=float) + [0.1, 0, 0]
    for _ in range(600):
        scene.step(0.01)
    X = body.get_articulated_link_transforms()[0]
    com = np.asarray(X.translation, dtype=float) + rotation_matrix(np.asarray(X.rotation, dtype=float)) @ [0.1, 0, 0]
    # the spring holds the weight at the centre of mass: a sag of m g / K, and the rotation tracking
    # stays at rest
    np.testing.assert_allclose(com - target_com, [0, 0, -2.0 * G / K], atol=2e-3 * 2.0 * G / K)
    force = np.asarray(body.get_articulated_controller_force())
    np.testing.assert_allclose(force[:3], [0, 0, 2.0 * G], rtol=1e-3, atol=1e-3)
    # on the free joint's rotation DOFs: the weight's torque about the link origin, 0.1 m away
    np.testing.assert_allclose(force[3:], [0, -0.1 * 2.0 * G, 0], rtol=1e-3, atol=1e-3)


def test_link_rotation_tracking_holds_a_pendulum_against_its_gravity_torque(scene):
    """A rod on a spherical joint, its mass L along X: rotation tracking to the identity balances
    gravity at K theta = m g L cos theta, turned about +Y."""
    links = [link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
             link("rod", parent=0, mass=M, center_of_mass=[L, 0, 0], moment_of_inertia=[ICOM, 0, 0, ICOM, 0, ICOM])]
    a = articulation(scene, "ball", links, [joint("weld", "hard"), joint("ball", "spherical")])
    K = 100.0
    params = sdp.PoseControllerParams(2)
    params.link_rot_tracking[1] = sdp.PoseTrackingParams(stiffness=K, damping=3.0)
    a.add_articulated_pose_controller(params)
    for _ in range(3000):
        scene.step(0.005)
    rotation = np.asarray(a.get_articulated_pose(), dtype=float)  # the rod's rotation vector
    theta = rotation[1]
    np.testing.assert_allclose(rotation[[0, 2]], 0, atol=1e-6)
    assert K * theta == pytest.approx(M * G * L * math.cos(theta), rel=1e-3)


def test_joint_and_link_targets_are_the_same_target(scene):
    """A joint target gives the link targets of forward kinematics (read off a second arm posed
    there); those link targets give the joint target back."""
    a, reference = arm(scene), arm(scene)
    a.add_articulated_pose_controller(joint_gains(10.0))
    pose = np.array([0.7])
    a.set_articulated_target_pose(pose)
    reference.set_articulated_pose_from_joints(pose)
    expected = reference.get_articulated_link_transforms()
    got = a.get_articulated_target_link_transforms()
    for x, y in zip(got, expected):
        np.testing.assert_allclose(x.translation, y.translation, atol=TIGHT)
        assert abs(abs(float(np.dot(np.asarray(x.rotation), np.asarray(y.rotation)))) - 1) < TIGHT
    a.set_articulated_target_pose(np.array([0.0]))
    a.set_articulated_target_link_transforms(expected)
    np.testing.assert_allclose(a.get_articulated_target_pose(), pose, atol=TIGHT)


def test_posing_the_joints_moves_the_target_there(scene):
    a = arm(scene)
    a.add_articulated_pose_controller(joint_gains(10.0))
    a.set_articulated_pose_from_joints(np.array([0.3]))
    np.testing.assert_allclose(a.get_articulated_target_pose(), [0.3], atol=TIGHT)


def test_constraints_gains_and_errors(scene):
    a = arm(scene)
    before = scene.get_num_constraints()
    with pytest.raises(sdp.Error, match="has no pose controller"):
        a.set_articulated_target_pose(np.array([0.0]))
    with pytest.raises(sdp.Error, match=r"joint_tracking\[1\].stiffness"):
        bad = joint_gains(1.0)
        bad.joint_tracking[1] = sdp.PoseTrackingParams(stiffness=-1.0)
        a.add_articulated_pose_controller(bad)
    with pytest.raises(sdp.Error, match="saturation"):
        a.add_articulated_pose_controller(sdp.PoseControllerParams(joint_tracking=[sdp.PoseTrackingParams(stiffness=1, saturation=0)]))
    with pytest.raises(sdp.Error, match="link_pos_tracking must hold"):
        a.add_articulated_pose_controller(sdp.PoseControllerParams(link_pos_tracking=[sdp.PoseTrackingParams()] * 3))
    assert not a.has_articulated_pose_controller()
    a.add_articulated_pose_controller(joint_gains(10.0, 1.0))
    with pytest.raises(sdp.Error, match="already"):
        a.add_articulated_pose_controller(joint_gains(10.0))
    # two links: two translations, two rotations, one joint (the weld has none)
    info = list(a.get_articulated_pose_constraints())
    T = sdp.PoseConstraintType
    assert [c.type for c in info] == [T.LINK_TRANSLATION, T.LINK_TRANSLATION, T.LINK_ROTATION, T.LINK_ROTATION, T.JOINT]
    assert [(c.link, c.parent) for c in info] == [(0, -1), (1, 0), (0, -1), (1, 0), (1, 0)]
    assert scene.get_num_constraints() == before + 5
    hinge = scene.get_constraint(info[4].handle)
    assert hinge.get_type() == sdp.ConstraintType.ARTICULATED_SINGLE_DOF_TARGET
    assert hinge.get_stiffness() == pytest.approx(10.0)
    with pytest.raises(sdp.Error, match="pose controller"):
        scene.destroy_constraint(hinge)
    # one entry for every link; the weld's joint reads back zero gains
    a.set_articulated_pose_controller_params(sdp.PoseControllerParams(link_rot_tracking=[sdp.PoseTrackingParams(stiffness=7.0)],
                                                                      joint_tracking=[sdp.PoseTrackingParams(stiffness=3.0)]))
    out = sdp.PoseControllerParams(2)
    a.get_articulated_pose_controller_params(out)
    assert [p.stiffness for p in out.link_rot_tracking] == [7.0, 7.0]
    assert [p.stiffness for p in out.link_pos_tracking] == [0.0, 0.0]
    assert [p.stiffness for p in out.joint_tracking] == [0.0, 3.0]
    with pytest.raises(sdp.Error, match="out_params.link_pos_tracking"):
        a.get_articulated_pose_controller_params(sdp.PoseControllerParams(1))
    with pytest.raises(sdp.Error, match="one value per DOF"):
        a.set_articulated_target_pose(np.array([0.0, 1.0]))
    with pytest.raises(sdp.Error, match="ARTICULATED_CONTROLLER_FORCE"):
        a.get_articulated_controller_force()
    a.remove_articulated_pose_controller()
    assert scene.get_num_constraints() == before
    assert not a.has_articulated_pose_controller()


def test_joint_target_constraints_made_directly(scene):
    """The joint targets a controller uses, made on their own: a hinge pulled to 0.4 rad (zero
    gravity) and a ball joint turned to a target rotation."""
    scene.set_gravity([0, 0, 0])
    a = arm(scene)
    c = scene.create_articulated_single_dof_target_constraint(actor=a.get_handle(), joint_index=1, target_value=0.4, stiffness=50.0,
                                                              damping=5.0)
    assert list(c.get_dof_indices_for_actor(0)) == [0]
    for _ in range(400):
        scene.step(0.01)
    assert q_of(a) == pytest.approx(0.4, abs=1e-6)
    assert float(c.get_deviation()[0]) == pytest.approx(0, abs=1e-6)
    with pytest.raises(sdp.Error, match="revolute or prismatic"):
        scene.create_articulated_single_dof_target_constraint(actor=a.get_handle(), joint_index=0)
    with pytest.raises(sdp.Error, match="must be an articulated actor"):
        scene.create_articulated_single_dof_target_constraint(actor=a.get_nested_link_actors()[1], joint_index=1)
    links = [link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
             link("rod", parent=0, mass=M, center_of_mass=[L, 0, 0], moment_of_inertia=[ICOM, 0, 0, ICOM, 0, ICOM])]
    ball = articulation(scene, "ball", links, [joint("weld", "hard"), joint("ball", "spherical")])
    target = sdp.Quaternion.from_axis_angle([0, 0, 1], 0.6)
    r = scene.create_articulated_3d_rotation_target_constraint(actor=ball.get_handle(), joint_index=1, target=target, stiffness=20.0,
                                                               damping=2.0)
    assert r.get_type() == sdp.ConstraintType.ARTICULATED_3D_ROTATION_TARGET
    for _ in range(500):
        scene.step(0.01)
    np.testing.assert_allclose(ball.get_articulated_pose(), [0, 0, 0.6], atol=1e-5)


def test_a_captured_state_carries_the_controller(scene):
    """Targets, their last values and a pending target velocity come back with restore_state: a
    run from the restored state replays the first bit for bit; a scene whose controllers differ
    refuses the state."""
    a = arm(scene)
    a.add_articulated_pose_controller(joint_gains(300.0, 10.0))
    a.set_articulated_target_pose(np.array([0.2]))
    a.set_articulated_target_velocity(np.array([0.4]))
    state = scene.capture_state()

    def run():
        poses = []
        for k in range(50):
            a.set_articulated_target_pose(np.array([0.2 + 0.01 * k]))
            scene.step(0.01)
            poses.append(q_of(a))
        return poses

    first = run()
    scene.restore_state(state, release_immediately=False)
    np.testing.assert_allclose(a.get_articulated_target_pose(), [0.2], atol=TIGHT)
    assert run() == first
    a.remove_articulated_pose_controller()
    with pytest.raises(sdp.Error, match="constraints|pose controller"):
        scene.restore_state(state, release_immediately=False)


def test_a_state_restores_into_another_scene_built_the_same_way(engine):
    """Bytes captured from one scene restore into another built by the same calls (its actors
    have other handles): the controller's targets come with them and the two scenes then run
    alike, bit for bit; a scene whose controller sits on another actor refuses the bytes."""
    source, twin = sdp.create_scene("source"), sdp.create_scene("twin")
    arms = []
    for scene in (source, twin):
        scene.set_gravity([0, 0, -9.81])
        arm(scene)  # an actor before the controlled one: the handles differ between the scenes
        arms.append(arm(scene))
        arms[-1].add_articulated_pose_controller(joint_gains(300.0, 10.0))
    assert arms[0].get_handle() != arms[1].get_handle()
    arms[0].set_articulated_target_pose(np.array([0.3]))
    blob = sdp.DynamicArrayUint8()
    source.capture_state_to_bytes(blob)
    twin.restore_state_from_bytes(bytes(blob))
    np.testing.assert_allclose(arms[1].get_articulated_target_pose(), [0.3], atol=TIGHT)
    runs = []
    for scene, a in zip((source, twin), arms):
        poses = []
        for _ in range(30):
            scene.step(0.01)
            poses.append(q_of(a))
        runs.append(poses)
    assert runs[0] == runs[1]

    other = sdp.create_scene("other")
    first = arm(other)
    first.add_articulated_pose_controller(joint_gains(300.0, 10.0))  # on the first arm, not the second
    arm(other)
    with pytest.raises(sdp.Error, match="pose controller 0 of the state is not on actor"):
        other.restore_state_from_bytes(bytes(blob))
