"""Python components declared on the links of a .superdex_bot file and built by create_bot.

The example bot declares a MY_CONTACT_FORCE_SENSOR on its end-effector link and two
MY_VELOCITY_SERVO_ACTUATORs on the driven links. Registered as Python classes, create_bot
constructs them through their factories: they are found by name, unwrapped with
get_python_*, receive the link actor and their params (inline JSON, or a JSON file relative
to the bot file), and reset() is called by the framework when asked. Then the contract rules
of API.md: a class without reset() is refused naming the class, a factory's exception
becomes sdp.Error with its message, an unregistered type is skipped with a warning.
"""

import base64
import json

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from robotics_helpers import EXAMPLE_BOT, copy_example_bot, example_bot_json, scene, write_bot  # noqa: F401
from superdex.physics.paths import resolve_asset


class Sensor:
    instances = []

    def __init__(self, actor, param_args: str):
        self.actor = actor
        self.param_args = param_args
        self.resets = 0
        Sensor.instances.append(self)

    def reset(self):
        self.resets += 1


class Servo:
    def __init__(self, actor, param_args: str):
        assert actor is not None
        self.actor = actor
        text = param_args.strip()
        source = text if text.startswith("{") or not text else open(text).read()
        self.params = json.loads(source) if source else {}
        self.resets = 0

    def reset(self):
        self.resets += 1


class Controller:
    def __init__(self, actor):
        self.actor = actor

    def reset(self):
        pass


def registered_context():
    ctx = sdr.create_context()
    sdr.register_python_sensor(ctx, "MY_CONTACT_FORCE_SENSOR", Sensor)
    sdr.register_python_actuator(ctx, "MY_VELOCITY_SERVO_ACTUATOR", Servo)
    sdr.register_python_controller(ctx, "MY_VELOCITY_FORCE_CONTROLLER", Controller)
    return ctx


def test_components_declared_in_the_bot_file(scene):
    ctx = registered_context()
    prefab = sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT)))
    bot = sdr.create_bot(scene, prefab, ctx)
    arm = bot.get_articulated_actor()
    links = arm.get_nested_link_actors()
    assert len(links) == 4 and arm.get_num_dofs() == 2

    (sensor_handle,) = bot.find_sensors_by_name("force_sensor")
    sensor = sdr.get_python_sensor(ctx, sensor_handle)
    assert isinstance(sensor, Sensor)
    assert sensor.actor.get_handle() == links[3], "the sensor is attached to the end-effector link"
    servos = [sdr.get_python_actuator(ctx, bot.find_actuators_by_name(n)[0]) for n in ("servo_1", "servo_2")]
    assert [s.actor.get_handle() for s in servos] == [links[1], links[2]]
    # inline JSON params reach the factory
    declared = json.loads(resolve_asset(EXAMPLE_BOT).read_text())["links"]
    assert servos[0].params == json.loads(declared[1]["actuators"][0]["params"])
    assert servos[1].params == json.loads(declared[2]["actuators"][0]["params"])
    assert servos[1].params["effort_limit"] == 3.0
    assert bot.find_actuators_by_type("MY_VELOCITY_SERVO_ACTUATOR") == bot.get_actuator_handles()
    assert ctx.find_sensors_by_type("MY_CONTACT_FORCE_SENSOR") == [sensor_handle]

    # the controller is created in code, on the articulation
    handle = ctx.create_controller("MY_VELOCITY_FORCE_CONTROLLER", None, arm, "my_controller")
    controller = sdr.get_python_controller(ctx, handle)
    assert controller.actor.get_handle() == arm.get_handle()
    assert ctx.find_controllers_by_name("my_controller") == [handle]

    # reset() when asked: by the bot (its components) and by the context (all)
    bot.reset()
    assert sensor.resets == 1 and all(s.resets == 1 for s in servos)
    ctx.reset_components()
    assert sensor.resets == 2

    # the default pose was applied
    np.testing.assert_allclose(arm.get_articulated_pose(), [0.411, -2.018], atol=1e-5)


