"""Mesh shapes from Python: create_tri_mesh_shape and load_shape_from_file for every format
(written by the tests), baking, and a corpus of malformed inputs, each raising
superdex.physics.Error with a message naming the file and the defect."""

import re
import struct

import h5py

import numpy as np
import pytest

import superdex.physics as sdp

# A unit cube centred at the origin: 8 corners (bit 0 = x, bit 1 = y, bit 2 = z) and 12
# triangles counter-clockwise seen from outside.
CUBE_V = np.array([[(i & 1) - 0.5, ((i >> 1) & 1) - 0.5, ((i >> 2) & 1) - 0.5] for i in range(8)])
CUBE_T = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
                   [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]])


@pytest.fixture(autouse=True)
def sdf_cache(tmp_path, monkeypatch):
    """Keeps computed distance grids in the test's temporary directory."""
    monkeypatch.setenv("SUPERDEX_CACHE_DIR", str(tmp_path / "sdf_cache"))
    return tmp_path / "sdf_cache"


def obj_text(v, t):
    return "".join(f"v {x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in v) + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in t)


def stl_ascii(v, t):
    facets = "".join("facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {v[i][0]} {v[i][1]} {v[i][2]}\n" for i in tri)
                     + "endloop\nendfacet\n" for tri in t)
    return "solid cube\n" + facets + "endsolid cube\n"


def stl_binary(v, t):
    out = b"\0" * 80 + struct.pack("<I", len(t))
    for tri in t:
        out += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *v[i]) for i in tri) + struct.pack("<H", 0)
    return out


def ply(v, t, binary):
    header = (f"ply\nformat {'binary_little_endian' if binary else 'ascii'} 1.0\nelement vertex {len(v)}\n"
              "property float x\nproperty float y\nproperty float z\n"
              f"element face {len(t)}\nproperty list uchar int vertex_indices\nend_header\n").encode()
    if binary:
        return header + b"".join(struct.pack("<3f", *p) for p in v) + b"".join(struct.pack("<B3i", 3, *tri) for tri in t)
    return header + ("".join(f"{x} {y} {z}\n" for x, y, z in v) + "".join(f"3 {a} {b} {c}\n" for a, b, c in t)).encode()


def write_mochi(path, v=None, t=None, **groups):
    """A .mochi.h5 file with mesh/ from v, t and primitive groups given as {group: {attr: value}}."""
    with h5py.File(path, "w") as f:
        if v is not None:
            g = f.create_group("mesh")
            g["coordinates"] = np.asarray(v, dtype=np.float64)
            g["connectivity"] = np.asarray(t, dtype=np.int32)
        for name, attrs in groups.items():
            g = f.create_group(name)
            for key, value in attrs.items():
                g.attrs[key] = value
    return str(path)


def write_sdf(path, grid=None, with_mesh=True, **attrs):
    """A .mochi.h5 file with the cube mesh and an sdf/ group with the given attributes."""
    with h5py.File(path, "w") as f:
        if with_mesh:
            f["mesh/coordinates"] = CUBE_V
            f["mesh/connectivity"] = CUBE_T.astype(np.int32)
        f["sdf/grid"] = np.ones((4, 4, 4)) if grid is None else grid
        for key, value in attrs.items():
            f["sdf"].attrs[key] = value
    return str(path)


def mass_of(scene, shape, name="body"):
    return scene.create_rigid_actor(name=name, shape=shape, density=1000.0).get_mass()


# ---------------------------------------------------------------------------------------------
# Loading


def test_create_tri_mesh_shape_cube(scene):
    shape = sdp.create_tri_mesh_shape(CUBE_V, CUBE_T)
    assert isinstance(shape, sdp.ShapeHandle) and shape.is_valid()
    assert mass_of(scene, shape) == pytest.approx(1000.0, rel=1e-5)
    # lists work too, and an inside-out cube is turned right side out
    flipped = sdp.create_tri_mesh_shape(CUBE_V.tolist(), CUBE_T[:, ::-1].tolist())
    assert mass_of(scene, flipped, "flipped") == pytest.approx(1000.0, rel=1e-5)


