"""Linear transmissions added to articulated actors at run time and their actuators
(superdex.physics.experimental), against analytic statics and dynamics:

- the displacement is sum c_k q_k and its Jacobian the coefficients summed per DOF;
- a displacement-control actuator (implicit spring-damper) on a transmission over a slider
  holds it where its tension stiffness (d - target), which shortens the transmission (joint
  force -f c), balances gravity; it pulls but never pushes unless allowed, and follows a target
  set through its state variable;
- a force-control actuator's tension f accelerates a free slider at -f c / m;
- a McKibben muscle holds a hanging slider where its model tension equals the weight, is slack
  when it would have to push, and keeps its pressure as its state variable;
- spatial tendons: the route's length change and its rate, and a tendon holding a rod up where
  the torques balance;
- bad indices, actors and values raise superdex.physics.Error naming the argument.
"""

from __future__ import annotations

import numpy as np
import pytest

import superdex.physics as sdp

ex = sdp.experimental
G = 9.81
REAL = np.float64 if sdp.uses_double_precision() else np.float32  # the build's scalar (out arrays)


@pytest.fixture
def scene():
    sdp.initialize(num_worker_threads=0)
    s = sdp.create_scene("transmissions")
    yield s
    sdp.destroy_scene(s)
    sdp.shutdown()


def slider(scene, mass=2.0, axis=(0.0, 0.0, 1.0), gravity=True):
    """A welded base and one prismatic joint along `axis` (a box of `mass`), gravity -z or none."""
    scene.set_gravity([0.0, 0.0, -G] if gravity else [0.0, 0.0, 0.0])
    box = sdp.create_box_shape(half_extents=[0.05, 0.05, 0.05])
    params = sdp.ArticulatedActorParams()
    params.joints = [sdp.ArticulatedJointParams(type=sdp.ArticulatedJointType.HARD),
                     sdp.ArticulatedJointParams(type=sdp.ArticulatedJointType.PRISMATIC, axis=list(axis))]
    params.links = [sdp.ArticulatedLinkParams(parent_link=-1, shape=box, mass=1.0, has_gravity=False),
                    sdp.ArticulatedLinkParams(parent_link=0, shape=box, mass=mass)]
    return scene.create_articulated_actor(params)


def chain(scene, n=3):
    """n revolute joints about x in a chain, no gravity."""
    scene.set_gravity([0.0, 0.0, 0.0])
    box = sdp.create_box_shape(half_extents=[0.05, 0.05, 0.05])
    params = sdp.ArticulatedActorParams()
    params.joints = [sdp.ArticulatedJointParams(type=sdp.ArticulatedJointType.REVOLUTE, axis=[1, 0, 0],
                                                parent_link_from_joint=sdp.TransformRT(translation=[0, 0, 0.2 if i else 0]))
                     for i in range(n)]
    params.links = [sdp.ArticulatedLinkParams(parent_link=i - 1, shape=box, mass=1.0) for i in range(n)]
    return scene.create_articulated_actor(params)


def test_displacement_and_jacobian_sum_the_coefficients(scene):
    actor = chain(scene)
    k = ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[2, 0, 2], joint_coefficients=[0.4, -0.3, 0.6]))
    assert k == 0
    actor.set_articulated_pose_from_joints(np.array([0.2, -0.7, 0.5]))
    assert ex.get_transmission_displacement(actor, k) == pytest.approx(-0.3 * 0.2 + (0.4 + 0.6) * 0.5, abs=1e-6)
    J = np.full(3, 7.0, dtype=REAL)
    ex.get_transmission_displacement_jacobian(actor, k, J)
    np.testing.assert_allclose(J, [-0.3, 0.0, 1.0], atol=1e-7)
    assert ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[1], joint_coefficients=[1.0])) == 1


