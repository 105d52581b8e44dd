"""Built-in actuators on a one-joint rotor, driven only by the pipeline.

The rotor turns about a vertical axis through its centre of mass, so its joint obeys
I dv/dt = tau exactly (no gravity torque, no velocity-dependent forces), with
I = Izz + armature = 0.1 kg m^2. A JOINT_COMMAND controller issues the commands; the actuator
declared in the bot file turns its DOF's command into the joint's effort.
"""

import json

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from pipeline_helpers import create_bot_from_json, rotor_bot_json, step, tolerance
from robotics_helpers import EXAMPLE_BOT, scene  # noqa: F401
from superdex.physics.paths import resolve_asset

INERTIA = 0.1  # kg m^2: Izz 0.02 + armature 0.08


def make_rotor(scene, tmp_path, actuator_type: str, params: dict, **rotor):
    doc = rotor_bot_json(**rotor)
    doc["links"][1]["actuators"] = [{"type": actuator_type, "name": "drive", "params": json.dumps(params)}]
    ctx, bot, arm = create_bot_from_json(scene, tmp_path, doc)
    command = bot.create_controller("JOINT_COMMAND", "command")
    return ctx, bot, arm, command


def velocity(arm) -> float:
    v = np.zeros(1, dtype=arm.get_articulated_pose().dtype)
    arm.get_articulated_joint_velocities(v)
    return float(v[0])


def seed_servo(k_p, k_i, effort_limit, profile_accel):
    """The seed's MyVelocityServoActuator.compute_effort, verbatim in its arithmetic."""
    state = {"integral": 0.0, "w_traj": 0.0}

    def compute_effort(w_present, w_goal, dt):
        if profile_accel <= 0:
            state["w_traj"] = w_goal
        else:
            max_step = profile_accel * dt
            state["w_traj"] = state["w_traj"] + float(np.clip(w_goal - state["w_traj"], -max_step, max_step))
        e = state["w_traj"] - w_present
        integral_next = state["integral"] + e * dt
        effort_unsat = k_p * e + k_i * integral_next
        effort = float(np.clip(effort_unsat, -effort_limit, effort_limit))
        if effort == effort_unsat or e * effort_unsat < 0:
            state["integral"] = integral_next
        return effort

    return compute_effort


def test_velocity_servo_tracks_a_velocity_step_with_the_pi_response(scene, tmp_path):
    params = {"k_p": 1.0, "k_i": 5.0, "effort_limit": 1.0, "profile_accel": 40.0}
    ctx, bot, arm, command = make_rotor(scene, tmp_path, "VELOCITY_SERVO", params)
    dt, n_before, n_after = 0.002, 25, 750
    ctx.configure_controller(command, {"velocity": [0.0]})
    step(scene, dt, n_before)
    ctx.configure_controller(command, {"velocity": [2.0]})  # the step, at t = 0.05 s
    simulated = []
    for _ in range(n_after):
        scene.step(dt)
        simulated.append(velocity(arm))

    # expected: the seed's PI law closing the loop on I dv/dt = tau, stepped like the engine
    # (semi-implicit Euler: v+ = v + dt tau / I, tau from the state at the start of the step)
    law = seed_servo(**params)
    v, expected, saturated = 0.0, [], 0
    for k in range(n_before + n_after):
        tau = law(v, 0.0 if k < n_before else 2.0, dt)
        saturated += abs(tau) == params["effort_limit"]
        v = v + dt * tau / INERTIA
        if k >= n_before:
            expected.append(v)
    assert saturated > 10, "the profile's 40 rad/s^2 needs 4 N m: the drive saturates at 1 N m"
    simulated, expected = np.array(simulated), np.array(expected)
    # the engine solves the same recurrence; the difference is rounding: float32 adds about
    # eps |v| ~ 1e-7 rad/s per step, bounded by the stable loop to well under 1e-4 over 750 steps
    np.testing.assert_allclose(simulated, expected, atol=tolerance(1e-9, 1e-4))

    # and the response is the one a PI servo should give: the ramp saturates the drive (anti-
    # windup engaged), the loop (wn = sqrt(k_i / I) = 7.1 rad/s, zeta = k_p / (2 sqrt(k_i I))
    # = 0.71) overshoots and settles on the goal with no steady-state error
    assert simulated.max() > 2.1
    assert abs(simulated[-1] - 2.0) < 1e-3
    np.testing.assert_allclose(abs(arm.get_external_forces()[0]), abs(law(v, 2.0, dt)), atol=1e-2)

    # reset() restarts the integrator and the profile
    bot.reset()
    scene.step(dt)
    first = seed_servo(**params)(simulated[-1], 2.0, dt)  # from w_traj = 0 again
    np.testing.assert_allclose(arm.get_external_forces()[0], first, rtol=1e-4)


