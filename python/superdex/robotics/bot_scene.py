"""Bot scenes (`.mochi_bot_scene`, JSON): a base physics scene, bots with their controllers, and
scene-level sensors, built in a new scene by load_bot_scene.

Top level
  metadata   {name, version}; optional, `name` names the scene
  scene      {baseScene}: a `.mochi_scene` path relative to the scene file (its actors and, with
             `scene` settings, gravity and solver); optional
  bots[]     {name, path, translation?, rotation?, controllers[]}
               name         unique within the scene; controllers are addressed "<bot>/<controller>"
               path         a .superdex_bot file: relative to the scene file, absolute, or starting
                            with an asset tag ("@bots/arms/fr3/fr3.superdex_bot", see below)
               translation  [x, y, z] m and rotation [x, y, z, w]: the bot root's world pose
               controllers[] {type, name, params?, initArgs?}; params and initArgs are inline JSON
                            (a string or an object) or JSON file paths relative to the scene file
  sensors[]  {type, name, params?, translation?, rotation?}: sensors bound to no actor, posed in
             the world (the scene root's frame)
Controller and sensor types that no one registered are skipped with a warning.

Asset tags. A path "@tag/rest" is looked up in `.superdex_root` files (JSON {"@tag": "/dir"}) in
the scene file's folder and its ancestors, the nearest first; "@bots" falls back to the bundled
assets' bots/ folder.
"""

from __future__ import annotations

import json
import os
import warnings
import weakref
from pathlib import Path

import superdex.physics as _sdp

ROOT_MARKER = ".superdex_root"


def _error(where: str, message: str) -> _sdp.Error:
    return _sdp.Error(f"{where}: {message}")


def _tag_roots(start_dir: Path) -> dict[str, str]:
    """Asset tags of the `.superdex_root` markers from `start_dir` up to the filesystem root (nearest wins)."""
    roots: dict[str, str] = {}
    for folder in [start_dir, *start_dir.parents]:
        marker = folder / ROOT_MARKER
        if not marker.is_file():
            continue
        try:
            entries = json.loads(marker.read_text())
        except (OSError, ValueError) as e:
            raise _error(str(marker), f"not a JSON object of asset tags: {e}") from None
        if not isinstance(entries, dict):
            raise _error(str(marker), "expected a JSON object {\"@tag\": \"/folder\"}")
        for tag, target in entries.items():
            if not isinstance(target, str):
                raise _error(str(marker), f"{tag}: expected a folder path string")
            # relative targets are relative to the marker's folder
            roots.setdefault(tag, str((folder / target).resolve()))
    return roots


def resolve_scene_path(path: str, scene_dir: Path, where: str) -> str:
    """An existing file from a scene entry's path: an asset tag, absolute, or relative to the scene's folder."""
    if not isinstance(path, str) or not path:
        raise _error(where, "expected a non-empty path string")
    if path.startswith("@"):
        tag, _, rest = path.partition("/")
        roots = _tag_roots(scene_dir)
        if tag not in roots and tag == "@bots":
            from superdex.physics.paths import get_assets_root

            roots[tag] = str(get_assets_root() / "bots")
        if tag not in roots:
            raise _error(where, f"asset tag {tag!r} is defined by no {ROOT_MARKER} file in {str(scene_dir)!r} or above")
        resolved = Path(roots[tag]) / rest
    else:
        resolved = Path(path) if os.path.isabs(path) else scene_dir / path
    if not resolved.is_file():
        raise _error(where, f"{path!r} resolves to {str(resolved)!r}, which does not exist")
    return str(resolved)


def _params_text(value, scene_dir: Path, where: str) -> str:
    """A params or initArgs value as the component API takes it: inline JSON or an absolute file path."""
    if value is None or value == "":
        return ""
    if isinstance(value, (dict, list)):
        return json.dumps(value)
    if not isinstance(value, str):
        raise _error(where, f"expected inline JSON (a string or an object) or a file path, got {type(value).__name__}")
    if value.lstrip().startswith("{"):
        return value
    return resolve_scene_path(value, scene_dir, where)


