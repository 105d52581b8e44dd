"""Prefabs: sets of actors described in `.mochi_prefab` / `.mochi_scene` files (FORMATS.md)."""

from dataclasses import dataclass, field
from pathlib import Path

from superdex._native import module as _m


@dataclass
class PrefabParams:
    """How to place a prefab: instance name (prefixes actor names as "name/actor"), uniform
    scale, and the rotation (Quaternion or [x, y, z, w]) and translation (m) of its frame."""

    name: str = ""
    scale: float = 1.0
    rotation: object = None
    translation: object = None
    apply_scene_settings: bool = False


@dataclass
class PrefabInstance:
    """What add_to_scene created: actor handles (file order) and constraint handles."""

    actors: list = field(default_factory=list)
    constraints: list = field(default_factory=list)


def _value(cls, value, field_name):
    """A Quaternion or Real3 from a PrefabParams field (None: identity / zero); Error names the field."""
    if value is None:
        return cls()
    try:
        return cls(value)
    except (TypeError, ValueError) as e:
        raise _m.Error(f"PrefabParams.{field_name}: {e}") from None


def add_to_scene(prefab_path, root_path, scene, params: PrefabParams | None = None) -> PrefabInstance:
    """Loads a prefab into `scene`; paths starting with ./ are relative to the prefab file, other
    relative paths to `root_path`. All or nothing: on an Error no actor of it remains."""
    params = params or PrefabParams()
    transform = _m.TransformRT(rotation=_value(_m.Quaternion, params.rotation, "rotation"),
                               translation=_value(_m.Real3, params.translation, "translation"))
    actors, constraints = _m._add_prefab_to_scene(
        str(Path(prefab_path)), str(Path(root_path)), scene, params.name, float(params.scale), transform,
        bool(params.apply_scene_settings))
    return PrefabInstance(actors=list(actors), constraints=list(constraints))
