"""ControllerBasicJscPdParams: a plain value, its JSON files, and its effect on a live BASIC_JSC_PD."""

import copy

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from superdex.physics.paths import resolve_asset

FR3 = "bots/arms/fr3/fr3.superdex_bot"
JSC = sdr.ControllerBasicJscPd.type_name()


@pytest.fixture
def scene():
    sdp.initialize(num_worker_threads=0)
    s = sdp.create_scene("jsc")
    s.set_gravity([0, 0, -9.81])
    yield s
    sdp.shutdown()


def test_params_value_semantics_and_file_round_trip(tmp_path):
    p = sdr.ControllerBasicJscPdParams(kp=[1.0, 2.0], kd=[0.5])
    assert list(p.kp) == [1.0, 2.0] and list(p.kd) == [0.5]
    assert len(sdr.ControllerBasicJscPdParams().kp) == 0, "empty: the controller's default"
    q = copy.deepcopy(p)
    assert q == p
    q.saturation = [30.0]
    assert q != p
    path = tmp_path / "gains.superdex_controller"
    q.save_to_file(str(path))
    assert sdr.ControllerBasicJscPdParams.load_from_file(str(path)) == q


def test_loading_bad_files_names_file_and_key(tmp_path):
    path = tmp_path / "bad.superdex_controller"
    path.write_text('{"kp": [1, "x"]}')
    with pytest.raises(sdp.Error, match=r"bad\.superdex_controller.*params\.kp\[1\]: expected a number"):
        sdr.ControllerBasicJscPdParams.load_from_file(str(path))
    path.write_text('{"kpp": 1}')
    with pytest.raises(sdp.Error, match="unknown parameter 'kpp'"):
        sdr.ControllerBasicJscPdParams.load_from_file(str(path))
    with pytest.raises(sdp.Error, match="cannot be read"):
        sdr.ControllerBasicJscPdParams.load_from_file(str(tmp_path / "absent.json"))


def _arm(scene, ctx):
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(resolve_asset(FR3))), ctx)
    return bot, ctx.get_controller(bot.create_controller(JSC, "jsc"))


def test_live_controller_reports_and_validates_its_gains(scene):
    ctx = sdr.create_context()
    bot, jsc = _arm(scene, ctx)
    assert isinstance(jsc, sdr.ControllerBasicJscPd)
    p = jsc.get_params()
    assert list(p.kp) == [100.0] * 7 and list(p.kd) == [10.0] * 7
    assert list(p.saturation) == [-1.0] * 7 and list(p.deadband) == [0.0] * 7
    jsc.set_params(sdr.ControllerBasicJscPdParams(kp=[50.0], kd=[1, 2, 3, 4, 5, 6, 7]))
    p = jsc.get_params()
    assert list(p.kp) == [50.0] * 7, "one value is broadcast"
    assert list(p.kd) == [1, 2, 3, 4, 5, 6, 7]
    with pytest.raises(sdp.Error, match=r"params\.kp: expected 1 or 7 values"):
        jsc.set_params(sdr.ControllerBasicJscPdParams(kp=[1.0, 2.0]))
    with pytest.raises(sdp.Error, match=r"params\.kd\[0\]: must be >= 0"):
        jsc.set_params(sdr.ControllerBasicJscPdParams(kd=[-1.0]))
    assert list(jsc.get_params().kp) == [50.0] * 7, "a rejected set_params changes nothing"
    # the scene-file hook: empty params restore the defaults, inline JSON is applied
    jsc.configure_from_scene_entry("", "")
    assert list(jsc.get_params().kp) == [100.0] * 7
    jsc.configure_from_scene_entry('{"kp": 400}', '{"gravity_compensation": true}')
    assert list(jsc.get_params().kp) == [400.0] * 7


def _sag(scene, ctx, params):
    """Largest joint deviation (rad) from the start pose after 0.5 s under gravity with these gains."""
    bot, jsc = _arm(scene, ctx)
    jsc.set_params(params)
    arm = bot.get_articulated_actor()
    start = np.array(arm.get_articulated_pose())
    for _ in range(500):
        scene.step(0.001)
    deviation = float(np.max(np.abs(np.array(arm.get_articulated_pose()) - start)))
    sdr.destroy_bot(scene, bot)
    return deviation


def test_gains_change_how_the_arm_holds_against_gravity(scene):
    ctx = sdr.create_context()
    stiff = _sag(scene, ctx, sdr.ControllerBasicJscPdParams(kp=[2000.0], kd=[40.0]))
    default = _sag(scene, ctx, sdr.ControllerBasicJscPdParams())
    # zero saturation: no effort reaches the arm, which falls as if uncontrolled
    limp = _sag(scene, ctx, sdr.ControllerBasicJscPdParams(saturation=[0.0]))
    assert stiff < 0.02, f"stiff gains hold the pose ({stiff:.4f} rad)"
    assert stiff < default < limp, (stiff, default, limp)
    assert limp > 0.3