@pytest.mark.parametrize("name, content", [
    ("cube.obj", lambda: obj_text(CUBE_V, CUBE_T).encode()),
    ("cube.stl", lambda: stl_ascii(CUBE_V, CUBE_T).encode()),
    ("cube_binary.stl", lambda: stl_binary(CUBE_V, CUBE_T)),
    ("cube.ply", lambda: ply(CUBE_V, CUBE_T, binary=False)),
    ("cube_binary.PLY", lambda: ply(CUBE_V, CUBE_T, binary=True)),
])
def test_load_mesh_files(scene, tmp_path, name, content):
    path = tmp_path / name
    path.write_bytes(content())
    shape = sdp.load_shape_from_file(path)
    assert mass_of(scene, shape) == pytest.approx(1000.0, rel=1e-5)


def test_load_mochi_h5_mesh_and_cache(scene, tmp_path, sdf_cache):
    shape = sdp.load_shape_from_file(write_mochi(tmp_path / "cube.mochi.h5", CUBE_V, CUBE_T))
    assert mass_of(scene, shape) == pytest.approx(1000.0, rel=1e-5)
    # the computed grid went to the cache as a readable .mochi.h5 sdf/ group
    entries = list(sdf_cache.glob("*.mochi.h5"))
    assert len(entries) == 1
    with h5py.File(entries[0], "r") as f:
        grid = f["sdf/grid"][...]
        assert grid.ndim == 3 and grid.min() < 0 < grid.max()
        assert np.all(f["sdf"].attrs["grid_min"] < f["sdf"].attrs["grid_max"])


def test_load_mochi_h5_primitives(scene, tmp_path):
    box = sdp.load_shape_from_file(write_mochi(tmp_path / "box.mochi.h5", box={"half_extents": [0.5, 1.0, 1.5]}))
    assert mass_of(scene, box, "box") == pytest.approx(6000.0, rel=1e-5)
    ball = sdp.load_shape_from_file(write_mochi(tmp_path / "ball.mochi.h5", sphere={"radius": 0.5}))
    assert mass_of(scene, ball, "ball") == pytest.approx(1000.0 * 4 / 3 * np.pi * 0.125, rel=1e-5)
    ground = sdp.load_shape_from_file(write_mochi(tmp_path / "ground.mochi.h5", plane={"normal": [0, 0, 1], "distance": 0.0}))
    scene.create_rigid_actor(name="ground", shape=ground, is_static=True)


def test_bake_scale_and_transform(scene, tmp_path):
    path = tmp_path / "cube.obj"
    path.write_text(obj_text(CUBE_V, CUBE_T))
    assert mass_of(scene, sdp.load_shape_from_file(path, bake_scale=2.0), "a") == pytest.approx(8000.0, rel=1e-5)
    assert mass_of(scene, sdp.load_shape_from_file(str(path), bake_scale=[1, 2, 3]), "b") == pytest.approx(6000.0, rel=1e-5)
    moved = sdp.TransformRT(sdp.Quaternion.from_axis_angle([0, 0, 1], 0.5), [1.0, 2.0, 3.0])
    assert mass_of(scene, sdp.load_shape_from_file(path, bake_scale=2.0, bake_transform=moved), "c") == pytest.approx(8000.0, rel=1e-5)
    box = write_mochi(tmp_path / "box.mochi.h5", box={"half_extents": [0.5, 0.5, 0.5]})
    assert mass_of(scene, sdp.load_shape_from_file(box, bake_scale=[1, 1, 2], bake_transform=moved), "d") == pytest.approx(2000.0, rel=1e-5)


def test_open_mesh_loads_but_has_no_volume(scene, tmp_path):
    path = tmp_path / "open.obj"
    path.write_text(obj_text(CUBE_V, CUBE_T[:-1]))
    shape = sdp.load_shape_from_file(path)
    scene.create_rigid_actor(name="static_open", shape=shape, is_static=True)
    with pytest.raises(sdp.Error, match=r"open\.obj: computing a volume needs a closed mesh: 3 boundary edges"):
        scene.create_rigid_actor(name="dynamic_open", shape=shape, density=1000.0)


# ---------------------------------------------------------------------------------------------
# Malformed inputs


