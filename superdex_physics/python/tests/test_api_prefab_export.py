"""prefab.export_scene / export_scene_excluding / export_actor: a scene written as a prefab
folder (<name>/<name>.mochi_scene and generated_assets/*.mochi.h5) and added to a fresh scene
must give back the same actors (names made unique, masses, inertias, poses, shapes, contact
params, joint structure) and, created in the same order, the same motion. Also: the prefab
writer saves every field its reader reads (solver settings, link shape poses, named link
layers), so that load -> save -> load is lossless."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import contact, cube_obj, joint, link, soft_material, transform
from superdex.physics.paths import get_assets_root

prefab = sdp.prefab
BOT = "bots/fun/example_bot_2dof/example_bot_2dof.superdex_bot"
DT = 0.01


def tet_cube(h=0.05):
    """A cube of half extent h (m) centred at the origin: 8 corners, 6 positively oriented
    tetrahedra around the diagonal 0 -> 7."""
    nodes = np.array([[x, y, z] for z in (-h, h) for y in (-h, h) for x in (-h, h)])
    tets = []
    for a, b in ((1, 3), (1, 5), (2, 3), (2, 6), (4, 5), (4, 6)):
        t = [0, a, b, 7]
        p = nodes[t]
        if np.linalg.det(np.array([p[1] - p[0], p[2] - p[0], p[3] - p[0]])) < 0:
            t[1], t[2] = t[2], t[1]
        tets.append(t)
    return nodes, np.array(tets, dtype=np.int64)


def quat_z(angle):
    return sdp.Quaternion(0, 0, math.sin(angle / 2), math.cos(angle / 2))


def build_mixed_scene(scene, tmp_path):
    """Rigid actors (two boxes named "box", a mesh cube, a static plane), a soft tet cube and two
    articulations (a 2-link arm from params with capsule links, the example bot from its file),
    in the order a prefab creates them (rigid, soft, articulated)."""
    scene.create_rigid_actor(name="box", shape=sdp.create_box_shape([0.1, 0.1, 0.1]), density=500.0, layer="crates",
                             contact=contact(0.8), world_from_local=transform([0, 0, 0.6], quat_z(0.5)))
    scene.create_rigid_actor(name="box", shape=sdp.create_box_shape([0.05, 0.1, 0.15]), mass=2.0,
                             world_from_local=transform([1, 0, 0.4]))
    mesh = sdp.load_shape_from_file(str(cube_obj(tmp_path / "cube.obj", 0.08)))
    scene.create_rigid_actor(name="mesh", shape=mesh, density=800.0, world_from_local=transform([-1, 0, 0.3]))
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0.0), is_static=True)
    nodes, tets = tet_cube()
    scene.create_soft_actor(name="jelly", shape=sdp.create_tet_mesh_shape(nodes, tets),
                            material=soft_material("neo_hookean", youngs_modulus=2e5, poisson_ratio=0.3, density=500.0,
                                                   mass_damping=0.5),
                            world_from_local=transform([0, 1, 0.3]), contact=contact(0.6))
    capsule = sdp.create_capsule_shape(0.03, 0.2)
    links = [
        link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
        link("l1", parent=0, shape=capsule, density=700.0, contact=contact(0.9)),
        link("l2", parent=1, mass=0.5, center_of_mass=[0, 0.05, 0.1], moment_of_inertia=[0.002, 0, 0, 0.002, 0, 0.0005],
             shape=capsule, parent_joint_from_link=transform([0, 0, 0.25])),
    ]
    joints = [
        joint("weld", "hard", at=[2, 0, 0.8]),
        joint("shoulder", "revolute", axis=[0, 1, 0], min_limit=[0, -1, 0], max_limit=[0, 1.5, 0], inertia=0.01,
              friction=sdp.ArticulatedJointFrictionParams(viscous=0.05, coulomb=0.01), limit_stiffness=500.0, limit_damping=2.0),
        joint("elbow", "revolute", at=[0, 0, 0.3], axis=[1, 0, 0]),
    ]
    scene.create_articulated_actor(name="arm", links=links, joints=joints, world_from_root=transform([0, 0, 0.1], quat_z(0.3)))
    bot = json.dumps({"actors": {"articulated": [{"name": "bot", "bot": BOT, "translation": [0, -2, 0]}]}})
    prefab.add_to_scene(prefab.load_from_json_string(bot, str(get_assets_root())), scene)


def links(actor):
    """The link actors of an articulated actor, in link order."""
    return [actor.get_scene().get_actor(h) for h in actor.get_nested_link_actors()]


def actors_by_name(scene):
    """Top-level actors (not links) by name."""
    out = {}
    scene.for_each_actor(lambda a: out.setdefault(a.get_name(), a) if not a.is_nested_link_actor() else None)
    return out


def export_and_reload(scene, tmp_path, name="mixed", engine_scene_name="reloaded", **kwargs):
    prefab.export_scene(scene, name, str(tmp_path / "out"))
    path = tmp_path / "out" / name / f"{name}.mochi_scene"
    assert path.is_file()
    again = sdp.create_scene(engine_scene_name)
    again.set_gravity(scene.get_gravity())
    prefab.add_to_scene(prefab.load_from_file(str(path), str(tmp_path)), again, prefab.PrefabParams(**kwargs))
    return again, json.loads(path.read_text())


def pose(actor):
    X = actor.get_root_transform()
    return np.array(X.translation, dtype=float), np.array(X.rotation, dtype=float)


def assert_same_pose(a, b, tol=1e-6):
    pa, qa = pose(a)
    pb, qb = pose(b)
    np.testing.assert_allclose(pb, pa, atol=tol)
    assert abs(abs(float(np.dot(qa, qb))) - 1) < tol, (qa, qb)


def aabb(actor):
    box = actor.get_aabb_world()
    return np.concatenate([np.array(box.min, dtype=float), np.array(box.max, dtype=float)])


def test_round_trip_of_a_mixed_scene_gives_the_same_actors(scene, tmp_path):
    build_mixed_scene(scene, tmp_path)
    again, doc = export_and_reload(scene, tmp_path)
    before, after = actors_by_name(scene), actors_by_name(again)
    # the second "box" is "box1" in the export; the others keep their names
    assert sorted(after) == sorted(["box", "box1", "mesh", "ground", "jelly", "arm", "bot"])
    assert [r["name"] for r in doc["actors"]["rigid"]] == ["box", "box1", "mesh", "ground"]
    boxes = []
    scene.for_each_actor(lambda a: boxes.append(a) if a.get_name() == "box" else None)
    before["box1"] = boxes[1]
    pairs = [(before[n], after[n]) for n in after]
    for a, b in pairs:
        assert b.get_type() == a.get_type()
        assert b.is_static() == a.is_static()
        assert b.get_mass() == pytest.approx(a.get_mass(), rel=1e-6)
        assert_same_pose(a, b)
        np.testing.assert_allclose(aabb(b), aabb(a), atol=1e-6)
        assert b.get_contact_params() == a.get_contact_params()
        assert b.get_contact_layer() == a.get_contact_layer()
    # independent facts: the first box's mass from its density and volume, the second's as given
    assert after["box"].get_mass() == pytest.approx(500.0 * 0.2 ** 3, rel=1e-6)
    assert after["box1"].get_mass() == pytest.approx(2.0, rel=1e-6)
    assert after["mesh"].get_mass() == pytest.approx(800.0 * 0.16 ** 3, rel=1e-5)
    assert after["box"].get_contact_layer() == "crates"
    assert after["box"].get_contact_params().coulomb_friction_coefficient == pytest.approx(0.8)
    for n in ("box", "box1", "mesh"):
        np.testing.assert_allclose(after[n].get_rigid_moment_of_inertia_local(), before[n].get_rigid_moment_of_inertia_local(),
                                   rtol=1e-6, atol=1e-12)
    h = 0.1
    np.testing.assert_allclose(after["box"].get_rigid_moment_of_inertia_local(), [4.0 * (2 * h) ** 2 / 6, 0, 0, 4.0 * (2 * h) ** 2 / 6, 0,
                                                                                  4.0 * (2 * h) ** 2 / 6], rtol=1e-5, atol=1e-9)
    # meshes: the same vertex counts (the mesh cube's 8 corners, the soft cube's 8 nodes)
    assert after["mesh"].get_mesh().get_num_nodes() == before["mesh"].get_mesh().get_num_nodes() == 8
    assert after["jelly"].get_mesh().get_num_nodes() == before["jelly"].get_mesh().get_num_nodes() == 8
    assert after["jelly"].get_mass() == pytest.approx(500.0 * 0.1 ** 3, rel=1e-5)
    assert after["jelly"].get_soft_material_params() == before["jelly"].get_soft_material_params()
    # articulations: structure, limits, joint friction and armature, link masses and poses
    for n in ("arm", "bot"):
        a, b = before[n], after[n]
        ia, ib = a.get_articulated_shape_info(), b.get_articulated_shape_info()
        assert list(ib.link_names) == list(ia.link_names) and list(ib.joint_names) == list(ia.joint_names)
        assert list(ib.parents) == list(ia.parents) and list(ib.joint_types) == list(ia.joint_types)
        np.testing.assert_allclose(np.array(ib.joint_axes, dtype=float), np.array(ia.joint_axes, dtype=float), atol=1e-7)
        for field in ("joint_min_limits", "joint_max_limits", "parent_link_from_joint", "joint_from_child_link"):
            got, want = getattr(ib, field), getattr(ia, field)
            if field.startswith("joint_m"):
                np.testing.assert_allclose(np.array(got, dtype=float), np.array(want, dtype=float), atol=1e-6)
            else:
                for x, y in zip(got, want):
                    np.testing.assert_allclose(np.array(x.translation, dtype=float), np.array(y.translation, dtype=float), atol=1e-6)
        np.testing.assert_allclose(b.get_articulated_joint_inertia_params(), a.get_articulated_joint_inertia_params(), rtol=1e-6)
        np.testing.assert_allclose([(f.viscous, f.coulomb) for f in b.get_articulated_joint_friction_params()],
                                   [(f.viscous, f.coulomb) for f in a.get_articulated_joint_friction_params()], rtol=1e-6)
        np.testing.assert_allclose(b.get_articulated_pose(), a.get_articulated_pose(), atol=1e-7)
        for la, lb in zip(links(a), links(b)):
            assert lb.get_name().split("/")[-1] == la.get_name().split("/")[-1]
            assert lb.get_mass() == pytest.approx(la.get_mass(), rel=1e-6)
            assert_same_pose(la, lb)
            np.testing.assert_allclose(aabb(lb), aabb(la), atol=1e-6)
            assert lb.get_contact_params() == la.get_contact_params()
    # the bot starts in its default pose, which the export keeps
    np.testing.assert_allclose(after["bot"].get_articulated_pose(), [0.411, -2.018], atol=1e-6)
    arm_links = links(after["arm"])
    assert arm_links[1].get_mass() == pytest.approx(700.0 * math.pi * 0.03 ** 2 * (0.4 + 4 / 3 * 0.03), rel=1e-5)
    assert arm_links[1].get_contact_params().coulomb_friction_coefficient == pytest.approx(0.9)
    limit = doc["actors"]["articulated"][0]["joints"][1]
    assert (limit["limitStiffness"], limit["limitDamping"]) == (500.0, 2.0)


def test_stepping_both_scenes_gives_the_same_motion(scene, tmp_path):
    build_mixed_scene(scene, tmp_path)
    again, _ = export_and_reload(scene, tmp_path)
    before, after = actors_by_name(scene), actors_by_name(again)
    boxes = []
    scene.for_each_actor(lambda a: boxes.append(a) if a.get_name() == "box" else None)
    before["box1"] = boxes[1]
    # something moves: the boxes fall onto the plane, the arm swings, the jelly drops
    start = {n: pose(a)[0] for n, a in before.items()}
    for _ in range(100):
        scene.step(DT)
        again.step(DT)
    assert np.linalg.norm(pose(before["box"])[0] - start["box"]) > 0.1
    assert np.linalg.norm(pose(before["jelly"])[0] - start["jelly"]) > 0.05
    assert pose(before["box"])[0][2] == pytest.approx(0.1, abs=0.01), "the box rests on the plane"
    for n, a in before.items():
        b = after[n]
        assert_same_pose(a, b)
        np.testing.assert_allclose(aabb(b), aabb(a), atol=1e-6)
        if a.get_type() == sdp.ActorType.ARTICULATED:
            np.testing.assert_allclose(b.get_articulated_pose(), a.get_articulated_pose(), atol=1e-6)
            for la, lb in zip(links(a), links(b)):
                assert_same_pose(la, lb)
    assert np.abs(before["arm"].get_articulated_pose()).max() > 0.01, "the arm swung"


def test_generated_assets_exist_and_are_referenced_relatively(scene, tmp_path):
    build_mixed_scene(scene, tmp_path)
    prefab.export_scene(scene, "mixed", str(tmp_path / "out"))
    folder = tmp_path / "out" / "mixed"
    doc = json.loads((folder / "mixed.mochi_scene").read_text())
    rigid = {r["name"]: r for r in doc["actors"]["rigid"]}
    # primitives inline; meshes as files in generated_assets, named relative to the prefab
    assert list(rigid["box"]["shape"]) == ["box"]
    assert rigid["box"]["shape"]["box"]["halfExtents"] == pytest.approx([0.1, 0.1, 0.1])
    assert "plane" in rigid["ground"]["shape"] and rigid["ground"]["isStatic"] is True
    mesh_file = rigid["mesh"]["shape"]
    soft_file = doc["actors"]["soft"][0]["shape"]
    for f in (mesh_file, soft_file):
        assert f.startswith("./generated_assets/") and f.endswith(".mochi.h5")
        assert (folder / f).is_file()
    assert sorted(p.name for p in (folder / "generated_assets").iterdir()) == sorted(Path(f).name for f in (mesh_file, soft_file))
    # the files are models in their own right: a triangle cube and the tet cube
    assert sdp.model.load_from_file(str(folder / mesh_file)).mesh.get_num_nodes() == 8
    tet = sdp.model.load_from_file(str(folder / soft_file)).mesh
    assert tet.nodes_per_element == 4 and tet.get_num_nodes() == 8
    # the folder moved elsewhere still loads: nothing names an absolute path
    moved = tmp_path / "elsewhere" / "mixed"
    moved.parent.mkdir()
    folder.rename(moved)
    fresh = sdp.create_scene("moved")
    made = prefab.add_to_scene(str(moved / "mixed.mochi_scene"), str(tmp_path), fresh)
    assert len(made.actors) == 7
    assert str(tmp_path) not in (moved / "mixed.mochi_scene").read_text(), "no absolute path"


def test_names_are_made_unique_in_creation_order(scene, tmp_path):
    shape = sdp.create_sphere_shape([0, 0, 0], 0.05)
    for i, name in enumerate(["box", "box1", "box", "box", ""]):
        scene.create_rigid_actor(name=name, shape=shape, mass=1.0, world_from_local=transform([i, 0, 0]))
    _, doc = export_and_reload(scene, tmp_path, "names")
    names = [r["name"] for r in doc["actors"]["rigid"]]
    assert names == ["box", "box1", "box2", "box3", "rigid"]
    xs = [r["translation"][0] for r in doc["actors"]["rigid"]]
    assert xs == [0, 1, 2, 3, 4], "in creation order"


def contact_scene(scene):
    """Boxes a, b, c and the arm, with actor and layer contact rules."""
    shape = sdp.create_box_shape([0.1, 0.1, 0.1])
    a = scene.create_rigid_actor(name="a", shape=shape, mass=1.0, layer="L1", world_from_local=transform([0, 0, 0.5]))
    b = scene.create_rigid_actor(name="b", shape=shape, mass=1.0, layer="L2", world_from_local=transform([0, 0, 0.1]))
    c = scene.create_rigid_actor(name="c", shape=shape, mass=1.0, layer="L3", world_from_local=transform([1, 0, 0.1]))
    arm = scene.create_articulated_actor(name="arm", links=[link("base", shape=shape, mass=1.0)], joints=[joint("weld", "hard", at=[3, 0, 1])])
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0.0), is_static=True)
    scene.enable_actor_contact_symmetric(a, b, False, sdp.IncludeNestedActors.NO)
    scene.enable_actor_contact_asymmetric(b, c, False, sdp.IncludeNestedActors.NO)
    scene.enable_actor_contact_symmetric(c, arm, False, sdp.IncludeNestedActors.YES)
    scene.enable_layer_contact_symmetric("L1", "L3", False)
    scene.enable_layer_contact_asymmetric("L2", "L3", False)
    return a, b, c, arm


def test_contact_rules_are_exported_and_applied(scene, tmp_path):
    contact_scene(scene)
    again, doc = export_and_reload(scene, tmp_path, "contacts")
    f = doc["contactFilter"]
    assert {"enable": False, "actors": ["a", "b"], "includeNestedActors": False} in f["actorContactSymmetric"]
    assert {"enable": False, "actors": ["c", "arm"], "includeNestedActors": True} in f["actorContactSymmetric"]
    assert f["actorContactAsymmetric"] == [{"enable": False, "actors": ["b", "c"], "includeNestedActors": False}]
    assert f["layerContactSymmetric"] == [{"enable": False, "layers": ["L1", "L3"]}]
    assert f["layerContactAsymmetric"] == [{"enable": False, "layers": ["L2", "L3"]}]
    for x, y in [("L1", "L3"), ("L3", "L1"), ("L2", "L3"), ("L3", "L2"), ("L1", "L2")]:
        assert again.is_layer_contact_enabled(x, y) == scene.is_layer_contact_enabled(x, y), (x, y)
    # box a falls through box b (their contact is off) in both scenes, and lands on the ground
    for s in (scene, again):
        for _ in range(60):
            s.step(DT)
        a = actors_by_name(s)["a"]
        assert pose(a)[0][2] < 0.15, "a fell through b"


def test_excluding_actors_drops_them_and_their_contact_entries(scene, tmp_path):
    a, b, c, arm = contact_scene(scene)
    prefab.export_scene_excluding(scene, "some", str(tmp_path / "out"), [b, arm.get_handle()])
    doc = json.loads((tmp_path / "out" / "some" / "some.mochi_scene").read_text())
    assert [r["name"] for r in doc["actors"]["rigid"]] == ["a", "c", "ground"]
    assert doc["actors"]["articulated"] == []
    f = doc["contactFilter"]
    assert "actorContactSymmetric" not in f and "actorContactAsymmetric" not in f, "the entries naming b or arm are dropped"
    assert f["layerContactSymmetric"] == [{"enable": False, "layers": ["L1", "L3"]}]
    again = sdp.create_scene("some")
    made = prefab.add_to_scene(str(tmp_path / "out" / "some" / "some.mochi_scene"), str(tmp_path), again)
    assert sorted(x.get_name() for x in made.actors) == ["a", "c", "ground"]
    # an empty list exports everything
    prefab.export_scene_excluding(scene, "all", str(tmp_path / "out"), [])
    every = json.loads((tmp_path / "out" / "all" / "all.mochi_scene").read_text())
    assert len(every["actors"]["rigid"]) == 4 and len(every["actors"]["articulated"]) == 1
    with pytest.raises(sdp.Error, match=r"exclude_actors\[0\].*link.*exclude the articulation"):
        prefab.export_scene_excluding(scene, "x", str(tmp_path / "out"), [links(arm)[0]])
    with pytest.raises(sdp.Error, match=r"exclude_actors\[1\]"):
        prefab.export_scene_excluding(scene, "x", str(tmp_path / "out"), [a, "not an actor"])


def test_export_actor_of_each_kind(scene, tmp_path):
    box = scene.create_rigid_actor(name="box", shape=sdp.create_box_shape([0.1, 0.2, 0.3]), mass=3.0,
                                   world_from_local=transform([1, 2, 3], quat_z(0.7)))
    nodes, tets = tet_cube()
    jelly = scene.create_soft_actor(name="jelly", shape=sdp.create_tet_mesh_shape(nodes, tets),
                                    material=soft_material("stvk", youngs_modulus=3e5, poisson_ratio=0.25, density=900.0),
                                    world_from_local=transform([0, 0, 1]))
    arm = scene.create_articulated_actor(
        name="arm", links=[link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
                           link("l1", parent=0, shape=sdp.create_capsule_shape(0.02, 0.1), density=1000.0)],
        joints=[joint("weld", "hard", at=[0, 0, 1]), joint("j", "revolute", axis=[0, 1, 0])])
    for actor, kind in [(box, "rigid"), (jelly, "soft"), (arm, "articulated")]:
        prefab.export_actor(actor, "thing_" + kind, str(tmp_path))
        path = tmp_path / ("thing_" + kind) / ("thing_" + kind + ".mochi_scene")
        doc = json.loads(path.read_text())
        assert [len(doc["actors"][k]) for k in ("rigid", "soft", "articulated")] == [kind == "rigid", kind == "soft", kind == "articulated"]
        assert doc["actors"][kind][0]["name"] == "thing_" + kind, "export_name names the actor"
        assert "contactFilter" not in doc and "scene" not in doc
        fresh = sdp.create_scene("fresh_" + kind)
        made = prefab.add_to_scene(str(path), str(tmp_path), fresh).actors
        assert len(made) == 1 and made[0].get_name() == "thing_" + kind
        assert made[0].get_mass() == pytest.approx(actor.get_mass(), rel=1e-6)
        assert_same_pose(actor, made[0])
    assert (tmp_path / "thing_soft" / "generated_assets" / "thing_soft.mochi.h5").is_file()
    with pytest.raises(sdp.Error, match=r"export_actor: actor: .*link.*pass the articulation"):
        prefab.export_actor(links(arm)[1], "link", str(tmp_path))


def test_a_box_collider_fitted_around_a_link_mesh_is_exported_as_that_box(scene, tmp_path):
    # an octahedron (vertices 0.1 m out along each axis) carried by a link as a BOX collider
    nodes = np.array([[0.1, 0, 0], [-0.1, 0, 0], [0, 0.1, 0], [0, -0.1, 0], [0, 0, 0.1], [0, 0, -0.1]])
    faces = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
    octahedron = sdp.create_tri_mesh_shape(nodes, faces)
    arm = scene.create_articulated_actor(
        name="arm", links=[link("base", shape=octahedron, collider_type=sdp.ColliderType.BOX, mass=1.0,
                                moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01])],
        joints=[joint("weld", "hard", at=[0, 0, 1])])
    again, doc = export_and_reload(scene, tmp_path, "fitted")
    assert list(doc["actors"]["articulated"][0]["links"][0]["shape"]) == ["box"]
    # a point inside the box but outside the octahedron is inside both the original and the export
    def distance(actor, point):
        out = np.zeros(1, dtype=np.float64 if sdp.uses_double_precision() else np.float32)
        actor.get_points_distance_to_surface(np.array([point], dtype=out.dtype), out)
        return float(out[0])

    corner = [0.09, 0.09, 1.09]
    before, after = links(arm)[0], links(actors_by_name(again)["arm"])[0]
    assert distance(before, corner) < 0
    assert distance(after, corner) == pytest.approx(distance(before, corner), abs=1e-6)


def test_exported_state_rigid_pose_and_velocity_kept_joint_pose_not(scene, tmp_path):
    ball = scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1), mass=1.0,
                                    world_from_local=transform([0, 0, 5]))
    ball.set_velocity([1, 0, 0], [0, 0, 2])
    scene.create_rigid_actor(name="balloon", shape=sdp.create_sphere_shape([0, 0, 0], 0.1), mass=1.0, has_gravity=False,
                             world_from_local=transform([0, -3, 2]))
    arm = scene.create_articulated_actor(
        name="arm", links=[link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
                           link("l1", parent=0, mass=1.0, center_of_mass=[0.5, 0, 0], moment_of_inertia=[1e-3, 0, 0, 1e-3, 0, 1e-3])],
        joints=[joint("weld", "hard", at=[0, 3, 1]), joint("j", "revolute", axis=[0, 1, 0])])
    for _ in range(20):
        scene.step(DT)
    assert abs(arm.get_articulated_pose()[0]) > 0.01
    again, _ = export_and_reload(scene, tmp_path, "state")
    moved = actors_by_name(again)
    assert_same_pose(ball, moved["ball"])
    np.testing.assert_allclose(moved["ball"].get_linear_velocity(), ball.get_linear_velocity(), rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(moved["ball"].get_angular_velocity(), ball.get_angular_velocity(), rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(moved["arm"].get_articulated_pose(), [0.0])
    np.testing.assert_allclose(moved["arm"].get_articulated_joint_velocities(), [0.0])
    assert_same_pose(arm, moved["arm"])  # the welded base stays where it is
    assert pose(moved["balloon"])[0][2] == 2.0, "no gravity on it"
    # the exported ball flies on as the original does; the balloon still floats
    for _ in range(10):
        scene.step(DT)
        again.step(DT)
    assert_same_pose(ball, moved["ball"])
    assert pose(moved["balloon"])[0][2] == pytest.approx(2.0, abs=1e-9)


def test_scene_settings_are_exported(scene, tmp_path):
    scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1), mass=1.0)
    solver = scene.get_solver_params()
    solver.non_linear_solver.max_iter = 17
    solver.non_linear_solver.abs_tol = 1e-7
    solver.implicit_step.contact_margin = 0.02
    solver.implicit_step.dense_island_max_dofs = 30
    solver.linear_solver.solver_type = sdp.LinearSolverType.LDLT
    scene.set_solver_params(solver)
    scene.set_gravity([0, 0, -1.62])
    again, doc = export_and_reload(scene, tmp_path, "settings", apply_scene_settings=True)
    assert doc["scene"]["solver"]["maxNewtonIterations"] == 17
    assert doc["scene"]["solver"]["linearSolver"] == {"solverType": "LDLT"}
    assert again.get_solver_params() == scene.get_solver_params()
    np.testing.assert_allclose(again.get_gravity(), [0, 0, -1.62], rtol=1e-6)


def test_errors_name_the_argument(scene, tmp_path):
    box = scene.create_rigid_actor(name="box", shape=sdp.create_box_shape([0.1, 0.1, 0.1]), mass=1.0)
    with pytest.raises(sdp.Error, match="export_scene: scene: expected a Scene, got None"):
        prefab.export_scene(None, "x", str(tmp_path))
    with pytest.raises(sdp.Error, match="export_scene_excluding: scene"):
        prefab.export_scene_excluding(None, "x", str(tmp_path), [])
    with pytest.raises(sdp.Error, match="export_actor: actor: expected an Actor, got None"):
        prefab.export_actor(None, "x", str(tmp_path))
    with pytest.raises(sdp.Error, match="export_scene: export_name: must not be empty"):
        prefab.export_scene(scene, "", str(tmp_path))
    with pytest.raises(sdp.Error, match="export_actor: export_name: must be a plain name"):
        prefab.export_actor(box, "a/b", str(tmp_path))
    blocker = tmp_path / "a_file"
    blocker.write_text("not a folder")
    with pytest.raises(sdp.Error, match="export_scene: output_dir: cannot create the folder"):
        prefab.export_scene(scene, "x", str(blocker))
    with pytest.raises(sdp.Error, match="export_scene: output_dir: must name a folder"):
        prefab.export_scene(scene, "x", "")
    # Path objects are taken as well
    prefab.export_scene(scene, "as_path", tmp_path)
    assert (tmp_path / "as_path" / "as_path.mochi_scene").is_file()


# -- the writer saves every field its reader reads --------------------------------------------

LOSSLESS_DOC = {
    "actors": {
        "rigid": [{"name": "ball", "shape": {"sphere": {"radius": 0.1}}, "translation": [0, 0, 1], "mass": 1.0}],
        "soft": [
            {"name": "s1", "shape": "./tet.mochi.h5", "translation": [0, 1, 0], "fixedNodes": [0, 3],
             "material": {"type": "StVK", "youngsModulus": 2e5, "poissonRatio": 0.4, "density": 900.0, "damping": 0.01,
                          "dampingAlpha": 0.5}},
            {"name": "s2", "shape": "./tet.mochi.h5", "translation": [0, 2, 0],
             "material": {"type": "Linear", "youngsModulus": 3e5, "poissonRatio": 0.2, "density": 800.0}},
        ],
        "articulated": [{
            "name": "arm", "translation": [0, 0, 1],
            "links": [
                {"name": "base", "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01], "layer": "robot"},
                {"name": "l1", "parentLink": 0, "density": 500.0, "shape": "./cube.obj", "shapeScale": [1, 1, 4],
                 "shapeRotation": [0, 0.7071067811865476, 0, 0.7071067811865476], "shapeTranslation": [0.2, 0, 0],
                 "jointFromLink": [0, 0, 0.1], "layer": 3},
            ],
            "joints": [{"name": "weld", "type": "Hard"},
                       {"name": "j", "type": "Revolute", "axis": [0, 1, 0],
                        "parentLinkFromJoint": {"rotation": [0, 0, 0, 1], "translation": [0, 0, 0.2]}}],
        }],
    },
    "scene": {"description": "d", "gravity": [0, 0, -9.81],
              "solver": {"maxNewtonIterations": 9, "contactMargin": 0.02,
                         "nonLinearSolver": {"absTol": 1e-6, "lineSearchMaxIter": 12, "convergenceMode": "GLOBAL"},
                         "linearSolver": {"solverType": "CG", "relTol": 1e-7},
                         "experimentalEval": {"fadeFriction": False},
                         "implicitStep": {"nearRigidBeta": 2.0, "driftCorrectionIterations": 3, "deferInactiveJointLimits": False,
                                          "deferSeparatingContacts": False}}},
}


def write_lossless_inputs(tmp_path):
    import h5py

    nodes, tets = tet_cube()
    with h5py.File(tmp_path / "tet.mochi.h5", "w") as f:
        f["mesh/coordinates"] = nodes
        f["mesh/connectivity"] = tets.astype(np.int32)
    cube_obj(tmp_path / "cube.obj", 0.05)
    path = tmp_path / "doc.mochi_prefab"
    path.write_text(json.dumps(LOSSLESS_DOC))
    return path


def test_load_save_load_is_lossless(engine, tmp_path):
    path = write_lossless_inputs(tmp_path)
    first = prefab.shallow_load_from_file(str(path))
    text = prefab.save_to_json_string(first)
    saved = json.loads(text)
    second = prefab.shallow_load_from_json_string(text)
    assert prefab.save_to_json_string(second) == text
    assert second.scene == first.scene and second.actors.soft[0] == first.actors.soft[0]
    assert second.actors.soft[1] == first.actors.soft[1] and second.actors.articulated[0] == first.actors.articulated[0]
    # what the document says, kept
    solver = second.scene.solver
    assert solver.non_linear_solver.max_iter == 9 and solver.implicit_step.contact_margin == pytest.approx(0.02)
    assert solver.non_linear_solver.abs_tol == pytest.approx(1e-6) and solver.non_linear_solver.line_search_max_iter == 12
    assert solver.non_linear_solver.convergence_mode == sdp.NonLinearSolverConvergenceMode.GLOBAL
    assert solver.linear_solver.solver_type == sdp.LinearSolverType.CG and solver.linear_solver.rel_tol == pytest.approx(1e-7)
    assert not solver.experimental_eval.fade_friction and not solver.implicit_step.defer_inactive_joint_limits
    assert not solver.implicit_step.defer_separating_contacts
    assert solver.implicit_step.near_rigid_beta == 2.0 and solver.implicit_step.drift_correction_iterations == 3
    assert saved["scene"]["solver"]["implicitStep"] == LOSSLESS_DOC["scene"]["solver"]["implicitStep"]
    s1, s2 = second.actors.soft
    assert s1.material.type == sdp.SoftMaterialType.ST_VENANT_KIRCHHOFF and s1.material.st_venant_kirchhoff.poisson_ratio == pytest.approx(0.4)
    assert s1.material.stiffness_damping_coefficient == pytest.approx(0.01) and s1.material.mass_damping_coefficient == 0.5
    assert s2.material.type == sdp.SoftMaterialType.LINEAR_ELASTIC and s2.material.linear_elastic.youngs_modulus == pytest.approx(3e5)
    base, l1 = second.actors.articulated[0].links
    assert base.layer == "robot" and l1.layer == "3"
    np.testing.assert_allclose(l1.shape_rotation, [0, math.sqrt(0.5), 0, math.sqrt(0.5)], atol=1e-7)
    np.testing.assert_allclose(l1.shape_translation, [0.2, 0, 0])
    np.testing.assert_allclose(l1.shape_scale, [1, 1, 4])
    np.testing.assert_allclose(l1.parent_joint_from_link.translation, [0, 0, 0.1])
    # a SolverParams set field by field in code comes back equal as a whole
    p = prefab.ScenePrefab()
    full = sdp.default_scene_solver_params()
    full.non_linear_solver.rel_step_tol = 1e-9
    full.non_linear_solver.line_search_type = sdp.LineSearchType.DEFAULT
    full.non_linear_solver.max_elapsed_time_seconds = 0.25
    full.linear_solver.max_iter = 77
    full.linear_solver.preconditioner_type = sdp.PreconditionerType.JACOBI
    full.experimental_eval.fitted_saturation_hessian.joint_friction = True
    full.implicit_step.soft_hessian_reuse_strain = 2e-3
    p.scene = prefab.SceneParams(solver=full)
    assert prefab.shallow_load_from_json_string(prefab.save_to_json_string(p)).scene.solver == full


def test_link_shape_file_pose_and_layer_names_take_effect(engine, tmp_path):
    path = write_lossless_inputs(tmp_path)
    scene = sdp.create_scene("lossless")
    made = prefab.add_to_scene(str(path), str(tmp_path), scene)
    arm = made.filter(sdp.ActorType.ARTICULATED)[0]
    base, l1 = links(arm)
    assert base.get_contact_layer() == "robot"
    # the cube (0.1 m) stretched 4x along z, then turned about y: 0.4 m long along x, centred
    # 0.2 m along x from the link origin, which is 0.1 m above the joint (1.2 m above the world)
    box = l1.get_aabb_world()
    np.testing.assert_allclose(np.array(box.max) - np.array(box.min), [0.4, 0.1, 0.1], atol=1e-5)
    np.testing.assert_allclose((np.array(box.max) + np.array(box.min)) / 2, [0.2, 0, 1.3], atol=1e-5)
    assert l1.get_mass() == pytest.approx(500.0 * 0.1 * 0.1 * 0.4, rel=1e-5)
    # exported again, the link keeps its shape where it was
    again, _ = export_and_reload(scene, tmp_path, "relinked")
    l1_again = links(actors_by_name(again)["arm"])[1]
    np.testing.assert_allclose(aabb(l1_again), aabb(l1), atol=1e-6)
    assert l1_again.get_contact_layer() == l1.get_contact_layer()
    assert links(actors_by_name(again)["arm"])[0].get_contact_layer() == "robot"


def test_soft_export_keeps_fixed_nodes_and_material(engine, tmp_path):
    path = write_lossless_inputs(tmp_path)
    scene = sdp.create_scene("soft")
    scene.set_gravity([0, 0, -9.81])
    prefab.add_to_scene(str(path), str(tmp_path), scene)
    again, doc = export_and_reload(scene, tmp_path, "soft_again")
    s1 = next(s for s in doc["actors"]["soft"] if s["name"] == "s1")
    assert s1["fixedNodes"] == [0, 3]
    assert s1["material"] == {"type": "StVK", "youngsModulus": 2e5, "poissonRatio": pytest.approx(0.4), "density": 900.0,
                              "damping": pytest.approx(0.01), "dampingAlpha": 0.5}
    a, b = actors_by_name(scene)["s1"], actors_by_name(again)["s1"]
    assert b.get_soft_material_params() == a.get_soft_material_params()
    for _ in range(20):
        scene.step(DT)
        again.step(DT)
    np.testing.assert_allclose(aabb(b), aabb(a), atol=1e-6)


def test_unwritable_soft_material_type_is_an_error_naming_the_field(engine):
    p = prefab.ScenePrefab()
    s = prefab.SoftActorPrefab(name="s", shape_file="./tet.mochi.h5")
    s.material.type = sdp.SoftMaterialType.ARAP
    p.actors.soft = [s]
    with pytest.raises(sdp.Error, match=r"actors\.soft\[0\]\.material\.type: .*cannot be written"):
        prefab.save_to_json_string(p)
