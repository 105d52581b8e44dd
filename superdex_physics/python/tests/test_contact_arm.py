"""A two-link arm pressing its tip sphere onto a static box: joint torques balance the contact force.

The arm: a base welded 1 m above the world origin, two revolute joints about +Y (shoulder
at the base origin, elbow 0.5 m along link 1), both links 0.5 m long. A positive joint angle
turns the link's x axis towards -z, so with q = (q1, q2):

    shoulder s = (0, 0, 1),  elbow e = s + L1 (cos q1, 0, -sin q1),
    tip      t = e + L2 (cos(q1 + q2), 0, -sin(q1 + q2)).

Link 2 carries a sphere of radius r = 0.05 centred at its tip; below it is a static box
whose top face is 2 mm under the sphere at the start pose. Masses are explicit (1 kg per
link, centres of mass a1 = 0.25 and a2 = 0.3 along each link), so gravity's generalized
force is analytic:  c(q, 0) = dV/dq with

    V = m1 g (1 - a1 sin q1) + m2 g (1 - L1 sin q1 - a2 sin(q1 + q2)).

A world force f applied at a point p of link 2 has generalized force J_p^T f, with the
columns of J_p the velocity of p per unit joint rate: axis x (p - joint origin), i.e.
y x d = (d_z, 0, -d_x). Static equilibrium of the arm with applied torques tau is therefore

    tau - c(q, 0) + J_p(q)^T f = 0.

The torques are chosen so that at the start pose this holds with f = (0, 0, 20 N) (a push
straight up from the box): tau = c(q0) + F (p - joint)_x for each joint. With friction
(mu = 1) the sphere sticks where it lands, the pair of joint equations fixes (f_x, f_z), and
the arm must come to rest with the contact force that satisfies the balance.
"""

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import articulation, joint, link
from contact_helpers import G, material, position, skew, step_for, vec

L1 = L2 = 0.5
A1, A2 = 0.25, 0.3
M1 = M2 = 1.0
R = 0.05
H = 1.0
MU = 1.0
F_TARGET = 20.0
Q0 = np.array([0.4, 0.9])
DT = 0.01


def forward(q):
    """shoulder, elbow, tip-sphere centre (world)."""
    s = np.array([0.0, 0.0, H])
    e = s + L1 * np.array([np.cos(q[0]), 0, -np.sin(q[0])])
    t = e + L2 * np.array([np.cos(q[0] + q[1]), 0, -np.sin(q[0] + q[1])])
    return s, e, t


def gravity_bias(q):
    """c(q, 0) = dV/dq (analytic)."""
    q12 = q[0] + q[1]
    return np.array([
        -M1 * G * A1 * np.cos(q[0]) - M2 * G * (L1 * np.cos(q[0]) + A2 * np.cos(q12)),
        -M2 * G * A2 * np.cos(q12),
    ])


def point_jacobian(q, p):
    """3 x 2 linear Jacobian of a world point p fixed to link 2 (analytic)."""
    s, e, _ = forward(q)
    cols = [np.array([d[2], 0.0, -d[0]]) for d in (p - s, p - e)]
    return np.stack(cols, axis=1)


def build(scene):
    inertia1 = [0.001, 0, 0, M1 * L1**2 / 12, 0, M1 * L1**2 / 12]
    links = [
        link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
        link("upper", parent=0, mass=M1, center_of_mass=[A1, 0, 0], moment_of_inertia=inertia1,
             shape=sdp.create_sphere_shape([L1, 0, 0], 0.04), contact=material(MU)),
        link("lower", parent=1, mass=M2, center_of_mass=[A2, 0, 0], moment_of_inertia=inertia1,
             shape=sdp.create_sphere_shape([L2, 0, 0], R), contact=material(MU)),
    ]
    joints = [
        joint("weld", "hard", at=[0, 0, H]),
        joint("shoulder", "revolute", axis=[0, 1, 0]),
        joint("elbow", "revolute", at=[L1, 0, 0], axis=[0, 1, 0]),
    ]
    arm = articulation(scene, "arm", links, joints)
    arm.set_articulated_pose_from_joints(Q0)
    _, _, tip = forward(Q0)
    top = tip[2] - R - 2e-3
    table = scene.create_rigid_actor(
        name="table", shape=sdp.create_box_shape([0.15, 0.15, 0.1]), is_static=True,
        world_from_local=sdp.TransformRT(rotation=sdp.Quaternion(0, 0, 0, 1), translation=[tip[0], 0, top - 0.1]),
        contact=material(MU))
    lower = scene.get_actor(arm.get_nested_link_actors()[2])
    return arm, lower, table


def applied_torques():
    """tau = c(q0) - J_p(q0)^T (0, 0, F): equilibrium at q0 with a purely vertical contact force."""
    _, _, tip = forward(Q0)
    p = tip - np.array([0, 0, R])
    return gravity_bias(Q0) - point_jacobian(Q0, p).T @ np.array([0, 0, F_TARGET])


