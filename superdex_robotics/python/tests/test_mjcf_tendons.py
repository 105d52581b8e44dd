"""MJCF fixed tendons and joint springs, against MuJoCo on the same files and against statics:
a joint spring holds a pendulum at the angle where its torque balances gravity; a tendon spring
over two hinges moves the finger along MuJoCo's path; unset spring lengths come from springref;
a tendon range holds a two-joint finger the way the Shadow hand's distal tendons do, at the
static pose and near MuJoCo's; the Shadow hand of
gymnasium-robotics imports all its tendons and keeps its coupled joints within their ranges;
defaults classes apply to tendons; bad tendons name the file and element; joint limits, like
MuJoCo's, come to rest at their margin.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

try:
    import mujoco
except ImportError as exc:  # a declared dev dependency: missing means a broken environment
    raise ImportError("mujoco (a dev dependency in pyproject.toml) is required by this test; run `uv sync`") from exc

import superdex.physics as sdp
import superdex.robotics as sdr

DT = 0.002


def bisect(f, lo: float, hi: float) -> float:
    """The root of f between lo and hi (f changes sign there), to round-off."""
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if np.sign(f(mid)) == np.sign(f(lo)) else (lo, mid)
    return 0.5 * (lo + hi)


def two_links(tendon: str, joint_attrs: str = 'damping="0.02"', gravity: str = "0 0 -9.81") -> str:
    """A two-link finger hanging from a hinge at the origin: 0.1 m links of 0.1 kg, hinges about y."""
    return f"""<mujoco>
  <compiler angle="radian"/>
  <option timestep="{DT}" gravity="{gravity}"/>
  <worldbody>
    <body name="proximal" euler="0 90 0">
      <joint name="j1" axis="0 1 0" {joint_attrs}/>
      <geom type="capsule" fromto="0 0 0 0.1 0 0" size="0.01" mass="0.1" contype="0" conaffinity="0"/>
      <body name="distal" pos="0.1 0 0">
        <joint name="j0" axis="0 1 0" {joint_attrs}/>
        <geom type="capsule" fromto="0 0 0 0.1 0 0" size="0.01" mass="0.1" contype="0" conaffinity="0"/>
      </body>
    </body>
  </worldbody>
  <tendon>{tendon}</tendon>
</mujoco>
"""


def pendulum(joint_attrs: str, angle: str = "radian") -> str:
    """A 1 kg ball 0.5 m below a hinge about y, under gravity, its joint given `joint_attrs`."""
    return f"""<mujoco>
  <compiler angle="{angle}"/>
  <option timestep="{DT}" gravity="0 0 -9.81"/>
  <worldbody>
    <body name="pendulum">
      <joint name="hinge" axis="0 1 0" {joint_attrs}/>
      <geom type="sphere" size="0.05" pos="0 0 -0.5" mass="1" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
