"""Model data (superdex.physics.ModelData and superdex.physics.model): file round trips in both
precisions, every validation rule, auto_correct, baked transforms against their analytic results,
coordinate spaces, signed-distance grids against the exact box distance, views, and surface meshes
from bytes. Run once per precision (SUPERDEX_PRECISION=float / double)."""

import copy
import gc
import itertools
import json
import math
import struct
from pathlib import Path

import numpy as np
import pytest

import superdex.physics as sdp
from superdex.physics import model

ASSETS = Path(__file__).resolve().parents[3] / "assets"
REAL = np.float64 if sdp.uses_double_precision() else np.float32


def real(x):
    """x rounded to the build's precision, as a Python float."""
    return float(REAL(x))


def cube_model():
    return model.load_from_file(str(ASSETS / "cube" / "cube_mesh.mochi.json"))


def coords(mesh):
    return np.array(mesh.coordinates, dtype=np.float64).reshape(-1, 3)


def tet_volumes(mesh):
    x = coords(mesh)
    t = np.array(mesh.connectivity).reshape(-1, 4)
    a, b, c, d = (x[t[:, k]] for k in range(4))
    return np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6


def single_tet(**parts):
    mesh = sdp.MeshData(nodes_per_element=4, coordinates=[0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1], connectivity=[0, 1, 2, 3])
    return sdp.ModelData(mesh=mesh, **parts)


def rich_model():
    """Every part present, with values that are not exact in binary (0.1, 1/3)."""
    mesh = sdp.MeshData(
        nodes_per_element=4,
        coordinates=[0.1, 0, 0, 1 / 3, 0, 0, 0, 1, 0, 0, 0, 1.7],
        connectivity=[0, 1, 2, 3],
        skinning=sdp.SkinningData(weights_per_node=2, indices=[0, 1, 1, 2, 2, 3, 3, 0], weights=[0.3, 0.7] * 4),
    )
    visual = sdp.MeshData(
        nodes_per_element=3,
        coordinates=[0.2, 0.1, 0.1, 0.3, 0.1, 0.1, 0.2, 0.3, 0.1],
        connectivity=[0, 1, 2],
        skinning=sdp.SkinningData(weights_per_node=1, indices=[0, 1, 2], weights=[1, 1, 1]),
    )
    sdf = sdp.GridSdfData(
        dims=sdp.Int3(2, 3, 2),
        values=[0.1 * i - 0.55 for i in range(12)],
        bounds=sdp.Aabb([-1, -1, -1], [1, 2, 3]),
        negative_value_bounds=sdp.Aabb([-0.5, -0.5, -0.5], [0.5, 1, 1.5]),
        scale=[0.5, 0.5, -0.5],
        rotation=sdp.Quaternion(0, 0, math.sin(0.2), math.cos(0.2)),
        translation=[0.1, 0.2, 0.3],
    )
    material = sdp.PerElementSoftMaterialData(
        type=sdp.SoftMaterialType.ACTIVE_NEO_HOOKEAN,
        psd_strategy=sdp.MaterialPsdStrategy.PROJECTION,
        youngs_modulus=[1.1e5],
        poisson_ratio=[0.3],
        aniso_alpha=[100.0],
        aniso_length=[0.9],
        aniso_theta=[0.1],
        aniso_phi=[0.2],
        arap_stiffness=[],
        shape_target_tensor=[],
    )
    return sdp.ModelData(
        mesh=mesh,
        visual_mesh=visual,
        blending=[
            sdp.BlendingData(source_shape="smile", indices=list(range(8)), weights=[0.25] * 8),
            sdp.BlendingData(source_shape="frown", indices=[0] * 8, weights=[0.5] * 8),
        ],
        constrained_nodes=[3, 1],
        element_frame_axes=[0.6, 0.8, 0],
        box=sdp.Box(center=[0.1, 0.2, 0.3], half_extents=[1, 2, 3], rotation=[0, 0, 0.6, 0.8]),
        plane=sdp.Plane(normal=[0, 0.6, 0.8], distance=-0.7),
        sphere=sdp.Sphere(center=[1, 2, 3], radius=0.25),
        sdf=sdf,
        material=material,
    )


# ------------------------------------------------------------------------------ round trips


@pytest.mark.parametrize("fmt", [sdp.FileFormat.JSON, sdp.FileFormat.H5])
def test_every_part_round_trips_exactly(tmp_path, fmt):
    data = rich_model()
    path = tmp_path / "nested" / "dir" / ("m.mochi.json" if fmt == sdp.FileFormat.JSON else "m.mochi.h5")
    model.save_to_file(data, str(path), fmt)  # creates the directories
    back = model.load_from_file_unchecked(str(path))
    assert back == data
    assert model.load_from_bytes_unchecked(path.read_bytes()) == data
    # blend shapes keep their order (H5 stores them as named groups)
    assert [b.source_shape for b in back.blending] == ["smile", "frown"]


@pytest.mark.parametrize("fmt", [sdp.FileFormat.JSON, sdp.FileFormat.H5])
def test_random_reals_round_trip_losslessly(tmp_path, fmt):
    rng = np.random.default_rng(7)
    values = (rng.standard_normal(300) * 10.0 ** rng.integers(-30, 30, 300)).astype(REAL)
    data = sdp.ModelData(mesh=sdp.MeshData(nodes_per_element=3, coordinates=values.tolist(), connectivity=[0, 1, 2]))
    path = tmp_path / ("r.json" if fmt == sdp.FileFormat.JSON else "r.h5")
    model.save_to_file(data, str(path), fmt)
    back = np.array(model.load_from_file_unchecked(str(path)).mesh.coordinates, dtype=REAL)
    assert np.array_equal(back, values)


def test_json_text_uses_camel_case_and_omits_absent_parts():
    data = single_tet(box=sdp.Box())
    text = model.save_to_json_string(data)
    doc = json.loads(text)
    assert set(doc) == {"mesh", "box"}
    assert doc["mesh"] == {"nodesPerElement": 4, "coordinates": [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1], "connectivity": [0, 1, 2, 3]}
    assert doc["box"] == {"center": [0, 0, 0], "halfExtents": [1, 1, 1], "rotation": [0, 0, 0, 1]}
    rich = json.loads(model.save_to_json_string(rich_model()))
    assert set(rich["sdf"]) == {"dims", "values", "bounds", "negativeValueBounds", "scale", "rotation", "translation"}
    assert rich["material"]["type"] == "ActiveNeoHookean" and rich["material"]["psdStrategy"] == "Projection"
    assert rich["material"]["arapStiffness"] == []
    assert rich["visualMesh"]["skinning"] == {"weightsPerNode": 1, "indices": [0, 1, 2], "weights": [1, 1, 1]}
    # a float build writes 0.1f as 0.1, not as its exact binary value
    assert rich["mesh"]["coordinates"][0] == 0.1


