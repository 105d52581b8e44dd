"""superdex.robotics: bot files, the component framework and the robotics context (API.md)."""

import os

from superdex._native import module as _m

_r = _m.robotics

Context = _r.Context
Bot = _r.Bot
BotPrefab = _r.BotPrefab
LinkDesc = _r.LinkDesc
JointDesc = _r.JointDesc
ComponentDecl = _r.ComponentDecl
ControllerHandle = _r.ControllerHandle
SensorHandle = _r.SensorHandle
ActuatorHandle = _r.ActuatorHandle
EFFORT_UNBOUNDED = _r.EFFORT_UNBOUNDED

create_context = _r.create_context
register_python_controller = _r.register_python_controller
register_python_sensor = _r.register_python_sensor
register_python_actuator = _r.register_python_actuator
get_python_controller = _r.get_python_controller
get_python_sensor = _r.get_python_sensor
get_python_actuator = _r.get_python_actuator


def load_bot_prefab_from_file(path):
    """Reads a .superdex_bot file (a str or os.PathLike) into a BotPrefab; Error names the file and field."""
    return _r.load_bot_prefab_from_file(os.fspath(path))

load_bot_prefab_from_urdf_file = _r.load_bot_prefab_from_urdf_file
create_bot = _r.create_bot
destroy_bot = _r.destroy_bot

__all__ = [name for name in dir() if not name.startswith("_")]
