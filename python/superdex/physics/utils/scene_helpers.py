"""Helpers for building and searching scenes: find an actor by a name pattern, add a ground
plane."""

from __future__ import annotations

import fnmatch

import superdex.physics as sdp


def find_actor(scene: sdp.Scene, pattern: str) -> sdp.Actor:
    """The one actor whose name matches `pattern`, a case-sensitive shell-style pattern (`*`,
    `?`, `[...]`): "tablePrefab/Table", "cube_*". Links of articulations are actors too (named
    "<articulation>/<link>"). Raises Error when no actor or more than one matches."""
    if scene is None:
        raise sdp.Error("find_actor: scene is None")
    matches = []
    scene.for_each_actor(lambda actor: matches.append(actor) if fnmatch.fnmatchcase(actor.get_name(), pattern) else None)
    if not matches:
        raise sdp.Error(f'find_actor: no actor of scene "{scene.get_name()}" matches "{pattern}"')
    if len(matches) > 1:
        names = ", ".join(sorted(a.get_name() for a in matches))
        raise sdp.Error(f'find_actor: {len(matches)} actors match "{pattern}": {names}')
    return matches[0]


def create_ground_plane(scene: sdp.Scene, normal=None, offset: float = 0.0,
                        contact_params: sdp.ContactParams | None = None) -> sdp.Actor:
    """A static plane actor named "StaticPlane" in layer "Environment": the points x with
    normal . x = offset (normal defaults to +Y, the engine's up), solid below."""
    shape = sdp.create_plane_shape(normal if normal is not None else sdp.Real3(0.0, 1.0, 0.0), offset)
    return scene.create_rigid_actor(name="StaticPlane", layer="Environment", shape=shape, is_static=True,
                                    collider_type=sdp.ColliderType.PLANE,
                                    contact=contact_params if contact_params is not None else sdp.ContactParams())