def test_analytic_model_matches_the_engine(scene):
    """Precondition for the balance test: the analytic kinematics, gravity torque and point
    Jacobian used below agree with the engine's (link pose, c(q, 0), and J_lin - [p - o]x J_ang)."""
    arm, lower, _ = build(scene)
    s, e, t = forward(Q0)
    np.testing.assert_allclose(position(lower), e, atol=1e-5)
    np.testing.assert_allclose(vec(arm.get_articulated_bias_forces()), gravity_bias(Q0), rtol=1e-4, atol=1e-5)
    J = vec(lower.get_articulated_jacobian()).reshape(6, 2)
    p = t - np.array([0, 0, R])
    J_p = J[:3] - skew(p - e) @ J[3:]
    np.testing.assert_allclose(J_p, point_jacobian(Q0, p), atol=1e-5)


def test_arm_pressing_on_a_box_balances_joint_torques(scene):
    """After 3 s the arm is at rest on the box, and with the measured contact force f on the
    lower link (TOTAL_CONTACT_FORCE), the measured contact point p (CONTACT_POINTS) and the
    final pose q:  |tau - c(q, 0) + J_p(q)^T f| < 1 % of |tau|.  Also: f is (0, 0, 20 N) to 2 %
    (the equilibrium the torques were designed for; the pose barely changes), inside the friction
    cone; the contact point is the sphere's lowest point (1 mm) with normal +z; and the contact
    torque about the lower link's centre of mass c = e + a2 (cos(q1 + q2), 0, -sin(q1 + q2)) is
    (p - c) x f."""
    arm, lower, table = build(scene)
    lower.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    lower.register_query(sdp.QueryType.CONTACT_POINTS)
    tau = applied_torques()
    arm.set_external_forces_on_dofs([0, 1], tau)
    step_for(scene, DT, 3.0)

    q = vec(arm.get_articulated_pose())
    assert np.abs(vec(arm.get_articulated_joint_velocities())).max() < 1e-3, "the arm is not at rest"
    assert np.abs(q - Q0).max() < 0.02, f"the arm moved far from its start pose: {q}"
    _, e, tip = forward(q)

    points = [p for p in lower.get_contact_points_world() if np.linalg.norm(vec(p.force)) > 1e-3 * F_TARGET]
    assert len(points) >= 1
    for pt in points:
        assert pt.actor_b == table.get_handle()
        np.testing.assert_allclose(vec(pt.normal), [0, 0, 1], atol=1e-3)
    p = np.sum([vec(pt.pos_a) * np.linalg.norm(vec(pt.force)) for pt in points], axis=0) / \
        np.sum([np.linalg.norm(vec(pt.force)) for pt in points])
    np.testing.assert_allclose(p, tip - np.array([0, 0, R]), atol=1e-3)

    f = vec(lower.get_contact_force_world())
    np.testing.assert_allclose(np.sum([vec(pt.force) for pt in points], axis=0), f, rtol=1e-4, atol=1e-4 * F_TARGET)
    residual = tau - gravity_bias(q) + point_jacobian(q, p).T @ f
    assert np.linalg.norm(residual) < 0.01 * np.linalg.norm(tau), f"torque balance residual {residual} for tau {tau}, f {f}"

    np.testing.assert_allclose(f, [0, 0, F_TARGET], atol=0.02 * F_TARGET)
    assert np.linalg.norm(f[:2]) <= MU * f[2]
    c = e + A2 * np.array([np.cos(q[0] + q[1]), 0, -np.sin(q[0] + q[1])])
    np.testing.assert_allclose(vec(lower.get_contact_torque_world()), np.cross(p - c, f), atol=0.01 * F_TARGET * L2)


def test_welded_base_touching_the_ground_is_not_a_contact(scene):
    """A robot's base welded to the world and resting on the ground plane: neither side can move,
    so the pair yields no contact (it used to produce a zero-compliance block and NaN)."""
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    # the base's box (half extents 0.05, 0.05, 0.1) stands on the plane: its centre is 0.1 m up;
    # create_box_shape centres a box on its shape origin, so the base link frame sits there
    links = [link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01],
                  shape=sdp.create_box_shape([0.05, 0.05, 0.1])),
             link("arm", parent=0, mass=0.5, center_of_mass=[0.2, 0, 0], moment_of_inertia=[1e-3, 0, 0, 1e-3, 0, 1e-3])]
    joints = [joint("weld", "hard", at=[0, 0, 0.1]),
              joint("j", "revolute", at=[0, 0, 0.2], axis=[0, 1, 0])]
    robot = articulation(scene, "robot", links, joints)
    robot.register_query(sdp.QueryType.CONTACT_POINTS)
    for _ in range(10):
        scene.step(0.004)
    v = np.zeros(1, dtype=np.float64 if sdp.uses_double_precision() else np.float32)
    robot.get_articulated_joint_velocities(out_velocities=v)
    assert np.isfinite(v).all() and v[0] != 0, "the arm swings under gravity"
    assert len(robot.get_contact_points_world()) == 0