</mujoco>
"""


def mujoco_settle(xml: str, qpos0, steps: int):
    m = mujoco.MjModel.from_xml_string(xml)
    d = mujoco.MjData(m)
    d.qpos[:] = qpos0
    for _ in range(steps):
        mujoco.mj_step(m, d)
    return np.array(d.qpos), np.array(d.ten_length)


def ours_settle(tmp_path, xml: str, qpos0, steps: int):
    path = tmp_path / "model.xml"
    path.write_text(xml)
    sdp.initialize(num_worker_threads=0)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # nothing of these models is left out
            model = sdr.load_mjcf_file(path)
        scene = sdp.create_scene("mjcf")
        scene.set_gravity(model.gravity)
        (prefab,) = model.bots
        art = sdr.create_bot(scene, prefab, sdr.create_context()).get_articulated_actor()
        art.set_articulated_pose_from_joints(list(qpos0))
        for _ in range(steps):
            scene.step(model.timestep)
        return np.asarray(art.get_articulated_pose(), dtype=float), list(prefab.fixed_tendons)
    finally:
        sdp.shutdown()


def test_joint_spring_balances_gravity(tmp_path):
    # a 1 kg ball 0.5 m below a hinge with k = 20 N m/rad towards springref = 60 degrees:
    # k (ref - q) = m g l sin q at rest
    xml = pendulum('damping="1" stiffness="20" springref="60"', angle="degree")
    q, tendons = ours_settle(tmp_path, xml, [0.0], 4000)
    assert [(t.name, list(t.joints), t.stiffness) for t in tendons] == [("hinge/spring", ["hinge"], 20.0)]
    assert tendons[0].rest_length == pytest.approx(np.pi / 3)
    q_static = bisect(lambda x: 20 * (np.pi / 3 - x) - 9.81 * 0.5 * np.sin(x), 0, np.pi / 3)
    assert abs(q[0] - q_static) < 1e-4
    q_ref, _ = mujoco_settle(xml, [0.0], 4000)
    assert abs(q_ref[0] - q_static) < 1e-4  # the reference agrees with the statics too


def test_tendon_spring_moves_the_finger_as_mujoco_does(tmp_path):
    # a spring on 0.5 j1 - j0 towards length 0.3 against gravity, the joints overdamped: the
    # finger creeps to the pose where the spring balances gravity, along MuJoCo's path
    xml = two_links('<fixed name="t" stiffness="2" damping="0.1" springlength="0.3">'
                    '<joint joint="j1" coef="0.5"/><joint joint="j0" coef="-1"/></fixed>', joint_attrs='damping="0.2"')
    for steps in (250, 3000):
        q_ref, L_ref = mujoco_settle(xml, [0.2, -0.1], steps)
        q, tendons = ours_settle(tmp_path, xml, [0.2, -0.1], steps)
        assert np.abs(q - q_ref).max() < 1e-4
    assert len(tendons) == 1 and list(tendons[0].coefficients) == [0.5, -1.0]
    # gravity keeps the spring stretched away from its rest length: the spring does work
    assert abs(L_ref[0] - 0.3) > 0.005


def test_default_spring_length_is_the_length_at_springref(tmp_path):
    # springlength unset: the spring is relaxed at the joints' springref (0.4 and -0.2: length
    # 0.5 * 0.4 + 0.2), not at their ref
    xml = two_links('<fixed name="t" stiffness="1"><joint joint="j1" coef="0.5"/><joint joint="j0" coef="-1"/></fixed>',
                    gravity="0 0 0").replace('name="j1"', 'name="j1" springref="0.4" ref="1"').replace('name="j0"', 'name="j0" springref="-0.2"')
    _, tendons = ours_settle(tmp_path, xml, [1.0, 0.0], 1)
    assert tendons[0].rest_length == pytest.approx(0.4)
    m = mujoco.MjModel.from_xml_string(xml)
    assert m.tendon_lengthspring[0][0] == pytest.approx(0.4)


def test_tendon_range_couples_the_finger_like_mujoco(tmp_path):
    # the Shadow hand's distal coupling: 0.00705 j0 - 0.00805 j1 within +-0.001. The proximal
    # joint j1 rests on its lower limit 1.2 under gravity; alone, the distal joint j0 would fall
    # to its own lower limit 0, but the tendon's lower bound holds it at
    # j0 = (0.00805 * 1.2 - 0.001) / 0.00705
    tendon = ('<fixed name="coupling" limited="true" range="-0.001 0.001">'
              '<joint joint="j0" coef="0.00705"/><joint joint="j1" coef="-0.00805"/></fixed>')
    xml = two_links(tendon, joint_attrs='damping="0.01" limited="true" range="0 1.6"').replace(
        '<joint name="j1" axis="0 1 0" damping="0.01" limited="true" range="0 1.6"/>',
        '<joint name="j1" axis="0 1 0" damping="0.01" limited="true" range="1.2 1.6"/>')
    assert 'range="1.2 1.6"' in xml
    q_ref, L_ref = mujoco_settle(xml, [1.4, 1.4], 3000)
    q, _ = ours_settle(tmp_path, xml, [1.4, 1.4], 3000)
    j0_static = (0.00805 * 1.2 - 0.001) / 0.00705
    assert abs(q[0] - 1.2) < 1e-4 and abs(q[1] - j0_static) < 2e-3
    L = 0.00705 * q[1] - 0.00805 * q[0]
    assert abs(L + 0.001) < 1e-5
    # MuJoCo's limits are soft (solref): it lets the tendon sag a little further
    assert np.abs(q - q_ref).max() < 0.02 and abs(L - L_ref[0]) < 2e-4


def shadow_hand_path() -> Path:
    import gymnasium_robotics

    return Path(gymnasium_robotics.__file__).parent / "envs/assets/hand/manipulate_block.xml"


def test_shadow_hand_keeps_its_distal_joints_coupled(tmp_path):
    path = shadow_hand_path()
    m = mujoco.MjModel.from_xml_path(str(path))
    sdp.initialize(num_worker_threads=0)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            model = sdr.load_mjcf_file(path)
        assert not any("tendon" in str(w.message) for w in caught)
        hand = next(p for p in model.bots if len(p.fixed_tendons) > 0)
        tendons = {t.name: t for t in hand.fixed_tendons}
        assert len(tendons) == m.ntendon
        for k in range(m.ntendon):
            t = tendons[mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_TENDON, k)]
            assert (t.lower, t.upper) == pytest.approx(tuple(m.tendon_range[k]))
        scene = sdp.create_scene("shadow")
        scene.set_gravity(model.gravity)
        ctx = sdr.create_context()
        art = sdr.create_bot(scene, hand, ctx).get_articulated_actor()
        for _ in range(500):  # 1 s, no actuation: the fingers fall under gravity
            scene.step(DT)
        q = np.asarray(art.get_articulated_pose(), dtype=float)
    finally:
        sdp.shutdown()
    # every coupled finger's length stays within its +-0.001 band (the hand's DOFs come first,
    # in MuJoCo's order, as its qpos)
    assert q.size == np.count_nonzero(m.jnt_type == mujoco.mjtJoint.mjJNT_HINGE) == 24
    coupled = [t for t in tendons.values() if t.name.endswith("J1c")]
    assert len(coupled) == 4
    for t in coupled:
        dofs = [m.jnt_qposadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, j)] for j in t.joints]
        L = sum(c * q[k] for k, c in zip(dofs, t.coefficients))
        assert t.lower - 2e-5 <= L <= t.upper + 2e-5, t.name


def test_defaults_class_applies_to_tendons(tmp_path):
    xml = two_links('<fixed name="t" class="tight"><joint joint="j1" coef="1"/></fixed>').replace(
        "<worldbody>", '<default><default class="tight"><tendon limited="true" range="-0.1 0.2" stiffness="3"/></default></default>\n  <worldbody>')
    _, tendons = ours_settle(tmp_path, xml, [0.0, 0.0], 1)
    t = tendons[0]
    assert (t.has_lower, t.lower, t.upper, t.stiffness) == (True, pytest.approx(-0.1), pytest.approx(0.2), 3.0)


@pytest.mark.parametrize(
    "tendon, message",
    [
        ('<fixed name="t"><joint joint="nope" coef="1"/></fixed>', r"model\.xml: line \d+: <mujoco>/<tendon>/<fixed name='t'>/<joint>: refers to joint 'nope', which is not defined"),
        ('<fixed name="t" limited="true" range="0.2 0.1"><joint joint="j1"/></fixed>', r"model\.xml.*<fixed name='t'>: attribute 'range': the lower limit 0\.2 exceeds"),
        ('<fixed name="t" stiffness="-1"><joint joint="j1"/></fixed>', r"model\.xml.*<fixed name='t'>: stiffness and damping must not be negative"),
        ('<fixed name="t"/>', r"model\.xml.*<fixed name='t'>: a fixed tendon needs at least one <joint>"),
    ],
)
def test_bad_tendons_name_the_file_and_element(tmp_path, tendon, message):
    path = tmp_path / "model.xml"
    path.write_text(two_links(tendon))
    with pytest.raises(sdp.Error, match=message):
        sdr.load_mjcf_file(path)


@pytest.mark.parametrize(
    "fields, message",
    [
        (dict(joints=["j1"], coefficients=[1.0, 2.0]), r"fixedTendons\[0\]\.coefficients: expected one per joint \(1\), got 2"),
        (dict(joints=["j1", "nope"], coefficients=[1.0, 2.0]), r"fixedTendons\[0\]\.joints\[1\]: no joint named 'nope'"),
        (dict(joints=["j1"], coefficients=[1.0], has_lower=True, has_upper=True, lower=0.5, upper=0.1),
         r"fixedTendons\[0\]\.range: lower \(0\.5\) is above upper \(0\.1\)"),
        (dict(joints=["j1"], coefficients=[float("nan")]), r"fixedTendons\[0\]\.coefficients\[0\]: must be finite"),
        (dict(joints=[], coefficients=[]), r"fixedTendons\[0\]\.joints: a tendon needs at least one joint"),
    ],
)
def test_tendons_set_in_code_are_checked_when_the_bot_is_built(tmp_path, fields, message):
    path = tmp_path / "model.xml"
    path.write_text(two_links(""))
    model = sdr.load_mjcf_file(path)
    (prefab,) = model.bots
    prefab.fixed_tendons = [sdr.FixedTendon(name="t", **fields)]
    sdp.initialize(num_worker_threads=0)
    try:
        scene = sdp.create_scene("bad")
        with pytest.raises(sdp.Error, match=message):
            sdr.create_bot(scene, prefab, sdr.create_context())
        # the scene is left as it was: nothing half-built stays behind
        assert scene.get_num_actors() == 0
    finally:
        sdp.shutdown()


def test_tendon_added_in_code_acts(tmp_path):
    # a tendon appended to an imported bot's list in place holds j0 = j1 (range 0 on j0 - j1)
    path = tmp_path / "model.xml"
    path.write_text(two_links(""))
    (prefab,) = sdr.load_mjcf_file(path).bots
    prefab.fixed_tendons.append(sdr.FixedTendon(name="same", joints=["j0", "j1"], coefficients=[1.0, -1.0],
                                                has_lower=True, has_upper=True))
    assert [t.name for t in prefab.fixed_tendons] == ["same"]
    sdp.initialize(num_worker_threads=0)
    try:
        scene = sdp.create_scene("code")
        scene.set_gravity([0, 0, -9.81])
        art = sdr.create_bot(scene, prefab, sdr.create_context()).get_articulated_actor()
        art.set_articulated_pose_from_joints([0.8, 0.8])
        for _ in range(200):
            scene.step(DT)
        q = np.asarray(art.get_articulated_pose(), dtype=float)
    finally:
        sdp.shutdown()
    assert abs(q[0] - q[1]) < 1e-4 and abs(q[0]) < 0.7  # swung down together (near-rigid: 3e-5 in float)


def test_joint_limits_rest_at_their_margin_like_mujoco(tmp_path):
    # MuJoCo's limit acts from `margin` inside the range: a pendulum falling onto its lower limit
    # 0.3 with margin 0.05 comes to rest at 0.35 (the Shadow hand's fingers rest 0.01 off theirs)
    xml = pendulum('damping="0.5" limited="true" range="0.3 1" margin="0.05"')
    q_ref, _ = mujoco_settle(xml, [0.6], 2000)
    q, _ = ours_settle(tmp_path, xml, [0.6], 2000)
    assert abs(q_ref[0] - 0.35) < 2e-3  # (MuJoCo's soft limit gives a little under gravity)
    assert abs(q[0] - 0.35) < 1e-5 and abs(q[0] - q_ref[0]) < 2e-3
