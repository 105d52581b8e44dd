"""Joint couplings (a URDF <mimic>: q = multiplier q_leader + offset) held by the step: a
two-finger gripper whose second finger mimics the first, the first driven by a stiff implicit
spring to a target, the second free. The follower tracks the relation within 1 % while the
leader moves and once it settles, and the leader's equilibrium is the target (the follower's
joint carries no spring of its own). A mimic of an unknown joint is ignored with a warning.
"""

from __future__ import annotations

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr


def gripper(multiplier: float, offset: float, leader: str = "left") -> str:
    finger = '<inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>'
    return f"""<robot name="gripper">
  <link name="palm"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="left">{finger}</link>
  <link name="right">{finger}</link>
  <joint name="left" type="prismatic"><parent link="palm"/><child link="left"/><origin xyz="0 0.05 0"/>
    <axis xyz="0 1 0"/><limit lower="-0.05" upper="0.05" effort="20" velocity="1"/></joint>
  <joint name="right" type="revolute"><parent link="palm"/><child link="right"/><origin xyz="0 -0.05 0"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="20" velocity="1"/><mimic joint="{leader}" multiplier="{multiplier}" offset="{offset}"/></joint>
</robot>
"""


@pytest.fixture
def engine():
    sdp.initialize(num_worker_threads=0)
    yield
    sdp.shutdown()


@pytest.mark.parametrize("multiplier,offset", [(-1.0, 0.0), (8.0, 0.05)])
def test_follower_keeps_the_relation_while_the_leader_moves(engine, tmp_path, multiplier, offset):
    path = tmp_path / "gripper.urdf"
    path.write_text(gripper(multiplier, offset))
    prefab = sdr.load_bot_prefab_from_urdf_file(str(path), fixed_base=True)
    scene = sdp.create_scene("coupling")
    scene.set_gravity([0, 0, -9.81])
    arm = sdr.create_bot(scene, prefab, sdr.create_context()).get_articulated_actor()
    target = 0.03
    arm.set_joint_drive(0, stiffness=200.0, damping=5.0, target_position=target)
    dt = 0.002
    # the relation holds from the first steps (the follower starts at 0, off it by the offset)
    errors = []
    for k in range(1500):
        scene.step(dt)
        q = np.asarray(arm.get_articulated_pose(), dtype=float)
        if k >= 10:
            errors.append(abs(q[1] - (multiplier * q[0] + offset)))
    scale = abs(multiplier) * target + abs(offset)
    assert max(errors) <= 0.01 * scale, max(errors)
    q = np.asarray(arm.get_articulated_pose(), dtype=float)
    assert abs(q[0] - target) <= 0.01 * target
    assert abs(q[1] - (multiplier * target + offset)) <= 0.01 * scale


def test_a_mimic_of_an_unknown_joint_is_ignored_with_a_warning(tmp_path):
    path = tmp_path / "gripper.urdf"
    path.write_text(gripper(1.0, 0.0, leader="thumb"))
    with pytest.warns(UserWarning, match=r"gripper.urdf: line \d+: .*<mimic>: <mimic> is ignored: it refers to joint 'thumb', which is not defined"):
        prefab = sdr.load_bot_prefab_from_urdf_file(str(path))
    assert len(prefab.couplings) == 0


MJCF_PAIR = """<mujoco>
  <option timestep="0.002"/>
  <worldbody>
    <body name="a" pos="0 0 1"><joint name="leader" axis="0 1 0" damping="0.2"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.02" contype="0" conaffinity="0"/></body>
    <body name="b" pos="0.5 0 1"><joint name="follower" axis="0 1 0" damping="0.2"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.02" contype="0" conaffinity="0"/></body>
  </worldbody>
  <equality><joint joint1="follower" joint2="leader" polycoef="0.1 -2 0 0 0"/></equality>
  <actuator><position joint="leader" kp="40" kv="2"/></actuator>
</mujoco>
"""


def test_mjcf_joint_equality_couples_like_mujocos(engine, tmp_path):
    """<equality><joint polycoef="0.1 -2"/>: follower = 0.1 - 2 leader, with the leader held at
    0.4 rad by a position servo: ours keeps the relation within 1 % and settles where MuJoCo's
    (soft) equality settles."""
    import mujoco

    m = mujoco.MjModel.from_xml_string(MJCF_PAIR)
    d = mujoco.MjData(m)
    d.ctrl[:] = 0.4
    for _ in range(2000):
        mujoco.mj_step(m, d)
    path = tmp_path / "pair.xml"
    path.write_text(MJCF_PAIR)
    model = sdr.load_mjcf_file(path)
    (prefab,) = model.bots
    assert [(c.joint, c.leader, c.ratio, c.offset) for c in prefab.couplings] == [("follower", "leader", -2.0, pytest.approx(0.1))]
    scene = sdp.create_scene("pair")
    scene.set_gravity(model.gravity)
    ctx = sdr.create_context()
    bot = sdr.create_bot(scene, prefab, ctx)
    command = bot.create_controller("JOINT_COMMAND", "command")
    ctx.configure_controller(command, {"position": [0.4, float("nan")]})
    arm = bot.get_articulated_actor()
    for _ in range(2000):
        scene.step(model.timestep)
    leader, follower = np.asarray(arm.get_articulated_pose(), dtype=float)
    assert abs(follower - (0.1 - 2 * leader)) <= 0.01 * 0.7
    assert abs(leader - d.qpos[0]) < 0.02 and abs(follower - d.qpos[1]) < 0.04, (leader, follower, d.qpos)