def test_params_from_a_file_relative_to_the_bot(scene, tmp_path):
    doc = example_bot_json()
    (tmp_path / "servo_params.json").write_text(json.dumps({"k_p": 7.5, "k_i": 1.25}))
    doc["links"][1]["actuators"][0]["params"] = "servo_params.json"
    path = write_bot(tmp_path, doc)
    ctx = registered_context()
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(path)), ctx)
    servo = sdr.get_python_actuator(ctx, bot.find_actuators_by_name("servo_1")[0])
    assert servo.params == {"k_p": 7.5, "k_i": 1.25}
    # empty params: defaults
    sensor = sdr.get_python_sensor(ctx, bot.find_sensors_by_name("force_sensor")[0])
    assert sensor.param_args == ""


def test_handles_are_typed_and_never_reused(scene):
    ctx = registered_context()
    prefab = sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT)))
    seen = set()
    for _ in range(3):
        bot = sdr.create_bot(scene, prefab, ctx)
        handles = bot.get_sensor_handles() + bot.get_actuator_handles()
        values = {int(h) for h in handles}
        assert not values & seen
        seen |= values
        sensor_handle = bot.get_sensor_handles()[0]
        with pytest.raises(sdp.Error, match="expected a actuator handle|expected an? actuator handle"):
            sdr.get_python_actuator(ctx, sensor_handle)
        sdr.destroy_bot(scene, bot)
        with pytest.raises(sdp.Error, match="does not exist"):
            sdr.get_python_sensor(ctx, sensor_handle)


def test_destroy_bot_releases_components_then_actor(scene):
    ctx = registered_context()
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT))), ctx)
    arm = bot.get_articulated_actor()
    Sensor.instances.clear()
    import gc
    import weakref

    sensor = sdr.get_python_sensor(ctx, bot.find_sensors_by_name("force_sensor")[0])
    ref = weakref.ref(sensor)
    del sensor
    sdr.destroy_bot(scene, bot)
    gc.collect()
    assert ref() is None, "the Python component was released"
    with pytest.raises(sdp.Error, match="does not exist"):
        arm.get_num_dofs()


def test_missing_reset_is_rejected_naming_the_class(scene):
    class NoReset:
        def __init__(self, actor, param_args):
            pass

    ctx = registered_context()
    sdr.register_python_sensor(ctx, "MY_CONTACT_FORCE_SENSOR", NoReset)
    prefab = sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT)))
    with pytest.raises(sdp.Error, match="class 'NoReset'.*has no reset"):
        sdr.create_bot(scene, prefab, ctx)
    # create_bot failed as a whole: nothing of the bot is left in the scene
    assert scene.get_num_actors() == 0


def test_factory_exception_becomes_error_with_its_message(scene):
    def broken(actor, param_args):
        raise ValueError("servo calibration file is missing")

    ctx = registered_context()
    sdr.register_python_actuator(ctx, "MY_VELOCITY_SERVO_ACTUATOR", broken)
    prefab = sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT)))
    with pytest.raises(sdp.Error, match="servo calibration file is missing"):
        sdr.create_bot(scene, prefab, ctx)


def test_unregistered_type_is_skipped_with_a_warning(scene):
    ctx = sdr.create_context()
    sdr.register_python_actuator(ctx, "MY_VELOCITY_SERVO_ACTUATOR", Servo)
    prefab = sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT)))
    with pytest.warns(UserWarning, match="sensor type 'MY_CONTACT_FORCE_SENSOR'.*not registered"):
        bot = sdr.create_bot(scene, prefab, ctx)
    assert bot.get_sensor_handles() == []
    assert len(bot.get_actuator_handles()) == 2
    assert ctx.is_actuator_type_registered("MY_VELOCITY_SERVO_ACTUATOR")
    assert not ctx.is_sensor_type_registered("MY_CONTACT_FORCE_SENSOR")