def test_h5_layout_matches_the_documented_one(tmp_path):
    h5py = pytest.importorskip("h5py")
    path = tmp_path / "m.mochi.h5"
    model.save_to_file(rich_model(), str(path), sdp.FileFormat.H5)
    with h5py.File(path) as f:
        assert f["mesh/coordinates"].shape == (4, 3) and f["mesh/coordinates"].dtype == REAL
        assert f["mesh/connectivity"].shape == (1, 4) and f["mesh/connectivity"].dtype == np.int32
        assert f["mesh/skinning/weights"].shape == (4, 2)
        assert f["visual_mesh/embedding/indices"].shape == (3, 1)
        assert f["mesh/blending/smile/weights"].shape == (4, 2)
        assert list(f["mesh/constrained_nodes"]) == [3, 1]
        assert f["mesh/element_frame_axes"].shape == (1, 3)
        grid = f["sdf/grid"]
        assert grid.shape == (2, 3, 2)
        # C order, z fastest, against GridSdfData's x-fastest values
        assert grid[1, 2, 0] == REAL(0.1 * (1 + 2 * (2 + 3 * 0)) - 0.55)
        assert list(grid.attrs["collider_max"]) == [0.5, 1, 1.5]
        assert f["material"].attrs["type"] == b"ActiveNeoHookean"
        assert f["material"].attrs["psd_strategy"] == b"Projection"
        assert "arap_stiffness" not in f["material"]
        assert list(f["box"].attrs["half_extents"]) == [1, 2, 3]
        assert float(f["sphere"].attrs["radius"]) == 0.25


def test_h5_files_of_the_older_layout_still_load(tmp_path):
    h5py = pytest.importorskip("h5py")
    path = tmp_path / "old.mochi.h5"
    with h5py.File(path, "w") as f:
        f["mesh/coordinates"] = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
        f["mesh/connectivity"] = np.array([[0, 1, 2, 3]], dtype=np.int32)
        g = f.create_group("sdf")
        g["grid"] = np.zeros((2, 2, 2))
        g.attrs["grid_min"] = [0, 0, 0]
        g.attrs["grid_max"] = [1, 1, 1]
        g.attrs["scale"] = 2.0  # legacy: a scalar for a uniform scale
        m = f.create_group("material")
        m.attrs["type"] = "StVK"  # the short name earlier files used
        m["mu"] = np.array([5.0])
    data = model.load_from_file_unchecked(str(path))
    assert data.sdf.bounds == sdp.Aabb([0, 0, 0], [1, 1, 1])
    assert data.sdf.negative_value_bounds == data.sdf.bounds
    assert list(data.sdf.scale) == [2, 2, 2]
    assert data.material.type == sdp.SoftMaterialType.ST_VENANT_KIRCHHOFF
    assert list(data.material.arap_stiffness) == [5]
    # a mesh without connectivity is a polyline through its nodes
    with h5py.File(tmp_path / "line.mochi.h5", "w") as f:
        f["mesh/coordinates"] = np.array([[0, 0, 0], [1, 0, 0], [2, 1, 0]], dtype=np.float32)
    line = model.load_from_file(str(tmp_path / "line.mochi.h5"))
    assert line.mesh.nodes_per_element == 2 and len(line.mesh.connectivity) == 0


def test_the_deprecated_flat_json_format_loads():
    text = json.dumps({
        "element_size": 4,
        "coordinates": [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1],
        "connectivity": [0, 1, 2, 3],
        "visual_coordinates": [0.1, 0.1, 0.1, 0.2, 0.1, 0.1, 0.1, 0.2, 0.1],
        "visual_connectivity": [0, 1, 2],
        "embedding_weights": [1, 0, 0, 0] * 3,
        "embedding_indices": [0, 1, 2, 3] * 3,
        "constrained_nodes": [2, 0],
        "blending_data": [{"bone_subset": "jaw", "weights": [0.5] * 8, "indices": [0] * 8}],
    })
    data = model.load_from_bytes(text.encode())
    assert data.mesh.nodes_per_element == 4 and data.mesh.get_num_elements() == 1
    assert data.visual_mesh.skinning.weights_per_node == 4
    assert list(data.constrained_nodes) == [0, 2]  # auto_correct sorted them
    assert data.blending[0].source_shape == "jaw"


@pytest.mark.parametrize(
    "text, message",
    [
        ('{"mesh": {"coordinates": [0, "x"]}}', "model bytes (JSON): /mesh/coordinates/1: expected a number, got string"),
        ('{"mesh": {"nodesPerElement": 2.5}}', "/mesh/nodesPerElement: expected an integer, got 2.5"),
        ('{"box": {"rotation": [0, 0, 1]}}', "/box/rotation: expected 4 values, got 3"),
        ('{"material": {"type": "Rubber"}}', "/material/type: unknown name 'Rubber'"),
        ('{"mesh": [1]}', "/mesh: expected an object, got array"),
        ("[1, 2]", "model bytes (JSON): /: expected a JSON object"),
        ('{"mesh": ', "model bytes (JSON): not valid JSON"),
    ],
)
def test_json_errors_name_the_json_path(text, message):
    with pytest.raises(sdp.Error, match=message.replace("(", r"\(").replace(")", r"\)")):
        model.load_from_bytes_unchecked(text.encode())


def test_file_errors_name_the_file(tmp_path):
    bad = tmp_path / "bad.mochi.json"
    bad.write_text('{"mesh": {"connectivity": [0, -1.5]}}')
    with pytest.raises(sdp.Error, match=r"bad\.mochi\.json: /mesh/connectivity/1: expected an integer"):
        model.load_from_file(str(bad))
    with pytest.raises(sdp.Error, match=r"missing\.mochi\.json: file not found"):
        model.load_from_file(str(tmp_path / "missing.mochi.json"))
    with pytest.raises(sdp.Error, match="not an HDF5 file"):
        model.load_from_file(str(bad.rename(tmp_path / "bad.mochi.h5")))
    with pytest.raises(sdp.Error, match=r"no data \(0 bytes\)"):
        model.load_from_bytes(b"")


