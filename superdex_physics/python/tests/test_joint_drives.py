"""Joint drives solved inside the step: an implicit spring-damper on a DOF.

- A pendulum held horizontally by a drive sags by exactly m g L / k (static balance of the
  spring and gravity), and the drive's reported effort equals the gravity torque m g L.
- A drive far stiffer than an explicit PD could bear at the step (dt sqrt(k / I) = 25) settles
  at 25 ms, without overshoot when critically damped.
- With max_effort the drive saturates: the joint accelerates at (tau_max - m g L cos q)/I (5 %).
- Drives are part of the captured state.
"""

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import articulation, joint, link

M, L, ICOM = 1.0, 0.5, 1e-3
IPIVOT = ICOM + M * L * L
G = 9.81


def arm(scene):
    links = [
        link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
        link("rod", parent=0, mass=M, center_of_mass=[L, 0, 0], moment_of_inertia=[ICOM, 0, 0, ICOM, 0, ICOM]),
    ]
    joints = [joint("weld", "hard"), joint("hinge", "revolute", axis=[0, 1, 0])]
    return articulation(scene, "arm", links, joints)


def test_static_sag_is_weight_over_stiffness(scene):
    a = arm(scene)
    k = 200.0
    a.set_joint_drive(0, stiffness=k, damping=5.0, target_position=0.0)
    for _ in range(2000):
        scene.step(0.005)
    q = float(a.get_articulated_pose()[0])
    # balance: k (0 - q) = -m g L cos q (gravity pulls the horizontal rod down: +q about +Y)
    assert k * (-q) + M * G * L * np.cos(q) == pytest.approx(0, abs=1e-3 * M * G * L)
    assert a.get_joint_drive_efforts()[0] == pytest.approx(-M * G * L * np.cos(q), rel=1e-3)


@pytest.mark.parametrize("damping_ratio", [0.0, 1.0])
def test_very_stiff_drive_is_stable_at_25_ms(scene, damping_ratio):
    """dt sqrt(k / I) = 25 (an explicit PD diverges beyond 2): the implicit drive settles. Undamped,
    it may overshoot once (backward Euler damps the oscillation by ~25x per step); critically
    damped it approaches the target without overshoot."""
    scene.set_gravity([0, 0, 0])
    a = arm(scene)
    dt = 0.025
    k = 625.0 * IPIVOT / dt**2
    a.set_joint_drive(0, stiffness=k, damping=damping_ratio * 2 * np.sqrt(k * IPIVOT), target_position=1.0)
    qs = []
    for _ in range(80):
        scene.step(dt)
        qs.append(float(a.get_articulated_pose()[0]))
    qs = np.array(qs)
    assert np.all(np.isfinite(qs))
    assert qs.max() <= 1.05
    assert np.abs(qs[20:] - 1.0).max() < 1e-3
    if damping_ratio > 0:
        assert np.all(np.diff(qs) >= -1e-6) and qs.max() <= 1.0 + 1e-6, "critically damped: no overshoot"


def test_saturated_drive_accelerates_at_max_effort(scene):
    scene.set_gravity([0, 0, 0])
    a = arm(scene)
    tau_max = 2.0
    a.set_joint_drive(0, stiffness=1e4, damping=10.0, target_position=3.0, max_effort=tau_max)
    dt = 0.001
    for _ in range(100):
        scene.step(dt)
    v = float(a.get_articulated_joint_velocities()[0])
    assert v == pytest.approx(tau_max / IPIVOT * 0.1, rel=0.05)
    assert a.get_joint_drive_efforts()[0] == pytest.approx(tau_max, rel=1e-4)


def test_drives_are_captured_and_validated(scene):
    a = arm(scene)
    state = scene.capture_state()
    a.set_joint_drive(0, stiffness=100.0, target_position=0.5)
    for _ in range(200):
        scene.step(0.01)
    moved = float(a.get_articulated_pose()[0])
    scene.restore_state(state, release_immediately=True)  # captured without a drive: the arm falls freely again
    for _ in range(200):
        scene.step(0.01)
    assert float(a.get_articulated_pose()[0]) != pytest.approx(moved, abs=1e-3)
    with pytest.raises(sdp.Error, match="dof 3 is out of range"):
        a.set_joint_drive(3, stiffness=1.0)
    with pytest.raises(sdp.Error, match="stiffness and damping must be >= 0"):
        a.set_joint_drive(0, stiffness=-1.0)


def rotation_angle_between(q1, q2):
    d = abs(float(np.dot(np.asarray(q1, float), np.asarray(q2, float))))
    return 2 * np.arccos(min(1.0, d))


def test_link_drive_brings_a_free_body_to_a_pose(scene):
    """A free box pulled by a critically damped link drive reaches a rotated, translated target."""
    scene.set_gravity([0, 0, 0])
    m = 2.0
    box = scene.create_rigid_actor(name="box", shape=sdp.create_box_shape([0.1, 0.2, 0.05]), mass=m)
    target = sdp.TransformRT(sdp.Quaternion.from_axis_angle([0.3, 0.2, 1.0], 1.2), [0.5, -0.3, 0.8])
    k_lin, k_ang = 400.0, 20.0
    box.set_link_drive(target, linear_stiffness=k_lin, linear_damping=2 * np.sqrt(k_lin * m),
                       angular_stiffness=k_ang, angular_damping=2.0)
    for _ in range(400):
        scene.step(0.01)
    pose = box.get_root_transform()
    np.testing.assert_allclose(np.array(pose.translation), [0.5, -0.3, 0.8], atol=1e-3)
    assert rotation_angle_between(np.array(pose.rotation), np.array(target.rotation)) < 1e-3


def test_link_drive_reaches_with_an_arm_at_25_ms(scene):
    """A three-joint arm's tip link is driven to a reachable world point under gravity, stiffly
    (5e4 N/m) and at 25 ms: it gets there within 1 mm."""
    links = [link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01])]
    joints = [joint("weld", "hard")]
    axes = [[0, 0, 1], [0, 1, 0], [0, 1, 0]]
    for i, axis in enumerate(axes):
        links.append(link(f"l{i}", parent=i, mass=1.0, center_of_mass=[0.15, 0, 0],
                          moment_of_inertia=[0.001, 0, 0, 0.008, 0, 0.008]))
        joints.append(joint(f"j{i}", "revolute", at=[0.3 if i > 0 else 0.0, 0, 0.5 if i == 0 else 0.0], axis=axis))
    links.append(link("tip", parent=3, mass=0.1, moment_of_inertia=[1e-4, 0, 0, 1e-4, 0, 1e-4]))
    joints.append(joint("tip_weld", "hard", at=[0.3, 0, 0]))
    arm = articulation(scene, "arm", links, joints)
    arm.set_articulated_pose_from_joints([0.2, -0.3, 0.6])  # the start pose (a bot file's defaultPose)
    tip = scene.get_actor(arm.get_nested_link_actors()[-1])
    target = [0.35, 0.35, 0.4]
    tip.set_link_drive(sdp.TransformRT(translation=target), linear_stiffness=5e4, linear_damping=2e3)
    for _ in range(200):
        scene.step(0.025)
    np.testing.assert_allclose(np.array(tip.get_root_transform().translation), target, atol=1e-3)
    assert np.all(np.isfinite(arm.get_articulated_joint_velocities()))
