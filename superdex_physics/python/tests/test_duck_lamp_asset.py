"""The committed duck-lamp asset (assets/prefabs/duck_lamp/), checked as files with h5py and json,
without the engine: a valid, well-shaped tetrahedral mesh of the right size, placed where the
seed's arm presses into it, with its material and a prefab that names it.

Regenerate the asset with `uv run --group tools python tools/build_duck_lamp.py`."""

import json
from pathlib import Path

import h5py
import numpy as np
import pytest

ASSET_DIR = Path(__file__).resolve().parents[3] / "assets" / "prefabs" / "duck_lamp"
H5_PATH = ASSET_DIR / "duck_lamp_body.mochi.h5"
PREFAB_PATH = ASSET_DIR / "duck_lamp_recumbent.mochi_prefab"

# The seed's end-effector circle: centre (-0.30, 0.15) in X-Z, radius 0.08 m.
PATH_CENTRE_X, PATH_CENTRE_Z, PATH_RADIUS = -0.30, 0.15, 0.08
PATH_LOWEST = np.array([PATH_CENTRE_X, 0.0, PATH_CENTRE_Z - PATH_RADIUS])  # z = 0.07

MIN_TET_VOLUME = 1e-10  # m^3 (0.1 mm^3); a 7 mm regular tet is about 4e-8 m^3


@pytest.fixture(scope="module")
def h5():
    with h5py.File(H5_PATH, "r") as f:
        yield {
            "nodes": f["mesh/coordinates"][()],
            "tets": f["mesh/connectivity"][()].astype(np.int64),
            "constrained": f["mesh/constrained_nodes"][()].astype(np.int64),
            "vis_nodes": f["visual_mesh/coordinates"][()],
            "vis_tris": f["visual_mesh/connectivity"][()].astype(np.int64),
            "vis_node_indices": f["visual_mesh/node_indices"][()].astype(np.int64),
            "material_type": f["material"].attrs["type"],
            "youngs": f["material/youngs_modulus"][()],
            "poisson": f["material/poisson_ratio"][()],
        }


@pytest.fixture(scope="module")
def prefab():
    return json.loads(PREFAB_PATH.read_text())


@pytest.fixture(scope="module")
def actor(prefab):
    soft = prefab["actors"]["soft"]
    assert len(soft) == 1
    return soft[0]


def world(actor, points):
    xf = actor["worldFromLocal"]
    assert xf["rotation"] == [0, 0, 0, 1], "the test assumes an unrotated actor"
    return points + np.asarray(xf["translation"], dtype=np.float64)


def signed_volumes(nodes, tets):
    a, b, c, d = (nodes[tets[:, k]] for k in range(4))
    return np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a) / 6.0


def boundary_faces(tets):
    """Faces used by one tet only, outward for positively oriented tets."""
    local = np.array([(1, 2, 3), (0, 3, 2), (0, 1, 3), (0, 2, 1)])
    faces = tets[:, local].reshape(-1, 3)
    _, inverse, counts = np.unique(np.sort(faces, axis=1), axis=0, return_inverse=True, return_counts=True)
    return faces[counts[inverse.reshape(-1)] == 1]


def top_height(nodes, tris, x, y):
    """Highest point of the triangulated surface straight above (x, y), or -inf."""
    a, b, c = nodes[tris[:, 0]], nodes[tris[:, 1]], nodes[tris[:, 2]]
    e1, e2, r = (b - a)[:, :2], (c - a)[:, :2], np.array([x, y]) - a[:, :2]
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    ok = np.abs(det) > 1e-18
    s = np.where(ok, (r[:, 0] * e2[:, 1] - r[:, 1] * e2[:, 0]) / np.where(ok, det, 1), -1)
    t = np.where(ok, (e1[:, 0] * r[:, 1] - e1[:, 1] * r[:, 0]) / np.where(ok, det, 1), -1)
    hit = ok & (s >= 0) & (t >= 0) & (s + t <= 1)
    z = a[:, 2] + s * (b - a)[:, 2] + t * (c - a)[:, 2]
    return float(z[hit].max()) if hit.any() else -np.inf


def test_tet_mesh_is_valid_and_positively_oriented(h5):
    nodes, tets = h5["nodes"], h5["tets"]
    assert nodes.ndim == 2 and nodes.shape[1] == 3 and nodes.dtype == np.float64
    assert tets.ndim == 2 and tets.shape[1] == 4
    assert 1000 <= len(tets) <= 5000
    assert tets.min() >= 0 and tets.max() < len(nodes)
    assert len(np.unique(tets)) == len(nodes), "unused nodes"
    assert np.all(np.isfinite(nodes))
    vol = signed_volumes(nodes, tets)
    assert np.all(vol > MIN_TET_VOLUME), f"{np.sum(vol <= MIN_TET_VOLUME)} inverted or degenerate tets, min {vol.min():.3e}"


def test_surface_is_closed_outward_and_matches_the_tets(h5):
    nodes, tets = h5["nodes"], h5["tets"]
    tris = h5["vis_tris"]
    vis = h5["vis_nodes"]
    assert tris.shape[1] == 3 and tris.min() >= 0 and tris.max() < len(vis)
    # closed and consistently oriented: every undirected edge in exactly two triangles, every
    # directed edge once
    directed = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    _, counts = np.unique(np.sort(directed, axis=1), axis=0, return_counts=True)
    assert np.all(counts == 2), "surface has open or non-manifold edges"
    assert len(np.unique(directed, axis=0)) == len(directed), "surface orientation is inconsistent"
    # outward: the enclosed volume is positive and equals the tets' total volume
    a, b, c = vis[tris[:, 0]], vis[tris[:, 1]], vis[tris[:, 2]]
    enclosed = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0
    total = signed_volumes(nodes, tets).sum()
    assert enclosed > 0 and enclosed == pytest.approx(total, rel=1e-9)
    # the visual mesh is the tet mesh's boundary (node_indices maps its vertices to mesh nodes)
    idx = h5["vis_node_indices"]
    np.testing.assert_array_equal(vis, nodes[idx])
    mapped = {tuple(np.roll(f, -np.argmin(f))) for f in idx[tris].tolist()}
    boundary = {tuple(np.roll(f, -np.argmin(f))) for f in boundary_faces(tets).tolist()}
    assert mapped == boundary


