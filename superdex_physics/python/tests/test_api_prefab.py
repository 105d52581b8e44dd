"""superdex.physics.prefab as objects: SceneParams, the actor prefabs (subclasses of the actor
params), ScenePrefab read from and written to JSON, shallow and full loads, nested prefabs with
their scale and poses, contact filters, AddToSceneResult, and errors naming the field."""

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import cube_obj
from superdex.physics.paths import get_assets_root

prefab = sdp.prefab
BOT = "bots/fun/example_bot_2dof/example_bot_2dof.superdex_bot"


def tet_h5(path: Path):
    """One tetrahedron (0.1 m legs) as a .mochi.h5 tet mesh."""
    import h5py

    path.parent.mkdir(parents=True, exist_ok=True)
    with h5py.File(path, "w") as f:
        f["mesh/coordinates"] = np.array([[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]], dtype=np.float64)
        f["mesh/connectivity"] = np.array([[0, 1, 2, 3]], dtype=np.int32)
    return path


def box(name, translation, **extra):
    return {"name": name, "shape": {"box": {"halfExtents": [0.1, 0.1, 0.1]}}, "translation": translation, **extra}


def position(actor):
    return np.array(actor.get_root_transform().translation, dtype=float)


def rotation_matrix(q):
    x, y, z, w = (float(c) for c in q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def test_module_is_the_native_submodule_and_classes_extend_the_params():
    assert sys.modules["superdex.physics.prefab"] is prefab
    assert issubclass(prefab.RigidActorPrefab, sdp.RigidActorParams)
    assert issubclass(prefab.SoftActorPrefab, sdp.SoftActorParams)
    assert issubclass(prefab.ArticulatedLinkPrefab, sdp.ArticulatedLinkParams)
    assert issubclass(prefab.ArticulatedJointPrefab, sdp.ArticulatedJointParams)
    # inherited keywords first, then the prefab's own
    r = prefab.RigidActorPrefab(name="crate", mass=2.0, is_static=True, shape_file="./crate.obj", scale=[2, 2, 2],
                                translation=[1, 2, 3], comment="a crate")
    assert (r.name, r.mass, r.is_static, r.shape_file, r.comment) == ("crate", 2.0, True, "./crate.obj", "a crate")
    np.testing.assert_allclose(r.scale, [2, 2, 2])
    np.testing.assert_allclose(r.translation, [1, 2, 3])
    np.testing.assert_allclose(r.rotation, [0, 0, 0, 1])
    assert prefab.ActorContactEntry().include_nested_actors


def test_scene_params_defaults_assignment_and_keywords():
    p = prefab.SceneParams()
    assert p.comment is None and p.description == "" and p.gravity is None and p.solver is None
    p.comment, p.description = "c", "d"
    p.gravity = [0, 0, 0]
    assert p.gravity == sdp.Real3()
    p.solver = sdp.SolverParams()
    assert p.solver == sdp.SolverParams()
    k = prefab.SceneParams(gravity=[1, 2, 3], comment="C", solver=sdp.SolverParams(linear_solver=sdp.LinearSolverParams(abs_tol=1e-12)))
    np.testing.assert_allclose(k.gravity, [1, 2, 3])
    assert k.comment == "C" and k.description == ""
    assert k.solver.linear_solver.abs_tol == pytest.approx(1e-12)


def test_scene_settings_apply_only_when_asked(scene):
    p = prefab.load_from_json_string(json.dumps({"actors": {"rigid": [box("a", [0, 0, 0], mass=1.0)]}}), ".")
    solver = sdp.default_scene_solver_params()
    solver.non_linear_solver.max_iter = 7
    p.scene = prefab.SceneParams(gravity=[0, 0, -1.62], solver=solver)
    gravity_before = np.array(scene.get_gravity())
    prefab.add_to_scene(p, scene)
    np.testing.assert_allclose(scene.get_gravity(), gravity_before)
    assert scene.get_solver_params().non_linear_solver.max_iter != 7
    prefab.add_to_scene(p, scene, prefab.PrefabParams(name="again", apply_scene_settings=True))
    np.testing.assert_allclose(scene.get_gravity(), [0, 0, -1.62], rtol=1e-6)
    assert scene.get_solver_params().non_linear_solver.max_iter == 7


DOC = {
    "comment": "a test scene",
    "actors": {
        "rigid": [
            {"name": "crate", "shape": "./crate.obj", "scale": [2, 1, 1], "rotation": [0, 0, 0.7071067811865476, 0.7071067811865476],
             "translation": [1, 2, 3], "mass": 2.5, "layer": "props", "contact": {"coulombFrictionCoefficient": 0.3}},
            box("ball_box", [0, 0, 1], density=500.0, isStatic=True),
        ],
        "soft": [{"name": "jelly", "shape": "./tet.mochi.h5", "translation": [0, 1, 0], "fixedNodes": [0],
                  "material": {"type": "StVK", "youngsModulus": 2e5, "poissonRatio": 0.4, "density": 900.0}}],
        "articulated": [{"name": "arm", "bot": BOT, "translation": [0, 0, 0.5]}],
    },
    "prefabs": [{"name": "inner", "path": "./inner.mochi_prefab", "scale": 2.0, "translation": [3, 0, 0]}],
    "contactFilter": {"layerContactSymmetric": [{"enable": False, "layers": ["props", "floor"]}],
                      "actorContactAsymmetric": [{"enable": False, "actors": ["crate", "arm"], "includeNestedActors": False}]},
    "scene": {"description": "test", "gravity": [0, 0, -9.81]},
}


def test_json_fields_and_round_trip():
    p = prefab.shallow_load_from_json_string(json.dumps(DOC))
    assert p.comment == "a test scene"
    crate, ball = p.actors.rigid
    assert (crate.name, crate.shape_file, crate.mass, crate.layer) == ("crate", "./crate.obj", 2.5, "props")
    np.testing.assert_allclose(crate.scale, [2, 1, 1])
    np.testing.assert_allclose(crate.translation, [1, 2, 3])
    np.testing.assert_allclose(crate.rotation, [0, 0, math.sqrt(0.5), math.sqrt(0.5)], atol=1e-7)
    assert crate.contact.coulomb_friction_coefficient == pytest.approx(0.3)
    assert not crate.shape.is_valid(), "a shallow load loads no shape"
    assert ball.is_static and ball.density == 500.0 and ball.shape_file == ""
    jelly = p.actors.soft[0]
    assert jelly.material.type == sdp.SoftMaterialType.ST_VENANT_KIRCHHOFF
    assert jelly.material.st_venant_kirchhoff.youngs_modulus == pytest.approx(2e5)
    assert list(jelly.fixed_nodes) == [0]
    arm = p.actors.articulated[0]
    assert arm.bot_file == BOT and len(arm.links) == 0, "the bot file is read with the nested prefabs"
    ref = p.prefabs[0]
    assert (ref.name, ref.path, ref.scale) == ("inner", "./inner.mochi_prefab", 2.0)
    assert p.contact_filter.layer_contact_symmetric[0] == prefab.LayerContactEntry(enable=False, layers=["props", "floor"])
    assert not p.contact_filter.actor_contact_asymmetric[0].include_nested_actors
    assert p.contact_filter.actor_contact_symmetric is None
    assert p.scene.description == "test" and p.scene.solver is None

    text = prefab.save_to_json_string(p)
    again = prefab.shallow_load_from_json_string(text)
    assert prefab.save_to_json_string(again) == text
    assert again.actors.rigid[0] == crate and again.actors.soft[0] == jelly
    assert again.actors.articulated[0] == arm and again.contact_filter == p.contact_filter and again.scene == p.scene


def test_save_to_file_and_load_from_file(engine, tmp_path):
    cube_obj(tmp_path / "root" / "meshes" / "cube.obj")
    p = prefab.ScenePrefab(comment="built in code")
    p.actors.rigid = [prefab.RigidActorPrefab(name="cube", shape_file="meshes/cube.obj", translation=[0, 0, 1], density=200.0,
                                              rotation=sdp.Quaternion.from_axis_angle([1, 0, 0], 0.3))]
    p.scene = prefab.SceneParams(gravity=[0, -9.8, 0])
    path = tmp_path / "out" / "deep" / "built.mochi_scene"
    prefab.save_to_json_file(p, path)
    loaded = prefab.load_from_file(path, tmp_path / "root")
    assert loaded.actors.rigid[0].shape.is_valid(), "a full load loads the shapes"
    assert loaded.actors.rigid[0].name == "cube" and loaded.actors.rigid[0].density == 200.0
    np.testing.assert_allclose(loaded.actors.rigid[0].rotation, p.actors.rigid[0].rotation, atol=1e-7)
    assert loaded.scene == p.scene and loaded.comment == "built in code"
    # the reader normalizes quaternions: from then on the text is stable
    text = prefab.save_to_json_string(loaded)
    prefab.save_to_json_file(loaded, path)
    assert prefab.save_to_json_string(prefab.shallow_load_from_file(path)) == text
    assert json.loads(text)["actors"]["rigid"][0]["shape"] == "meshes/cube.obj"


def test_object_and_file_forms_add_the_same_actors(scene, tmp_path):
    cube_obj(tmp_path / "crate.obj")
    tet_h5(tmp_path / "tet.mochi.h5")
    (tmp_path / "inner.mochi_prefab").write_text(json.dumps({"actors": {"rigid": [box("pebble", [0.5, 0, 0], mass=0.1)]}}))
    path = tmp_path / "scene.mochi_scene"
    path.write_text(json.dumps(DOC))
    (tmp_path / "bots").symlink_to(Path(get_assets_root()) / "bots")
    params = prefab.PrefabParams(name="a", translation=[0, 0, 2], rotation=sdp.Quaternion.from_axis_angle([0, 0, 1], 0.4))
    from_file = prefab.add_to_scene(path, tmp_path, scene, params)
    loaded = prefab.load_from_file(path, tmp_path)
    params.name = "b"
    from_object = prefab.add_to_scene(loaded, scene, params)
    assert len(from_file.actors) == len(from_object.actors) == 5
    for x, y in zip(from_file.actors, from_object.actors):
        assert x.get_name()[2:] == y.get_name()[2:] and x.get_name()[:2] == "a/" and y.get_name()[:2] == "b/"
        np.testing.assert_allclose(position(x), position(y), atol=1e-6)
        np.testing.assert_allclose(x.get_root_transform().rotation, y.get_root_transform().rotation, atol=1e-6)
        assert x.get_mass() == pytest.approx(y.get_mass(), rel=1e-6)
    names = [a.get_name()[2:] for a in from_file.actors]
    assert names == ["inner/pebble", "crate", "ball_box", "jelly", "arm"], "nested first, then rigid, soft, articulated"
    # the contact filter: layers named in the prefab, and the crate no longer colliding with the arm
    assert not scene.is_layer_contact_enabled("props", "floor") and not scene.is_layer_contact_enabled("floor", "props")


def test_nested_prefab_poses_compose(scene, tmp_path):
    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "inner.mochi_prefab").write_text(json.dumps({"actors": {"rigid": [
        box("block", [0.5, 0, 0], density=1000.0, rotation=[math.sqrt(0.5), 0, 0, math.sqrt(0.5)])]}}))
    outer = prefab.ScenePrefab()
    R_PN = sdp.Quaternion.from_axis_angle([0, 0, 1], math.pi / 2)
    outer.prefabs = [prefab.PrefabReference(name="n", path="parts/inner.mochi_prefab", scale=2.0, rotation=R_PN, translation=[1, 0, 0])]
    prefab.ensure_fully_loaded(outer, tmp_path)
    R_WP = sdp.Quaternion.from_axis_angle([0, 0, 1], math.pi / 2)
    result = prefab.add_to_scene(outer, scene, prefab.PrefabParams(rotation=R_WP, translation=[0, 0, 1]))
    (block,) = result.actors
    assert block.get_name() == "n/block"
    # by hand: p_W = p_WP + R_WP (p_PN + R_PN (2 * p_NL)) = (0,0,1) + Rz90 ((1,0,0) + (0,1,0)) = (-1, 1, 1)
    np.testing.assert_allclose(position(block), [-1, 1, 1], atol=1e-5)
    R = rotation_matrix(block.get_root_transform().rotation)
    Rz180 = np.diag([-1.0, -1.0, 1.0])
    Rx90 = np.array([[1.0, 0, 0], [0, 0, -1], [0, 1, 0]])
    np.testing.assert_allclose(R, Rz180 @ Rx90, atol=1e-5)
    # the nested scale doubles the box: (0.4 m)^3 of density 1000
    assert block.get_mass() == pytest.approx(1000 * 0.4**3, rel=1e-4)


