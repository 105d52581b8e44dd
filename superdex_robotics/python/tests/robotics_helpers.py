"""Shared pieces of the robotics tests: engine fixtures and the example bot's path."""

import json
import shutil
from pathlib import Path

import pytest

import superdex.physics as sdp
from superdex.physics.paths import resolve_asset

EXAMPLE_BOT = "bots/fun/example_bot_2dof/example_bot_2dof.superdex_bot"


@pytest.fixture
def scene():
    sdp.initialize(num_worker_threads=0)
    s = sdp.create_scene("robotics test")
    s.set_gravity([0, 0, -9.81])
    yield s
    sdp.shutdown()


@pytest.fixture
def ground_scene(scene):
    """The scene with a static ground plane at z = 0."""
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    return scene


def example_bot_json() -> dict:
    """The example bot's JSON, its render model paths made absolute (the copy lives elsewhere)."""
    path = Path(resolve_asset(EXAMPLE_BOT))
    doc = json.loads(path.read_text())
    for link in doc["links"]:
        if "renderModel" in link:
            link["renderModel"] = str(path.parent / link["renderModel"])
    return doc


def write_bot(folder: Path, doc: dict, name: str = "bot.superdex_bot") -> Path:
    path = folder / name
    path.write_text(json.dumps(doc, indent=1))
    return path


def copy_example_bot(folder: Path) -> Path:
    dst = folder / "example_bot_2dof.superdex_bot"
    shutil.copy(resolve_asset(EXAMPLE_BOT), dst)
    shutil.copytree(Path(resolve_asset(EXAMPLE_BOT)).parent / "models", folder / "models", dirs_exist_ok=True)
    return dst
