"""Robotics handles: the invalid default, kinds kept apart, liveness through the context."""

import pytest

import superdex.physics as sdp
import superdex.robotics as sdr


@pytest.fixture
def ctx():
    sdp.initialize(num_worker_threads=0)
    yield sdr.create_context()
    sdp.shutdown()


@pytest.mark.parametrize("cls", [sdr.RoboticsHandle, sdr.BotHandle, sdr.ControllerHandle, sdr.SensorHandle, sdr.ActuatorHandle])
def test_default_handle_is_invalid_and_a_value_round_trips(cls):
    assert not cls().is_valid()
    assert cls().value == 0
    h = cls(42)
    assert h.is_valid() and h.value == 42 and int(h) == 42
    h.value = 7
    assert h == cls(7) and h != cls(8)
    assert issubclass(cls, sdr.RoboticsHandle)


def test_handles_of_different_kinds_never_compare_equal():
    assert sdr.SensorHandle(5) != sdr.ActuatorHandle(5)
    assert sdr.ControllerHandle(5) != sdr.BotHandle(5)
    assert sdr.SensorHandle(5) != 5
    # equal handles hash alike, so they work as dict keys and in sets
    assert {sdr.SensorHandle(3), sdr.SensorHandle(3), sdr.SensorHandle(4)} == {sdr.SensorHandle(3), sdr.SensorHandle(4)}
    assert sorted([sdr.SensorHandle(9), sdr.SensorHandle(2)])[0].value == 2


def test_liveness_follows_create_and_destroy(ctx):
    handle = ctx.create_sensor(sdr.CameraSensor.type_name(), None, "cam", "")
    assert handle.is_valid() and ctx.is_valid_sensor(handle)
    assert isinstance(handle, sdr.SensorHandle)
    # a live sensor handle is not a live actuator or controller
    with pytest.raises(sdp.Error, match="expected a actuator handle, got a SensorHandle"):
        ctx.is_valid_actuator(handle)
    ctx.destroy_sensor(handle)
    assert not ctx.is_valid_sensor(handle)
    assert ctx.get_sensor(handle) is None
    assert not ctx.is_valid_sensor(sdr.SensorHandle())


def test_python_component_lookup_with_invalid_stale_and_cpp_handles(ctx):
    class Probe:
        def __init__(self, actor, param_args):
            self.param_args = param_args

        def reset(self):
            pass

    sdr.register_python_sensor(ctx, "PROBE", Probe)
    assert sdr.get_python_sensor(ctx, sdr.SensorHandle()) is None
    assert sdr.get_python_actuator(ctx, sdr.ActuatorHandle()) is None
    assert sdr.get_python_controller(ctx, sdr.ControllerHandle()) is None
    handle = ctx.create_sensor("PROBE", None, "p", "relative/spec.json")
    # a string param_args reaches a Python factory verbatim: no path resolution, no check
    assert sdr.get_python_sensor(ctx, handle).param_args == "relative/spec.json"
    camera = ctx.create_sensor(sdr.CameraSensor.type_name(), None, "cam", "")
    assert sdr.get_python_sensor(ctx, camera) is None
    ctx.destroy_sensor(handle)
    with pytest.raises(sdp.Error, match="does not exist"):
        sdr.get_python_sensor(ctx, handle)


def test_find_results_are_python_lists_of_typed_handles(ctx):
    a = ctx.create_sensor(sdr.CameraSensor.type_name(), None, "same", "")
    b = ctx.create_sensor(sdr.CameraSensor.type_name(), None, "same", "")
    found = ctx.find_sensors_by_name("same")
    assert isinstance(found, list) and found == [a, b], "every match, in creation order"
    assert ctx.find_sensors_by_type(sdr.CameraSensor.type_name()) == [a, b]
    assert ctx.find_sensors_by_name("other") == []


def test_bot_handles(ctx):
    scene = sdp.create_scene("bots")
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(_fr3()), ctx)
    handle = bot.get_handle()
    assert isinstance(handle, sdr.BotHandle) and handle.is_valid()
    assert ctx.is_valid_bot(handle) and ctx.get_bot(handle).get_name() == "fr3"
    assert ctx.find_bots_by_name("fr3") == [handle]
    assert ctx.get_bot_containing_actor(bot.get_articulated_actor()).get_handle() == handle
    link = scene.get_actor(bot.get_articulated_actor().get_nested_link_actors()[3])
    assert ctx.get_bot_containing_actor(link).get_handle() == handle
    assert ctx.get_bot_containing_actor(None) is None
    assert bot.get_scene() == scene
    with pytest.raises(sdp.Error, match="get_bot: handle: expected a BotHandle"):
        ctx.get_bot(sdr.SensorHandle(int(handle)))
    sdr.destroy_bot(scene, bot)
    assert not ctx.is_valid_bot(handle) and ctx.get_bot(handle) is None
    assert ctx.find_bots_by_name("fr3") == []


def _fr3():
    from superdex.physics.paths import resolve_asset

    return str(resolve_asset("bots/arms/fr3/fr3.superdex_bot"))
