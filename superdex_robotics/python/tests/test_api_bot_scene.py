"""load_bot_scene: bot scene files resolved through asset tags, their controllers configured and
run, scene-level sensors, errors naming the JSON path, and teardown."""

import gc
import json
import os
import weakref
from pathlib import Path

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from superdex.physics.paths import get_assets_root

JSC = sdr.ControllerBasicJscPd.type_name()
CAMERA = sdr.CameraSensor.type_name()


@pytest.fixture
def ctx():
    sdp.initialize(num_worker_threads=0)
    yield sdr.create_context()
    sdp.shutdown()


class Probe:
    def __init__(self, actor, param_args):
        self.actor, self.param_args = actor, param_args

    def reset(self):
        pass


def write_scene(folder: Path, doc: dict, marker: bool = True) -> Path:
    """The scene file, its z-up base scene and (optionally) a .superdex_root defining @bots."""
    if marker:
        (folder / ".superdex_root").write_text(json.dumps({"@bots": str(get_assets_root() / "bots")}))
    (folder / "base.mochi_scene").write_text(json.dumps({"scene": {"gravity": [0.0, 0.0, -9.81]}}))
    path = folder / "test.mochi_bot_scene"
    path.write_text(json.dumps(doc))
    return path


def arm_scene(**bot_fields) -> dict:
    bot = {"name": "arm", "path": "@bots/arms/fr3/fr3.superdex_bot",
           "controllers": [{"type": JSC, "name": "hold", "params": {"kp": 2000, "kd": 40},
                            "initArgs": {"gravity_compensation": True}}]}
    bot.update(bot_fields)
    return {"metadata": {"name": "Hold", "version": "1.0"}, "scene": {"baseScene": "base.mochi_scene"}, "bots": [bot]}


def test_scene_with_a_controlled_arm_holds_its_pose(ctx, tmp_path):
    bot_scene = sdr.load_bot_scene(write_scene(tmp_path, arm_scene(translation=[0.5, 0.0, 0.0])), ctx)
    bot = bot_scene.get_bot("arm")
    assert bot_scene.get_bot_names() == ["arm"]
    jsc = ctx.get_controller(bot_scene.get_controller_handle("arm/hold"))
    assert list(jsc.get_params().kp) == [2000.0] * 7, "params of the entry were applied"
    arm = bot.get_articulated_actor()
    np.testing.assert_allclose(np.asarray(arm.get_root_transform().translation), [0.5, 0.0, 0.0], atol=1e-6)
    start = np.array(arm.get_articulated_pose())
    scene = bot_scene.get_scene()
    np.testing.assert_allclose(np.asarray(scene.get_gravity()), [0.0, 0.0, -9.81], rtol=1e-6)
    for _ in range(500):
        scene.step(0.001)
    # gravity (from the base scene) is compensated and stiff gains hold the ready pose
    assert np.max(np.abs(np.array(arm.get_articulated_pose()) - start)) < 5e-3
    with pytest.raises(sdp.Error, match="no controller 'arm/missing'"):
        bot_scene.get_controller_handle("arm/missing")
    with pytest.raises(sdp.Error, match="no bot 'robot'.*bots: arm"):
        bot_scene.get_bot("robot")


