"""superdex.physics.paths and superdex.physics.utils.scene_helpers, and the assets they serve:

- find_actor: exact names, shell patterns, prefab-qualified names; no match or several raise Error
  naming the pattern (and the candidates);
- create_ground_plane: a static plane "StaticPlane" in layer "Environment" that a ball rests on
  one radius above, along any normal and offset;
- resolve_asset takes relative and absolute paths, resolve_asset_root gives the folder a prefab's
  relative paths are written against; missing paths raise Error naming them;
- create_scene_from_prefab from a path under the assets folder or from an edited ScenePrefab
  (its shapes loaded first); a failure leaves no scene behind;
- the unit icosphere asset (642 vertices on the unit sphere, outward, closed) and the table prefab:
  a ball of radius 0.2 m and a cube of edge 0.4 m dropped on the table, turned Y-up as a prefab,
  come to rest on its top (0.75 m above the floor) at their half sizes above it.
"""

import math
from pathlib import Path

import numpy as np
import pytest

import superdex.physics as sdp
from superdex.physics.paths import get_assets_root, resolve_asset, resolve_asset_root
from superdex.physics.utils.scene_helpers import create_ground_plane, create_scene_from_prefab, find_actor

from conftest import unit_sphere_triangles

TABLE_TOP = 0.75  # m above the floor, tools/make_model_assets.py


def ball(scene, name, center, radius=0.1):
    return scene.create_rigid_actor(name=name, shape=sdp.create_sphere_shape([0, 0, 0], radius), mass=1.0,
                                    world_from_local=sdp.TransformRT(translation=list(center)))


def test_find_actor(scene):
    a = ball(scene, "cube_1", [0, 0, 1])
    b = ball(scene, "cube_2", [1, 0, 1])
    ball(scene, "sphere", [2, 0, 1])
    assert find_actor(scene, "cube_1").get_handle() == a.get_handle()
    assert find_actor(scene, "*_2").get_handle() == b.get_handle()
    assert find_actor(scene, "sph?re").get_name() == "sphere"
    with pytest.raises(sdp.Error, match=r'2 actors match "cube_\*": cube_1, cube_2'):
        find_actor(scene, "cube_*")
    with pytest.raises(sdp.Error, match='no actor .* matches "Cube_1"'):
        find_actor(scene, "Cube_1")  # case-sensitive
    # code written against SuperDex catches a ValueError
    with pytest.raises(ValueError, match="no actor"):
        find_actor(scene, "nothing")


@pytest.mark.parametrize("normal, offset", [([0, 1, 0], 0.0), ([0, 0, 1], -0.5), ([1, 1, 0], 0.25)])
def test_ground_plane_carries_a_ball_one_radius_up(scene, normal, offset):
    n = np.array(normal, dtype=float) / np.linalg.norm(normal)
    scene.set_gravity(list(-9.81 * n))
    ground = create_ground_plane(scene, normal=sdp.Real3(*n), offset=offset)
    assert ground.get_name() == "StaticPlane" and ground.get_contact_layer() == "Environment" and ground.is_static()
    assert ground.get_collider_type() == sdp.ColliderType.PLANE
    r = 0.1
    b = ball(scene, "ball", (offset + 0.3) * n, radius=r)
    for _ in range(150):
        scene.step(0.01)
    height = float(np.dot(np.array(b.get_root_transform().translation), n))
    assert height == pytest.approx(offset + r, abs=2e-3)


def test_default_ground_plane_is_y_up(engine):
    scene = sdp.create_scene("y up")  # the engine's default gravity, -Y
    create_ground_plane(scene)
    b = ball(scene, "ball", [0, 0.3, 0])
    for _ in range(150):
        scene.step(0.01)
    assert b.get_root_transform().translation[1] == pytest.approx(0.1, abs=2e-3)


def test_asset_paths(tmp_path):
    root = get_assets_root()
    rel = "sphere/icosphere_3subdiv.1.mochi.json"
    assert resolve_asset(rel) == root / rel
    assert resolve_asset(str(root / rel)) == root / rel  # absolute paths as they are
    assert resolve_asset_root(rel) == root
    outside = tmp_path / "mine.mochi.json"
    outside.write_text("{}")
    assert resolve_asset(outside) == outside.resolve()
    with pytest.raises(sdp.Error, match="no_such_asset"):
        resolve_asset("no_such_asset.mochi.h5")
    with pytest.raises(sdp.Error, match="does not exist"):
        resolve_asset(tmp_path / "missing.obj")
    with pytest.raises(sdp.Error, match="relative"):
        resolve_asset_root(root / rel)


def test_icosphere_asset():
    x, t = unit_sphere_triangles("sphere/icosphere_3subdiv.1.mochi.json")
    assert (len(x), len(t)) == (642, 1280)


