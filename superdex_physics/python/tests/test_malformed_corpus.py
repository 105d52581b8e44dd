"""The corpus of malformed inputs (malformed_corpus/, written by tools/make_malformed_corpus.py):
every file makes its loader raise superdex.physics.Error with a message that names the file and
matches the manifest's expectation (the field and what was expected). Nothing crashes or hangs.

Run one file by hand: `uv run python superdex_physics/python/tests/test_malformed_corpus.py FILE`.
"""

import json
import re
import sys
import warnings
from pathlib import Path

import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from superdex.physics.prefab import PrefabParams, add_to_scene

CORPUS = Path(__file__).parent / "malformed_corpus"
MANIFEST = json.loads((CORPUS / "manifest.json").read_text())


def load_bot(path, scene, entry):
    prefab = sdr.load_bot_prefab_from_file(str(path))
    sdr.create_bot(scene, prefab, sdr.create_context())


def load_urdf(path, scene, entry):
    prefab = sdr.load_bot_prefab_from_urdf_file(str(path))
    sdr.create_bot(scene, prefab, sdr.create_context())


def load_mjcf(path, scene, entry):
    ctx = sdr.create_context()
    for prefab in sdr.load_mjcf_file(path).bots:
        sdr.create_bot(scene, prefab, ctx)


def load_prefab(path, scene, entry):
    params = PrefabParams(name="corpus", apply_scene_settings=entry.get("apply_scene_settings", False))
    add_to_scene(str(path), str(path.parent), scene, params=params)


def load_shape(path, scene, entry):
    shape = sdp.load_shape_from_file(str(path))
    # a shape that loads must also make a body (some defects show only then)
    scene.create_rigid_actor(name="corpus", shape=shape, density=1000.0)


def load_soft_shape(path, scene, entry):
    shape = sdp.load_shape_from_file(str(path))
    scene.create_soft_actor(name="corpus", shape=shape, material=sdp.SoftMaterialParams(density=1000.0))


def replay(path, scene, entry):
    server = sdp.get_debug_server()
    try:
        server.start_replay(str(path))
    finally:
        server.stop()


LOADERS = {"bot": load_bot, "urdf": load_urdf, "mjcf": load_mjcf, "prefab": load_prefab, "h5": load_shape, "h5_soft": load_soft_shape,
           "mesh": load_shape, "recording": replay}


def test_corpus_is_large_and_covers_every_format():
    folders = {entry["file"].split("/")[0] for entry in MANIFEST}
    assert folders == {"bot", "prefab", "urdf", "mjcf", "h5", "obj", "stl", "ply", "dae", "recording"}
    assert len(MANIFEST) >= 100
    on_disk = {p.relative_to(CORPUS).as_posix() for p in CORPUS.rglob("*") if p.is_file() and not p.name.startswith("valid_")}
    assert on_disk - {"manifest.json"} == {entry["file"] for entry in MANIFEST}, "every corpus file is in the manifest"


@pytest.mark.parametrize("entry", MANIFEST, ids=[e["file"] for e in MANIFEST])
def test_malformed_file(scene, sdf_cache, entry):
    assert entry["exception"] == "superdex.physics.Error"
    path = CORPUS / entry["file"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # unknown component types in bot files warn
        with pytest.raises(sdp.Error) as info:
            LOADERS[entry["loader"]](path, scene, entry)
    message = str(info.value)
    assert path.name in message, f"the message names the file: {message}"
    assert re.search(entry["message"], message), f"expected /{entry['message']}/, got: {message}"
    # the engine is still usable: the scene steps
    scene.step(0.01)


@pytest.fixture
def sdf_cache(tmp_path, monkeypatch):
    """Keeps computed distance grids out of the user's cache."""
    monkeypatch.setenv("SUPERDEX_CACHE_DIR", str(tmp_path / "sdf_cache"))


if __name__ == "__main__":
    # one file by hand: prints the message its loader raises
    target = Path(sys.argv[1]).resolve()
    entry = next(e for e in MANIFEST if (CORPUS / e["file"]).resolve() == target)
    sdp.initialize(0)
    s = sdp.create_scene("corpus")
    try:
        LOADERS[entry["loader"]](target, s, entry)
        print("NO ERROR")
    except sdp.Error as err:
        print("Error:", err)