def _pose(entry: dict, where: str):
    """TransformRT from an entry's optional translation [3] and rotation [x, y, z, w]."""
    def vector(key, n):
        value = entry.get(key)
        if value is None:
            return None
        if not isinstance(value, list) or len(value) != n or not all(isinstance(x, (int, float)) for x in value):
            raise _error(f"{where}.{key}", f"expected {n} numbers, got {value!r}")
        return [float(x) for x in value]

    translation = vector("translation", 3) or [0.0, 0.0, 0.0]
    rotation = vector("rotation", 4)
    if rotation is None:
        return _sdp.TransformRT(translation=translation)
    if sum(x * x for x in rotation) < 1e-12:
        raise _error(f"{where}.rotation", "the quaternion must not be zero")
    return _sdp.TransformRT(rotation=_sdp.Quaternion(rotation), translation=translation)


def _require(entry, key: str, kind, where: str):
    if not isinstance(entry, dict):
        raise _error(where, "expected a JSON object")
    if key not in entry:
        raise _error(f"{where}.{key}", "is required")
    value = entry[key]
    if not isinstance(value, kind):
        raise _error(f"{where}.{key}", f"expected a {kind.__name__}, got {type(value).__name__}")
    return value


def _optional_name(entry: dict, where: str) -> str:
    """The entry's "name" ("" when absent); Error when it is not a string."""
    name = entry.get("name", "")
    if not isinstance(name, str):
        raise _error(f"{where}.name", "expected a string")
    return name


def _list(doc: dict, key: str, where: str) -> list:
    value = doc.get(key, [])
    if not isinstance(value, list):
        raise _error(f"{where}: {key}", "expected a list")
    return value


def _teardown(ctx, scene, bot_handles, sensor_handles):
    """Destroys what a bot scene built: scene-level sensors, bots (with their components), the scene."""
    for h in sensor_handles:
        if ctx.is_valid_sensor(h):
            ctx.destroy_sensor(h)
    for h in bot_handles:
        bot = ctx.get_bot(h)
        if bot is not None:
            _sdp_robotics().destroy_bot(scene, bot)
    _sdp.destroy_scene(scene)


def _sdp_robotics():
    import superdex.robotics as sdr

    return sdr


class BotScene:
    """A scene built from a bot scene file: owns the scene, its bots and scene-level sensors, and
    destroys them when it is garbage-collected or destroy() is called."""

    def __init__(self, ctx, scene, source: str):
        self._ctx = ctx
        self._scene = scene
        self._source = source
        self._bots: dict[str, object] = {}  # name -> BotHandle, file order
        self._controllers: dict[str, object] = {}  # "bot/controller" -> ControllerHandle
        self._sensors: dict[str, object] = {}  # scene-level sensor name -> SensorHandle
        self._finalizer = weakref.finalize(self, _teardown, ctx, scene, [], [])

    def _track(self):
        # the finalizer holds the lists, not self, so that collecting self runs it
        self._finalizer.detach()
        self._finalizer = weakref.finalize(self, _teardown, self._ctx, self._scene, list(self._bots.values()),
                                           list(self._sensors.values()))

    def get_scene(self):
        """The physics scene (valid until this BotScene is destroyed)."""
        return self._scene

    def get_context(self):
        return self._ctx

    def get_source(self) -> str:
        """The bot scene file it was loaded from."""
        return self._source

    def get_bot_names(self) -> list[str]:
        return list(self._bots)

    def get_bot(self, name: str):
        """The bot named `name` in the scene file; Error naming the known bots otherwise."""
        handle = self._bots.get(name)
        bot = self._ctx.get_bot(handle) if handle is not None else None
        if bot is None:
            raise _sdp.Error(f"get_bot: no bot {name!r} in {self._source!r} (bots: {', '.join(self._bots) or 'none'})")
        return bot

    def get_controller_handle(self, path: str):
        """The handle of controller "<bot>/<controller>" declared in the scene file."""
        if path not in self._controllers:
            raise _sdp.Error(f"get_controller_handle: no controller {path!r} in {self._source!r} "
                             f"(controllers: {', '.join(self._controllers) or 'none'})")
        return self._controllers[path]

    def get_sensor_handle(self, name: str):
        """The handle of the scene-level sensor `name`."""
        if name not in self._sensors:
            raise _sdp.Error(f"get_sensor_handle: no scene-level sensor {name!r} in {self._source!r}")
        return self._sensors[name]

    def destroy(self) -> None:
        """Destroys the scene-level sensors, the bots (and their components) and the scene; idempotent."""
        self._finalizer()

    def is_alive(self) -> bool:
        return self._finalizer.alive


