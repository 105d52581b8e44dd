"""Loading .mochi_prefab files: rigid and articulated actors, nested prefabs with transforms and
scale, names, scene settings, contact filters, the path rules, and all-or-nothing errors."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import cube_obj, node_positions_world
from superdex.physics.paths import get_assets_root
from superdex.physics.prefab import PrefabParams, add_to_scene


def write(path: Path, doc) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(doc))
    return path


def box_entry(name, translation, **extra):
    return {"name": name, "shape": {"box": {"halfExtents": [0.1, 0.1, 0.1]}},
            "worldFromLocal": {"rotation": [0, 0, 0, 1], "translation": translation}, "mass": 1.0, **extra}


def position(actor):
    return np.array(actor.get_root_transform().translation, dtype=float)


def test_rigid_actors_names_and_transforms(scene, tmp_path, monkeypatch):
    monkeypatch.setenv("SUPERDEX_CACHE_DIR", str(tmp_path / "cache"))
    cube_obj(tmp_path / "root" / "meshes" / "cube.obj")
    cube_obj(tmp_path / "root" / "props" / "local_cube.obj")
    prefab = write(tmp_path / "root" / "props" / "table.mochi_prefab", {
        "actors": {"rigid": [
            box_entry("box", [1, 0, 0.1]),
            {"name": "mesh_from_root", "shape": "meshes/cube.obj", "translation": [0, 1, 0.1], "density": 500},
            {"name": "mesh_from_prefab", "shape": "./local_cube.obj", "translation": [0, -1, 0.1], "isStatic": True},
        ], "soft": [], "articulated": []},
    })
    rot = sdp.Quaternion.from_axis_angle([0, 0, 1], math.pi / 2)
    inst = add_to_scene(prefab, tmp_path / "root", scene, PrefabParams(name="table", rotation=rot, translation=[0, 0, 2]))
    assert len(inst.actors) == 3
    names = [a.get_name() for a in inst.actors]
    assert names == ["table/box", "table/mesh_from_root", "table/mesh_from_prefab"]
    # the prefab's frame is turned 90 deg about z and raised 2 m: local (1, 0, 0.1) -> (0, 1, 2.1)
    np.testing.assert_allclose(position(inst.actors[0]), [0, 1, 2.1], atol=1e-6)
    np.testing.assert_allclose(position(inst.actors[1]), [-1, 0, 2.1], atol=1e-6)
    assert inst.actors[1].get_mass() == pytest.approx(500 * 0.2**3, rel=1e-4)
    assert inst.actors[2].get_num_dofs() == 0


def test_nested_prefabs_scale_and_bot(scene, tmp_path):
    write(tmp_path / "inner.mochi_prefab", {"actors": {"rigid": [box_entry("crate", [0.5, 0, 0])]}})
    outer = write(tmp_path / "outer.mochi_prefab", {
        "actors": {"articulated": [{"name": "arm", "bot": "bots/fun/example_bot_2dof/example_bot_2dof.superdex_bot",
                                    "translation": [0, 2, 0]}]},
        "prefabs": [{"name": "pile", "path": "./inner.mochi_prefab", "scale": 2.0, "translation": [0, 0, 1]}],
    })
    inst = add_to_scene(outer, get_assets_root(), scene, PrefabParams(name="world", scale=1.0))
    # a nested prefab's actors come before its parent's own
    names = [a.get_name() for a in inst.actors]
    assert names == ["world/pile/crate", "world/arm"]
    crate, arm = inst.actors
    assert arm.get_num_dofs() == 2
    np.testing.assert_allclose(np.array(arm.get_root_transform().translation), [0, 2, 0], atol=1e-6)
    # nested scale 2: the crate's offset doubles and its box is 0.4 m wide (mass kept: 1 kg)
    np.testing.assert_allclose(position(crate), [1.0, 0, 1.0], atol=1e-6)
    crate.register_query(sdp.QueryType.CONTACT_POINTS)
    assert crate.get_mass() == pytest.approx(1.0)


def test_mass_takes_precedence_over_density(scene, tmp_path):
    """An entry with both a mass and a density gets the mass (SuperDex's RigidActorParams rule)."""
    prefab = write(tmp_path / "p.mochi_prefab", {"actors": {"rigid": [box_entry("both", [0, 0, 0], density=500.0)]}})
    inst = add_to_scene(prefab, tmp_path, scene)
    assert inst.actors[0].get_mass() == pytest.approx(1.0)


def test_scene_settings_and_contact_filter(scene, tmp_path):
    prefab = write(tmp_path / "p.mochi_prefab", {
        "actors": {"rigid": [box_entry("a", [0, 0, 0]), box_entry("b", [0.15, 0, 0])]},
        "contactFilter": {"disabledPairs": [["a", "b"]]},
        "scene": {"gravity": [0, 0, -1.62], "description": "moon"},
    })
    add_to_scene(prefab, tmp_path, scene, PrefabParams(apply_scene_settings=False))
    np.testing.assert_allclose(scene.get_gravity(), [0, 0, -9.81])
    inst = add_to_scene(prefab, tmp_path, scene, PrefabParams(name="second", apply_scene_settings=True))
    np.testing.assert_allclose(scene.get_gravity(), [0, 0, -1.62], rtol=1e-6)
    # the overlapping pair is filtered: no contact between them
    scene.set_gravity([0, 0, 0])
    a = inst.actors[0]
    a.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    scene.step(0.01)
    np.testing.assert_allclose(a.get_contact_force_from_actor_world(inst.actors[1]), 0, atol=1e-9)


@pytest.mark.parametrize("shape, message", [
    ("../outside.obj", r"actors\.rigid\[0\]\.shape: paths containing '\.\.' are not allowed"),
    ("/etc/passwd", r"actors\.rigid\[0\]\.shape: absolute paths are not allowed"),
    ("./missing.obj", r"actors\.rigid\[0\]\.shape: shape file .*missing\.obj' does not exist"),
])
def test_path_rules(scene, tmp_path, shape, message):
    prefab = write(tmp_path / "p.mochi_prefab", {"actors": {"rigid": [{"name": "x", "shape": shape, "mass": 1.0}]}})
    with pytest.raises(sdp.Error, match=message) as info:
        add_to_scene(prefab, tmp_path, scene)
    assert "p.mochi_prefab" in str(info.value)


def test_errors_leave_nothing_behind(scene, tmp_path):
    prefab = write(tmp_path / "p.mochi_prefab", {"actors": {"rigid": [
        box_entry("fine", [0, 0, 0]),
        {"name": "bad", "shape": {"sphere": {"radius": -1}}, "mass": 1.0},
    ]}})
    with pytest.raises(sdp.Error, match=r"actors\.rigid\[1\]\.shape.*sphere radius must be a positive"):
        add_to_scene(prefab, tmp_path, scene)
    assert scene.get_num_actors() == 0, "all or nothing"


def test_other_errors(scene, tmp_path):
    soft = write(tmp_path / "soft.mochi_prefab", {"actors": {"soft": [{"name": "s", "shape": "./x.mochi.h5"}]}})
    with pytest.raises(sdp.Error, match=r"actors\.soft\[0\]\.shape: shape file .*x\.mochi\.h5' does not exist"):
        add_to_scene(soft, tmp_path, scene)
    loop = write(tmp_path / "loop.mochi_prefab", {"prefabs": [{"path": "./loop.mochi_prefab"}]})
    with pytest.raises(sdp.Error, match="nest more than 16 deep"):
        add_to_scene(loop, tmp_path, scene)
    (tmp_path / "broken.mochi_prefab").write_text("{ nope")
    with pytest.raises(sdp.Error, match="broken.mochi_prefab: not valid JSON"):
        add_to_scene(tmp_path / "broken.mochi_prefab", tmp_path, scene)
    with pytest.raises(sdp.Error, match="cannot open the prefab file"):
        add_to_scene(tmp_path / "absent.mochi_prefab", tmp_path, scene)
    nameless = write(tmp_path / "nameless.mochi_prefab", {"actors": {"rigid": [{"shape": {"sphere": {"radius": 1}}}]}})
    with pytest.raises(sdp.Error, match=r"actors\.rigid\[0\]\.name: required"):
        add_to_scene(nameless, tmp_path, scene)
    with pytest.raises(sdp.Error, match="scale must be a positive"):
        add_to_scene(nameless, tmp_path, scene, PrefabParams(scale=0))


def test_duck_lamp_prefab_loads_as_a_pinned_soft_actor(scene):
    """The seed's prop: one soft actor of the committed tet mesh, placed at x = -0.30, its bottom
    pinned by fixedRegion; under gravity its pinned nodes stay put and the rest sags only a little
    (E = 100 kPa), with no contact needed to hold it."""
    from superdex.physics.paths import resolve_asset

    inst = add_to_scene(resolve_asset("prefabs/duck_lamp/duck_lamp_recumbent.mochi_prefab"), get_assets_root(), scene,
                        PrefabParams(name="duck_lamp"))
    assert len(inst.actors) == 1
    duck = inst.actors[0]
    assert duck.get_type() == sdp.ActorType.SOFT and duck.get_name() == "duck_lamp/duck_lamp"
    import h5py

    with h5py.File(resolve_asset("prefabs/duck_lamp/duck_lamp_body.mochi.h5"), "r") as f:
        nodes, tets = f["mesh/coordinates"][()], f["mesh/connectivity"][()]
    a, b, c, d = (nodes[tets[:, k]] for k in range(4))
    volume = np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a).sum() / 6
    duck.register_query_and_compute(sdp.QueryType.NODE_POSITIONS)
    x0 = node_positions_world(duck)
    assert x0.shape == nodes.shape
    np.testing.assert_allclose(x0, nodes + [-0.30, 0, 0], atol=1e-6)
    assert duck.get_mass() == pytest.approx(1100 * volume, rel=1e-5)
    bottom = np.flatnonzero(x0[:, 2] <= 1e-3)
    for _ in range(10):
        scene.step(0.02)
    x = node_positions_world(duck)
    np.testing.assert_allclose(x[bottom], x0[bottom], atol=1e-12)
    sag = np.abs(x - x0).max()
    assert 0 < sag < 0.005