def test_dimensions_and_placement(h5, actor):
    p = world(actor, h5["nodes"])
    lo, hi = p.min(axis=0), p.max(axis=0)
    assert 0.12 <= hi[0] - lo[0] <= 0.16, f"length {hi[0] - lo[0]:.4f} m"
    assert lo[2] == 0.0, "the duck rests on the ground: its lowest nodes are at z = 0"
    assert 0.06 <= hi[2] <= 0.08, f"top height {hi[2]:.4f} m"
    assert (lo[0] + hi[0]) / 2 == pytest.approx(-0.30, abs=0.01)
    assert (lo[1] + hi[1]) / 2 == pytest.approx(0.0, abs=0.005)
    # a flat belly: a real footprint on the ground, so it rests stably
    bottom = p[p[:, 2] == 0.0]
    assert len(bottom) >= 20
    assert np.ptp(bottom[:, 0]) > 0.05 and np.ptp(bottom[:, 1]) > 0.04


def test_seed_path_presses_into_the_top(h5, actor):
    tris = boundary_faces(h5["tets"])
    p = world(actor, h5["nodes"])
    top = top_height(p, tris, PATH_LOWEST[0], PATH_LOWEST[1])
    # the path's lowest point is inside the duck, or at most 5 mm above its top: the arm reaches it
    assert top >= PATH_LOWEST[2] - 0.005, f"top surface at z = {top:.4f}, the path only goes down to 0.07"
    # and not absurdly deep (it presses into the back, it does not dive through the duck)
    assert top <= PATH_LOWEST[2] + 0.015
    # along the lower arc the path dips into the duck only over its back, by at most 15 mm: it does
    # not run into the head or the tail
    for theta in np.linspace(np.pi * 1.05, np.pi * 1.95, 73):
        x = PATH_CENTRE_X + PATH_RADIUS * np.cos(theta)
        z = PATH_CENTRE_Z + PATH_RADIUS * np.sin(theta)
        depth = top_height(p, tris, x, 0.0) - z
        assert depth <= 0.015, f"path {depth * 1000:.1f} mm deep at x = {x:.3f}"
        if depth > 0:
            assert abs(x - PATH_CENTRE_X) < 0.03, f"path enters the duck at x = {x:.3f}, away from its back"


def test_bottom_nodes_and_fixed_region(h5, actor):
    nodes, constrained = h5["nodes"], h5["constrained"]
    assert len(constrained) >= 3
    assert np.all(nodes[constrained, 2] <= 1e-3)
    np.testing.assert_array_equal(np.sort(constrained), np.flatnonzero(nodes[:, 2] <= 1e-3))
    region = actor["fixedRegion"]
    lo, hi = np.asarray(region["min"]), np.asarray(region["max"])
    inside = np.all((nodes >= lo) & (nodes <= hi), axis=1)
    # fixedRegion (an AABB in the actor's local frame) pins exactly the bottom layer
    np.testing.assert_array_equal(np.flatnonzero(inside), np.sort(constrained))


def test_material(h5, actor):
    mtype = h5["material_type"]
    mtype = mtype.decode() if isinstance(mtype, bytes) else str(mtype)
    assert mtype == "NeoHookean"
    m = len(h5["tets"])
    assert h5["youngs"].shape == (m,) and h5["poisson"].shape == (m,)
    assert np.all((h5["youngs"] >= 5e4) & (h5["youngs"] <= 2e5)), "silicone-like: 50-200 kPa"
    assert np.all((h5["poisson"] > 0) & (h5["poisson"] < 0.5))
    mat = actor["material"]
    assert mat["type"] == "NeoHookean"
    assert mat["youngsModulus"] == pytest.approx(float(h5["youngs"][0]))
    assert mat["poissonRatio"] == pytest.approx(float(h5["poisson"][0]))
    assert mat["density"] > 0 and mat["damping"] >= 0


def test_prefab_names_the_shape_file(prefab, actor):
    assert set(prefab) >= {"actors", "constraints", "prefabs", "scene"}
    assert set(prefab["actors"]) == {"rigid", "soft", "articulated"}
    assert prefab["actors"]["rigid"] == [] and prefab["actors"]["articulated"] == []
    assert actor["name"] == "duck_lamp"
    shape = actor["shape"]
    assert shape.startswith("./") and ".." not in shape
    assert (PREFAB_PATH.parent / shape).resolve() == H5_PATH.resolve() and H5_PATH.is_file()
    assert actor["worldFromLocal"]["translation"] == pytest.approx([-0.30, 0.0, 0.0])
    assert actor["contact"]["coulombFrictionCoefficient"] > 0
    assert prefab["scene"]["gravity"] == [0, 0, -9.81]


def test_full_prefab_is_the_seed_prefab_without_the_reduction(prefab):
    """The seed's prefab makes the duck a reduced soft body; its _full twin is the same prop as a
    full nonlinear finite-element model."""
    full = json.loads((ASSET_DIR / "duck_lamp_recumbent_full.mochi_prefab").read_text())
    reduced = json.loads(json.dumps(prefab))
    assert reduced["actors"]["soft"][0]["material"].pop("reducedModes") > 0
    assert "reducedModes" not in full["actors"]["soft"][0]["material"]
    assert full == reduced
