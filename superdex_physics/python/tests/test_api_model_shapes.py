"""Shapes from model data: create_model_shape, create_mesh_shape, load_shape_from_file / _bytes
with bakes, the meshes of shapes and actors (get_shape_mesh, get_shape_surface_mesh,
get_shape_visual_mesh, Actor.get_mesh / get_surface_mesh / get_visual_mesh) and the file cache.
Expected values are geometry worked out by hand (a unit cube split into 5 tetrahedra, boxes and
balls with known bounds)."""

import math

import numpy as np
import pytest

import superdex.physics as sdp
from superdex.physics import model as sdm

# a cube [0, 1]^3: corner i has x = bit 0, y = bit 1, z = bit 2
CUBE_NODES = np.array([[(i >> 0) & 1, (i >> 1) & 1, (i >> 2) & 1] for i in range(8)], dtype=float)
# five positively oriented tetrahedra: four corners and the central one
CUBE_TETS = np.array([[0, 1, 2, 4], [1, 3, 2, 7], [1, 5, 7, 4], [2, 7, 6, 4], [2, 1, 7, 4]])
# its 12 boundary triangles, counter-clockwise seen from outside
CUBE_TRIS = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
                      [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]])


def tet_volume(nodes, tet):
    a, b, c, d = (nodes[i] for i in tet)
    return np.linalg.det(np.array([b - a, c - a, d - a])) / 6


def mesh(npe, nodes, elements):
    return sdp.MeshData(nodes_per_element=npe, coordinates=np.asarray(nodes, float).ravel(),
                        connectivity=np.asarray(elements).ravel())


def aabb(shape):
    box = sdp.get_shape_aabb(shape)
    return np.array(box.min, float), np.array(box.max, float)


@pytest.fixture
def engine():
    sdp.initialize()
    yield
    sdp.shutdown()


def test_the_cube_fixture_is_a_partition_of_the_cube():
    # the reference data itself: five positive tetrahedra filling volume 1
    volumes = [tet_volume(CUBE_NODES, t) for t in CUBE_TETS]
    assert min(volumes) > 0 and sum(volumes) == pytest.approx(1.0)


def test_tet_model_shape_keeps_its_mesh_and_has_the_boundary_as_surface(engine):
    shape = sdp.create_model_shape(mesh=mesh(4, CUBE_NODES, CUBE_TETS))
    m = sdp.get_shape_mesh(shape)
    assert (m.nodes_per_element, m.get_num_nodes(), m.get_num_elements()) == (4, 8, 5)
    np.testing.assert_allclose(np.asarray(m.coordinates).reshape(-1, 3), CUBE_NODES)
    surface = sdp.get_shape_surface_mesh(shape)
    assert (surface.nodes_per_element, surface.get_num_nodes(), surface.get_num_elements()) == (3, 8, 12)
    # the faces that belong to one tetrahedron only (as node sets)
    count = {}
    for t in CUBE_TETS.tolist():
        for skip in range(4):
            face = frozenset(t[:skip] + t[skip + 1:])
            count[face] = count.get(face, 0) + 1
    faces = {frozenset(t) for t in np.asarray(surface.connectivity).reshape(-1, 3).tolist()}
    assert faces == {f for f, n in count.items() if n == 1}
    # each face's normal points out of the cube: away from its centre
    xyz = np.asarray(surface.coordinates, float).reshape(-1, 3)
    for a, b, c in np.asarray(surface.connectivity).reshape(-1, 3):
        n = np.cross(xyz[b] - xyz[a], xyz[c] - xyz[a])
        assert n @ ((xyz[a] + xyz[b] + xyz[c]) / 3 - 0.5) > 0
    assert sdp.get_shape_visual_mesh(shape) == sdp.MeshDataView()
    np.testing.assert_allclose(aabb(shape), [[0, 0, 0], [1, 1, 1]])


def test_triangle_surface_is_compact_over_the_nodes_it_uses(engine):
    # a tenth node no triangle uses: the mesh keeps it, the surface drops it
    nodes = np.vstack([CUBE_NODES[:4], [[5, 5, 5]], CUBE_NODES[4:]])
    tris = np.where(CUBE_TRIS >= 4, CUBE_TRIS + 1, CUBE_TRIS)
    shape = sdp.create_mesh_shape(nodes_per_element=3, coordinates=nodes.ravel(), connectivity=tris.ravel())
    assert sdp.get_shape_mesh(shape).get_num_nodes() == 9
    surface = sdp.get_shape_surface_mesh(shape)
    assert surface.get_num_nodes() == 8
    np.testing.assert_allclose(np.asarray(surface.coordinates).reshape(-1, 3), CUBE_NODES)
    np.testing.assert_array_equal(np.asarray(surface.connectivity).reshape(-1, 3), CUBE_TRIS)