def test_assets_hold_the_same_cube_in_both_formats():
    json_cube = model.load_from_file(str(ASSETS / "cube" / "cube_mesh.mochi.json"))
    h5_cube = model.load_from_file(str(ASSETS / "cube" / "cube_mesh.mochi.h5"))
    assert json_cube == h5_cube
    assert json_cube.mesh.get_num_elements() == 48 and json_cube.mesh.get_num_nodes() == 27
    assert np.all(tet_volumes(json_cube.mesh) > 0) and math.isclose(tet_volumes(json_cube.mesh).sum(), 1.0, rel_tol=1e-6)


def test_duck_asset_embeds_its_surface_in_the_cage():
    duck = model.load_from_file(str(ASSETS / "duck" / "duck_coarse.mochi.h5"))
    skin = duck.visual_mesh.skinning
    w = np.array(skin.weights, dtype=np.float64).reshape(-1, 4)
    idx = np.array(skin.indices).reshape(-1, 4)
    assert np.all(w >= 0) and np.abs(w.sum(axis=1) - 1).max() < 1e-6
    placed = np.einsum("pk,pkj->pj", w, coords(duck.mesh)[idx])
    assert np.abs(placed - coords(duck.visual_mesh)).max() < 1e-6
    assert np.all(tet_volumes(duck.mesh) > 0)


# ------------------------------------------------------------------------------ validation

def _tri_model(**parts):
    return sdp.ModelData(mesh=sdp.MeshData(nodes_per_element=3, coordinates=[0, 0, 0, 1, 0, 0, 0, 1, 0], connectivity=[0, 1, 2]), **parts)


def _polyline(n=3, closed=False, **parts):
    c = []
    for i in range(n):
        c += [math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n), 0] if closed else [i, 0.1 * i * i, 0]
    conn = [x for i in range(n if closed else n - 1) for x in (i, (i + 1) % n)]
    return sdp.ModelData(mesh=sdp.MeshData(nodes_per_element=2, coordinates=c, connectivity=conn), **parts)


def _set(obj, path, value):
    """obj with the attribute path (dotted) set to value, rebuilding the optional parts it goes through."""
    head, _, rest = path.partition(".")
    if not rest:
        setattr(obj, head, value)
        return obj
    setattr(obj, head, _set(getattr(obj, head), rest, value))
    return obj


def _mesh_case(path, value):
    return lambda: _set(single_tet(), path, value() if callable(value) else value)


def _sdf(**kw):
    args = dict(dims=sdp.Int3(2, 2, 2), values=[1.0] * 8, bounds=sdp.Aabb([0, 0, 0], [1, 1, 1]),
                negative_value_bounds=sdp.Aabb([0.2, 0.2, 0.2], [0.8, 0.8, 0.8]))
    args.update(kw)
    return sdp.GridSdfData(**args)


def _material(**kw):
    args = dict(type=sdp.SoftMaterialType.NEO_HOOKEAN, youngs_modulus=[1e5], poisson_ratio=[0.3])
    args.update(kw)
    return sdp.PerElementSoftMaterialData(**args)