def test_filter_by_actor_type(scene, tmp_path):
    tet_h5(tmp_path / "tet.mochi.h5")
    doc = {"actors": {"rigid": [box("a", [0, 0, 0], mass=1.0), box("b", [1, 0, 0], mass=1.0)],
                      "soft": [{"name": "s", "shape": "./tet.mochi.h5", "translation": [0, 2, 0]}],
                      "articulated": [{"name": "arm", "bot": BOT, "translation": [0, -2, 0]}]}}
    (tmp_path / "bots").symlink_to(Path(get_assets_root()) / "bots")
    p = prefab.load_from_json_string(json.dumps(doc), tmp_path)
    r = prefab.add_to_scene(prefab=p, scene=scene)
    assert isinstance(r, prefab.AddToSceneResult)
    assert [a.get_name() for a in r.actors] == ["a", "b", "s", "arm"]
    assert [a.get_name() for a in r.filter(sdp.ActorType.RIGID)] == ["a", "b"]
    assert [a.get_name() for a in r.filter(sdp.ActorType.SOFT)] == ["s"]
    (arm,) = r.filter(sdp.ActorType.ARTICULATED)
    assert arm.get_name() == "arm" and arm.get_num_dofs() == 2
    assert len(r.filter(sdp.ActorType.RIGID)) + 2 == len(r.actors)


