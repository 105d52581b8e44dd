"""Helpers for building and searching scenes: find an actor by a name pattern, add a ground
plane, make a scene from a prefab."""

from __future__ import annotations

import fnmatch
import os
from pathlib import Path

import superdex.physics as sdp
from superdex.physics.paths import get_assets_root


class ActorLookupError(sdp.Error, ValueError):
    """find_actor found no actor or several: a superdex.physics.Error that is also a ValueError
    (as SuperDex raises for a bad pattern)."""


def find_actor(scene: sdp.Scene, pattern: str) -> sdp.Actor:
    """The one actor whose name matches `pattern`, a case-sensitive shell-style pattern (`*`,
    `?`, `[...]`): "tablePrefab/Table", "cube_*". Links of articulations are actors too (named
    "<articulation>/<link>"). Raises ActorLookupError (an Error and a ValueError) when no actor or
    more than one matches."""
    if scene is None:
        raise sdp.Error("find_actor: scene is None")
    matches = []
    scene.for_each_actor(lambda actor: matches.append(actor) if fnmatch.fnmatchcase(actor.get_name(), pattern) else None)
    if not matches:
        raise ActorLookupError(f'find_actor: no actor of scene "{scene.get_name()}" matches "{pattern}"')
    if len(matches) > 1:
        names = ", ".join(sorted(a.get_name() for a in matches))
        raise ActorLookupError(f'find_actor: {len(matches)} actors match "{pattern}": {names}')
    return matches[0]


def create_ground_plane(scene: sdp.Scene, normal=None, offset: float = 0.0,
                        contact_params: sdp.ContactParams | None = None) -> sdp.Actor:
    """A static plane actor named "StaticPlane" in layer "Environment": the points x with
    normal . x = offset (normal defaults to +Y, the engine's up), solid below."""
    shape = sdp.create_plane_shape(normal if normal is not None else sdp.Real3(0.0, 1.0, 0.0), offset)
    return scene.create_rigid_actor(name="StaticPlane", layer="Environment", shape=shape, is_static=True,
                                    collider_type=sdp.ColliderType.PLANE,
                                    contact=contact_params if contact_params is not None else sdp.ContactParams())


def create_scene_from_prefab(prefab, root_dir=None, params=None, scene_name: str = "") -> sdp.Scene:
    """A new scene holding `prefab`: a prefab file path (relative paths are taken under
    `root_dir`) or a ScenePrefab (its nested prefabs and shapes are loaded first where missing).
    `root_dir` resolves the prefab's own relative paths; None or "" is the assets folder (a Path
    is taken as it is, Path("") being the current folder). `params`: PrefabParams (default
    ones when None). The scene is destroyed again if adding the prefab fails."""
    params = params if params is not None else sdp.prefab.PrefabParams()
    root = get_assets_root() if root_dir is None or (isinstance(root_dir, str) and root_dir == "") else Path(root_dir)
    if isinstance(prefab, (str, os.PathLike)):
        path = Path(prefab)
        loaded = sdp.prefab.load_from_file(str(path if path.is_absolute() else root / path), str(root))
    elif isinstance(prefab, sdp.prefab.ScenePrefab):
        sdp.prefab.ensure_fully_loaded(prefab=prefab, root_path=str(root))
        loaded = prefab
    else:
        raise TypeError(f"create_scene_from_prefab: prefab must be a file path or a prefab.ScenePrefab, got {type(prefab).__name__}")
    scene = sdp.create_scene(scene_name)
    try:
        sdp.prefab.add_to_scene(prefab=loaded, scene=scene, params=params)
    except BaseException:
        sdp.destroy_scene(scene)
        raise
    return scene