def test_ball_and_cube_rest_on_the_table(scene):
    """Y-up, the floor at y = -1: the table prefab turned by -90 degrees about x stands on it."""
    scene.set_gravity([0, -9.8, 0])
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape(normal=[0, 1, 0], distance=-1.0), is_static=True)
    sphere_shape = sdp.load_shape_from_file(file_path=str(resolve_asset("sphere/icosphere_3subdiv.1.mochi.json")),
                                            bake_scale=[0.2, 0.2, 0.2])
    sphere = scene.create_rigid_actor(name="sphere", shape=sphere_shape, density=1000.0,
                                      world_from_local=sdp.TransformRT(translation=[-0.5, 0.2, 0]),
                                      collider_type=sdp.ColliderType.SPHERE)
    cube = scene.create_rigid_actor(name="cube", shape=sdp.create_box_shape([0.2, 0.2, 0.2]), density=1000.0,
                                    world_from_local=sdp.TransformRT(translation=[0.5, 0.2, 0]))
    path = "table/table.mochi_scene"
    sdp.prefab.add_to_scene(prefab_path=str(resolve_asset(path)), root_path=str(resolve_asset_root(path)), scene=scene,
                            params=sdp.prefab.PrefabParams(name="tablePrefab", rotation=sdp.Quaternion.rotation_x(-math.pi / 2),
                                                           translation=[0, -1.0, 0]))
    table = find_actor(scene, "tablePrefab/Table")
    assert table.is_static()
    for _ in range(120):
        scene.step(1 / 60)
    top = -1.0 + TABLE_TOP
    np.testing.assert_allclose(np.array(sphere.get_root_transform().translation), [-0.5, top + 0.2, 0], atol=2e-3)
    np.testing.assert_allclose(np.array(cube.get_root_transform().translation), [0.5, top + 0.2, 0], atol=2e-3)
    assert Path(str(resolve_asset(path))).parent.name == "table"


def test_fine_duck_falls_as_a_soft_body(scene):
    """The finer duck cage loads as a tetrahedral soft body whose mass is density x the cage's
    volume, and falls freely for its first steps (no contact yet): its centre of mass drops by
    g t^2 / 2 to within the implicit step's error of g t dt / 2."""
    shape = sdp.load_shape_from_file(file_path=str(resolve_asset("duck/duck_1899.mochi.h5")))
    duck = scene.create_soft_actor(name="duck", shape=shape, world_from_local=sdp.TransformRT(translation=[0, 0, 1.0]))
    mesh = duck.get_mesh()
    x = np.array(mesh.coordinates, dtype=float).reshape(-1, 3)
    tets = np.array(mesh.connectivity).reshape(-1, 4)
    assert (len(x), len(tets)) == (1842, 8166)
    volume = np.abs(np.einsum("ij,ij->i", x[tets[:, 1]] - x[tets[:, 0]],
                              np.cross(x[tets[:, 2]] - x[tets[:, 0]], x[tets[:, 3]] - x[tets[:, 0]]))).sum() / 6
    density = duck.get_soft_material_params().density
    assert duck.get_mass() == pytest.approx(density * volume, rel=1e-4)
    z0 = duck.get_aabb_world().get_center()[2]
    dt, n = 0.01, 5
    for _ in range(n):
        scene.step(dt)
    t = n * dt
    drop = z0 - duck.get_aabb_world().get_center()[2]
    assert drop == pytest.approx(9.81 * t * t / 2, abs=9.81 * t * dt)


def test_create_scene_from_prefab(engine):
    scene = create_scene_from_prefab("table/table.mochi_scene", scene_name="from file")
    assert scene.get_name() == "from file"
    assert find_actor(scene, "Table").is_static()
    # an edited, shallow-loaded prefab: its shapes are loaded before it is added
    prefab = sdp.prefab.shallow_load_from_file(str(resolve_asset("table/table.mochi_scene")))
    prefab.actors.rigid[0].name = "Desk"
    other = create_scene_from_prefab(prefab, root_dir=get_assets_root() / "table",
                                     params=sdp.prefab.PrefabParams(name="office", translation=[0, 0, 2]))
    desk = find_actor(other, "office/Desk")
    assert desk.get_aabb_world().get_center()[2] == pytest.approx(2 + 0.75 / 2, abs=1e-3)
    with pytest.raises(TypeError, match="ScenePrefab"):
        create_scene_from_prefab(42)
    with pytest.raises(sdp.Error, match="no_such.mochi_scene"):
        create_scene_from_prefab("no_such.mochi_scene")


def test_create_scene_from_prefab_leaves_no_scene_on_failure(engine, monkeypatch):
    created = []
    create = sdp.create_scene
    monkeypatch.setattr(sdp, "create_scene", lambda name="": created.append(create(name)) or created[-1])
    prefab = sdp.prefab.shallow_load_from_file(str(resolve_asset("table/table.mochi_scene")))
    prefab.actors.rigid[0].mass = -1.0
    with pytest.raises(sdp.Error, match="mass"):
        create_scene_from_prefab(prefab, root_dir=get_assets_root() / "table")
    assert len(created) == 1 and not sdp.is_valid_scene(created[0])