def test_prefab_is_editable_before_create_bot(scene):
    ctx = registered_context()
    prefab = sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT)))
    assert prefab.name == "example_bot_2dof"
    assert [l.name for l in prefab.links] == ["base_link", "link_1", "link_2", "ball"]
    assert [j.name for j in prefab.joints] == ["base_weld", "shoulder", "elbow", "ball_weld"]
    prefab.links[3].mass = 0.5
    prefab.joints[1].viscous_friction = 0.2
    prefab.default_pose = [0.3, -1.5]
    prefab.world_from_root = sdp.TransformRT(translation=[1.0, 0.0, 0.0])
    prefab.name = "edited"
    bot = sdr.create_bot(scene, prefab, ctx)
    arm = bot.get_articulated_actor()
    assert bot.get_name() == "edited"
    assert scene.get_actor(arm.get_nested_link_actors()[3]).get_mass() == pytest.approx(0.5)
    np.testing.assert_allclose(arm.get_articulated_pose(), [0.3, -1.5], atol=1e-5)
    np.testing.assert_allclose(np.array(arm.get_root_transform().translation), [1, 0, 0], atol=1e-6)


@pytest.mark.parametrize("pose", [[0.411, -2.018], [0.678, -1.814], [0.239, -1.229], [0.059, -1.427]])
def test_example_bot_has_no_self_contact_on_its_path(scene, pose):
    """At its default pose and at poses along the seed's circle (elbow up, computed by inverse
    kinematics in the asset's README), no link of the example bot touches another: with gravity
    off and no actuation it stays still."""
    scene.set_gravity([0, 0, 0])
    ctx = sdr.create_context()
    prefab = sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT)))
    prefab.default_pose = pose
    with pytest.warns(UserWarning):  # its custom component types are not registered here
        bot = sdr.create_bot(scene, prefab, ctx)
    arm = bot.get_articulated_actor()
    links = [scene.get_actor(h) for h in arm.get_nested_link_actors()]
    for link in links:
        link.register_query(sdp.QueryType.CONTACT_POINTS)
    for _ in range(10):
        scene.step(0.004)
    assert all(len(link.get_contact_points_world()) == 0 for link in links)
    np.testing.assert_allclose(arm.get_articulated_joint_velocities(), 0, atol=1e-9)


def test_render_models_travel_in_recordings_byte_for_byte(scene, tmp_path):
    """The bot's render model (.glb, relative to the bot file) is embedded in the recording's actor
    line, base64 of the file's bytes, with its scale: a replay needs no asset files."""
    path = copy_example_bot(tmp_path)
    recording = tmp_path / "run.jsonl"
    sdp.start_recording(str(recording), 0.0)
    with pytest.warns(UserWarning, match="not registered"):
        bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(path)), sdr.create_context())
    scene.step(0.01)
    sdp.stop_recording()
    (actor,) = [l for l in map(json.loads, recording.read_text().splitlines()) if l["type"] == "actor"]
    models = {link["name"]: link.get("renderModel") for link in actor["links"]}
    assert models["base_link"] is None and models["link_1"] is None
    ball = models["ball"]
    assert ball["name"] == "ball.glb" and ball["scale"] == [1, 1, 1]
    glb = base64.b64decode(ball["glb"], validate=True)
    assert glb == (tmp_path / "models" / "ball.glb").read_bytes()
    assert glb[:4] == b"glTF"
    sdr.destroy_bot(scene, bot)


def test_links_and_joints_of_a_prefab_can_be_replaced(scene):
    """API.md: BotPrefab's links and joints are writable. Replacing them keeps one list of sensors
    and of actuators per link; the bot built from the edited prefab has the new structure."""
    prefab = sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT)))
    prefab.links = list(prefab.links)[:3]  # drop the ball and its weld
    prefab.joints = list(prefab.joints)[:3]
    assert [l.name for l in prefab.links] == ["base_link", "link_1", "link_2"]
    assert len(prefab.sensors) == len(prefab.actuators) == 3
    with pytest.warns(UserWarning, match="not registered"):
        bot = sdr.create_bot(scene, prefab, sdr.create_context())
    arm = bot.get_articulated_actor()
    assert len(arm.get_nested_link_actors()) == 3 and arm.get_num_dofs() == 2
    sdr.destroy_bot(scene, bot)