def load_bot_scene(scene_file, ctx) -> BotScene:
    """Builds the bot scene in `scene_file` (a str or os.PathLike) in a new physics scene, using the
    robotics context `ctx` for its bots and components. All or nothing: on an Error nothing of it
    remains. Errors name the file and the JSON path."""
    sdr = _sdp_robotics()
    if not isinstance(ctx, sdr.RoboticsContext):
        raise _sdp.Error(f"load_bot_scene: ctx: expected a RoboticsContext (create_context()), got {type(ctx).__name__}")
    path = Path(os.fspath(scene_file)).resolve()
    if not path.is_file():
        raise _sdp.Error(f"load_bot_scene: scene_file: {str(path)!r} does not exist")
    where = str(path)
    try:
        doc = json.loads(path.read_text())
    except (OSError, ValueError) as e:
        raise _error(where, f"not valid JSON: {e}") from None
    if not isinstance(doc, dict):
        raise _error(where, "expected a JSON object")
    scene_dir = path.parent
    metadata = doc.get("metadata", {})
    name = metadata.get("name", path.stem) if isinstance(metadata, dict) else path.stem
    scene = _sdp.create_scene(str(name))
    result = BotScene(ctx, scene, where)
    try:
        _build(result, doc, scene_dir, where)
    except BaseException:
        result.destroy()
        raise
    return result


def _build(result: BotScene, doc: dict, scene_dir: Path, where: str) -> None:
    sdr = _sdp_robotics()
    ctx, scene = result._ctx, result._scene
    settings = doc.get("scene", {})
    if not isinstance(settings, dict):
        raise _error(f"{where}: scene", "expected a JSON object")
    base = settings.get("baseScene")
    if base:
        base_path = resolve_scene_path(base, scene_dir, f"{where}: scene.baseScene")
        _sdp.prefab.add_to_scene(base_path, str(Path(base_path).parent), scene,
                                 _sdp.prefab.PrefabParams(apply_scene_settings=True))

    for i, entry in enumerate(_list(doc, "bots", where)):
        at = f"{where}: bots[{i}]"
        bot_name = _require(entry, "name", str, at)
        if bot_name in result._bots:
            raise _error(f"{at}.name", f"bot {bot_name!r} is declared twice")
        prefab = sdr.load_bot_prefab_from_file(resolve_scene_path(_require(entry, "path", str, at), scene_dir, f"{at}.path"))
        if "translation" in entry or "rotation" in entry:
            prefab.world_from_root = _pose(entry, at)
        bot = sdr.create_bot(scene, prefab, ctx)
        result._bots[bot_name] = bot.get_handle()
        result._track()
        for k, c in enumerate(_list(entry, "controllers", at)):
            cat = f"{at}.controllers[{k}]"
            type_name = _require(c, "type", str, cat)
            controller_name = _optional_name(c, cat)
            if not ctx.is_controller_type_registered(type_name):
                warnings.warn(f"{cat}: controller type {type_name!r} is not registered; skipped", stacklevel=3)
                continue
            handle = bot.create_controller(type_name, controller_name)
            params = _params_text(c.get("params"), scene_dir, f"{cat}.params")
            init_args = _params_text(c.get("initArgs"), scene_dir, f"{cat}.initArgs")
            try:
                ctx.get_controller(handle).configure_from_scene_entry(params, init_args)
            except _sdp.Error as e:
                raise _error(cat, str(e)) from None
            result._controllers[f"{bot_name}/{controller_name}"] = handle

    for i, entry in enumerate(_list(doc, "sensors", where)):
        at = f"{where}: sensors[{i}]"
        type_name = _require(entry, "type", str, at)
        sensor_name = _optional_name(entry, at)
        if not ctx.is_sensor_type_registered(type_name):
            warnings.warn(f"{at}: sensor type {type_name!r} is not registered; skipped", stacklevel=3)
            continue
        params = _params_text(entry.get("params"), scene_dir, f"{at}.params")
        try:
            handle = ctx.create_sensor(type_name, None, sensor_name, params)
        except _sdp.Error as e:
            raise _error(at, str(e)) from None
        result._sensors[sensor_name] = handle
        result._track()
        ctx.get_sensor(handle).set_parent_from_sensor(_pose(entry, at))
