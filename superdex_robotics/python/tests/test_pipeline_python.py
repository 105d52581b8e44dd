"""Python components in the bot pipeline, its lifecycle, and the seed's hand-written loop.

Python components take part when they define the pipeline methods (python_component.h):
  sensor.update(t, dt); controller.compute(t, dt) -> {"position"|"velocity"|"effort": [...]};
  actuator.compute_pipeline_effort(commands, dt) -> float; optional `rate` (Hz).
Components without them (the seed's) are left to the script's own loop, as before.
"""

import gc
import math
import weakref

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from robotics_helpers import EXAMPLE_BOT, scene  # noqa: F401
from superdex.physics.paths import resolve_asset


class PipelineSensor:
    rate = 100.0  # Hz: every 5 steps of 2 ms

    def __init__(self, actor, param_args):
        self.actor = actor
        self.calls = []

    def reset(self):
        self.calls.clear()

    def update(self, t, dt):
        self.calls.append((t, dt))

    def signal(self):
        return [len(self.calls), 42.0]


class PipelineServo:
    def __init__(self, actor, param_args):
        self.actor = actor
        self.commands = []

    def reset(self):
        pass

    def compute_pipeline_effort(self, commands, dt):
        self.commands.append(dict(commands))
        return 0.1 * (commands["velocity"] or 0.0)


class PipelineController:
    def __init__(self, actor):
        self.actor = actor
        self.calls = []
        self.fail = None

    def reset(self):
        pass

    def configure(self, params):
        self.configured = params

    def compute(self, t, dt):
        self.calls.append((t, dt))
        if self.fail:
            raise self.fail
        return {"velocity": [1.0, math.nan], "effort": np.array([math.nan, 0.3])}


def pipeline_context():
    ctx = sdr.create_context()
    sdr.register_python_sensor(ctx, "MY_CONTACT_FORCE_SENSOR", PipelineSensor)
    sdr.register_python_actuator(ctx, "MY_VELOCITY_SERVO_ACTUATOR", PipelineServo)
    sdr.register_python_controller(ctx, "PY_CONTROLLER", PipelineController)
    return ctx


def example_bot(scene, ctx, x=0.0):
    prefab = sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT)))
    prefab.world_from_root = sdp.TransformRT(translation=[x, 0.0, 0.0])
    return sdr.create_bot(scene, prefab, ctx)


def test_python_components_run_in_the_pipeline(scene):
    ctx = pipeline_context()
    bot = example_bot(scene, ctx)
    assert bot.is_pipeline_active(), "the declared Python sensor and actuators define pipeline methods"
    arm = bot.get_articulated_actor()
    handle = ctx.create_controller("PY_CONTROLLER", None, arm, "py")  # context-level, on the bot's actor
    controller = sdr.get_python_controller(ctx, handle)
    sensor = sdr.get_python_sensor(ctx, bot.find_sensors_by_name("force_sensor")[0])
    servo_1 = sdr.get_python_actuator(ctx, bot.find_actuators_by_name("servo_1")[0])
    # without an actuator, DOF 1 takes the controller's effort directly
    ctx.destroy_actuator(bot.find_actuators_by_name("servo_2")[0])

    for _ in range(20):
        scene.step(0.002)
    np.testing.assert_allclose(arm.get_external_forces(), [0.1 * 1.0, 0.3], rtol=1e-6)
    assert servo_1.commands[-1] == {"position": None, "velocity": 1.0, "effort": None}
    assert len(controller.calls) == 20
    assert controller.calls[0] == (0.0, pytest.approx(0.002))  # t at the start of the step
    # the sensor runs after the step at its rate: t = 0.002, 0.012, 0.022, 0.032 s, dt = its period
    assert [t for t, _ in sensor.calls] == pytest.approx([0.002, 0.012, 0.022, 0.032], abs=1e-6)
    assert [dt for _, dt in sensor.calls] == pytest.approx([0.01] * 4, abs=1e-6)
    np.testing.assert_array_equal(ctx.get_sensor_signal(bot.find_sensors_by_name("force_sensor")[0]), [4, 42])


@pytest.mark.parametrize("where", ["controller", "actuator", "sensor"])
def test_a_python_exception_propagates_out_of_step(scene, where):
    ctx = pipeline_context()
    bot = example_bot(scene, ctx)
    handle = bot.create_controller("PY_CONTROLLER", "py")
    controller = sdr.get_python_controller(ctx, handle)
    if where == "controller":
        controller.fail = ValueError("controller exploded")
    elif where == "actuator":
        servo = sdr.get_python_actuator(ctx, bot.find_actuators_by_name("servo_1")[0])
        servo.compute_pipeline_effort = lambda commands, dt: 1 / 0
    else:
        sensor = sdr.get_python_sensor(ctx, bot.find_sensors_by_name("force_sensor")[0])
        sensor.update = lambda t, dt: (_ for _ in ()).throw(KeyError("sensor exploded"))
    expected = {"controller": (ValueError, "controller exploded"), "actuator": (ZeroDivisionError, "division by zero"),
                "sensor": (KeyError, "sensor exploded")}[where]
    with pytest.raises(expected[0], match=expected[1]):
        scene.step(0.002)
    # the scene is still usable once the culprit is gone
    controller.fail = None
    sdr.destroy_bot(scene, bot)
    scene.step(0.002)