def test_displacement_control_holds_a_slider_against_gravity(scene):
    # d = -2 q: the rope shortens (d down) by raising the slider. Tension f = K (d - target) on the
    # joint as -f c = 2 f balances m g: f = m g / 2, d = target + m g / (2 K), q = -d / 2
    actor = slider(scene)
    k = ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[1], joint_coefficients=[-2.0]))
    K, target = 400.0, -0.6
    ex.attach_displacement_control_actuator(actor, k, ex.DisplacementControlActuatorParams(target_displacement=target, stiffness=K,
                                                                                           damping=40.0))
    for _ in range(1500):
        scene.step(0.004)
    q = float(actor.get_articulated_pose()[0])
    # a rope pulls only: here it pulls up (f > 0 shortens d = -2 q), f = m g / 2
    assert q == pytest.approx(-(target + 2.0 * G / (2 * K)) / 2, abs=1e-6)


def test_a_rope_pulls_but_does_not_push(scene):
    # d = q: falling shortens the transmission below its target (compression), so the rope would
    # have to push to hold the slider: it falls freely; allowed to push, the actuator holds it
    actor = slider(scene)
    k = ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[1], joint_coefficients=[1.0]))
    ex.attach_displacement_control_actuator(actor, k, ex.DisplacementControlActuatorParams(target_displacement=0.0, stiffness=1e4))
    for _ in range(50):  # 0.2 s of free fall: 0.196 m
        scene.step(0.004)
    q = float(actor.get_articulated_pose()[0])
    assert q == pytest.approx(-0.5 * G * 0.2 * 0.2, rel=0.03)
    ex.attach_displacement_control_actuator(actor, k, ex.DisplacementControlActuatorParams(target_displacement=0.0, stiffness=1e4,
                                                                                           damping=200.0, allow_compressive_force=True))
    for _ in range(1000):
        scene.step(0.004)
    # q = d, pushed back where the compression K d (joint force -K d) balances m g: q = -m g / K
    assert float(actor.get_articulated_pose()[0]) == pytest.approx(-2.0 * G / 1e4, abs=1e-6)


def test_the_target_is_the_state_variable(scene):
    actor = slider(scene, gravity=False)
    k = ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[1], joint_coefficients=[1.0]))
    ex.attach_displacement_control_actuator(actor, k, ex.DisplacementControlActuatorParams(target_displacement=0.42, stiffness=1e3,
                                                                                           damping=100.0, allow_compressive_force=True))
    out = np.zeros(1, dtype=REAL)
    ex.get_transmission_actuator_state_variables(actor, k, out)
    assert ex.get_num_transmission_actuator_state_variables(actor, k) == 1 and out[0] == pytest.approx(0.42)
    ex.set_transmission_actuator_state_variables(actor, k, np.array([-0.25]))
    ex.get_transmission_actuator_state_variables(actor, k, out)
    assert out[0] == pytest.approx(-0.25)
    for _ in range(1000):
        scene.step(0.004)
    assert float(actor.get_articulated_pose()[0]) == pytest.approx(-0.25, abs=1e-6)


def test_force_control_accelerates_a_free_slider(scene):
    # tension f = 3 N along d = 0.5 q: joint force -1.5 N on 2 kg, from rest: q = -0.75 t^2 / 2
    actor = slider(scene, gravity=False)
    k = ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[1], joint_coefficients=[0.5]))
    ex.attach_force_control_actuator(actor, k, ex.ForceControlActuatorParams(force=3.0))
    for _ in range(250):
        scene.step(0.002)
    t = 0.5
    assert float(actor.get_articulated_joint_velocities()[0]) == pytest.approx(-0.75 * t, rel=1e-5)
    assert float(actor.get_articulated_pose()[0]) == pytest.approx(-0.75 * t * t / 2, rel=5e-3)  # (semi-implicit Euler: dt / t)


