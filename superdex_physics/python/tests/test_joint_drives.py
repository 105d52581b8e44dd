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

M, L, ICOM = 1.0, 0.5, 1e-3
IPIVOT = ICOM + M * L * L
G = 9.81


def arm(scene):
    links = [
        {"name": "base", "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01]},
        {"name": "rod", "parentLink": 0, "mass": M, "centerOfMass": [L, 0, 0], "momentOfInertia": [ICOM, 0, 0, ICOM, 0, ICOM]},
    ]
    joints = [{"name": "weld", "type": "Hard"}, {"name": "hinge", "type": "Revolute", "axis": [0, 1, 0]}]
    return scene.create_articulated_actor("arm", links, joints)


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
    scene.restore_state(state)  # captured without a drive: the arm falls freely again
    for _ in range(200):
        scene.step(0.01)
    assert float(a.get_articulated_pose()[0]) != pytest.approx(moved, abs=1e-3)
    with pytest.raises(sdp.Error, match="dof 3 is out of range"):
        a.set_joint_drive(3, stiffness=1.0)
    with pytest.raises(sdp.Error, match="stiffness and damping must be >= 0"):
        a.set_joint_drive(0, stiffness=-1.0)