def test_destroy_bot_cancels_the_pipeline(scene):
    ctx = pipeline_context()
    bot = example_bot(scene, ctx)
    controller = sdr.get_python_controller(ctx, bot.create_controller("PY_CONTROLLER", "py"))
    scene.step(0.002)
    sdr.destroy_bot(scene, bot)
    # step callbacks are named by handles that only the pipeline holds: that the scene has none
    # left is checked in C++ (pipeline_test.cpp, Scene::num_step_callbacks); here, that none runs
    calls = len(controller.calls)
    for _ in range(5):
        scene.step(0.002)
    assert len(controller.calls) == calls, "nothing of the bot runs any more"


def test_context_destroyed_before_the_scene(scene):
    ctx = pipeline_context()
    bot = example_bot(scene, ctx)
    arm = bot.get_articulated_actor()
    controller = sdr.get_python_controller(ctx, bot.create_controller("PY_CONTROLLER", "py"))
    scene.step(0.002)
    assert np.any(arm.get_external_forces() != 0)
    ref, calls = weakref.ref(controller), len(controller.calls)
    del ctx, bot, controller
    gc.collect()
    assert ref() is None, "the context released its Python components"
    # the pipeline's step callbacks went with the context (pipeline_test.cpp counts the scene's)
    scene.step(0.002)  # no callback into freed memory
    np.testing.assert_array_equal(arm.get_external_forces(), 0.0)  # the pipeline's forces stopped with it
    assert calls == 1


def test_scene_destroyed_before_the_context(scene):
    ctx = pipeline_context()
    bot = example_bot(scene, ctx)
    other = example_bot(scene, ctx, x=1.0)
    bot.create_controller("BASIC_JSC_PD", "jsc", {"kp": 5.0, "kd": 0.5})
    ctx.create_sensor("CONTACT_FORCE", scene.get_actor(other.get_articulated_actor().get_nested_link_actors()[3]), "cf")
    scene.step(0.002)
    sdp.destroy_scene(scene)
    sdr.destroy_bot(scene, bot)  # its scene is gone: only the bookkeeping is left to drop
    assert not ctx.find_controllers_by_name("jsc")
    del bot, other, ctx
    gc.collect()  # the other bot's pipeline and sensor go with the context


def test_seed_loop_without_pipeline_methods_is_unchanged(scene):
    class SeedSensor:
        def __init__(self, actor, param_args):
            self.actor = actor
            actor.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)

        def reset(self):
            pass

        def compute_signal(self):
            return np.array(self.actor.get_contact_force_world())

    class SeedServo:
        def __init__(self, actor, param_args):
            self.actor = actor

        def reset(self):
            pass

        def compute_effort(self, obsv, w_goal, dt):
            return 0.25

    ctx = sdr.create_context()
    sdr.register_python_sensor(ctx, "MY_CONTACT_FORCE_SENSOR", SeedSensor)
    sdr.register_python_actuator(ctx, "MY_VELOCITY_SERVO_ACTUATOR", SeedServo)
    bot = example_bot(scene, ctx)
    assert not bot.is_pipeline_active(), "no component defines pipeline methods"
    arm = bot.get_articulated_actor()
    servos = [sdr.get_python_actuator(ctx, h) for h in bot.get_actuator_handles()]
    for _ in range(3):
        efforts = np.array([s.compute_effort({}, 0.0, 0.002) for s in servos])
        arm.set_external_forces_on_dofs(dof_indices=[0, 1], force_values=efforts)
        scene.step(0.002)
        np.testing.assert_allclose(arm.get_external_forces(), [0.25, 0.25])
    # the sensor's reading through the context: its compute_signal()
    (sensor_handle,) = bot.get_sensor_handles()
    np.testing.assert_array_equal(ctx.get_sensor_signal(sensor_handle), sdr.get_python_sensor(ctx, sensor_handle).compute_signal())


def test_switching_the_pipeline_on_and_off(scene):
    ctx = pipeline_context()
    bot = example_bot(scene, ctx)
    arm = bot.get_articulated_actor()
    controller = sdr.get_python_controller(ctx, bot.create_controller("PY_CONTROLLER", "py"))
    scene.step(0.002)
    bot.set_pipeline_enabled(False)
    assert not bot.is_pipeline_active()
    np.testing.assert_array_equal(arm.get_external_forces(), 0.0)  # its forces stop with it
    scene.step(0.002)
    assert len(controller.calls) == 1
    bot.set_pipeline_enabled(None)  # automatic again: it has pipeline components
    assert ctx.is_pipeline_active(bot)
    scene.step(0.002)
    assert len(controller.calls) == 2
    # forced on without controllers or actuators, it leaves the user's forces alone
    ctx2 = sdr.create_context()
    with pytest.warns(UserWarning, match="not registered"):
        plain = example_bot(scene, ctx2, x=1.0)
    ctx2.set_pipeline_enabled(plain, True)
    assert plain.is_pipeline_active()
    plain_arm = plain.get_articulated_actor()
    plain_arm.set_external_forces_on_dofs([0, 1], [0.5, -0.5])
    scene.step(0.002)
    np.testing.assert_allclose(plain_arm.get_external_forces(), [0.5, -0.5])