def test_visual_mesh_is_kept_and_views_outlive_the_shape(engine):
    shape = sdp.create_model_shape(sdp.ModelData(mesh=mesh(4, CUBE_NODES, CUBE_TETS),
                                                 visual_mesh=mesh(3, CUBE_NODES * 2, CUBE_TRIS)))
    visual = sdp.get_shape_visual_mesh(shape)
    sdp.release_shape(shape)
    assert sdp.get_num_shapes() == 0
    assert (visual.nodes_per_element, visual.get_num_nodes(), visual.get_num_elements()) == (3, 8, 12)
    assert np.asarray(visual.coordinates).max() == 2


def test_primitive_models(engine):
    ball = sdp.create_model_shape(sphere=sdp.Sphere(center=[1, 2, 3], radius=0.5))
    np.testing.assert_allclose(aabb(ball), [[0.5, 1.5, 2.5], [1.5, 2.5, 3.5]])
    assert sdp.get_shape_mesh(ball) == sdp.MeshDataView() and sdp.get_shape_surface_mesh(ball) == sdp.MeshDataView()
    ground = sdp.create_model_shape(plane=sdp.Plane(normal=[0, 0, 1], distance=3))
    assert aabb(ground)[1][2] == pytest.approx(3)
    # a box off the origin and turned 90 degrees about z: its x and y extents swap
    turned = sdp.create_model_shape(box=sdp.Box(center=[1, 0, 0], half_extents=[0.5, 0.25, 0.1],
                                                rotation=sdp.Quaternion.rotation_z(math.pi / 2)))
    np.testing.assert_allclose(aabb(turned), [[0.75, -0.5, -0.1], [1.25, 0.5, 0.1]], atol=1e-6)
    # its mass is the box's whatever its placement: density x volume
    scene = sdp.create_scene("boxes")
    actor = scene.create_rigid_actor(name="b", shape=turned, density=1000.0)
    assert actor.get_mass() == pytest.approx(1000 * 1.0 * 0.5 * 0.2, rel=1e-5)


def test_bad_models_raise_errors_naming_the_field(engine):
    with pytest.raises(sdp.Error, match="create_model_shape.*connectivity"):
        sdp.create_model_shape(mesh=mesh(4, CUBE_NODES, [[0, 1, 2, 8]]))
    # an inverted tetrahedron
    with pytest.raises(sdp.Error, match="create_mesh_shape.*tetrahedron 0"):
        sdp.create_mesh_shape(mesh(4, CUBE_NODES, [[0, 2, 1, 4]]))
    with pytest.raises(sdp.Error, match="either model or its fields"):
        sdp.create_model_shape(sdp.ModelData(), sphere=sdp.Sphere(radius=1))
    with pytest.raises(sdp.Error, match="mesh: expected a MeshData"):
        sdp.create_mesh_shape(42)
    for getter in (sdp.get_shape_mesh, sdp.get_shape_surface_mesh, sdp.get_shape_visual_mesh):
        with pytest.raises(sdp.Error, match="not set"):
            getter(sdp.ShapeHandle())
    assert sdp.get_num_shapes() == 0


def test_actor_meshes(engine):
    scene = sdp.create_scene("meshes")
    tets = sdp.create_tet_mesh_shape(CUBE_NODES, CUBE_TETS)
    soft = scene.create_soft_actor(name="soft", shape=tets)
    assert (soft.get_mesh().nodes_per_element, soft.get_mesh().get_num_elements()) == (4, 5)
    np.testing.assert_allclose(np.asarray(soft.get_surface_mesh().coordinates).reshape(-1, 3), CUBE_NODES)
    # a rigid body simulates the surface of the same tetrahedra
    rigid = scene.create_rigid_actor(name="rigid", shape=tets)
    assert rigid.get_mesh() == rigid.get_surface_mesh()
    assert (rigid.get_mesh().nodes_per_element, rigid.get_mesh().get_num_elements()) == (3, 12)
    ground = scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    assert ground.get_mesh() == sdp.MeshDataView() and ground.get_visual_mesh() == sdp.MeshDataView()


OFF_CUBE = "OFF\n8 12 0\n" + "".join(f"{x:g} {y:g} {z:g}\n" for x, y, z in CUBE_NODES) + "".join(
    f"3 {a} {b} {c}\n" for a, b, c in CUBE_TRIS)


