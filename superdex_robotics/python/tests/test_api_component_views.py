"""Component views (RoboticsContext.get_sensor / get_controller / get_actuator): identity, sensor
poses, ownership inferred from the actor, and behaviour once the component is gone."""

import gc
import weakref

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from superdex.physics.paths import resolve_asset

FR3 = "bots/arms/fr3/fr3.superdex_bot"
CAMERA = sdr.CameraSensor.type_name()


@pytest.fixture
def scene():
    sdp.initialize(num_worker_threads=0)
    s = sdp.create_scene("views")
    s.set_gravity([0, 0, -9.81])
    yield s
    sdp.shutdown()


class Counter:
    """A Python sensor/actuator/controller that counts resets and keeps its configuration."""

    def __init__(self, actor, param_args=""):
        self.actor = actor
        self.resets = 0
        self.configured = []

    def reset(self):
        self.resets += 1

    def configure(self, params):
        self.configured.append(params)


def test_actor_less_sensor_identity_and_pose(scene):
    ctx = sdr.create_context()
    handle = ctx.create_sensor(CAMERA, None, "fixed", "")
    view = ctx.get_sensor(handle)
    assert isinstance(view, sdr.CameraSensor) and isinstance(view, sdr.SensorBase) and isinstance(view, sdr.ComponentBase)
    assert (view.get_name(), view.get_type_name()) == ("fixed", CAMERA)
    assert view.get_actor() is None and view.get_owning_bot() is None
    assert view.get_parent_from_sensor() == sdp.TransformRT()
    pose = sdp.TransformRT(rotation=sdp.Quaternion([0.0, 0.0, 1.0, 0.0]), translation=[0.5, -1.0, 2.0])
    view.set_parent_from_sensor(pose)
    # a second view of the same sensor sees the change: views hold a handle, not a copy
    assert ctx.get_sensor(handle).get_parent_from_sensor() == pose
    assert view.get_world_transform() == pose


def test_sensor_on_a_moving_actor_follows_it(scene):
    ctx = sdr.create_context()
    ball = scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1),
                                    world_from_local=sdp.TransformRT(translation=[0, 0, 1]))
    view = ctx.get_sensor(ctx.create_sensor(CAMERA, ball, "on_ball", ""))
    view.set_parent_from_sensor(sdp.TransformRT(translation=[0.0, 0.0, 0.25]))
    assert view.get_actor() == ball
    for _ in range(20):
        scene.step(0.01)
    world = view.get_world_transform()
    ball_z = np.asarray(ball.get_root_transform().translation)[2]
    assert ball_z < 0.95, "the ball fell"
    np.testing.assert_allclose(np.asarray(world.translation)[2], ball_z + 0.25, atol=1e-5)


def test_destroyed_component_view_is_invalid_and_raises(scene):
    ctx = sdr.create_context()
    handle = ctx.create_sensor(CAMERA, None, "gone", "")
    view = ctx.get_sensor(handle)
    ctx.destroy_sensor(handle)
    assert not view.is_valid()
    with pytest.raises(sdp.Error, match="no longer exists"):
        view.get_name()
    with pytest.raises(sdp.Error, match="no longer exists"):
        view.set_parent_from_sensor(sdp.TransformRT())
    assert "destroyed" in repr(view)


def test_views_reach_python_components_without_keeping_them_alive(scene):
    ctx = sdr.create_context()
    sdr.register_python_sensor(ctx, "COUNTER_SENSOR", Counter)
    sdr.register_python_controller(ctx, "COUNTER_CONTROLLER", Counter)
    handle = ctx.create_sensor("COUNTER_SENSOR", None, "c", "")
    view = ctx.get_sensor(handle)
    assert type(view) is sdr.SensorBase, "a Python sensor has the generic view"
    obj = sdr.get_python_sensor(ctx, handle)
    view.reset()
    view.reset()
    assert obj.resets == 2
    # the scene-entry hook hands a Python controller its params as a dict
    arm = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(resolve_asset(FR3))), ctx).get_articulated_actor()
    controller_handle = ctx.create_controller("COUNTER_CONTROLLER", None, arm, "cc")
    controller = ctx.get_controller(controller_handle)
    assert type(controller) is sdr.ControllerBase
    controller.configure_from_scene_entry('{"gain": 3}', "")
    assert sdr.get_python_controller(ctx, controller_handle).configured == [{"gain": 3}]
    ref = weakref.ref(obj)
    del obj
    ctx.destroy_sensor(handle)
    gc.collect()
    assert ref() is None, "the view held no reference to the Python sensor"
    assert not view.is_valid()