def test_empty_mesh(engine, tmp_path):
    with pytest.raises(sdp.Error, match=r"create_tri_mesh_shape: empty mesh: no vertices"):
        sdp.create_tri_mesh_shape(np.zeros((0, 3)), np.zeros((0, 3), dtype=int))
    with pytest.raises(sdp.Error, match=r"create_tri_mesh_shape: empty mesh: no triangles"):
        sdp.create_tri_mesh_shape(CUBE_V, np.zeros((0, 3), dtype=int))
    (tmp_path / "empty.obj").write_text("# no geometry\n")
    with pytest.raises(sdp.Error, match=r"empty\.obj: empty mesh: no vertices"):
        sdp.load_shape_from_file(tmp_path / "empty.obj")
    (tmp_path / "empty.stl").write_text("solid nothing\nendsolid nothing\n")
    with pytest.raises(sdp.Error, match=r"empty\.stl: empty mesh"):
        sdp.load_shape_from_file(tmp_path / "empty.stl")
    path = tmp_path / "empty.mochi.h5"
    with h5py.File(path, "w") as f:
        f["mesh/coordinates"] = np.zeros((0, 3))
        f["mesh/connectivity"] = np.zeros((0, 3), dtype=np.int32)
    with pytest.raises(sdp.Error, match=r"empty\.mochi\.h5: mesh/coordinates: empty mesh: no nodes"):
        sdp.load_shape_from_file(path)


def test_degenerate_triangles(engine, tmp_path, log_messages):
    v = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0]], dtype=float)
    t = np.array([[0, 1, 3], [0, 1, 2], [0, 0, 3]])
    # arrays given in code are checked strictly
    with pytest.raises(sdp.Error, match=r"create_tri_mesh_shape: 2 degenerate \(zero-area\) triangles; the first is triangle 1 \(vertices 0, 1, 2\)"):
        sdp.create_tri_mesh_shape(v, t)
    # files as exporters write them: the slivers are dropped with a warning naming the file
    for name, data in [("flat.obj", obj_text(v, t)), ("flat.stl", stl_binary(v, t))]:
        path = tmp_path / name
        path.write_text(data) if isinstance(data, str) else path.write_bytes(data)
        log_messages.clear()
        shape = sdp.load_shape_from_file(path)
        mesh = sdp.get_shape_mesh(shape)
        assert mesh.get_num_elements() == 1
        xyz = np.asarray(mesh.coordinates).reshape(-1, 3)
        tri = xyz[np.asarray(mesh.connectivity)]
        assert np.linalg.norm(np.cross(tri[1] - tri[0], tri[2] - tri[0])) == pytest.approx(1.0)  # the good triangle
        warnings = [m for c, m in log_messages if c == sdp.LogChannel.WARNING]
        assert len(warnings) == 1 and re.search(rf"{name}: 2 degenerate \(zero-area\) triangles ignored", warnings[0]), warnings
        sdp.release_shape(shape)
    # a file of nothing but degenerate triangles has no surface: an error
    (tmp_path / "line.obj").write_text(obj_text(v, t[1:]))
    with pytest.raises(sdp.Error, match=r"line\.obj: 2 degenerate \(zero-area\) triangles"):
        sdp.load_shape_from_file(tmp_path / "line.obj")


def test_open_mesh_where_a_closed_one_is_needed(scene, tmp_path):
    shape = sdp.create_tri_mesh_shape(CUBE_V, CUBE_T[:-2])
    with pytest.raises(sdp.Error, match=r"create_tri_mesh_shape: computing a volume needs a closed mesh: 4 boundary edges"):
        scene.create_rigid_actor(name="open", shape=shape)
    # a stored grid with a rotation can only be re-laid from a closed mesh
    path = tmp_path / "rotated_open.mochi.h5"
    with h5py.File(path, "w") as f:
        f["mesh/coordinates"] = CUBE_V
        f["mesh/connectivity"] = CUBE_T[:-1].astype(np.int32)
        f["sdf/grid"] = np.ones((3, 3, 3))
        f["sdf"].attrs.update(grid_min=[-1.0, -1, -1], grid_max=[1.0, 1, 1], rotation=[0, 0, 0.6, 0.8])
    with pytest.raises(sdp.Error, match=r"rotated_open\.mochi\.h5: sdf/: the grid's rotation or non-uniform scale cannot be applied to an open mesh"):
        sdp.load_shape_from_file(path)


def test_nan_in_coordinates(engine, tmp_path):
    v = CUBE_V.copy()
    v[1, 1] = np.nan
    with pytest.raises(sdp.Error, match=r"create_tri_mesh_shape: vertex 1 has a non-finite coordinate"):
        sdp.create_tri_mesh_shape(v, CUBE_T)
    (tmp_path / "nan.obj").write_text("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n")
    with pytest.raises(sdp.Error, match=r"nan\.obj:2: vertex 2 has a non-finite coordinate 'nan'"):
        sdp.load_shape_from_file(tmp_path / "nan.obj")
    (tmp_path / "nan.ply").write_bytes(ply(v, CUBE_T, binary=True))
    with pytest.raises(sdp.Error, match=r"nan\.ply: vertex 1 has a non-finite coordinate"):
        sdp.load_shape_from_file(tmp_path / "nan.ply")
    with pytest.raises(sdp.Error, match=r"nan\.mochi\.h5: mesh/coordinates: NaN at row 1, column 1"):
        sdp.load_shape_from_file(write_mochi(tmp_path / "nan.mochi.h5", v, CUBE_T))