VALIDATION_CASES = [
    # exactly one shape
    (lambda: sdp.ModelData(), "model: must contain exactly one type of shape (mesh, box, plane or sphere), got 0"),
    (lambda: single_tet(box=sdp.Box()), "got 2"),
    # meshes
    (_mesh_case("mesh.nodes_per_element", 5), "mesh.nodes_per_element: must be 2 (polyline), 3 (triangles) or 4 (tetrahedra), got 5"),
    (_mesh_case("mesh.coordinates", [0] * 13), "mesh.coordinates: must hold 3 values per node, got 13"),
    (_mesh_case("mesh.coordinates", [0, 0, 0, 1, 0, 0, 0, 1, 0]), "mesh.coordinates: must hold at least 4 nodes, got 3"),
    (_mesh_case("mesh.coordinates", [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, math.nan]), "mesh.coordinates[11]: must be finite"),
    (_mesh_case("mesh.connectivity", [0, 1, 2]), "mesh.connectivity: must hold 4 values per element, got 3"),
    (_mesh_case("mesh.connectivity", [0, 1, 2, 40]), "mesh.connectivity[3]: node 40 out of range (4 nodes)"),
    (_mesh_case("mesh.skinning", lambda: sdp.SkinningData(weights_per_node=0)), "mesh.skinning.weights_per_node: must be >= 1, got 0"),
    (_mesh_case("mesh.skinning", lambda: sdp.SkinningData(weights_per_node=1, indices=[0] * 4, weights=[1] * 3)),
     "mesh.skinning.weights: must have 4 values (1 per node), got 3"),
    (_mesh_case("mesh.skinning", lambda: sdp.SkinningData(weights_per_node=1, indices=[0] * 3, weights=[1] * 4)),
     "mesh.skinning.indices: must have 4 values (1 per node), got 3"),
    (_mesh_case("mesh.skinning", lambda: sdp.SkinningData(weights_per_node=1, indices=[0] * 4, weights=[1, 1, math.inf, 1])),
     "mesh.skinning.weights[2]: must be finite"),
    (_mesh_case("mesh.skinning", lambda: sdp.SkinningData(weights_per_node=1, indices=[0, 0, -1, 0], weights=[1] * 4)),
     "mesh.skinning.indices[2]: index -1 out of range (must be >= 0)"),
    (_mesh_case("mesh.skinning", lambda: sdp.SkinningData(weights_per_node=2, indices=[0] * 8, weights=[0.5, 0.5, 0.5, 0.6, 1, 0, 0, 1])),
     "mesh.skinning.weights: the weights of node 1 sum to 1.1"),
    # polylines
    (lambda: sdp.ModelData(mesh=sdp.MeshData(nodes_per_element=2, coordinates=[0, 0, 0, 1, 0, 0, 2, 0, 0], connectivity=[0, 1, 2, 1])),
     "mesh.connectivity[2]: segment 1 must be [1, 2], got [2, 1]"),
    (lambda: sdp.ModelData(mesh=sdp.MeshData(nodes_per_element=2, coordinates=[0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0], connectivity=[0, 1, 1, 2])),
     "mesh.connectivity: a polyline's segments join consecutive nodes: expected 6 (open) or 8 (closed) values, got 4"),
    (lambda: sdp.ModelData(mesh=sdp.MeshData(nodes_per_element=2, coordinates=[0, 0, 0, 1, 0, 0], connectivity=[0, 1, 1, 0])),
     "mesh.connectivity: a closed polyline needs at least 3 nodes, got 2"),
    (lambda: sdp.ModelData(mesh=sdp.MeshData(nodes_per_element=2, coordinates=[0, 0, 0, 1e-7, 0, 0])),
     "mesh.coordinates: segment 0 is shorter than 1e-6 m"),
    (lambda: sdp.ModelData(mesh=sdp.MeshData(nodes_per_element=2, coordinates=[0, 0, 0, 1, 0, 0, 0, 0, 0])),
     "mesh.coordinates: segments 0 and 1 fold back onto each other"),
    # visual mesh
    (lambda: _set(single_tet(visual_mesh=sdp.MeshData(nodes_per_element=4, coordinates=[0] * 12, connectivity=[0, 1, 2, 3])), "mesh.nodes_per_element", 4),
     "visual_mesh.nodes_per_element: must be 3 (triangles), got 4"),
    (lambda: single_tet(visual_mesh=sdp.MeshData(nodes_per_element=3, coordinates=[0, 0, 0, 1, 0, 0, 0, 1, 0], connectivity=[0, 1, 2],
                                                 skinning=sdp.SkinningData(weights_per_node=1, indices=[0, 1, 4], weights=[1, 1, 1]))),
     "visual_mesh.skinning.indices[2]: node 4 out of range (4 nodes)"),
    (lambda: _polyline(visual_mesh=sdp.MeshData(nodes_per_element=3, coordinates=[0, 0, 0, 1, 0, 0, 0, 1, 0], connectivity=[0, 1, 2])),
     "visual_mesh.skinning: is required when the simulation mesh is a polyline"),
    (lambda: _polyline(visual_mesh=sdp.MeshData(nodes_per_element=3, coordinates=[0, 0, 0, 1, 0, 0, 0, 1, 0], connectivity=[0, 1, 2],
                                                skinning=sdp.SkinningData(weights_per_node=1, indices=[0, 1, 2], weights=[1, 1, 1]))),
     "visual_mesh.skinning.indices[2]: element 2 out of range (2 elements)"),
    # blending, constrained nodes, frame axes
    (lambda: sdp.ModelData(box=sdp.Box(), blending=[]), "blending: needs a mesh"),
    (lambda: single_tet(blending=[sdp.BlendingData(indices=[0] * 8, weights=[0] * 8)]), "blending[0].source_shape: must not be empty"),
    (lambda: single_tet(blending=[sdp.BlendingData(source_shape="a", indices=[0] * 8, weights=[0] * 7)]),
     "blending[0].weights: must have 8 values (2 per mesh node), got 7"),
    (lambda: single_tet(blending=[sdp.BlendingData(source_shape="a", indices=[0] * 7 + [-2], weights=[0] * 8)]),
     "blending[0].indices[7]: must be >= 0, got -2"),
    (lambda: single_tet(constrained_nodes=[0, 4]), "constrained_nodes[1]: node 4 out of range (4 nodes)"),
    (lambda: sdp.ModelData(sphere=sdp.Sphere(radius=1), constrained_nodes=[]), "constrained_nodes: needs a mesh"),
    (lambda: single_tet(element_frame_axes=[0, 0, 1]), "element_frame_axes: needs a polyline mesh"),
    (lambda: _polyline(element_frame_axes=[0, 0, 1]), "element_frame_axes: must have 6 values (3 per element), got 3"),
    (lambda: _polyline(element_frame_axes=[0, 0, 1, 0, 0, 2]), "element_frame_axes[3]: the axis of element 1 must have length 1"),
    (lambda: _polyline(element_frame_axes=[0, 0, 1, 1, 0, 0]), "element_frame_axes[3]: the axis of element 1 must be normal to the element"),
    # primitives
    (lambda: sdp.ModelData(box=sdp.Box(half_extents=[1, 0, 1])), "box.half_extents[1]: must be positive, got 0"),
    (lambda: sdp.ModelData(box=sdp.Box(center=[0, math.nan, 0])), "box.center[1]: must be finite"),
    (lambda: sdp.ModelData(box=sdp.Box(rotation=[0, 0, 0, 2])), "box.rotation: must be a unit quaternion, its norm is 2"),
    (lambda: sdp.ModelData(plane=sdp.Plane(normal=[0, 0, 2])), "plane.normal: must have length 1, got 2"),
    (lambda: sdp.ModelData(plane=sdp.Plane(distance=math.inf)), "plane.distance: must be finite"),
    (lambda: sdp.ModelData(sphere=sdp.Sphere()), "sphere.radius: must be positive, got 0"),
    # grids
    (lambda: single_tet(sdf=_sdf(dims=sdp.Int3(1, 2, 2), values=[1] * 4)), "sdf.dims: every dimension must be at least 2, got [1, 2, 2]"),
    (lambda: single_tet(sdf=_sdf(values=[1] * 7)), "sdf.values: must have 8 values (dims[0] x dims[1] x dims[2]), got 7"),
    (lambda: single_tet(sdf=_sdf(values=[1] * 7 + [math.nan])), "sdf.values[7]: must be finite"),
    (lambda: single_tet(sdf=_sdf(bounds=sdp.Aabb([0, 0, 0], [1, 0, 1]))), "sdf.bounds: max must exceed min on every axis"),
    (lambda: single_tet(sdf=_sdf(negative_value_bounds=sdp.Aabb([0.5, 0.5, 0.5], [2, 2, 2]))), "sdf.negative_value_bounds: must lie within sdf.bounds"),
    (lambda: single_tet(sdf=_sdf(scale=[1, 0, 1])), "sdf.scale: components must not be zero"),
    (lambda: single_tet(sdf=_sdf(scale=[1, 2, 1])), "sdf.scale: must be uniform in absolute value"),
    (lambda: single_tet(sdf=_sdf(rotation=[0, 0, 0, 0.5])), "sdf.rotation: must be a unit quaternion"),
    (lambda: single_tet(sdf=_sdf(translation=[0, 0, math.inf])), "sdf.translation[2]: must be finite"),
    # materials
    (lambda: sdp.ModelData(box=sdp.Box(), material=_material()), "material: needs a mesh"),
    (lambda: single_tet(material=_material(youngs_modulus=[1e5, 1e5])), "material.youngs_modulus: must have 1 values (1 per element of the mesh), got 2"),
    (lambda: single_tet(material=_material(youngs_modulus=[0])), "material.youngs_modulus[0]: must be in (0, inf), got 0"),
    (lambda: single_tet(material=_material(poisson_ratio=[0.5])), "material.poisson_ratio[0]: must be in (-1, 0.5), got 0.5"),
    (lambda: single_tet(material=_material(psd_strategy=sdp.MaterialPsdStrategy.PER_TERM_PROJECTION)),
     "material.psd_strategy: strategy 5 is not available for material type 0"),
    (lambda: single_tet(material=_material(type=sdp.SoftMaterialType.ARAP, arap_stiffness=[-1])),
     "material.arap_stiffness[0]: must be in (0, inf), got -1"),
    (lambda: single_tet(material=_material(type=sdp.SoftMaterialType.ACTIVE_NEO_HOOKEAN)),
     "material.aniso_alpha: must have 1 values (1 per element of the mesh), got 0"),
    (lambda: single_tet(material=_material(type=sdp.SoftMaterialType.ACTIVE_SHAPE_TARGETING_ARAP, arap_stiffness=[1], shape_target_tensor=[0] * 5)),
     "material.shape_target_tensor: must have 6 values (6 per element of the mesh), got 5"),
]