def test_bad_calls_name_the_argument(scene):
    actor = chain(scene, 2)
    with pytest.raises(sdp.Error, match=r"transmission_index 0 is out of range: the actor has 0 transmissions"):
        ex.get_transmission_displacement(actor, 0)
    with pytest.raises(sdp.Error, match=r"params.joint_indices\[1\]: expected the index of a joint \(0 to 2 - 1\), got 5"):
        ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[0, 5], joint_coefficients=[1.0, 1.0]))
    with pytest.raises(sdp.Error, match=r"one coefficient per joint"):
        ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[0, 1], joint_coefficients=[1.0]))
    k = ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[0], joint_coefficients=[0.5]))
    with pytest.raises(sdp.Error, match=r"transmission 0 has no actuator attached"):
        ex.get_num_transmission_actuator_state_variables(actor, k)
    with pytest.raises(sdp.Error, match=r"a rope-like transmission only pulls"):
        ex.attach_force_control_actuator(actor, k, ex.ForceControlActuatorParams(force=-1.0))
    ex.attach_force_control_actuator(actor, k, ex.ForceControlActuatorParams(force=1.0))
    with pytest.raises(sdp.Error, match=r"state_variables has 2 values; the actuator has 1"):
        ex.set_transmission_actuator_state_variables(actor, k, np.array([1.0, 2.0]))
    with pytest.raises(sdp.Error, match=r"a negative force on a transmission that only pulls"):
        ex.set_transmission_actuator_state_variables(actor, k, np.array([-1.0]))
    with pytest.raises(sdp.Error, match=r"out_jacobian"):
        ex.get_transmission_displacement_jacobian(actor, k, np.zeros(1, dtype=REAL))
    rigid = scene.create_rigid_actor(name="box", shape=sdp.create_box_shape(half_extents=[0.1, 0.1, 0.1]))
    with pytest.raises(sdp.Error, match=r"get_transmission_displacement: .* is a rigid actor, not an articulated one"):
        ex.get_transmission_displacement(rigid, 0)


def test_a_captured_state_keeps_the_actuator_target(scene):
    actor = slider(scene, gravity=False)
    k = ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[1], joint_coefficients=[1.0]))
    ex.attach_displacement_control_actuator(actor, k, ex.DisplacementControlActuatorParams(target_displacement=0.1, stiffness=1e3,
                                                                                           damping=100.0, allow_compressive_force=True))
    state = scene.capture_state()
    ex.set_transmission_actuator_state_variables(actor, k, np.array([0.5]))
    scene.restore_state(state, True)
    out = np.zeros(1, dtype=REAL)
    ex.get_transmission_actuator_state_variables(actor, k, out)
    assert out[0] == pytest.approx(0.1)


# ---- McKibben muscles


def muscle_tension(d, pressure, minimum, b, n, k, L0):
    """Chou and Hannaford's static tension of a McKibben muscle of length L0 + d (N), with the
    deflated spring k d, written from the model: F = (P - P_min) b^2 / (4 pi n^2) (3 L^2 / b^2 - 1)."""
    L = L0 + d
    return max(0.0, pressure - minimum) * (3 * L * L - b * b) / (4 * np.pi * n * n) + k * d


MUSCLE = dict(pressure=1e5, minimum_pressure=1e3, thread_length=0.15, number_of_wraps=3.0, deflated_stiffness=500.0,
              deflated_equilibrium_length=0.1)


