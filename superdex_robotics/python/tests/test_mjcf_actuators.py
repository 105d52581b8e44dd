"""MJCF joint actuators imported as IDEAL_PD actuators, driven by a JOINT_COMMAND controller,
against MuJoCo running the same file with the same control: a position servo holding a pendulum
against gravity settles at MuJoCo's equilibrium (gear 1 and 2), a velocity servo on a damped
slider reaches MuJoCo's steady speed, and a geared motor saturated by its force range gives
MuJoCo's acceleration. The commands are joint quantities: ctrl / gear for a position servo's
target, ctrl x gear for a motor's effort.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

try:
    import mujoco
except ImportError as exc:  # a declared dev dependency: missing means a broken environment
    raise ImportError("mujoco (a dev dependency in pyproject.toml) is required by this test; run `uv sync`") from exc

import superdex.physics as sdp
import superdex.robotics as sdr

DT = 0.002


def pendulum(actuator: str) -> str:
    """A 1 kg ball on a 0.5 m massless rod, hinged about y at the origin, hanging along -z."""
    return f"""<mujoco>
  <option timestep="{DT}" gravity="0 0 -9.81"/>
  <worldbody>
    <body name="pendulum">
      <joint name="hinge" axis="0 1 0" damping="0.05"/>
      <geom type="sphere" size="0.05" pos="0 0 -0.5" mass="1" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
  <actuator>{actuator}</actuator>
</mujoco>
"""


def slider(actuator: str) -> str:
    """A 2 kg block on a damped horizontal slide (no contact, no gravity along it)."""
    return f"""<mujoco>
  <option timestep="{DT}"/>
  <worldbody>
    <body name="block">
      <joint name="slide" type="slide" axis="1 0 0" damping="3"/>
      <geom type="box" size="0.1 0.1 0.1" mass="2" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
  <actuator>{actuator}</actuator>
</mujoco>
"""


def mujoco_run(xml: str, ctrl: float, steps: int):
    m = mujoco.MjModel.from_xml_string(xml)
    d = mujoco.MjData(m)
    d.ctrl[:] = ctrl
    for _ in range(steps):
        mujoco.mj_step(m, d)
    return float(d.qpos[0]), float(d.qvel[0])


def ours(tmp_path, xml: str, command: dict, steps: int):
    path = tmp_path / "model.xml"
    path.write_text(xml)
    sdp.initialize(num_worker_threads=0)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # nothing of these models is left out
            model = sdr.load_mjcf_file(path)
        scene = sdp.create_scene("mjcf")
        scene.set_gravity(model.gravity)
        ctx = sdr.create_context()
        (prefab,) = model.bots
        bot = sdr.create_bot(scene, prefab, ctx)
        controller = bot.create_controller("JOINT_COMMAND", "command")
        ctx.configure_controller(controller, command)
        art = bot.get_articulated_actor()
        for _ in range(steps):
            scene.step(model.timestep)
        q = np.asarray(art.get_articulated_pose(), dtype=float)
        v = np.asarray(art.get_articulated_joint_velocities(), dtype=float)
        actuators = [(a.type, a.name) for decls in prefab.actuators for a in decls]
        return float(q[0]), float(v[0]), actuators
    finally:
        sdp.shutdown()


@pytest.mark.parametrize("gear", [1.0, 2.0])
def test_position_servo_holds_the_pendulum_where_mujoco_does(tmp_path, gear):
    kp, kv, ctrl = 20.0, 2.0, 0.6 * gear
    xml = pendulum(f'<position name="servo" joint="hinge" kp="{kp}" kv="{kv}" gear="{gear}"/>')
    q_ref, _ = mujoco_run(xml, ctrl, 3000)
    q, v, actuators = ours(tmp_path, xml, {"position": [ctrl / gear]}, 3000)
    assert actuators == [("IDEAL_PD", "servo")]
    # the equilibrium kp g^2 (ctrl / g - q) = m g l sin q, short of the target
    assert 0.1 < q_ref < 0.6
    assert abs(q - q_ref) < 1e-4
    assert abs(v) < 1e-4


def test_velocity_servo_reaches_mujocos_steady_speed(tmp_path):
    xml = slider('<velocity joint="slide" kv="12"/>')
    _, v_ref = mujoco_run(xml, 0.5, 2000)
    _, v, actuators = ours(tmp_path, xml, {"velocity": [0.5]}, 2000)
    assert actuators == [("IDEAL_PD", "<velocity joint='slide'>")]
    # kv (0.5 - v) = damping v: v = 12 * 0.5 / 15 = 0.4 m/s
    assert abs(v_ref - 0.4) < 1e-6
    assert abs(v - v_ref) < (1e-6 if sdp.uses_double_precision() else 1e-5)  # float32: 3e-6 of round-off


def test_geared_motor_saturates_at_its_force_range(tmp_path):
    # 1 N x gear 10 asked, the force range allows 0.3: 3 N on the 2 kg block
    xml = slider('<motor joint="slide" gear="10" forcerange="-0.3 0.3"/>')
    _, v_ref = mujoco_run(xml, 1.0, 1)
    _, v, _ = ours(tmp_path, xml, {"effort": [10.0]}, 1)
    # one step from rest: the velocity damping acts implicitly in both (3 N / (2 kg + 3 N s/m dt))
    assert abs(v_ref - DT * 3 / (2 + 3 * DT)) < 1e-9
    assert abs(v - v_ref) < 1e-9 * (1 if sdp.uses_double_precision() else 1e3)


def settle_uncommanded(tmp_path, xml: str, steps: int) -> float:
    """Our pendulum's angle after `steps` with no controller at all: the actuators hold ctrl = 0."""
    path = tmp_path / "model.xml"
    path.write_text(xml)
    sdp.initialize(num_worker_threads=0)
    try:
        model = sdr.load_mjcf_file(path)
        scene = sdp.create_scene("mjcf")
        scene.set_gravity(model.gravity)
        (prefab,) = model.bots
        bot = sdr.create_bot(scene, prefab, sdr.create_context())  # (keeps its context, and its actuators, alive)
        art = bot.get_articulated_actor()
        art.set_articulated_pose_from_joints([0.5])
        for _ in range(steps):
            scene.step(model.timestep)
        return float(np.asarray(art.get_articulated_pose(), dtype=float)[0])
    finally:
        sdp.shutdown()


@pytest.mark.parametrize("ctrlrange, gear", [("", 1.0), ('ctrllimited="true" ctrlrange="0.3 1"', 2.0)])
def test_an_uncommanded_position_servo_holds_ctrl_zero_like_mujoco(tmp_path, ctrlrange, gear):
    # MuJoCo's ctrl starts at 0 (clamped into ctrlrange): the servo pulls towards ctrl / gear from
    # the first step, before any controller exists. Started at 0.5 rad, the pendulum settles where
    # kp g^2 (target - q) balances gravity: target 0 (hangs below it) or 0.3 / 2
    xml = pendulum(f'<position name="servo" joint="hinge" kp="20" kv="2" gear="{gear}" {ctrlrange}/>')
    m = mujoco.MjModel.from_xml_string(xml)
    d = mujoco.MjData(m)
    d.qpos[0] = 0.5
    for _ in range(3000):
        mujoco.mj_step(m, d)
    q = settle_uncommanded(tmp_path, xml, 3000)
    target = 0.15 if ctrlrange else 0.0
    assert abs(d.qpos[0] - target) < 0.1 and abs(q - d.qpos[0]) < 1e-4