def test_load_from_bytes_with_bakes(engine):
    data = bytearray(OFF_CUBE.encode())
    shape = sdp.load_shape_from_bytes(data, sdp.MeshFileType.OFF)
    np.testing.assert_allclose(aabb(shape), [[0, 0, 0], [1, 1, 1]], atol=1e-6)
    # scale (2, 3, 4), then a quarter turn about x (y -> z, z -> -y), then (1, 2, 3)
    baked = sdp.load_shape_from_bytes(file_data=data, format=sdp.MeshFileType.OFF, bake_scale=[2, 3, 4],
                                      bake_transform=sdp.TransformRT(rotation=sdp.Quaternion.rotation_x(math.pi / 2),
                                                                     translation=[1, 2, 3]))
    np.testing.assert_allclose(aabb(baked), [[1, -2, 3], [3, 2, 6]], atol=1e-5)
    with pytest.raises(sdp.Error, match="load_shape_from_bytes: file_data"):
        sdp.load_shape_from_bytes(b"OFF\n8 12 0\n1 2\n", sdp.MeshFileType.OFF)
    with pytest.raises(sdp.Error, match="format"):
        sdp.load_shape_from_bytes(data, "off")


def test_load_json_model_file_and_the_file_cache(engine, tmp_path):
    path = tmp_path / "cube.mochi.json"
    sdm.save_to_file(sdp.ModelData(mesh=mesh(4, CUBE_NODES, CUBE_TETS)), str(path), sdp.FileFormat.JSON)
    was = sdp.is_file_cache_enabled()
    try:
        sdp.enable_file_cache(True)
        first = sdp.load_shape_from_file(path, bake_scale=2.0)
        np.testing.assert_allclose(aabb(first), [[0, 0, 0], [2, 2, 2]], atol=1e-6)
        assert sdp.get_shape_mesh(first).get_num_elements() == 5
        # the file changes on disk: a cached load still gives the first contents ...
        sdm.save_to_file(sdp.ModelData(mesh=mesh(4, CUBE_NODES * 3, CUBE_TETS)), str(path), sdp.FileFormat.JSON)
        np.testing.assert_allclose(aabb(sdp.load_shape_from_file(path, bake_scale=2.0)), [[0, 0, 0], [2, 2, 2]], atol=1e-6)
        # ... another bake is another entry, and clearing the file's entries reads it again
        np.testing.assert_allclose(aabb(sdp.load_shape_from_file(path)), [[0, 0, 0], [3, 3, 3]], atol=1e-6)
        sdp.clear_file_from_cache(str(path))
        np.testing.assert_allclose(aabb(sdp.load_shape_from_file(path, bake_scale=2.0)), [[0, 0, 0], [6, 6, 6]], atol=1e-6)
        # without the cache every load reads the file
        sdp.enable_file_cache(False)
        sdm.save_to_file(sdp.ModelData(mesh=mesh(4, CUBE_NODES, CUBE_TETS)), str(path), sdp.FileFormat.JSON)
        np.testing.assert_allclose(aabb(sdp.load_shape_from_file(path, bake_scale=2.0)), [[0, 0, 0], [2, 2, 2]], atol=1e-6)
    finally:
        sdp.enable_file_cache(was)
    with pytest.raises(sdp.Error, match="missing.mochi.json"):
        sdp.load_shape_from_file(tmp_path / "missing.mochi.json")


@pytest.mark.parametrize("suffix,fmt", [(".h5", "H5"), (".json", "JSON"), (".mochi.h5", "H5")])
def test_a_saved_tet_model_loads_back_as_a_soft_body_shape_whatever_its_file_name(engine, tmp_path, suffix, fmt):
    # temporary files rarely end in ".mochi.h5": the format follows the extension alone
    path = tmp_path / f"tmp_cube{suffix}"
    sdm.save_to_file(sdp.ModelData(mesh=mesh(4, CUBE_NODES, CUBE_TETS)), str(path), getattr(sdp.FileFormat, fmt))
    shape = sdp.load_shape_from_file(file_path=path)
    assert shape.is_valid()
    m = sdp.get_shape_mesh(shape)
    assert (m.nodes_per_element, m.get_num_elements()) == (4, 5)
    scene = sdp.create_scene("tets")
    try:
        soft = scene.create_soft_actor(name="cube", shape=shape, material=sdp.SoftMaterialParams(density=500.0))
        # the soft body is the file's unit cube: eight nodes of three DOFs each, mass density x 1 m^3
        assert soft.get_num_dofs() == 24
        assert soft.get_mass() == pytest.approx(500.0, rel=1e-5)
    finally:
        sdp.destroy_scene(scene)
        sdp.release_shape(shape)