@pytest.mark.parametrize("pressure", [1e5, 500.0])
def test_a_mc_kibben_muscle_holds_a_slider_where_its_tension_is_the_weight(scene, pressure):
    """The slider hangs from the muscle (d = -q: falling stretches it). At rest its tension equals
    the weight m g: the root of the model's tension (numpy's polynomial roots, here) within 1e-5 m;
    below the minimum pressure only the deflated spring acts (d = m g / k)."""
    actor = slider(scene, mass=2.0)
    k = ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[1], joint_coefficients=[-1.0]))
    params = dict(MUSCLE, pressure=pressure)
    ex.attach_mc_kibben_actuator(actor, k, ex.McKibbenActuatorParams(**params))
    actor.set_articulated_joint_friction_params([sdp.ArticulatedJointFrictionParams(), sdp.ArticulatedJointFrictionParams(viscous=20.0)])
    for _ in range(1500):
        scene.step(0.004)
    d = -float(actor.get_articulated_pose()[0])
    b, n, kd, L0 = params["thread_length"], params["number_of_wraps"], params["deflated_stiffness"], params["deflated_equilibrium_length"]
    c = max(0.0, pressure - params["minimum_pressure"]) / (4 * np.pi * n * n)
    # 3 c (L0 + d)^2 - c b^2 + kd d - m g = 0 in d
    roots = np.roots([3 * c, 6 * c * L0 + kd, 3 * c * L0 * L0 - c * b * b - 2.0 * G]) if c > 0 else np.array([2.0 * G / kd])
    expected = float(roots[np.argmin(np.abs(roots))].real)
    assert d == pytest.approx(expected, abs=1e-5)
    assert muscle_tension(d, pressure, params["minimum_pressure"], b, n, kd, L0) == pytest.approx(2.0 * G, rel=1e-3)
    if pressure < params["minimum_pressure"]:
        assert d == pytest.approx(2.0 * G / kd, abs=1e-5)


def test_a_mc_kibben_muscle_never_pushes_and_its_pressure_is_its_state(scene):
    """Compressed below the length where its tension would turn negative, the muscle is slack: a
    slider it would have to push falls freely. Its one state variable is the pressure; raising it
    pulls the slider up, and a captured state restores it."""
    actor = slider(scene, mass=1.0)
    k = ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[1], joint_coefficients=[1.0]))
    ex.attach_mc_kibben_actuator(actor, k, ex.McKibbenActuatorParams(**dict(MUSCLE, pressure=0.0)))
    for _ in range(50):  # d = q < 0: the deflated spring's tension k d < 0 is slack: 0.2 s of free fall
        scene.step(0.004)
    assert float(actor.get_articulated_pose()[0]) == pytest.approx(-0.5 * G * 0.2 * 0.2, rel=0.03)
    assert ex.get_num_transmission_actuator_state_variables(actor, k) == 1
    out = np.zeros(1, dtype=REAL)
    ex.get_transmission_actuator_state_variables(actor, k, out)
    assert out[0] == 0.0
    state = scene.capture_state()
    ex.set_transmission_actuator_state_variables(actor, k, np.array([2e5]))
    ex.get_transmission_actuator_state_variables(actor, k, out)
    assert out[0] == pytest.approx(2e5)
    scene.restore_state(state, True)
    ex.get_transmission_actuator_state_variables(actor, k, out)
    assert out[0] == 0.0


@pytest.mark.parametrize("field", ["thread_length", "number_of_wraps", "deflated_stiffness", "deflated_equilibrium_length"])
def test_mc_kibben_params_must_be_positive(scene, field):
    actor = slider(scene)
    k = ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[1], joint_coefficients=[1.0]))
    with pytest.raises(sdp.Error, match=rf"params\.{field} must be a positive"):
        ex.attach_mc_kibben_actuator(actor, k, ex.McKibbenActuatorParams(**dict(MUSCLE, **{field: 0.0})))


# ---- spatial tendons: a route of waypoints on links, and linear-joint elements


def waypoint(link, p):
    return sdp.RoutingElement(type=sdp.RoutingElementType.WAYPOINT, index=link, local_position=list(p))


def linear_joint(joint, c):
    return sdp.RoutingElement(type=sdp.RoutingElementType.LINEAR_JOINT, index=joint, coefficient=c)


def points_W(actor, route):
    """The world positions of a route's waypoints from the link transforms (float64)."""
    from contact_helpers import rotation_matrix

    X = actor.get_articulated_link_transforms()
    out = []
    for e in route:
        x = X[e.index]
        out.append(rotation_matrix(np.asarray(x.rotation, dtype=float)) @ np.asarray(e.local_position, dtype=float) +
                   np.asarray(x.translation, dtype=float))
    return out


def route_length(actor, route, pose):
    actor.set_articulated_pose_from_joints(np.asarray(pose, dtype=REAL))
    p = points_W(actor, route)
    return sum(float(np.linalg.norm(b - a)) for a, b in zip(p, p[1:]))


