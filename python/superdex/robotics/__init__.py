"""superdex.robotics: bot files, the component framework and the robotics context (API.md)."""

import contextlib
import functools
import os

from superdex._native import module as _m

_r = _m.robotics

RoboticsContext = _r.RoboticsContext
Context = RoboticsContext  # the name this package used first
Bot = _r.Bot
BotPrefab = _r.BotPrefab
LinkDesc = _r.LinkDesc
JointDesc = _r.JointDesc
# the SuperDex API's names of the bot description's parts
BotJointPrefab = JointDesc
BotLinkPrefab = _r.BotLinkPrefab
BotSensorPrefab = _r.BotSensorPrefab
BotActuatorPrefab = _r.BotActuatorPrefab
BotLinearTransmissionPrefab = _r.BotLinearTransmissionPrefab
JointCoupling = _r.JointCoupling
FixedTendon = _r.FixedTendon
ComponentDecl = _r.ComponentDecl
# handles: 0 (a default-constructed handle) is invalid
RoboticsHandle = _r.RoboticsHandle
BotHandle = _r.BotHandle
ControllerHandle = _r.ControllerHandle
SensorHandle = _r.SensorHandle
ActuatorHandle = _r.ActuatorHandle
EFFORT_UNBOUNDED = _r.EFFORT_UNBOUNDED
# views of live components (RoboticsContext.get_controller / get_sensor / get_actuator)
ComponentBase = _r.ComponentBase
ControllerBase = _r.ControllerBase
SensorBase = _r.SensorBase
ActuatorBase = _r.ActuatorBase
ControllerBasicJscPd = _r.ControllerBasicJscPd
ControllerBasicJscPdParams = _r.ControllerBasicJscPdParams
ControllerMochiArticulatedPose = _r.ControllerMochiArticulatedPose
ControllerMochiArticulatedPoseParams = _r.ControllerMochiArticulatedPoseParams
ControllerMochiArticulatedPoseObsv = _r.ControllerMochiArticulatedPoseObsv
ControllerMochiArticulatedPoseTarget = _r.ControllerMochiArticulatedPoseTarget
CameraSensor = _r.CameraSensor
CameraSensorParams = _r.CameraSensorParams
# batched stepping of scenes of one model (scene_batch.h; superdex.lab builds on it)
SceneBatch = _r.SceneBatch
SceneBatchSpec = _r.SceneBatchSpec
BatchActionMode = _r.BatchActionMode
BatchTask = _r.BatchTask
BatchTaskKind = _r.BatchTaskKind

create_context = _r.create_context
register_python_controller = _r.register_python_controller


def _keep_readings(sensor):
    """Wraps the sensor's signal()/compute_signal() on the instance so that each reading the user's
    code obtains is also kept for the debugger's plots: the debugger never calls the sensor itself
    (a sample can have side effects, such as drawing noise)."""
    for name in ("signal", "compute_signal"):
        method = getattr(sensor, name, None)
        if not callable(method):
            continue

        @functools.wraps(method)
        def keeping(*args, _method=method, **kwargs):
            value = _method(*args, **kwargs)
            with contextlib.suppress(AttributeError, TypeError):
                sensor._superdex_latest_reading = value
            return value

        try:
            setattr(sensor, name, keeping)
        except (AttributeError, TypeError):  # __slots__ or a read-only attribute: no plot
            return sensor
    return sensor


def register_python_sensor(ctx, type_name, factory):
    """Registers a Python sensor type: `factory(actor_or_None, param_args)` makes one (API.md)."""
    if not callable(factory):
        return _r.register_python_sensor(ctx, type_name, factory)  # the native error names the argument

    @functools.wraps(factory, updated=())
    def making(actor, param_args):
        return _keep_readings(factory(actor, param_args))

    return _r.register_python_sensor(ctx, type_name, making)

register_python_actuator = _r.register_python_actuator
get_python_controller = _r.get_python_controller
get_python_sensor = _r.get_python_sensor
get_python_actuator = _r.get_python_actuator


def load_bot_prefab_from_file(path):
    """Reads a .superdex_bot file (a str or os.PathLike) into a BotPrefab; Error names the file and field."""
    return _r.load_bot_prefab_from_file(os.fspath(path))

load_bot_prefab_from_urdf_file = _r.load_bot_prefab_from_urdf_file
load_mjcf_file = _r.load_mjcf_file
save_to_urdf_string = _r.save_to_urdf_string
save_to_urdf_file = _r.save_to_urdf_file
MjcfModel = _r.MjcfModel
create_bot = _r.create_bot
destroy_bot = _r.destroy_bot

# bot scenes: a base scene, bots with controllers, scene-level sensors (bot_scene.py)
from superdex.robotics.bot_scene import BotScene, load_bot_scene  # noqa: E402

__all__ = [name for name in dir() if not name.startswith("_")]