def test_procedural_contact_filter_sets_layers(scene):
    p = prefab.load_from_json_string(json.dumps({"actors": {"rigid": [
        box("Floor", [0, 0, 0], layer="LayerA", isStatic=True), box("CubeA", [0, 0, 1], layer="LayerB", mass=1.0),
        box("CubeB", [0, 0, 2], layer="LayerC", mass=1.0), box("CubeC", [0, 0, 3], layer="LayerD", mass=1.0)]}}), ".")
    assert p.contact_filter is None
    f = prefab.ContactFilter()
    f.actor_contact_symmetric = [prefab.ActorContactEntry(enable=False, actors=["CubeA", "CubeB"], include_nested_actors=False)]
    f.actor_contact_asymmetric = [prefab.ActorContactEntry(enable=False, actors=["CubeC", "Floor"])]
    f.layer_contact_symmetric = [prefab.LayerContactEntry(enable=False, layers=["LayerB", "LayerC"])]
    f.layer_contact_asymmetric = [prefab.LayerContactEntry(enable=False, layers=["LayerD", "LayerA"])]
    p.contact_filter = f
    assert list(p.contact_filter.actor_contact_symmetric[0].actors) == ["CubeA", "CubeB"]
    prefab.add_to_scene(p, scene)
    assert not scene.is_layer_contact_enabled("LayerB", "LayerC") and not scene.is_layer_contact_enabled("LayerC", "LayerB")
    assert not scene.is_layer_contact_enabled("LayerD", "LayerA")
    assert scene.is_layer_contact_enabled("LayerA", "LayerD") and scene.is_layer_contact_enabled("LayerA", "LayerB")