@pytest.mark.parametrize("make, message", VALIDATION_CASES, ids=[m for _, m in VALIDATION_CASES])
def test_validate_names_the_field_that_breaks_a_rule(make, message):
    data = make()
    with pytest.raises(sdp.Error) as error:
        model.validate(data)
    assert message in str(error.value)


def test_valid_models_pass_validation():
    for data in [cube_model(), _tri_model(), _polyline(), _polyline(4, closed=True), sdp.ModelData(box=sdp.Box()),
                 sdp.ModelData(plane=sdp.Plane()), sdp.ModelData(sphere=sdp.Sphere(radius=1)),
                 single_tet(sdf=_sdf(scale=[2, -2, 2], rotation=[0, 0, 0, 1]), material=_material()),
                 _polyline(element_frame_axes=[0, 0, 1, 0, 0, 1]),
                 sdp.ModelData(mesh=sdp.MeshData(nodes_per_element=2, coordinates=[0, 0, 0, 1, 0, 0, 2, 0, 0]))]:
        model.validate(data)
        model.validate(sdp.ModelDataView(src=data))  # views too


def test_loading_validates_unless_unchecked(tmp_path):
    path = tmp_path / "bad.mochi.json"
    model.save_to_file(single_tet(constrained_nodes=[9]), str(path), sdp.FileFormat.JSON)
    with pytest.raises(sdp.Error, match=r"constrained_nodes\[0\]: node 9 out of range"):
        model.load_from_file(str(path))
    assert list(model.load_from_file_unchecked(str(path)).constrained_nodes) == [9]


# ------------------------------------------------------------------------------ auto_correct


def test_auto_correct_fixes_what_has_one_fix():
    data = single_tet(
        visual_mesh=sdp.MeshData(nodes_per_element=3, coordinates=[0] * 9, connectivity=[]),
        blending=[],
        constrained_nodes=[3, 1, 3, 0],
        box=sdp.Box(rotation=[0, 0, 0, -1]),
        plane=sdp.Plane(normal=[0, 3, 4], distance=2),
        sdf=_sdf(scale=[1, 1, 1], rotation=[0, 0, 0, -1], translation=[0, 0, 0]),
    )
    data.mesh = _set(data.mesh, "skinning", sdp.SkinningData(weights_per_node=2, indices=[0] * 8, weights=[1, 3, 0.5, 0.5, 2, 2, 0.25, 0.25]))
    model.auto_correct(data)
    assert data.visual_mesh is None and data.blending is None
    assert list(data.constrained_nodes) == [0, 1, 3]
    assert list(data.mesh.skinning.weights) == [0.25, 0.75, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5]
    assert data.box.rotation == sdp.Quaternion(0, 0, 0, 1)
    assert list(data.plane.normal) == [0, real(0.6), real(0.8)] and data.plane.distance == 2  # distance unchanged
    assert data.sdf.scale is None and data.sdf.rotation is None and data.sdf.translation is None

    axes = _polyline(element_frame_axes=[0, 0, 2, 0, 0, 1])
    model.auto_correct(axes)
    assert list(axes.element_frame_axes) == [0, 0, 1, 0, 0, 1]
    empty = _polyline(element_frame_axes=[], constrained_nodes=[])
    model.auto_correct(empty)
    assert empty.element_frame_axes is None and empty.constrained_nodes is None
    rotated = single_tet(sdf=_sdf(rotation=[0, 0, 0.6, 0.8 + 1e-3]))
    model.auto_correct(rotated)
    assert abs(np.linalg.norm(list(rotated.sdf.rotation)) - 1) < 1e-6


def test_auto_correct_refuses_weights_summing_to_zero():
    data = single_tet()
    data.mesh = _set(data.mesh, "skinning", sdp.SkinningData(weights_per_node=1, indices=[0] * 4, weights=[1, 0, 1, 1]))
    with pytest.raises(sdp.Error, match="mesh.skinning.weights: the weights of node 1 sum to 0"):
        model.auto_correct(data)


def test_auto_correct_then_validate_accepts_doubled_weights():
    duck = model.load_from_file(str(ASSETS / "duck" / "duck_coarse.mochi.h5"))
    visual = duck.visual_mesh
    skin = visual.skinning
    skin.weights = [2 * w for w in skin.weights]
    visual.skinning = skin
    duck.visual_mesh = visual
    with pytest.raises(sdp.Error, match="visual_mesh.skinning.weights: the weights of node 0 sum to 2"):
        model.validate(duck)
    model.auto_correct(duck)
    model.validate(duck)


# ------------------------------------------------------------------------------ transforms


def test_bake_transform_matches_the_analytic_map():
    src = cube_model()
    x = coords(src.mesh)
    s = np.array([0.5, 2.0, 3.0])
    q = sdp.Quaternion(0, 0, math.sin(math.pi / 4), math.cos(math.pi / 4))  # 90 degrees about z
    t = np.array([1.0, -2.0, 0.5])
    data = sdp.ModelData(src)
    model.bake_transform(data, scale=s.tolist(), rotation=q, translation=t.tolist())
    scaled = x * s
    expected = np.column_stack([-scaled[:, 1], scaled[:, 0], scaled[:, 2]]) + t
    np.testing.assert_allclose(coords(data.mesh), expected, atol=1e-5)
    assert list(data.mesh.connectivity) == list(src.mesh.connectivity)
    # the TransformRT overload does the same
    other = sdp.ModelData(src)
    model.bake_transform(data=other, scale=s.tolist(), transform=sdp.TransformRT(q, t.tolist()))
    assert other == data