ROUTE = [waypoint(0, (0.0, 0.1, 0.0)), waypoint(1, (0.0, 0.05, 0.1)), waypoint(2, (0.0, -0.08, 0.12))]


def test_a_spatial_tendon_is_its_route_length_less_the_length_with_the_joints_at_zero(scene):
    actor = chain(scene)
    k = ex.add_spatial_tendon(actor, ex.SpatialTendonParams(routing_elements=ROUTE))
    rest = route_length(actor, ROUTE, [0, 0, 0])
    rng = np.random.default_rng(3)
    for _ in range(4):
        pose = rng.uniform(-1.2, 1.2, 3)
        expected = route_length(actor, ROUTE, pose) - rest
        assert ex.get_transmission_displacement(actor, k) == pytest.approx(expected, abs=1e-6)
    assert abs(expected) > 1e-2  # the joints change the route


def test_a_linear_joint_element_adds_its_term_and_breaks_the_route(scene):
    actor = chain(scene)
    # waypoints 0-1, then a joint term, then waypoint 2: the segment 1-2 is not part of it
    k = ex.add_spatial_tendon(actor, ex.SpatialTendonParams(routing_elements=ROUTE[:2] + [linear_joint(1, 0.5)] + ROUTE[2:]))
    pose = [0.3, 0.4, -0.5]
    expected = route_length(actor, ROUTE[:2], pose) - route_length(actor, ROUTE[:2], [0, 0, 0]) + 0.5 * 0.4
    actor.set_articulated_pose_from_joints(np.asarray(pose, dtype=REAL))
    assert ex.get_transmission_displacement(actor, k) == pytest.approx(expected, abs=1e-6)


def test_a_spatial_tendons_jacobian_is_its_displacements_rate(scene):
    actor = chain(scene)
    k = ex.add_spatial_tendon(actor, ex.SpatialTendonParams(routing_elements=ROUTE + [linear_joint(0, -0.2)]))
    pose = np.array([0.4, -0.6, 0.9])
    actor.set_articulated_pose_from_joints(pose.astype(REAL))
    J = np.zeros(3, dtype=REAL)
    ex.get_transmission_displacement_jacobian(actor, k, J)
    h = 1e-6 if sdp.uses_double_precision() else 1e-3
    for i in range(3):
        d = []
        for s in (1, -1):
            actor.set_articulated_pose_from_joints((pose + s * h * np.eye(3)[i]).astype(REAL))
            d.append(ex.get_transmission_displacement(actor, k))
        assert J[i] == pytest.approx((d[0] - d[1]) / (2 * h), abs=1e-6 if sdp.uses_double_precision() else 2e-3)