def test_errors_name_the_field_and_leave_nothing(scene):
    p = prefab.load_from_json_string(json.dumps({"actors": {"rigid": [box("a", [0, 0, 0], mass=1.0), box("b", [1, 0, 0], mass=1.0)]}}), ".")
    gravity = np.array(scene.get_gravity())
    p.actors.rigid[1].mass = -1.0
    p.scene = prefab.SceneParams(gravity=[0, 0, 0])
    with pytest.raises(sdp.Error, match=r"actors\.rigid\[1\]\.mass: must be a positive finite number, got -1"):
        prefab.add_to_scene(p, scene, prefab.PrefabParams(apply_scene_settings=True))
    assert scene.get_num_actors() == 0, "all or nothing"
    np.testing.assert_allclose(scene.get_gravity(), gravity)
    p.actors.rigid[1].mass = 1.0
    p.actors.rigid[0].rotation = [0, 0, 0, 0]
    with pytest.raises(sdp.Error, match=r"actors\.rigid\[0\]\.rotation: must be a finite, non-zero quaternion"):
        prefab.add_to_scene(p, scene)
    p.actors.rigid[0].rotation = [0, 0, 0, 1]
    with pytest.raises(sdp.Error, match=r"params\.scale"):
        prefab.add_to_scene(p, scene, prefab.PrefabParams(scale=2.0))
    p.actors.rigid.append(prefab.RigidActorPrefab(name="c", shape_file="missing.obj"))
    with pytest.raises(sdp.Error, match=r"actors\.rigid\[2\]\.shape: not loaded"):
        prefab.add_to_scene(p, scene)
    with pytest.raises(sdp.Error, match=r"actors\.rigid\[2\]\.shape: shape file '.*missing\.obj' does not exist"):
        prefab.load_shapes(p, "/nowhere")
    for key in ("constraints", "controllers"):
        with pytest.raises(sdp.Error, match=f"{key}: {key} are not supported yet"):
            prefab.shallow_load_from_json_string(json.dumps({key: [{"actor": "a"}]}))