def test_a_mirroring_scale_flips_the_winding():
    data = cube_model()
    model.bake_transform(data, scale=[-1, 1, 1])
    assert np.all(tet_volumes(data.mesh) > 0)  # mirrored and re-wound: still positively oriented
    np.testing.assert_array_equal(coords(data.mesh), coords(cube_model().mesh) * [-1, 1, 1])
    assert data.mesh.connectivity != cube_model().mesh.connectivity


def test_bake_transform_of_primitives_axes_and_grids():
    q = sdp.Quaternion(0, 0, math.sin(math.pi / 4), math.cos(math.pi / 4))
    box = sdp.ModelData(box=sdp.Box(center=[1, 0, 0], half_extents=[1, 2, 3]))
    model.bake_transform(box, scale=[2, -1, 1], rotation=q, translation=[0, 0, 1])
    np.testing.assert_allclose(list(box.box.center), [0, 2, 1], atol=1e-6)
    np.testing.assert_allclose(list(box.box.half_extents), [2, 2, 3], atol=1e-6)
    model.validate(box)  # the rotation stayed a proper unit quaternion

    plane = sdp.ModelData(plane=sdp.Plane(normal=[0, 0, 1], distance=1))
    model.bake_transform(plane, scale=[1, 1, 2], translation=[0, 0, 0.5])
    np.testing.assert_allclose(list(plane.plane.normal), [0, 0, 1])
    assert math.isclose(plane.plane.distance, 2.5, rel_tol=1e-6)  # z = 1 -> z = 2 + 0.5
    tilted = sdp.ModelData(plane=sdp.Plane(normal=[math.sqrt(0.5), math.sqrt(0.5), 0], distance=0))
    model.bake_transform(tilted, scale=[2, 1, 1])  # normals take the inverse transpose
    np.testing.assert_allclose(list(tilted.plane.normal), np.array([0.5, 1, 0]) / math.sqrt(1.25), atol=1e-6)

    sphere = sdp.ModelData(sphere=sdp.Sphere(center=[1, 1, 1], radius=0.5))
    model.bake_transform(sphere, scale=[-2, 2, 2])
    assert list(sphere.sphere.center) == [-2, 2, 2] and sphere.sphere.radius == 1
    with pytest.raises(sdp.Error, match="sphere: cannot take a non-uniform scale"):
        model.bake_transform(sphere, scale=[1, 2, 1])
    rotated_box = sdp.ModelData(box=sdp.Box(rotation=q))
    with pytest.raises(sdp.Error, match="box: a rotated box cannot take a non-uniform scale"):
        model.bake_transform(rotated_box, scale=[1, 2, 1])

    line = _polyline(element_frame_axes=[math.sqrt(0.5), -math.sqrt(0.5), 0, 1, 0, 0])
    line.mesh = sdp.MeshData(nodes_per_element=2, coordinates=[0, 0, 0, 1, 1, 0, 1, 1, 1], connectivity=[0, 1, 1, 2])
    model.validate(line)
    model.bake_transform(line, scale=[2, 1, 1])
    model.validate(line)  # still unit and normal to the (sheared) segments
    np.testing.assert_allclose(list(line.element_frame_axes)[:3], np.array([0.5, -1, 0]) / math.sqrt(1.25), atol=1e-6)

    grid = single_tet(sdf=_sdf())
    model.bake_transform(grid, scale=[-2, 2, 2], translation=[1, 0, 0])
    assert list(grid.sdf.scale) == [-2, 2, 2] and grid.sdf.rotation is None and list(grid.sdf.translation) == [1, 0, 0]
    model.validate(grid)
    model.bake_transform(grid, scale=[1, 2, 1])
    assert grid.sdf is None  # a grid cannot stretch


def test_flip_winding_order_negates_volumes_and_undoes_itself():
    src = cube_model()
    data = sdp.ModelData(src)
    model.flip_winding_order(data)
    np.testing.assert_allclose(tet_volumes(data.mesh), -tet_volumes(src.mesh))
    mesh = sdp.MeshData(src.mesh)
    model.flip_winding_order(mesh)
    assert mesh == data.mesh
    model.flip_winding_order(data)
    assert data == src


def test_coordinate_space_conversions_round_trip_exactly():
    src = rich_model()
    src.box = None
    src.plane = None
    engine = sdp.CoordinateSpace.default()
    for axes in sdp.CoordinateSpaceAxes:
        space = sdp.CoordinateSpace(axes=axes, units_per_meter=1)
        data = sdp.ModelData(src)
        model.bake_coordinate_space_transform(data, engine, space)
        # the x axis of the engine (forward) lands where `space` says forward is
        fwd = np.array(list(space.get_forward()))
        np.testing.assert_array_equal(coords(data.mesh)[1], real(1 / 3) * fwd)
        model.bake_coordinate_space_transform(data, space, engine)
        assert data.mesh == src.mesh and data.visual_mesh == src.visual_mesh, axes
        assert list(data.element_frame_axes) == list(src.element_frame_axes)
        assert list(data.sphere.center) == list(src.sphere.center)


def test_unreal_conversion_scales_mirrors_and_rewinds():
    src = cube_model()
    data = sdp.ModelData(src)
    model.bake_coordinate_space_transform(data, sdp.CoordinateSpace.default(), sdp.CoordinateSpace.unreal())
    np.testing.assert_array_equal(coords(data.mesh), coords(src.mesh) * [100, -100, 100])
    assert np.all(tet_volumes(data.mesh) > 0)
    mesh = sdp.MeshData(src.mesh)
    model.bake_coordinate_space_transform(mesh, sdp.CoordinateSpace.default(), sdp.CoordinateSpace.unreal())
    assert mesh == data.mesh
    # Y-up (Unity: x right, y up, z forward) from the engine's Z-up
    up = sdp.ModelData(src)
    model.bake_coordinate_space_transform(up, sdp.CoordinateSpace.default(), sdp.CoordinateSpace.unity())
    x = coords(src.mesh)
    np.testing.assert_array_equal(coords(up.mesh), np.column_stack([-x[:, 1], x[:, 2], x[:, 0]]))
    bad = sdp.CoordinateSpace(axes=sdp.CoordinateSpaceAxes.FLU, units_per_meter=0)
    with pytest.raises(sdp.Error, match="to_space.units_per_meter: must be a positive finite number"):
        model.bake_coordinate_space_transform(data, sdp.CoordinateSpace.default(), bad)


