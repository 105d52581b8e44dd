"""An exception raised by Python code that scene.step calls (pre- and post-step callbacks, and the
sensors, controllers and actuators of a bot's pipeline) reaches the caller of step as itself, its
traceback naming the user's function; the engine stays usable: the same scene, bot and components
step again, and nothing has to be rebuilt.

What the failed step did: an exception before the physics (pre-step callback, controller, actuator)
leaves the scene as it was; one after it (post-step callback, sensor) comes after the bodies moved.
"""

import traceback

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from robotics_helpers import EXAMPLE_BOT, scene  # noqa: F401
from superdex.physics.paths import resolve_asset


class Once:
    """Raises the first time it is armed and called, then never again."""

    def __init__(self):
        self.armed = False

    def check(self):
        if self.armed:
            self.armed = False
            raise ValueError("the user's code failed")


FAIL = {kind: Once() for kind in ("sensor", "controller", "actuator", "pre_step", "post_step")}


class Sensor:
    def __init__(self, actor, params):
        self.updates = 0

    def reset(self):
        pass

    def update(self, t, dt):
        user_sensor_update(self)


def user_sensor_update(sensor):
    FAIL["sensor"].check()
    sensor.updates += 1


class Servo:
    def __init__(self, actor, params):
        self.calls = 0

    def reset(self):
        pass

    def compute_pipeline_effort(self, commands, dt):
        return user_actuator_effort(self)


def user_actuator_effort(servo):
    FAIL["actuator"].check()
    servo.calls += 1
    return 0.0


class Controller:
    def __init__(self, actor):
        self.calls = 0

    def reset(self):
        pass

    def compute(self, t, dt):
        return user_controller_compute(self)


def user_controller_compute(controller):
    FAIL["controller"].check()
    controller.calls += 1
    return {"effort": [0.0, 0.0]}


def user_pre_step(info):
    FAIL["pre_step"].check()


def user_post_step(info):
    FAIL["post_step"].check()


EXPECTED_FRAME = {"sensor": "user_sensor_update", "controller": "user_controller_compute",
                  "actuator": "user_actuator_effort", "pre_step": "user_pre_step", "post_step": "user_post_step"}
AFTER_PHYSICS = {"sensor", "post_step"}


@pytest.mark.parametrize("where", sorted(EXPECTED_FRAME))
def test_exception_reaches_step_with_its_traceback_and_the_engine_goes_on(scene, where):
    ctx = sdr.create_context()
    sdr.register_python_sensor(ctx, "MY_CONTACT_FORCE_SENSOR", Sensor)
    sdr.register_python_actuator(ctx, "MY_VELOCITY_SERVO_ACTUATOR", Servo)
    sdr.register_python_controller(ctx, "PY_CONTROLLER", Controller)
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT))), ctx)
    controller = sdr.get_python_controller(ctx, bot.create_controller("PY_CONTROLLER", "py"))
    sensor = sdr.get_python_sensor(ctx, bot.find_sensors_by_name("force_sensor")[0])
    servo = sdr.get_python_actuator(ctx, bot.find_actuators_by_name("servo_1")[0])
    scene.register_pre_step_callback("user pre", user_pre_step)
    scene.register_post_step_callback("user post", user_post_step)
    arm = bot.get_articulated_actor()
    for _ in range(3):
        scene.step(0.01)
    t = scene.get_total_simulation_time()
    pose = arm.get_articulated_pose().copy()

    FAIL[where].armed = True
    with pytest.raises(ValueError, match="the user's code failed") as info:
        scene.step(0.01)
    text = "".join(traceback.format_exception(info.type, info.value, info.tb))
    assert EXPECTED_FRAME[where] in text, f"the traceback shows the user's function:\n{text}"
    assert "Once.check" in text or "in check" in text
    if where in AFTER_PHYSICS:
        assert scene.get_total_simulation_time() == pytest.approx(t + 0.01)
    else:
        assert scene.get_total_simulation_time() == t
        np.testing.assert_array_equal(arm.get_articulated_pose(), pose)

    # the same scene, bot and components keep working
    counts = (sensor.updates, controller.calls, servo.calls)
    t = scene.get_total_simulation_time()
    for _ in range(5):
        scene.step(0.01)
    assert scene.get_total_simulation_time() == pytest.approx(t + 0.05)
    assert sensor.updates > counts[0] and controller.calls == counts[1] + 5 and servo.calls > counts[2]
    assert np.all(np.isfinite(arm.get_articulated_pose()))
    sdr.destroy_bot(scene, bot)
    scene.step(0.01)