def test_shallow_load_then_ensure_fully_loaded(scene, tmp_path):
    cube_obj(tmp_path / "cube.obj")
    (tmp_path / "child.mochi_scene").write_text(json.dumps({"actors": {"rigid": [{"name": "child_cube", "shape": "./cube.obj", "mass": 1.0}]}}))
    (tmp_path / "parent.mochi_scene").write_text(json.dumps({
        "actors": {"rigid": [{"name": "parent_cube", "shape": "cube.obj", "mass": 1.0}]},
        "prefabs": [{"name": "child", "path": "./child.mochi_scene"}]}))
    shapes = sdp.get_num_shapes()
    p = prefab.shallow_load_from_file(tmp_path / "parent.mochi_scene")
    assert len(p.actors.rigid) == 1 and len(p.prefabs) == 1
    assert not p.actors.rigid[0].shape.is_valid() and sdp.get_num_shapes() == shapes
    with pytest.raises(sdp.Error, match=r"prefabs\[0\]: not loaded"):
        prefab.add_to_scene(p, scene)
    prefab.ensure_fully_loaded(p, tmp_path)
    assert p.actors.rigid[0].shape.is_valid() and sdp.get_num_shapes() == shapes + 2
    r = prefab.add_to_scene(p, scene)
    assert [a.get_name() for a in r.actors] == ["child/child_cube", "parent_cube"]
    prefab.ensure_fully_loaded(p, tmp_path)
    assert sdp.get_num_shapes() == shapes + 2, "nothing loaded twice"


def test_get_prefab_full_path():
    assert prefab.get_prefab_full_path("./a/b.obj", "/root", "/data/scenes/s.mochi_scene") == "/data/scenes/a/b.obj"
    assert prefab.get_prefab_full_path("a/b.obj", "/root", "/data/scenes/s.mochi_scene") == "/root/a/b.obj"
    assert prefab.get_prefab_full_path("/abs/b.obj", "/root", "/data/scenes/s.mochi_scene") == "/abs/b.obj"
    assert prefab.get_prefab_full_path("./b.obj", "/root", "") == "/root/b.obj"


def test_contact_entries_enable_by_default(scene):
    """An entry without `enable` (object or JSON) enables contact, as SuperDex's do: only
    `enable: false` disables it."""
    assert prefab.ActorContactEntry().enable and prefab.LayerContactEntry().enable
    assert prefab.ActorContactEntry().include_nested_actors
    p = prefab.load_from_json_string(
        '{"actors": {"rigid": []}, "contactFilter": {"layerContactSymmetric": [{"layers": ["a", "b"]}], '
        '"layerContactAsymmetric": [{"enable": false, "layers": ["c", "d"]}]}}', ".")
    assert p.contact_filter.layer_contact_symmetric[0].enable
    assert not p.contact_filter.layer_contact_asymmetric[0].enable
    prefab.add_to_scene(p, scene)
    assert scene.is_layer_contact_enabled("a", "b") and scene.is_layer_contact_enabled("b", "a")
    assert not scene.is_layer_contact_enabled("c", "d") and scene.is_layer_contact_enabled("d", "c")


def test_shapes_load_from_every_format_load_shape_from_file_reads(scene):
    # model files (.mochi.json) for a rigid surface and a soft tetrahedral body, from the assets
    doc = {"actors": {"rigid": [{"name": "ball", "shape": "sphere/icosphere_3subdiv.1.mochi.json", "density": 1000.0,
                                 "scale": [0.1, 0.1, 0.1], "translation": [0, 0, 1]}],
                      "soft": [{"name": "block", "shape": "cube/cube_mesh.mochi.json", "translation": [1, 0, 1]}]}}
    p = prefab.load_from_json_string(json.dumps(doc), get_assets_root())
    r = prefab.add_to_scene(prefab=p, scene=scene)
    (ball,) = r.filter(sdp.ActorType.RIGID)
    (block,) = r.filter(sdp.ActorType.SOFT)
    # an icosphere of radius 0.1 m: a little under the sphere's volume, 4/3 pi r^3
    assert ball.get_mass() == pytest.approx(1000 * 4 / 3 * np.pi * 0.1**3, rel=0.02)
    assert block.get_mesh().nodes_per_element == 4 and block.get_num_dofs() == 81
    # a surface mesh cannot be a soft body: the error names the field and the file
    bad = {"actors": {"soft": [{"name": "s", "shape": "sphere/icosphere_3subdiv.1.mochi.json"}]}}
    with pytest.raises(sdp.Error, match=r"actors\.soft\[0\]\.shape: .*icosphere_3subdiv\.1\.mochi\.json' has no tetrahedral mesh"):
        prefab.add_to_scene(prefab=prefab.load_from_json_string(json.dumps(bad), get_assets_root()), scene=scene)