def test_a_component_cannot_be_destroyed_from_inside_the_pipeline(scene):
    ctx = pipeline_context()
    bot = example_bot(scene, ctx)
    handle = bot.create_controller("PY_CONTROLLER", "py")
    controller = sdr.get_python_controller(ctx, handle)
    controller.compute = lambda t, dt: ctx.destroy_controller(handle)
    with pytest.raises(sdp.Error, match="cannot be destroyed while its bot's pipeline is running"):
        scene.step(0.002)
    controller.compute = lambda t, dt: sdr.destroy_bot(scene, bot)
    with pytest.raises(sdp.Error, match="while its pipeline is running"):
        scene.step(0.002)
    del controller.compute
    scene.step(0.002)


def test_configure_reaches_python_components(scene):
    ctx = pipeline_context()
    bot = example_bot(scene, ctx)
    handle = bot.create_controller("PY_CONTROLLER", "py")
    ctx.configure_controller(handle, {"gain": 2.0})
    assert sdr.get_python_controller(ctx, handle).configured == {"gain": 2.0}
    ctx.configure_controller(handle, '{"gain": 3.0}')  # JSON text is parsed for Python components too
    assert sdr.get_python_controller(ctx, handle).configured == {"gain": 3.0}
    with pytest.raises(sdp.Error, match="class 'PipelineServo' has no configure"):
        ctx.configure_actuator(bot.get_actuator_handles()[0], {"k_p": 1.0})


def test_the_debugger_plots_readings_without_sampling_the_sensor(scene, tmp_path):
    """Recorded (and live) frames carry each sensor's latest reading, the one the user's loop
    obtained, and each actuator's effort; the debugger never calls the sensor itself, so a sensor
    with side effects (here: a counter) behaves the same with and without a recording."""
    import json

    class CountingSensor:
        def __init__(self, actor, param_args):
            self.calls = 0

        def reset(self):
            pass

        def compute_signal(self):
            self.calls += 1
            return np.array([float(self.calls), -1.0])

    class ConstantServo:
        def __init__(self, actor, param_args):
            pass

        def reset(self):
            pass

    ctx = sdr.create_context()
    sdr.register_python_sensor(ctx, "MY_CONTACT_FORCE_SENSOR", CountingSensor)
    sdr.register_python_actuator(ctx, "MY_VELOCITY_SERVO_ACTUATOR", ConstantServo)
    bot = example_bot(scene, ctx)
    arm = bot.get_articulated_actor()
    (sensor_handle,) = bot.get_sensor_handles()
    sensor = sdr.get_python_sensor(ctx, sensor_handle)
    ref = weakref.ref(sensor)
    recording = tmp_path / "run.jsonl"
    sdp.start_recording(str(recording), 0.0)
    returned = []
    for k in range(6):
        arm.set_external_forces_on_dofs(dof_indices=[0, 1], force_values=np.array([0.1 * k, -0.2 * k]))
        scene.step(0.002)
        returned.append(sensor.compute_signal().tolist())
    sdp.stop_recording()
    assert sensor.calls == 6, "only the user's loop sampled the sensor"
    lines = list(map(json.loads, recording.read_text().splitlines()))
    frames = [l for l in lines if l["type"] == "frame"]
    signals = [f["signals"] for f in frames]
    name = bot.get_name() + ".force_sensor"
    # each signal's kind is told once, before the first frame that has it
    kinds = {}
    for l in lines:
        if l["type"] == "signals":
            assert not set(l["kinds"]) & set(kinds), "a kind is sent once"
            kinds.update(l["kinds"])
        if l["type"] == "frame":
            assert set(l["signals"]) <= set(kinds)
    assert kinds[name] == "sensor" and kinds[bot.get_name() + ".servo_1.effort"] == "actuator"
    assert kinds[bot.get_name() + ".link_1.velocity"] == "velocity" and kinds[bot.get_name() + ".ball.contact_force"] == "contact"
    assert name not in signals[0], "no reading before the loop obtained one"
    # frame k is written at the end of step k, before the loop reads the sensor again
    assert [s[name] for s in signals[1:]] == returned[:-1]
    np.testing.assert_allclose([s[bot.get_name() + ".servo_1.effort"] for s in signals], [0.1 * k for k in range(6)], atol=1e-6)
    np.testing.assert_allclose([s[bot.get_name() + ".servo_2.effort"] for s in signals], [-0.2 * k for k in range(6)], atol=1e-6)
    sdr.destroy_bot(scene, bot)
    del sensor, ctx, bot
    gc.collect()
    assert ref() is None, "the reading wrapper keeps no sensor alive"
