"""Linear transmissions added to articulated actors at run time and their actuators
(superdex.physics.experimental), against analytic statics and dynamics:

- the displacement is sum c_k q_k and its Jacobian the coefficients summed per DOF;
- a displacement-control actuator (implicit spring-damper) on a transmission over a slider
  holds it where stiffness (target - d) balances gravity, pulls but never pushes unless allowed,
  and follows a target set through its state variable;
- a force-control actuator accelerates a free slider at f c / m;
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
    # d = -2 q (pulling the slider up lowers d... the tension pulls d up, i.e. the slider down)
    # with c = +2: tension f = K (target - 2 q) on the joint as 2 f balances m g: q = (target - m g / (2 K)) / 2
    actor = slider(scene)
    k = ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[1], joint_coefficients=[2.0]))
    K, target = 400.0, 0.3
    ex.attach_displacement_control_actuator(actor, k, ex.DisplacementControlActuatorParams(target_displacement=target, stiffness=K,
                                                                                           damping=40.0))
    for _ in range(1500):
        scene.step(0.004)
    q = float(actor.get_articulated_pose()[0])
    # a rope pulls only: here it must pull up (f > 0 raises d = 2 q), f = m g / 2
    assert q == pytest.approx((target - 2.0 * G / (2 * K)) / 2, abs=1e-6)


def test_a_rope_pulls_but_does_not_push(scene):
    # the slider rests above the target: the rope would have to push it up to hold it, so it
    # falls freely; allowed to push, the actuator holds it
    actor = slider(scene)
    k = ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[1], joint_coefficients=[-1.0]))
    ex.attach_displacement_control_actuator(actor, k, ex.DisplacementControlActuatorParams(target_displacement=0.0, stiffness=1e4))
    for _ in range(50):  # 0.2 s of free fall: 0.196 m
        scene.step(0.004)
    q = float(actor.get_articulated_pose()[0])
    assert q == pytest.approx(-0.5 * G * 0.2 * 0.2, rel=0.03)
    ex.attach_displacement_control_actuator(actor, k, ex.DisplacementControlActuatorParams(target_displacement=0.0, stiffness=1e4,
                                                                                           damping=200.0, allow_compressive_force=True))
    for _ in range(1000):
        scene.step(0.004)
    # -q = d, pushed to where K d balances m g: d = -m g / K... the push holds q = -m g / K
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
    # f = 3 N along d = 0.5 q: joint force 1.5 N on 2 kg, from rest: q = 0.75 t^2 / 2
    actor = slider(scene, gravity=False)
    k = ex.add_linear_transmission(actor, ex.LinearTransmissionParams(joint_indices=[1], joint_coefficients=[0.5]))
    ex.attach_force_control_actuator(actor, k, ex.ForceControlActuatorParams(force=3.0))
    for _ in range(250):
        scene.step(0.002)
    t = 0.5
    assert float(actor.get_articulated_joint_velocities()[0]) == pytest.approx(0.75 * t, rel=1e-5)
    assert float(actor.get_articulated_pose()[0]) == pytest.approx(0.75 * t * t / 2, rel=5e-3)  # (semi-implicit Euler: dt / t)


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
