"""The FR3-like arm asset: generated reproducibly, carrying the published parameters, and stable in
simulation under joint-space control."""

import importlib.util
import json
from pathlib import Path

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from superdex.physics.paths import resolve_asset

REPO = Path(__file__).resolve().parents[3]
ASSET = "bots/arms/fr3/fr3.superdex_bot"
ASSET_V2 = "bots/arms/fr3_v2/fr3_v2.superdex_bot"


def _generator():
    spec = importlib.util.spec_from_file_location("make_fr3_bot", REPO / "tools" / "make_fr3_bot.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture
def scene():
    sdp.initialize(num_worker_threads=0)
    s = sdp.create_scene("fr3")
    s.set_gravity([0, 0, -9.81])
    yield s
    sdp.shutdown()


def test_the_asset_is_what_the_generator_writes(tmp_path, monkeypatch):
    gen = _generator()
    monkeypatch.setattr(gen, "OUT", tmp_path / "fr3.superdex_bot")
    monkeypatch.setattr(gen, "OUT_V2", tmp_path / "fr3_v2.superdex_bot")
    gen.main()
    assert (tmp_path / "fr3.superdex_bot").read_text() == Path(resolve_asset(ASSET)).read_text()
    assert (tmp_path / "fr3_v2.superdex_bot").read_text() == Path(resolve_asset(ASSET_V2)).read_text()


def test_published_parameters_reach_the_prefab():
    gen = _generator()
    prefab = sdr.load_bot_prefab_from_file(resolve_asset(ASSET))
    assert len(prefab.links) == 8 and len(prefab.default_pose) == 7
    assert [l.mass for l in prefab.links] == pytest.approx([m for m, _, _ in gen.INERTIALS])
    revolute = prefab.joints[1:]
    assert [j.effort_limit for j in revolute] == pytest.approx([87.0] * 4 + [12.0] * 3)
    assert [j.min_limit[2] for j in revolute] == pytest.approx(gen.LOWER)
    assert [j.max_limit[2] for j in revolute] == pytest.approx(gen.UPPER)
    for q, lo, hi in zip(prefab.default_pose, gen.LOWER, gen.UPPER):
        assert lo < q < hi, "the default pose is inside the limits"


def test_forward_kinematics_matches_the_published_geometry(scene):
    ctx = sdr.create_context()
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(resolve_asset(ASSET)), ctx)
    arm = bot.get_articulated_actor()
    arm.set_articulated_pose_from_joints([0.0] * 7)
    links = arm.get_nested_link_actors()
    flange = scene.get_actor(links[7]).get_root_transform() * sdp.TransformRT(translation=[0.0, 0.0, 0.107])
    # at zero pose the flange sits 0.088 m forward and 0.333 + 0.316 + 0.384 - 0.107 m up
    np.testing.assert_allclose(np.asarray(flange.translation), [0.088, 0.0, 0.926], atol=1e-5)


def test_gravity_compensated_pd_holds_the_ready_pose(scene):
    ctx = sdr.create_context()
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(resolve_asset(ASSET)), ctx)
    bot.create_controller(sdr.ControllerBasicJscPd.type_name(), "hold", {"gravity_compensation": True})
    arm = bot.get_articulated_actor()
    start = np.array(arm.get_articulated_pose())
    for _ in range(1000):
        scene.step(0.001)
    # default gains (kp 100, kd 10) with gravity compensation: the pose drifts by less than 1 mrad
    assert np.max(np.abs(np.array(arm.get_articulated_pose()) - start)) < 1e-3
    assert np.all(np.isfinite(arm.get_articulated_joint_velocities()))