def test_coordinate_space_basics():
    assert sdp.CoordinateSpace() == sdp.CoordinateSpace.default()
    assert sdp.CoordinateSpaceAxes.DEFAULT == sdp.CoordinateSpaceAxes.FLU
    assert len(list(sdp.CoordinateSpaceAxes)) == 48
    assert int(sdp.CoordinateSpaceAxes.RUB) == 336 and int(sdp.CoordinateSpaceAxes.FRU) == 132
    assert list(sdp.CoordinateSpace.default().get_right()) == [0, -1, 0]
    assert list(sdp.CoordinateSpace.open_gl().get_forward()) == [0, 0, -1]
    assert sdp.CoordinateSpace.unreal().units_per_meter == 100
    sdp.CoordinateSpace.filament().validate()
    with pytest.raises(sdp.Error, match="units_per_meter"):
        sdp.CoordinateSpace(units_per_meter=math.nan).validate()


# ------------------------------------------------------------------------------ distance grids


def box_distance(p, half):
    q = np.abs(p) - half
    return np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0)


def test_bake_sdf_of_the_cube_is_the_exact_box_distance():
    data = cube_model()
    model.bake_sdf(data, params=sdp.GridSdfParams(boundary_padding_dist=0.25))
    sdf = data.sdf
    n = np.array(list(sdf.dims))
    lo, hi = np.array(list(sdf.bounds.min)), np.array(list(sdf.bounds.max))
    np.testing.assert_allclose(lo, [-0.75] * 3, atol=1e-6)
    np.testing.assert_allclose(hi, [0.75] * 3, atol=1e-6)
    assert sdf.negative_value_bounds == sdp.Aabb([-0.5] * 3, [0.5] * 3)
    i, j, k = np.meshgrid(*(np.arange(d) for d in n), indexing="ij")
    flat = i + n[0] * (j + n[1] * k)  # values are x fastest
    points = lo + np.stack([i, j, k], axis=-1).reshape(-1, 3) * (hi - lo) / (n - 1)
    values = np.array(sdf.values, dtype=np.float64)[flat.reshape(-1)]
    np.testing.assert_allclose(values, box_distance(points, 0.5), atol=2e-6)
    model.validate(data)
    # the default layout: voxels of a quarter of the mean surface edge, at least 6 per axis
    model.bake_sdf(data)
    mean_edge = 0.5 * (2 + math.sqrt(2)) / 3
    assert list(data.sdf.dims) == [math.ceil(1.01 / (0.25 * mean_edge) - 1e-9) + 1] * 3


def test_bake_sdf_resolution_and_errors():
    data = cube_model()
    model.bake_sdf(data, sdp.GridSdfParams(resolution_mode=sdp.GridSdfResolutionMode.EXPLICIT, resolution_delta=[0.5, 0.1, 1.0],
                                          boundary_padding_dist=0))
    assert list(data.sdf.dims) == [7, 11, 7]  # at least 6 voxels per axis, else 1 m / delta
    tri = _tri_model()
    with pytest.raises(sdp.Error, match="needs a closed mesh"):
        model.bake_sdf(tri)
    with pytest.raises(sdp.Error, match="needs triangles"):
        model.bake_sdf(_polyline())
    with pytest.raises(sdp.Error, match="no mesh"):
        model.bake_sdf(sdp.ModelData(box=sdp.Box()))


# ------------------------------------------------------------------------------ views


def test_views_read_their_source_and_keep_it_alive():
    data = rich_model()
    view = sdp.ModelDataView(src=data)
    assert sdp.ModelData(src=view) == data
    assert view == sdp.ModelDataView(src=sdp.ModelData(data))  # equal contents
    mesh = sdp.MeshData(nodes_per_element=3, coordinates=[0, 0, 0, 1, 0, 0, 0, 1, 0], connectivity=[0, 1, 2])
    mesh_view = sdp.MeshDataView(src=mesh)
    connectivity = mesh_view.connectivity
    assert type(connectivity).__name__ == "SpanConstInt"
    mesh.connectivity[0] = 7
    mesh.nodes_per_element = 2
    assert list(mesh_view.connectivity) == [7, 1, 2] and list(connectivity) == [7, 1, 2] and mesh_view.nodes_per_element == 2
    mesh.connectivity = [5, 6, 7, 8]  # a new array: the view reads it
    assert list(mesh_view.connectivity) == [5, 6, 7, 8]
    del mesh
    gc.collect()
    assert list(mesh_view.connectivity) == [5, 6, 7, 8]  # the view kept its source
    # nested views read into the same source
    mv = view.mesh
    assert isinstance(mv, sdp.MeshDataView) and isinstance(mv.skinning, sdp.SkinningDataView)
    assert list(mv.skinning.indices) == list(data.mesh.skinning.indices)
    assert [b.source_shape for b in view.blending] == ["smile", "frown"]
    assert list(view.constrained_nodes) == [3, 1] and isinstance(view.sdf, sdp.GridSdfDataView)
    assert list(view.material.aniso_phi) == [real(0.2)]
    del data
    gc.collect()
    assert list(mv.coordinates)[0] == real(0.1)


def test_setting_a_view_field_never_writes_the_source():
    skin = sdp.SkinningData(weights_per_node=1, indices=[0, 1], weights=[1, 1])
    view = sdp.SkinningDataView(src=skin)
    view.indices = [4, 5]
    assert list(view.indices) == [4, 5] and list(skin.indices) == [0, 1]
    assert view.weights_per_node == 1 and list(view.weights) == [1, 1]