@pytest.mark.parametrize("attrs, grid, message", [
    ({"grid_max": [1.0, 1, 1]}, None, r"a\.mochi\.h5: sdf/grid_min: missing attribute"),
    ({"grid_min": [0.0, 0], "grid_max": [1.0, 1, 1]}, None, r"sdf/grid_min: wrong shape: expected 3 values, got 2"),
    ({"grid_min": [0.0, 0, 0], "grid_max": [1.0, 0, 1]}, None,
     r"sdf: grid_min must be < grid_max on every axis, got grid_min \[0, 0, 0\] and grid_max \[1, 0, 1\]"),
    ({"grid_min": "zero", "grid_max": [1.0, 1, 1]}, None, r"sdf/grid_min: wrong type: expected numbers, got a string"),
    ({"grid_min": [0.0, np.nan, 0], "grid_max": [1.0, 1, 1]}, None, r"sdf/grid_min: NaN at index 1"),
    ({"grid_min": [0.0, 0, 0], "grid_max": [1.0, 1, 1], "scale": [1.0, -1, 1]}, None, r"sdf/scale: must be positive"),
    ({"grid_min": [0.0, 0, 0], "grid_max": [1.0, 1, 1]}, np.ones((4, 4)), r"sdf/grid: wrong rank: expected a 3-D dataset \[nx, ny, nz\], got \[4, 4\]"),
    ({"grid_min": [0.0, 0, 0], "grid_max": [1.0, 1, 1]}, np.full((2, 2, 2), np.nan), r"sdf/grid: NaN at \[0, 0, 0\]"),
    ({"grid_min": [0.0, 0, 0], "grid_max": [1.0, 1, 1]}, np.array([[[b"a"] * 2] * 2] * 2), r"sdf/grid: wrong type: expected numbers, got a string"),
    # integer distances are numbers too: accepted
    ({"grid_min": [-1.0, -1, -1], "grid_max": [1.0, 1, 1]}, np.ones((2, 2, 2), dtype=np.int32), None),
])
def test_sdf_grid_with_wrong_attributes(engine, tmp_path, attrs, grid, message):
    path = write_sdf(tmp_path / "a.mochi.h5", grid=grid, **attrs)
    if message is None:
        sdp.load_shape_from_file(path)  # integer grids are numbers too
        return
    with pytest.raises(sdp.Error, match=message):
        sdp.load_shape_from_file(path)


def test_sdf_without_mesh_and_tetrahedra(engine, tmp_path):
    path = write_sdf(tmp_path / "grid_only.mochi.h5", with_mesh=False, grid_min=[0.0, 0, 0], grid_max=[1.0, 1, 1])
    with pytest.raises(sdp.Error, match=r"grid_only\.mochi\.h5: sdf/ without mesh/"):
        sdp.load_shape_from_file(path)
    # tetrahedra load as a tet-mesh shape for soft actors; an inverted one is named with the file
    with h5py.File(tmp_path / "tet.mochi.h5", "w") as f:
        f["mesh/coordinates"] = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
        f["mesh/connectivity"] = np.array([[0, 1, 2, 3]], dtype=np.int32)
    scene = sdp.create_scene("soft")
    soft = scene.create_soft_actor(name="tet", shape=sdp.load_shape_from_file(tmp_path / "tet.mochi.h5"),
                                   material=sdp.SoftMaterialParams(density=600))
    assert soft.get_mass() == pytest.approx(600 / 6)
    with h5py.File(tmp_path / "inverted.mochi.h5", "w") as f:
        f["mesh/coordinates"] = np.array([[0, 0, 0], [0, 1, 0], [1, 0, 0], [0, 0, 1]], dtype=float)
        f["mesh/connectivity"] = np.array([[0, 1, 2, 3]], dtype=np.int32)
    with pytest.raises(sdp.Error, match=r"inverted\.mochi\.h5: tetrahedron 0 is inverted"):
        sdp.load_shape_from_file(tmp_path / "inverted.mochi.h5")


