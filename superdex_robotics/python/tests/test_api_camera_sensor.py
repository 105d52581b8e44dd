"""SENSOR_CAMERA: params validated by field, JSON files, run-time configuration, and a wrist camera
that follows its link."""

import math

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from superdex.physics.paths import resolve_asset

CAMERA = sdr.CameraSensor.type_name()


@pytest.fixture
def ctx():
    sdp.initialize(num_worker_threads=0)
    yield sdr.create_context()
    sdp.shutdown()


def test_camera_type_is_registered_with_defaults(ctx):
    assert CAMERA == "SENSOR_CAMERA"
    assert ctx.is_sensor_type_registered(CAMERA)
    camera = ctx.get_sensor(ctx.create_sensor(CAMERA, None, "cam"))
    p = camera.get_params()
    assert p == sdr.CameraSensorParams()
    assert (p.image_width, p.fov_vertical_deg, p.near_clip) == (0, 0.0, 0.0)
    with pytest.raises(sdp.Error, match="provides no signal"):
        ctx.get_sensor_signal(ctx.find_sensors_by_name("cam")[0])


def test_inline_params_and_their_errors(ctx):
    params = '{"name": "front", "imageWidth": 640, "imageHeight": 480, "fovVerticalDeg": 90, "nearClip": 0.01, "farClip": 10}'
    p = ctx.get_sensor(ctx.create_sensor(CAMERA, None, "cam", params)).get_params()
    assert (p.name, p.image_width, p.image_height, p.fov_vertical_deg, p.far_clip) == ("front", 640, 480, 90.0, 10.0)
    fx, fy, cx, cy = p.get_pinhole_intrinsics()
    assert fy == pytest.approx(240.0 / math.tan(math.radians(45.0)))
    assert (fx, cx, cy) == (pytest.approx(fy), 320.0, 240.0)
    with pytest.raises(sdp.Error, match="unknown parameter 'fov'"):
        ctx.create_sensor(CAMERA, None, "bad", '{"fov": 90}')
    with pytest.raises(sdp.Error, match="fov_vertical_deg must be in \\[0, 180\\)"):
        ctx.create_sensor(CAMERA, None, "bad", '{"fovVerticalDeg": 200}')
    with pytest.raises(sdp.Error, match="far_clip must be greater than near_clip"):
        ctx.create_sensor(CAMERA, None, "bad", '{"nearClip": 1, "farClip": 0.5}')
    with pytest.raises(sdp.Error, match="imageWidth: expected a whole number of pixels"):
        ctx.create_sensor(CAMERA, None, "bad", '{"imageWidth": 10.5}')
    assert ctx.find_sensors_by_name("bad") == [], "a rejected camera is not created"


def test_set_params_validates_and_configure_merges(ctx):
    handle = ctx.create_sensor(CAMERA, None, "cam", '{"imageWidth": 320, "imageHeight": 240}')
    camera = ctx.get_sensor(handle)
    with pytest.raises(sdp.Error, match="forward_axis must be a finite, non-zero direction"):
        camera.set_params(sdr.CameraSensorParams(forward_axis=[0.0, 0.0, 0.0]))
    with pytest.raises(sdp.Error, match="image_height must be >= 0"):
        camera.set_params(sdr.CameraSensorParams(image_height=-1))
    assert camera.get_params().image_width == 320, "a rejected set_params changes nothing"
    camera.set_params(sdr.CameraSensorParams(image_width=64, image_height=48, fov_vertical_deg=60.0))
    assert camera.get_params().image_width == 64
    # run-time configuration keeps the keys it does not name
    ctx.configure_sensor(handle, {"fovVerticalDeg": 45.0})
    p = camera.get_params()
    assert (p.image_width, p.fov_vertical_deg) == (64, 45.0)


def test_params_file_round_trip(ctx, tmp_path):
    p = sdr.CameraSensorParams(name="wrist", image_width=1280, image_height=720, fov_vertical_deg=58.0,
                               near_clip=0.05, far_clip=4.0, offset_local=[0.0, 0.05, 0.1], look_distance=0.3)
    path = tmp_path / "wrist.superdex_sensor"
    p.save_to_file(str(path))
    assert sdr.CameraSensorParams.load_from_file(str(path)) == p
    # the file is also a camera's params
    camera = ctx.get_sensor(ctx.create_sensor(CAMERA, None, "from_file", str(path)))
    assert camera.get_params() == p
    with pytest.raises(sdp.Error, match="fov_vertical_deg"):
        sdr.CameraSensorParams(fov_vertical_deg=-5.0).save_to_file(str(tmp_path / "bad.superdex_sensor"))


def test_wrist_camera_follows_its_link(ctx):
    scene = sdp.create_scene("wrist")
    scene.set_gravity([0, 0, -9.81])
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(resolve_asset("bots/arms/fr3/fr3.superdex_bot"))), ctx)
    link7 = scene.get_actor(bot.get_articulated_actor().get_nested_link_actors()[7])
    camera = ctx.get_sensor(ctx.create_sensor(CAMERA, link7, "wrist"))
    camera.set_parent_from_sensor(sdp.TransformRT(translation=[0.0, 0.0, 0.107]))
    before = np.asarray(camera.get_world_transform().translation).copy()
    for _ in range(200):  # no controller: the arm falls under gravity
        scene.step(0.002)
    after = np.asarray(camera.get_world_transform().translation)
    link = link7.get_root_transform()
    expected = np.asarray((link * sdp.TransformRT(translation=[0.0, 0.0, 0.107])).translation)
    np.testing.assert_allclose(after, expected, atol=1e-5)
    assert np.linalg.norm(after - before) > 0.05, "the camera moved with the link"