def test_component_created_on_a_bot_actor_belongs_to_the_bot(scene):
    ctx = sdr.create_context()
    sdr.register_python_actuator(ctx, "COUNTER_ACTUATOR", Counter)
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(resolve_asset(FR3))), ctx)
    link7 = scene.get_actor(bot.get_articulated_actor().get_nested_link_actors()[7])
    sensor = ctx.create_sensor(CAMERA, link7, "wrist", "")
    actuator = ctx.create_actuator("COUNTER_ACTUATOR", link7, "motor", "")
    loose = ctx.create_sensor(CAMERA, None, "loose", "")
    assert ctx.get_sensor(sensor).get_owning_bot().get_name() == "fr3"
    assert ctx.get_actuator(actuator).get_owning_bot().get_handle() == bot.get_handle()
    assert ctx.get_sensor(loose).get_owning_bot() is None
    assert bot.get_sensor_handles() == [sensor] and bot.get_actuator_handles() == [actuator]
    assert bot.get_sensor(sensor).get_name() == "wrist"
    # a sensor on a link resolves its world pose through the link
    link_pose = link7.get_root_transform()
    world = ctx.get_sensor(sensor).get_world_transform()
    np.testing.assert_allclose(np.asarray(world.translation), np.asarray(link_pose.translation), atol=1e-6)
    with pytest.raises(sdp.Error, match="does not belong to bot 'fr3'"):
        other = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(resolve_asset(FR3))), ctx)
        other.get_sensor(sensor)
    # destroying the bot destroys what was created on its actors, not the loose sensor
    sdr.destroy_bot(scene, bot)
    assert not ctx.is_valid_sensor(sensor) and not ctx.is_valid_actuator(actuator)
    assert ctx.is_valid_sensor(loose)


def test_bot_components_by_link_name(scene):
    ctx = sdr.create_context()
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(resolve_asset(FR3))), ctx)
    handle = bot.create_sensor(CAMERA, "fr3_link7", "wrist")
    assert bot.get_sensor_link_name(handle) == "fr3_link7"
    link7 = scene.get_actor(bot.get_articulated_actor().get_nested_link_actors()[7])
    assert ctx.get_sensor(handle).get_actor() == link7
    with pytest.raises(sdp.Error, match=r"link: bot 'fr3' has no link 'hand' \(links: fr3_link0, .*fr3_link7\)"):
        bot.create_sensor(CAMERA, "hand", "nowhere")
    loose = ctx.create_sensor(CAMERA, None, "loose")
    assert bot.get_sensor_link_name(loose) is None


def test_set_params_refuses_other_types_naming_the_argument(scene):
    ctx = sdr.create_context()
    camera = ctx.get_sensor(ctx.create_sensor(CAMERA, None, "cam"))
    with pytest.raises(sdp.Error, match="set_params: params: expected a CameraSensorParams, got .*ControllerBasicJscPdParams"):
        camera.set_params(sdr.ControllerBasicJscPdParams())
    with pytest.raises(sdp.Error, match="set_params: params: expected a CameraSensorParams"):
        camera.set_params(None)
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(resolve_asset(FR3))), ctx)
    jsc = ctx.get_controller(bot.create_controller(sdr.ControllerBasicJscPd.type_name(), "jsc"))
    with pytest.raises(sdp.Error, match="set_params: params: expected a ControllerBasicJscPdParams"):
        jsc.set_params({"kp": 1})