def test_bad_arrays_and_arguments(engine, tmp_path):
    with pytest.raises(sdp.Error, match=r"connectivity: expected integers, got dtype float64"):
        sdp.create_tri_mesh_shape(CUBE_V, CUBE_T.astype(float))
    with pytest.raises(sdp.Error, match=r"connectivity: expected 3 values per row, flat or of shape \(n, 3\), got shape \(3, 4\)"):
        sdp.create_tri_mesh_shape(CUBE_V, np.zeros((3, 4), dtype=int))
    with pytest.raises(sdp.Error, match=r"coordinates: expected 3 values per row, flat or of shape \(n, 3\), got shape \(8, 2\)"):
        sdp.create_tri_mesh_shape(np.zeros((8, 2)), CUBE_T)
    with pytest.raises(sdp.Error, match=r"coordinates: expected a multiple of 3 values, got 23"):
        sdp.create_tri_mesh_shape(CUBE_V.ravel()[:-1], CUBE_T)
    # SuperDex takes flat arrays too: 3 values per vertex, 3 indices per triangle
    flat = sdp.create_tri_mesh_shape(CUBE_V.ravel(), CUBE_T.ravel())
    assert sdp.get_shape_aabb(flat) == sdp.Aabb([-0.5, -0.5, -0.5], [0.5, 0.5, 0.5])
    bad = CUBE_T.copy()
    bad[0, 2] = 9
    with pytest.raises(sdp.Error, match=r"connectivity\[2\] = 9 is out of range \[0, 8\)"):  # the flat index of [0, 2]
        sdp.create_tri_mesh_shape(CUBE_V, bad)
    path = tmp_path / "cube.obj"
    path.write_text(obj_text(CUBE_V, CUBE_T))
    with pytest.raises(sdp.Error, match=r"bake_scale: must be positive and finite"):
        sdp.load_shape_from_file(path, bake_scale=[1, -1, 1])
    with pytest.raises(sdp.Error, match=r"bake_scale: expected a number or 3 numbers, got 2 values"):
        sdp.load_shape_from_file(path, bake_scale=[1, 2])
    with pytest.raises(sdp.Error, match=r"bake_transform: expected a TransformRT"):
        sdp.load_shape_from_file(path, bake_transform="identity")
    with pytest.raises(sdp.Error, match=r"missing\.stl: file not found"):
        sdp.load_shape_from_file(tmp_path / "missing.stl")
    with pytest.raises(sdp.Error, match=r"shape\.fbx: unknown shape file extension '\.fbx'"):
        sdp.load_shape_from_file(tmp_path / "shape.fbx")
    (tmp_path / "bad.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n")
    with pytest.raises(sdp.Error, match=r"bad\.obj:3: malformed number 'x' in vertex"):
        sdp.load_shape_from_file(tmp_path / "bad.obj")
    (tmp_path / "range.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    with pytest.raises(sdp.Error, match=r"range\.obj:4: face index 7 out of range: the file has 3 vertices"):
        sdp.load_shape_from_file(tmp_path / "range.obj")
    (tmp_path / "text.mochi.h5").write_text("not hdf5")
    with pytest.raises(sdp.Error, match=r"text\.mochi\.h5: not an HDF5 file"):
        sdp.load_shape_from_file(tmp_path / "text.mochi.h5")


def test_missing_hdf5_groups_name_the_file_and_group(engine, tmp_path):
    """A .mochi.h5 with no shape group, and one whose material/ group lacks its type, are refused
    naming the file and what is missing."""
    with h5py.File(tmp_path / "nomesh.mochi.h5", "w") as f:
        f.create_group("material").attrs["type"] = "NeoHookean"
    with pytest.raises(sdp.Error, match=r"nomesh\.mochi\.h5: no shape: expected a mesh/, box/, sphere/ or plane/ group"):
        sdp.load_shape_from_file(str(tmp_path / "nomesh.mochi.h5"))
    with h5py.File(tmp_path / "notype.mochi.h5", "w") as f:
        f["mesh/coordinates"] = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
        f["mesh/connectivity"] = np.array([[0, 1, 2, 3]], dtype=np.int32)
        f.create_group("material")
    with pytest.raises(sdp.Error, match=r"notype\.mochi\.h5: material/type: missing attribute"):
        sdp.load_shape_from_file(str(tmp_path / "notype.mochi.h5"))
