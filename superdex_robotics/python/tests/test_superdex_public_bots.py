"""The bot files of SuperDex's public asset tree, with stand-in shapes (tools/make_superdex_bots.py):
the Revo2 hands, the FR3 v2 + Revo2 mod-bots and the googly eye load, build and step; the Revo2's
distal joints follow their proximal joints by the transmission ratios within 1 %; the massless
fingertip and flange links sit where the file's joint frames put them; the googly eye swings as
the pendulum its inertials make.
"""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from robotics_helpers import scene  # noqa: F401
from superdex.physics.paths import resolve_asset

HANDS = {side: f"bots/hands/revo2/{side}/revo2_{side}.superdex_bot" for side in ("left", "right")}
COMBOS = {side: f"bots/arm_hand_combos/fr3_v2_revo2/fr3_v2_revo2_{side}.superdex_bot" for side in ("left", "right")}
GOOGLY = "bots/fun/googly_eyes/googly_eyes_extra_small.superdex_bot"
FR3_V2 = "bots/arms/fr3_v2/fr3_v2.superdex_bot"
ROOT_DOFS = 6  # a Free root
# poses agree to round-off: of doubles, or of floats over a chain of about 20 joints
ATOL = 1e-9 if sdp.uses_double_precision() else 2e-6


def load(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the TACTILE_PAD and boundaryElementType notes
        return sdr.load_bot_prefab_from_file(str(resolve_asset(path)))


def create(scene, prefab):  # noqa: F811
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return sdr.create_bot(scene, prefab, sdr.create_context()).get_articulated_actor()


def rotation(q):
    """3x3 rotation matrix of a quaternion [x, y, z, w]."""
    x, y, z, w = np.asarray(q, float) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def homogeneous(pose):
    T = np.eye(4)
    T[:3, :3] = rotation(pose.get("rotation", [0, 0, 0, 1]))
    T[:3, 3] = pose.get("translation", [0, 0, 0])
    return T


def link_pose(actor, scene, index):  # noqa: F811
    X = scene.get_actor(actor.get_nested_link_actors()[index]).get_root_transform()
    T = np.eye(4)
    T[:3, :3] = rotation(X.rotation.tolist())
    T[:3, 3] = np.asarray(X.translation, float)
    return T


def file_chain(doc, index):
    """The link's pose in the root link's frame at zero joint positions, from the file's joint frames."""
    T = np.eye(4)
    while index > 0:
        T = homogeneous(doc["joints"][index].get("parentLinkFromJoint", {})) @ T
        index = doc["links"][index]["parentLink"]
    return T


@pytest.mark.parametrize("side", ["left", "right"])
def test_revo2_loads_with_its_massless_tips_merged_and_couplings(scene, side):  # noqa: F811
    doc = json.loads(Path(resolve_asset(HANDS[side])).read_text())
    prefab = load(HANDS[side])
    assert [l.name for l in prefab.links] == [l["name"] for l in doc["links"]]
    assert len(prefab.default_pose) == 11
    assert [(list(t.joint_indices), list(t.joint_coefficients)) for t in prefab.linear_transmissions] == [
        (t["jointIndices"], [pytest.approx(c) for c in t["jointCoefficients"]]) for t in doc["linearTransmissions"]]
    hand = create(scene, prefab)
    # the massless tip links are frames on their distal links: where the file's joints put them
    base = link_pose(hand, scene, 0)
    for i, link in enumerate(doc["links"]):
        if link["mass"] == 0:
            np.testing.assert_allclose(np.linalg.inv(base) @ link_pose(hand, scene, i), file_chain(doc, i), atol=ATOL)


@pytest.mark.parametrize("side", ["left", "right"])
def test_revo2_distal_joints_follow_the_proximal_joints(scene, side):  # noqa: F811
    doc = json.loads(Path(resolve_asset(HANDS[side])).read_text())
    scene.set_gravity([0, 0, 0])
    hand = create(scene, load(HANDS[side]))
    # bot DOF k (after the root) is joint k + 1 of the file; drive every leader to half its range (the follower to half of its own)
    dof = {}
    for j in doc["joints"][1:]:
        if j["type"] == "Revolute":
            dof[j["name"]] = ROOT_DOFS + len(dof)
    pairs = []
    for t in doc["linearTransmissions"]:
        leader, follower = (doc["joints"][i] for i in t["jointIndices"])
        ratio = -t["jointCoefficients"][0] / t["jointCoefficients"][1]
        axis = np.asarray(leader["axis"], float)
        upper = float(axis @ np.asarray(leader["maxLimit"], float))
        hand.set_joint_drive(dof[leader["name"]], stiffness=0.5, damping=0.01, target_position=0.5 * upper / max(ratio, 1.0))
        pairs.append((dof[leader["name"]], dof[follower["name"]], ratio))
    for _ in range(500):
        scene.step(0.002)
    q = np.asarray(hand.get_articulated_pose(), float)
    assert np.all(np.isfinite(q))
    for lead, follow, ratio in pairs:
        assert q[lead] > 0.3, "the drive moved the leader"
        assert abs(q[follow] - ratio * q[lead]) <= 0.01 * ratio * q[lead]


@pytest.mark.parametrize("side", ["left", "right"])
def test_fr3_v2_revo2_mod_bot_builds_the_arm_the_mount_and_the_hand(scene, side):  # noqa: F811
    arm_doc = json.loads(Path(resolve_asset(FR3_V2)).read_text())
    hand_doc = json.loads(Path(resolve_asset(HANDS[side])).read_text())
    combo = json.loads(Path(resolve_asset(COMBOS[side])).read_text())
    prefab = load(COMBOS[side])
    assert prefab.name == f"fr3_v2_revo2_{side}"
    names = [l.name for l in prefab.links]
    assert names == [l["name"] for l in arm_doc["links"]] + ["fr3_revo2_mount"] + [l["name"] for l in hand_doc["links"]]
    # the arm's ready pose, then the hand's (the welds add no DOF); the hand's couplings come along
    np.testing.assert_allclose(prefab.default_pose, arm_doc["defaultPose"] + hand_doc["defaultPose"])
    # the hand's transmissions come along, their joint indices moved past the arm's and the mount's
    hand_offset = len(arm_doc["joints"]) + 1
    assert [list(t.joint_indices) for t in prefab.linear_transmissions] == [
        [i + hand_offset for i in t["jointIndices"]] for t in hand_doc["linearTransmissions"]]
    robot = create(scene, prefab)
    robot.set_articulated_pose_from_joints([0.0] * 18)
    # mount: flange link 8, turned by the AttachLink joint; hand base: 15 mm above the mount
    mount_joint = homogeneous(combo["modifications"][0]["AttachLink"]["joint"]["parentLinkFromJoint"])
    hand_joint = homogeneous(combo["modifications"][1]["AttachBot"]["joint"]["parentLinkFromJoint"])
    link8 = names.index("fr3_link8")
    flange = link_pose(robot, scene, link8)
    np.testing.assert_allclose(link_pose(robot, scene, link8 - 1) @ np.linalg.inv(file_chain(arm_doc, link8 - 1)) @ file_chain(arm_doc, link8),
                               flange, atol=ATOL)
    np.testing.assert_allclose(link_pose(robot, scene, names.index("fr3_revo2_mount")), flange @ mount_joint, atol=ATOL)
    hand_base = flange @ mount_joint @ hand_joint
    np.testing.assert_allclose(link_pose(robot, scene, names.index(f"{side}_base_link")), hand_base, atol=ATOL)
    # hold the arm at its ready pose with joint drives under gravity: 1 s, finite, couplings held
    ready = np.asarray(arm_doc["defaultPose"], float)
    robot.set_articulated_pose_from_joints(list(prefab.default_pose))
    for k in range(7):
        robot.set_joint_drive(k, stiffness=4000.0, damping=200.0, target_position=ready[k])
    for _ in range(500):
        scene.step(0.002)
    q = np.asarray(robot.get_articulated_pose(), float)
    assert np.all(np.isfinite(q)) and np.max(np.abs(q[:7] - ready)) < 0.01
    dof = {i: k for k, i in enumerate(i for i, j in enumerate(prefab.joints) if j.type == sdp.ArticulatedJointType.REVOLUTE)}
    for t in prefab.linear_transmissions:
        lead, follow = t.joint_indices
        ratio = -t.joint_coefficients[0] / t.joint_coefficients[1]
        assert abs(q[dof[follow]] - ratio * q[dof[lead]]) <= 1e-3


def test_googly_eye_swings_as_its_inertials_say(scene):  # noqa: F811
    doc = json.loads(Path(resolve_asset(GOOGLY)).read_text())
    eye = create(scene, load(GOOGLY))
    mass, com = doc["links"][1]["mass"], np.asarray(doc["links"][1]["centerOfMass"], float)
    Iyy = doc["links"][1]["momentOfInertia"][3]
    # a compound pendulum about y (horizontal): I = Iyy + m d^2, period 2 pi sqrt(I / (m g d))
    d = math.hypot(com[0], com[2])
    period = 2 * math.pi * math.sqrt((Iyy + mass * d * d) / (mass * 9.81 * d))
    # hanging equilibrium: the centre of mass below the axis; start 0.1 rad off it
    rest = math.atan2(com[2], com[0]) + math.pi / 2
    eye.set_articulated_pose_from_joints([rest + 0.1])
    dt, angles = period / 400, []
    for _ in range(1200):
        scene.step(dt)
        angles.append(eye.get_articulated_pose()[0] - rest)
    angles = np.asarray(angles)
    crossings = np.nonzero((angles[:-1] > 0) & (angles[1:] <= 0))[0]
    measured = (crossings[-1] - crossings[0]) * dt / (len(crossings) - 1)
    assert measured == pytest.approx(period, rel=0.01)


@pytest.mark.parametrize("side", ["left", "right"])
def test_revo2_fingertip_pads_are_tactile_sensors(scene, side):  # noqa: F811
    doc = json.loads(Path(resolve_asset(HANDS[side])).read_text())
    ctx = sdr.create_context()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        bot = sdr.create_bot(scene, load(HANDS[side]), ctx)
    assert not [w for w in caught if "not registered" in str(w.message)]
    for link in doc["links"]:
        for sensor in link.get("sensors", []):
            params = json.loads(sensor["params"])
            (handle,) = bot.find_sensors_by_name(sensor["name"])
            scene.step(0.002)
            taxels = np.asarray(ctx.get_sensor_signal(handle))
            assert taxels.shape == (params["rows"] * params["cols"],)
            np.testing.assert_array_equal(taxels, 0.0)  # nothing touches the fingertips
