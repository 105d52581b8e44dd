"""Mod-bots: a `.superdex_bot` holding a `base` bot and `modifications` (AttachLink, AttachBot)
builds one flat bot; paths start at the file's folder, at the asset root ("//", the nearest
`.superdex_root` marker) or at an asset tag ("@tag/"); disabled modifications are skipped. Massless
links on Hard joints are frames merged into their parent's body; anything else without mass is an
error naming the link. Bad mod-bots end in errors naming the file and the field.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from robotics_helpers import scene  # noqa: F401

INERTIA = [1e-4, 0, 0, 1e-4, 0, 1e-4]


def arm():
    """A one-joint arm: a welded base, a 0.3 m link on a revolute joint, a massless tool frame."""
    return {
        "name": "arm",
        "links": [
            {"name": "base", "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01]},
            {"name": "upper", "parentLink": 0, "mass": 0.5, "centerOfMass": [0, 0, 0.15], "momentOfInertia": [4e-3, 0, 0, 4e-3, 0, 1e-4]},
            {"name": "tool", "parentLink": 1, "mass": 0.0},
        ],
        "joints": [
            {"name": "weld", "type": "Hard"},
            {"name": "shoulder", "type": "Revolute", "axis": [0, 1, 0], "parentLinkFromJoint": {"translation": [0, 0, 0.1]}},
            {"name": "tool_weld", "type": "Hard", "parentLinkFromJoint": {"translation": [0, 0, 0.3]}},
        ],
        "defaultPose": [0.25],
    }


def gripper():
    """A free-floating palm with one finger on a prismatic joint."""
    return {
        "name": "gripper",
        "links": [
            {"name": "palm", "mass": 0.2, "momentOfInertia": INERTIA, "shape": {"box": {"halfExtents": [0.02, 0.02, 0.01]}}},
            {"name": "finger", "parentLink": 0, "mass": 0.02, "momentOfInertia": [1e-6, 0, 0, 1e-6, 0, 1e-6]},
        ],
        "joints": [
            {"name": "world_joint", "type": "Free"},
            {"name": "slide", "type": "Prismatic", "axis": [1, 0, 0], "minLimit": 0.0, "maxLimit": 0.04,
             "parentLinkFromJoint": {"translation": [0, 0, 0.02]}},
        ],
        "defaultPose": [0.01],
    }


def attach_bot(path, parent="tool", **extra):
    mod = {"joint": {"name": "tool_to_gripper", "type": "Hard", "parentLinkFromJoint": {"translation": [0, 0, 0.01]}},
           "parentLinkName": parent, "path": path, "name": "gripper"}
    return {"AttachBot": {**mod, **extra}}


def attach_link(parent="upper", **extra):
    mod = {"joint": {"name": "camera_mount", "type": "Hard", "parentLinkFromJoint": {"translation": [0.05, 0, 0.1]}},
           "link": {"name": "camera", "mass": 0.1, "momentOfInertia": [1e-5, 0, 0, 1e-5, 0, 1e-5],
                    "sensors": [{"type": "CONTACT_FORCE", "name": "camera_touch"}]},
           "parentLinkName": parent, "name": "camera"}
    return {"AttachLink": {**mod, **extra}}


def write(folder, name, doc):
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    path.write_text(json.dumps(doc))
    return str(path)


@pytest.fixture
def tree(tmp_path):
    """An asset root with arms/arm.superdex_bot and grippers/gripper.superdex_bot."""
    (tmp_path / ".superdex_root").write_text("")
    write(tmp_path / "arms", "arm.superdex_bot", arm())
    write(tmp_path / "grippers", "gripper.superdex_bot", gripper())
    return tmp_path


def test_a_mod_bot_attaches_a_link_and_a_bot(scene, tree):  # noqa: F811
    path = write(tree / "combos", "arm_gripper.superdex_bot",
                 {"base": "//arms/arm.superdex_bot", "name": "arm_gripper",
                  "modifications": [attach_link(), attach_bot("//grippers/gripper.superdex_bot")]})
    prefab = sdr.load_bot_prefab_from_file(path)
    assert prefab.name == "arm_gripper"
    assert [l.name for l in prefab.links] == ["base", "upper", "tool", "camera", "palm", "finger"]
    assert [l.parent_link for l in prefab.links] == [-1, 0, 1, 1, 2, 4]
    assert [j.name for j in prefab.joints] == ["weld", "shoulder", "tool_weld", "camera_mount", "tool_to_gripper", "slide"]
    # the gripper's Free root became the modification's weld; the poses follow the DOFs
    assert prefab.joints[4].type == sdp.ArticulatedJointType.HARD
    np.testing.assert_allclose(prefab.default_pose, [0.25, 0.01])
    assert [d.name for d in prefab.sensors[3]] == ["camera_touch"]
    ctx = sdr.create_context()
    robot = sdr.create_bot(scene, prefab, ctx).get_articulated_actor()
    assert robot.get_num_dofs() == 2
    robot.set_articulated_pose_from_joints([0.0, 0.0])
    links = robot.get_nested_link_actors()
    # palm: shoulder at 0.1, tool 0.3 above it, gripper 0.01 above the tool
    np.testing.assert_allclose(list(scene.get_actor(links[4]).get_root_transform().translation), [0, 0, 0.41], atol=1e-6)
    for _ in range(100):
        scene.step(0.005)
    assert np.all(np.isfinite(robot.get_articulated_pose()))


def test_paths_relative_to_the_file_and_through_asset_tags(scene, tree):  # noqa: F811
    relative = write(tree / "arms", "with_gripper.superdex_bot",
                     {"base": "arm.superdex_bot", "modifications": [attach_bot("../grippers/gripper.superdex_bot")]})
    assert len(sdr.load_bot_prefab_from_file(relative).links) == 5
    (tree / "combos").mkdir()
    (tree / "combos" / ".superdex_root").write_text(json.dumps({"@hands": "../grippers"}))
    tagged = write(tree / "combos", "tagged.superdex_bot",
                   {"base": "//arms/arm.superdex_bot", "modifications": [attach_bot("@hands/gripper.superdex_bot")]})
    # the nearest marker (combos/) is the root for "//" too: no arms/ there
    with pytest.raises(sdp.Error, match=r"tagged.superdex_bot: base: '//arms/arm.superdex_bot' resolves to '.*combos/arms/arm.superdex_bot', which does not exist"):
        sdr.load_bot_prefab_from_file(tagged)
    doc = json.loads((tree / "combos" / "tagged.superdex_bot").read_text())
    doc["base"] = "../arms/arm.superdex_bot"
    (tree / "combos" / "tagged.superdex_bot").write_text(json.dumps(doc))
    assert [l.name for l in sdr.load_bot_prefab_from_file(tagged).links][-2:] == ["palm", "finger"]


def test_disabled_modifications_are_skipped(tree):
    path = write(tree, "off.superdex_bot", {"base": "arms/arm.superdex_bot", "modifications": [attach_link(enabled=False)]})
    prefab = sdr.load_bot_prefab_from_file(path)
    assert [l.name for l in prefab.links] == ["base", "upper", "tool"]
    assert prefab.name == "arm"


def test_massless_links_must_be_welded_frames(scene, tmp_path):  # noqa: F811
    doc = arm()
    doc["joints"][2] = {"name": "tool_joint", "type": "Revolute", "axis": [1, 0, 0]}
    doc["defaultPose"] = [0.25, 0.0]
    prefab = sdr.load_bot_prefab_from_file(write(tmp_path, "bad.superdex_bot", doc))
    with pytest.raises(sdp.Error, match=r"links\[2\]\.mass: must be a positive finite number, got 0 \(a massless link must hang from a Hard "
                                        r"joint, which merges it into its parent\)"):
        sdr.create_bot(scene, prefab, sdr.create_context())
    doc = arm()
    doc["links"][2]["momentOfInertia"] = [1e-6, 0, 0, 1e-6, 0, 1e-6]
    prefab = sdr.load_bot_prefab_from_file(write(tmp_path, "bad2.superdex_bot", doc))
    with pytest.raises(sdp.Error, match=r"links\[2\]\.momentOfInertia: must be zero on a massless link"):
        sdr.create_bot(scene, prefab, sdr.create_context())
    # a moving body made only of massless links
    doc = arm()
    doc["links"][1]["mass"] = 0.0
    doc["links"][1].pop("momentOfInertia")
    doc["joints"][1]["type"], doc["joints"][2]["type"] = "Revolute", "Hard"
    doc["links"].append({"name": "hand", "parentLink": 2, "mass": 0.0})
    doc["joints"].append({"name": "hand_weld", "type": "Hard"})
    prefab = sdr.load_bot_prefab_from_file(write(tmp_path, "bad3.superdex_bot", doc))
    with pytest.raises(sdp.Error, match=r"links\[1\]\.mass: must be a positive finite number, got 0"):
        sdr.create_bot(scene, prefab, sdr.create_context())


def test_a_massless_welded_link_adds_nothing(scene, tmp_path):  # noqa: F811
    # the arm swings as a pendulum of its upper link alone: period 2 pi sqrt(I_o / (m g d))
    doc = arm()
    doc["defaultPose"] = [0.1]
    robot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(write(tmp_path, "arm.superdex_bot", doc)),
                           sdr.create_context()).get_articulated_actor()
    robot.set_articulated_pose_from_joints([np.pi - 0.05])  # hanging, 0.05 rad off
    m, d, I_com = 0.5, 0.15, 4e-3
    period = 2 * np.pi * np.sqrt((I_com + m * d * d) / (m * 9.81 * d))
    dt, q = period / 500, []
    for _ in range(1500):
        scene.step(dt)
        q.append(robot.get_articulated_pose()[0] - np.pi)
    q = np.asarray(q)
    crossings = np.nonzero((q[:-1] > 0) & (q[1:] <= 0))[0]
    assert (crossings[-1] - crossings[0]) * dt / (len(crossings) - 1) == pytest.approx(period, rel=0.01)


@pytest.mark.parametrize("mods, message", [
    ([attach_link(parent="elbow")], r"modifications\[0\]\.AttachLink\.parentLinkName: no link named 'elbow'"),
    ([{"ReplaceLink": {}}], r"modifications\[0\]: unknown modification 'ReplaceLink' \(this version builds AttachLink and AttachBot\)"),
    ([{"AttachLink": {}, "AttachBot": {}}], r"modifications\[0\]: expected an object with one key naming the modification"),
    ([attach_bot("//grippers/nothing.superdex_bot")], r"modifications\[0\]\.AttachBot\.path: '//grippers/nothing.superdex_bot' resolves to"),
    ([attach_link(), attach_link(link={"name": "camera", "mass": 0.1, "momentOfInertia": INERTIA})], r"modifications\[1\]\.AttachLink: link name 'camera' is already used in the bot"),
    ([attach_bot("//grippers/gripper.superdex_bot", joint={"name": "j", "type": "Free"})],
     r"modifications\[0\]\.AttachBot\.joint\.type: an attached bot hangs from its parent link: Free is not allowed"),
    ([attach_link(enabled="yes")], r"modifications\[0\]\.AttachLink\.enabled: expected true or false"),
])
def test_bad_mod_bots_name_the_field(tree, mods, message):
    path = write(tree / "combos", "bad.superdex_bot", {"base": "//arms/arm.superdex_bot", "modifications": mods})
    with pytest.raises(sdp.Error, match=r"bad.superdex_bot: " + message):
        sdr.load_bot_prefab_from_file(path)


def test_a_bot_that_includes_itself_is_an_error(tree):
    path = write(tree, "loop.superdex_bot", {"base": "loop.superdex_bot"})
    with pytest.raises(sdp.Error, match=r"loop.superdex_bot: the bot includes itself"):
        sdr.load_bot_prefab_from_file(path)


def test_root_paths_need_a_marker(tmp_path):
    write(tmp_path / "arms", "arm.superdex_bot", arm())
    path = write(tmp_path / "x", "combo.superdex_bot", {"base": "//arms/arm.superdex_bot"})
    with pytest.raises(sdp.Error, match=r"combo.superdex_bot: base: '//arms/arm.superdex_bot' is relative to the asset root, but no "
                                        r"\.superdex_root marker is in"):
        sdr.load_bot_prefab_from_file(path)
    path = write(tmp_path / "x", "tagged.superdex_bot", {"base": "@nowhere/arm.superdex_bot"})
    with pytest.raises(sdp.Error, match=r"tagged.superdex_bot: base: asset tag @nowhere is defined by no \.superdex_root marker"):
        sdr.load_bot_prefab_from_file(path)


def test_a_mod_bot_cannot_also_list_links(tree):
    path = write(tree, "both.superdex_bot", {"base": "arms/arm.superdex_bot", "links": []})
    with pytest.raises(sdp.Error, match=r"both.superdex_bot: links: a mod-bot \(one with a base\) takes its links and joints"):
        sdr.load_bot_prefab_from_file(path)