def test_delayed_actuator_delays_the_command(scene, tmp_path):
    params = {"inner": {"type": "IDEAL_PD", "params": {"kp": 0.0, "kd": 0.0}}, "delay": 0.05}
    ctx, bot, arm, command = make_rotor(scene, tmp_path, "DELAYED", params)
    dt = 0.01
    applied = []
    for k in range(40):
        if k == 10:
            ctx.configure_controller(command, {"effort": [0.5]})  # issued at t = 0.10 s
        if k == 25:
            ctx.configure_controller(command, {"effort": [-0.25]})  # issued at t = 0.25 s
        scene.step(dt)
        applied.append(float(arm.get_external_forces()[0]))
    expected = [0.0] * 15 + [0.5] * 15 + [-0.25] * 10  # each arrives 0.05 s = 5 steps later
    np.testing.assert_allclose(applied, expected, atol=1e-7)
    # the delay can change at run time; the inner actuator is configured through "inner"
    (drive,) = bot.find_actuators_by_name("drive")
    ctx.configure_actuator(drive, {"delay": 0.0, "inner": {"params": {"effort_limit": 0.1}}})
    scene.step(dt)
    assert arm.get_external_forces()[0] == pytest.approx(-0.1)


def test_dc_motor_torque_speed_curve_and_reflected_armature(scene, tmp_path):
    params = {"stall_torque": 0.5, "no_load_speed": 100.0, "gear_ratio": 10.0, "armature": 1e-4}
    ctx, bot, arm, command = make_rotor(scene, tmp_path, "DC_MOTOR", params)
    # the rotor's inertia reflected through the gearbox: N^2 J = 100 x 1e-4 = 0.01 kg m^2
    m = np.array(arm.get_articulated_mass_matrix()).reshape(-1)
    assert m[0] == pytest.approx(INERTIA + 0.01, rel=1e-6)
    (drive,) = bot.find_actuators_by_name("drive")
    # at rest, a huge request gets the stall torque through the gearbox (N t_s = 5 N m), or
    # the current limit when it is lower
    ctx.configure_controller(command, {"effort": [100.0]})
    ctx.configure_actuator(drive, {"torque_limit": 0.2})
    scene.step(0.002)
    assert arm.get_external_forces()[0] == pytest.approx(2.0)
    ctx.configure_actuator(drive, {"torque_limit": -1})
    v = velocity(arm)  # the effort of a step comes from the state at its start
    scene.step(0.002)
    assert arm.get_external_forces()[0] == pytest.approx(5.0 * (1 - 10 * v / 100.0), rel=1e-5)
    # unloaded, it runs up the torque-speed line to the no-load speed w0 / N = 10 rad/s
    # (time constant I w0 / (N^2 t_s) = 0.22 s)
    step(scene, 0.002, 1500)
    assert velocity(arm) == pytest.approx(10.0, abs=1e-3)


def test_ideal_pd_reaches_the_commanded_position(scene, tmp_path):
    ctx, bot, arm, command = make_rotor(scene, tmp_path, "IDEAL_PD", {"kp": 20.0, "kd": 2.5, "effort_limit": 3.0})
    ctx.configure_controller(command, {"position": [0.5]})
    scene.step(0.002)
    assert arm.get_external_forces()[0] == pytest.approx(3.0), "20 x 0.5 = 10 N m, limited to 3"
    step(scene, 0.002, 1500)
    assert arm.get_articulated_pose()[0] == pytest.approx(0.5, abs=1e-4)


def test_actuators_need_a_one_dof_joint(scene, tmp_path):
    ctx, _, rotor = create_bot_from_json(scene, tmp_path, rotor_bot_json())
    base, wheel = rotor.get_nested_link_actors()
    with pytest.raises(sdp.Error, match=r"link 'base' has joint 'weld' \(Hard, 0 DOFs\)"):
        ctx.create_actuator("IDEAL_PD", scene.get_actor(base), "bad")
    with pytest.raises(sdp.Error, match=r"params.inner.type: required"):
        ctx.create_actuator("DELAYED", scene.get_actor(wheel), "bad", {"inner": {}})
    with pytest.raises(sdp.Error, match=r"no actuator type 'NOPE'"):
        ctx.create_actuator("DELAYED", scene.get_actor(wheel), "bad", {"inner": {"type": "NOPE"}})


def test_the_example_bot_with_builtin_components(scene):
    # the seed's bot file with the built-in types in place of the Python ones: VELOCITY_SERVO
    # takes the very params of MY_VELOCITY_SERVO_ACTUATOR (k_p, k_i, effort_limit, profile_accel)
    prefab = sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT)))
    for declared in prefab.actuators:
        for d in declared:
            d.type = "VELOCITY_SERVO"
    for declared in prefab.sensors:
        for d in declared:
            d.type = "CONTACT_FORCE"
    ctx = sdr.create_context()
    bot = sdr.create_bot(scene, prefab, ctx)
    arm = bot.get_articulated_actor()
    bot.create_controller("JOINT_COMMAND", "command", {"velocity": [0.5, -0.5]})
    limits = np.array([6.0, 3.0])  # effort_limit of servo_1 and servo_2 in the bot file
    for _ in range(500):
        scene.step(0.002)
        assert np.all(np.abs(arm.get_external_forces()) <= limits + 1e-5)
    v = np.zeros(2, dtype=arm.get_articulated_pose().dtype)
    arm.get_articulated_joint_velocities(v)
    np.testing.assert_allclose(v, [0.5, -0.5], atol=0.05)  # the integrators still work off the gravity load
    (force_sensor,) = bot.find_sensors_by_name("force_sensor")
    np.testing.assert_array_equal(ctx.get_sensor_signal(force_sensor), 0.0)  # nothing touches the ball
