"""Malformed .superdex_bot files: each validation rule gives sdp.Error naming the file and JSON path."""

import json

import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from robotics_helpers import EXAMPLE_BOT, example_bot_json, scene, write_bot  # noqa: F401
from superdex.physics.paths import resolve_asset


def edit(doc, fn):
    fn(doc)
    return doc


CASES = [
    ("duplicate link name", lambda d: d["links"][2].__setitem__("name", "link_1"), r"links\[2\]\.name: duplicate link name 'link_1'"),
    ("duplicate joint name", lambda d: d["joints"][2].__setitem__("name", "shoulder"), r"joints\[2\]\.name: duplicate joint name"),
    ("one joint per link", lambda d: d["joints"].pop(), r"joints: expected exactly one joint per link \(4 links\), got 3"),
    ("root joint", lambda d: d["joints"][0].update({"type": "Revolute", "axis": [0, 1, 0]}), r"joints\[0\]\.type: the root joint must be Hard or Free"),
    ("free non-root", lambda d: d["joints"][2].update({"type": "Free"}), r"joints\[2\]\.type: only the root joint"),
    ("zero axis", lambda d: d["joints"][1].update({"axis": [0, 0, 0]}), r"joints\[1\]\.axis: must be a finite, non-zero vector"),
    ("limits ordered", lambda d: d["joints"][2].update({"minLimit": [0, 2, 0], "maxLimit": [0, 1, 0]}), r"joints\[2\]\.minLimit: the lower limit 2 exceeds the upper limit 1"),
    ("negative mass", lambda d: d["links"][1].update({"mass": -0.3}), r"links\[1\]\.mass: must be a positive finite number"),
    ("inertia not positive definite", lambda d: d["links"][2].update({"momentOfInertia": [0, 0, 0, 0.001, 0, 0.001]}), r"links\[2\]\.momentOfInertia: must be positive definite"),
    ("inertia triangle", lambda d: d["links"][2].update({"momentOfInertia": [0.001, 0, 0, 0.001, 0, 0.01]}), r"links\[2\]\.momentOfInertia: is not physically valid"),
    ("wrong type", lambda d: d["links"][0].update({"mass": "heavy"}), r"links\[0\]\.mass: expected a number, got a string"),
    ("unknown joint type", lambda d: d["joints"][1].update({"type": "Hinge"}), r"joints\[1\]\.type: unknown joint type 'Hinge'"),
    ("missing parent", lambda d: d["links"][2].pop("parentLink"), r"links\[2\]\.parentLink: missing"),
    ("cycle", lambda d: d["links"][1].update({"parentLink": 2}), r"cycle"),
    ("sensor without type", lambda d: d["links"][3]["sensors"][0].pop("type"), r"links\[3\]\.sensors\[0\]\.type: required"),
    ("duplicate actuator name", lambda d: d["links"][2]["actuators"][0].update({"name": "servo_1"}), r"links\[2\]\.actuators\[0\]\.name: duplicate name 'servo_1'"),
    ("params not a string", lambda d: d["links"][1]["actuators"][0].update({"params": 5}), r"links\[1\]\.actuators\[0\]\.params: expected a string"),
    ("missing shape file", lambda d: d["links"][3].update({"shape": "meshes/nothing.obj"}), r"links\[3\]\.shape: shape file .*nothing\.obj' does not exist"),
    ("missing render model", lambda d: d["links"][3].update({"renderModel": "models/nothing.glb"}), r"links\[3\]\.renderModel: render model .*nothing\.glb' does not exist"),
    ("render model not glTF", lambda d: d["links"][3].update({"renderModel": str(resolve_asset(EXAMPLE_BOT))}), r"links\[3\]\.renderModel: render models are binary glTF \(\.glb\) files"),
    ("bad default pose", lambda d: d.update({"defaultPose": [0.0]}), r"defaultPose: expected 2 values"),
    ("no name", lambda d: d.pop("name"), r"name: required"),
]


@pytest.mark.parametrize("label, change, message", CASES, ids=[c[0] for c in CASES])
def test_malformed_bot_file(scene, tmp_path, label, change, message):
    path = write_bot(tmp_path, edit(example_bot_json(), change))
    with pytest.raises(sdp.Error, match=message) as info:
        prefab = sdr.load_bot_prefab_from_file(str(path))
        sdr.create_bot(scene, prefab, sdr.create_context())
    assert str(path) in str(info.value), "the message names the file"


def test_not_json_and_missing_file(tmp_path):
    bad = tmp_path / "bad.superdex_bot"
    bad.write_text("{ links: ")
    with pytest.raises(sdp.Error, match="bad.superdex_bot: not valid JSON"):
        sdr.load_bot_prefab_from_file(str(bad))
    with pytest.raises(sdp.Error, match="cannot open the bot file"):
        sdr.load_bot_prefab_from_file(str(tmp_path / "nothing.superdex_bot"))


def test_params_file_missing(scene, tmp_path):
    doc = example_bot_json()
    doc["links"][1]["actuators"][0]["params"] = "absent.json"
    path = write_bot(tmp_path, doc)
    ctx = sdr.create_context()
    sdr.register_python_actuator(ctx, "MY_VELOCITY_SERVO_ACTUATOR", lambda a, p: None)
    with pytest.raises(sdp.Error, match=r"links\[1\]\.actuators\[0\]\.params: params file .*absent\.json' does not exist"):
        sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(path)), ctx)


def test_unknown_field_warns(tmp_path):
    doc = example_bot_json()
    doc["links"][0]["colour"] = "blue"
    with pytest.warns(UserWarning, match=r"links\[0\]\.colour: unknown field"):
        sdr.load_bot_prefab_from_file(str(write_bot(tmp_path, doc)))


def test_create_bot_arguments_of_the_wrong_type(scene):
    prefab = sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT)))
    ctx = sdr.create_context()
    with pytest.raises(sdp.Error, match=r"create_bot: prefab: expected a BotPrefab \(load_bot_prefab_from_file\), got str"):
        sdr.create_bot(scene, str(resolve_asset(EXAMPLE_BOT)), ctx)
    with pytest.raises(sdp.Error, match="create_bot: scene: expected a superdex.physics.Scene, got NoneType"):
        sdr.create_bot(None, prefab, ctx)
    with pytest.raises(sdp.Error, match=r"create_bot: ctx: expected a robotics context \(create_context\(\)\), got dict"):
        sdr.create_bot(scene, prefab, {})
    with pytest.warns(UserWarning):  # the example's component types are not registered here
        bot = sdr.create_bot(scene, prefab, ctx)
    assert bot.get_articulated_actor().get_num_dofs() == 2