def test_views_built_field_by_field_and_copies():
    blending = sdp.BlendingDataView(source_shape="s", indices=[1, 2], weights=np.array([0.5, 0.5]))
    assert sdp.BlendingData(src=blending) == sdp.BlendingData(source_shape="s", indices=[1, 2], weights=[0.5, 0.5])
    mesh_view = sdp.MeshDataView(nodes_per_element=3, coordinates=[0, 0, 0], connectivity=[0],
                                 skinning=sdp.SkinningData(weights_per_node=1, indices=[0], weights=[1]))
    assert mesh_view.skinning.weights_per_node == 1
    model_view = sdp.ModelDataView(mesh=mesh_view, box=sdp.Box(), constrained_nodes=[0])
    assert sdp.ModelData(src=model_view).mesh == sdp.MeshData(src=mesh_view)
    for v in (blending, mesh_view, model_view):
        with pytest.raises(TypeError):
            copy.copy(v)
        with pytest.raises(TypeError):
            copy.deepcopy(v)
    owning = sdp.ModelData(src=model_view)
    assert copy.deepcopy(owning) == owning and copy.copy(owning) is not owning
    with pytest.raises(TypeError, match="src must be"):
        sdp.MeshDataView(src=sdp.SkinningData())
    with pytest.raises(TypeError):
        sdp.SkinningDataView(3)  # fields are keyword-only
    with pytest.raises(TypeError):
        sdp.SkinningData(3)
    # an array of views made with a size holds empty views, not dangling ones
    empty = sdp.DynamicArrayBlendingDataView(2)
    assert empty[1].source_shape == "" and len(empty[1].weights) == 0


def test_save_and_validate_take_views(tmp_path):
    data = cube_model()
    view = sdp.ModelDataView(src=data)
    model.save_to_file(view, str(tmp_path / "v.mochi.h5"), sdp.FileFormat.H5)
    assert model.load_from_file(str(tmp_path / "v.mochi.h5")) == data
    assert model.save_to_json_string(view) == model.save_to_json_string(data)


def test_optional_fields_read_back_as_none_and_clear():
    data = rich_model()
    for name in ("mesh", "visual_mesh", "blending", "constrained_nodes", "element_frame_axes", "box", "plane", "sphere", "sdf", "material"):
        assert getattr(data, name) is not None
        setattr(data, name, None)
        assert getattr(data, name) is None
    assert data == sdp.ModelData()


# ------------------------------------------------------------------------------ surface meshes

CUBE_V = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2)]
CUBE_F = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (2, 7, 6), (2, 3, 7), (0, 4, 7), (0, 7, 3), (1, 6, 5), (1, 2, 6)]


def cube_bytes(kind):
    if kind == "OFF":
        lines = ["OFF", "# a comment", f"{len(CUBE_V)} {len(CUBE_F)} 0"] + [" ".join(map(str, v)) for v in CUBE_V]
        lines += [f"3 {a} {b} {c}" for a, b, c in CUBE_F]
    elif kind == "PLY":
        lines = ["ply", "format ascii 1.0", f"element vertex {len(CUBE_V)}", "property float x", "property float y", "property float z",
                 f"element face {len(CUBE_F)}", "property list uchar int vertex_indices", "end_header"]
        lines += [" ".join(map(str, v)) for v in CUBE_V] + [f"3 {a} {b} {c}" for a, b, c in CUBE_F]
    elif kind == "OBJ":
        lines = [f"v {x} {y} {z}" for x, y, z in CUBE_V] + [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in CUBE_F]
    else:  # binary STL
        body = b"".join(struct.pack("<12fH", 0, 0, 0, *CUBE_V[a], *CUBE_V[b], *CUBE_V[c], 0) for a, b, c in CUBE_F)
        return b"\0" * 80 + struct.pack("<I", len(CUBE_F)) + body
    return "\n".join(lines).encode()


@pytest.mark.parametrize("kind", ["OFF", "PLY", "OBJ", "STL"])
def test_surface_meshes_load_from_bytes_and_files(tmp_path, kind):
    fmt = getattr(sdp.MeshFileType, kind)
    data = model.load_from_bytes(cube_bytes(kind), format=fmt)
    assert data.mesh.nodes_per_element == 3
    assert data.mesh.get_num_nodes() == 8 and data.mesh.get_num_elements() == 12
    x = coords(data.mesh)
    tris = [tuple(sorted(tuple(x[i]) for i in tri)) for tri in np.array(data.mesh.connectivity).reshape(-1, 3)]
    assert sorted(tris) == sorted(tuple(sorted(CUBE_V[i] for i in f)) for f in CUBE_F)
    path = tmp_path / f"cube.{kind.lower()}"
    path.write_bytes(cube_bytes(kind))
    assert model.load_from_file(str(path)) == data
    assert model.load_from_bytes_unchecked(cube_bytes(kind), int(fmt)) == data  # the format as an int
    model.bake_sdf(data)  # closed and outward: a distance grid can be made of it
    assert min(data.sdf.values) < 0


def test_off_reader_errors_and_polygons():
    square = b"OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n"
    assert model.load_from_bytes(square, sdp.MeshFileType.OFF).mesh.get_num_elements() == 2  # fan-triangulated
    with pytest.raises(sdp.Error, match=r"model bytes \(OFF\):6: face index 9 out of range: the file has 3 vertices"):
        model.load_from_bytes(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n", sdp.MeshFileType.OFF)
    with pytest.raises(sdp.Error, match="malformed number 'x'"):
        model.load_from_bytes(b"OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", sdp.MeshFileType.OFF)
    with pytest.raises(sdp.Error, match="more than the file holds"):
        model.load_from_bytes(b"OFF\n300000 1 0\n0 0 0\n", sdp.MeshFileType.OFF)


def test_load_from_bytes_tells_hdf5_from_json(tmp_path):
    cube = cube_model()
    for fmt, name in [(sdp.FileFormat.H5, "c.h5"), (sdp.FileFormat.JSON, "c.json")]:
        model.save_to_file(cube, str(tmp_path / name), fmt)
        raw = (tmp_path / name).read_bytes()
        assert model.load_from_bytes(raw) == cube
        assert model.load_from_bytes(bytearray(raw), sdp.MeshFileType.LEGACY) == cube
    assert model.load_from_bytes(model.save_to_json_string(cube)) == cube  # str is taken as UTF-8


def test_every_axes_value_matches_its_name():
    names = {"R": (0, 1), "L": (0, -1), "U": (1, 1), "D": (1, -1), "F": (2, 1), "B": (2, -1)}
    for axes in sdp.CoordinateSpaceAxes:
        space = sdp.CoordinateSpace(axes=axes)
        right, up, forward = (np.array(list(v)) for v in (space.get_right(), space.get_up(), space.get_forward()))
        for axis, letter in enumerate(axes.name):
            line, sign = names[letter]
            direction = [right, up, forward][line] * sign
            assert direction[axis] == 1, (axes.name, letter)
    for a, b in itertools.combinations(["RUF", "RUB", "FLU", "FRU"], 2):
        assert getattr(sdp.CoordinateSpaceAxes, a) != getattr(sdp.CoordinateSpaceAxes, b)