def test_a_tendon_under_tension_holds_a_rod_where_the_torques_balance(scene):
    """A rod on a hinge (about Y, its 1 kg at L along X) held up by a tendon from a point A of the
    base (above the rod's horizontal tip) to its tip: at rest the tension's torque -f dl/dq
    balances the weight's m g L cos q, with dl/dq of the geometry (tip B = L (cos q, 0, -sin q),
    route l = |B - A|), within 1 %."""
    scene.set_gravity([0.0, 0.0, -G])
    L, m, f = 0.4, 1.0, 30.0
    A = np.array([0.4, 0.0, 0.3])
    params = sdp.ArticulatedActorParams()
    params.joints = [sdp.ArticulatedJointParams(type=sdp.ArticulatedJointType.HARD),
                     sdp.ArticulatedJointParams(type=sdp.ArticulatedJointType.REVOLUTE, axis=[0, 1, 0],
                                                friction=sdp.ArticulatedJointFrictionParams(viscous=2.0))]
    params.links = [sdp.ArticulatedLinkParams(parent_link=-1, mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
                    sdp.ArticulatedLinkParams(parent_link=0, mass=m, center_of_mass=[L, 0, 0], moment_of_inertia=[1e-3, 0, 0, 1e-3, 0, 1e-3])]
    rod = scene.create_articulated_actor(params)
    k = ex.add_spatial_tendon(rod, ex.SpatialTendonParams(routing_elements=[waypoint(0, A), waypoint(1, (L, 0, 0))]))
    ex.attach_force_control_actuator(rod, k, ex.ForceControlActuatorParams(force=f))
    for _ in range(3000):
        scene.step(0.005)
    q = float(rod.get_articulated_pose()[0])
    B = L * np.array([np.cos(q), 0.0, -np.sin(q)])
    u = (B - A) / np.linalg.norm(B - A)
    dLdq = float(u @ (L * np.array([-np.sin(q), 0.0, -np.cos(q)])))
    assert abs(float(rod.get_articulated_joint_velocities()[0])) < (1e-6 if sdp.uses_double_precision() else 1e-4)
    assert -1.2 < q < 1.2 and abs(np.cos(q)) > 0.3  # held up off the vertical: the balance is not trivial
    # the generalized forces on the hinge: the tension's -f dl/dq (it shortens the route) and
    # gravity's m g L cos q
    assert -f * dLdq + m * G * L * np.cos(q) == pytest.approx(0, abs=1e-2 * m * G * L)


RECORD_A_TENDON = """
import sys
import superdex.physics as sdp
sdp.initialize(num_worker_threads=0)
scene = sdp.create_scene("tendon")
params = sdp.ArticulatedActorParams()
params.joints = [sdp.ArticulatedJointParams(type=sdp.ArticulatedJointType.REVOLUTE, axis=[1, 0, 0],
                                            parent_link_from_joint=sdp.TransformRT(translation=[0, 0, 0.2 if i else 0])) for i in range(3)]
params.links = [sdp.ArticulatedLinkParams(parent_link=i - 1, shape=sdp.create_box_shape(half_extents=[0.05, 0.05, 0.05]), mass=1.0)
                for i in range(3)]
arm = scene.create_articulated_actor(params)
W = lambda link, p: sdp.RoutingElement(type=sdp.RoutingElementType.WAYPOINT, index=link, local_position=p)
sdp.experimental.add_spatial_tendon(arm, sdp.experimental.SpatialTendonParams(routing_elements=[
    W(0, [0, 0.1, 0]), W(1, [0, 0.05, 0.1]),
    sdp.RoutingElement(type=sdp.RoutingElementType.LINEAR_JOINT, index=1, coefficient=0.1), W(2, [0, -0.08, 0.12])]))
arm.set_articulated_pose_from_joints([0.3, -0.4, 0.5])
sdp.debugger.attach()
scene.step(0.001)
sdp.debugger.detach()
X = arm.get_articulated_link_transforms()
print(repr([list(x.translation) + list(x.rotation) for x in X]))
"""


def test_the_debugger_frames_carry_the_tendons_segments(tmp_path):
    """A frame of a recording holds the route's one segment (the linear-joint element breaks the
    route between waypoints 1 and 2): from waypoint 0 to waypoint 1, at the links' frames."""
    import ast
    import json
    import os
    import subprocess
    import sys

    from contact_helpers import rotation_matrix

    recording = tmp_path / "tendon.jsonl"
    env = dict(os.environ, SUPERDEX_DEBUGGER_RECORD=str(recording), SUPERDEX_DEBUGGER_FRAME_INTERVAL="0")
    proc = subprocess.run([sys.executable, "-c", RECORD_A_TENDON], env=env, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    X = ast.literal_eval(proc.stdout.strip().splitlines()[-1])
    frames = [json.loads(line) for line in recording.read_text().splitlines() if '"frame"' in line]
    (tendon,) = frames[-1]["tendons"]
    assert tendon["i"] == 0
    world = lambda link, p: rotation_matrix(np.asarray(X[link][3:], dtype=float)) @ np.asarray(p, dtype=float) + X[link][:3]
    np.testing.assert_allclose(tendon["s"], np.concatenate([world(0, [0, 0.1, 0]), world(1, [0, 0.05, 0.1])]), atol=1e-5)