def test_scene_level_sensors_and_unknown_types(ctx, tmp_path):
    sdr.register_python_sensor(ctx, "SCENE_PROBE", Probe)
    doc = arm_scene(controllers=[{"type": "NOBODY_REGISTERED_THIS", "name": "x"}])
    doc["sensors"] = [
        {"type": CAMERA, "name": "overhead", "params": {"imageWidth": 64, "imageHeight": 48},
         "translation": [1.0, 2.0, 3.0], "rotation": [0.0, 0.0, 0.0, 1.0]},
        {"type": "SCENE_PROBE", "name": "probe", "params": '{"rate": 5}'},
        {"type": "NOT_A_SENSOR", "name": "ghost"},
    ]
    with pytest.warns(UserWarning) as caught:
        bot_scene = sdr.load_bot_scene(write_scene(tmp_path, doc), ctx)
    messages = " ".join(str(w.message) for w in caught)
    assert "controllers[0]: controller type 'NOBODY_REGISTERED_THIS' is not registered" in messages
    assert "sensors[2]: sensor type 'NOT_A_SENSOR' is not registered" in messages
    overhead = ctx.get_sensor(bot_scene.get_sensor_handle("overhead"))
    assert overhead.get_params().image_width == 64
    assert overhead.get_world_transform() == sdp.TransformRT(translation=[1.0, 2.0, 3.0])
    assert overhead.get_actor() is None and overhead.get_owning_bot() is None
    probe = sdr.get_python_sensor(ctx, bot_scene.get_sensor_handle("probe"))
    assert probe.param_args == '{"rate": 5}' and probe.actor is None
    assert ctx.find_sensors_by_name("ghost") == []
    # teardown when the scene object goes away: components, bots, the scene
    scene = bot_scene.get_scene()
    ref = weakref.ref(probe)
    del probe, overhead, bot_scene
    gc.collect()
    assert ref() is None
    assert ctx.find_sensors_by_name("overhead") == [] and ctx.find_bots_by_name("fr3") == []
    with pytest.raises(sdp.Error):
        scene.step(0.001)


def test_asset_tags_resolve_from_the_nearest_marker(ctx, tmp_path):
    inner = tmp_path / "deep" / "er"
    inner.mkdir(parents=True)
    # the marker sits two folders up and maps @bots relatively to itself
    (tmp_path / "bots").symlink_to(get_assets_root() / "bots")
    (tmp_path / ".superdex_root").write_text(json.dumps({"@bots": "bots"}))
    path = write_scene(inner, arm_scene(), marker=False)
    bot_scene = sdr.load_bot_scene(str(path), ctx)
    assert bot_scene.get_bot("arm").get_name() == "fr3"
    bot_scene.destroy()
    assert not bot_scene.is_alive()
    bot_scene.destroy()  # idempotent


@pytest.mark.parametrize("change, message", [
    (lambda d: d["bots"][0].pop("path"), r"bots\[0\]\.path: is required"),
    (lambda d: d["bots"][0].update(path="@nowhere/x.superdex_bot"), r"bots\[0\]\.path: asset tag '@nowhere' is defined by no"),
    (lambda d: d["bots"][0].update(path="missing.superdex_bot"), r"bots\[0\]\.path: 'missing\.superdex_bot' resolves to .* which does not exist"),
    (lambda d: d["bots"].append(dict(d["bots"][0])), r"bots\[1\]\.name: bot 'arm' is declared twice"),
    (lambda d: d["bots"][0]["controllers"][0].update(params={"kp": [1, 2]}), r"bots\[0\]\.controllers\[0\].*params\.kp: expected 1 or 7 values"),
    (lambda d: d["bots"][0].update(rotation=[0, 0, 0]), r"bots\[0\]\.rotation: expected 4 numbers"),
    (lambda d: d.update(sensors=[{"name": "no type"}]), r"sensors\[0\]\.type: is required"),
    (lambda d: d["scene"].update(baseScene="absent.mochi_scene"), r"scene\.baseScene: 'absent\.mochi_scene' resolves to"),
])
def test_bad_scene_files_name_the_field_and_leave_nothing(ctx, tmp_path, change, message):
    doc = arm_scene()
    change(doc)
    path = write_scene(tmp_path, doc)
    with pytest.raises(sdp.Error, match=message) as info:
        sdr.load_bot_scene(path, ctx)
    assert str(path) in str(info.value), "the message names the file"
    assert ctx.find_bots_by_name("fr3") == [], "a failed load destroys what it built"


def test_bad_arguments(ctx, tmp_path):
    with pytest.raises(sdp.Error, match="scene_file: .* does not exist"):
        sdr.load_bot_scene(tmp_path / "none.mochi_bot_scene", ctx)
    with pytest.raises(sdp.Error, match="ctx: expected a RoboticsContext"):
        sdr.load_bot_scene(write_scene(tmp_path, arm_scene()), None)
    (tmp_path / "broken.mochi_bot_scene").write_text("{ not json")
    with pytest.raises(sdp.Error, match="not valid JSON"):
        sdr.load_bot_scene(os.fspath(tmp_path / "broken.mochi_bot_scene"), ctx)
