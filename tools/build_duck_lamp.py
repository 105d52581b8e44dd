#!/usr/bin/env python3
"""Generate the duck-lamp soft-body asset (assets/prefabs/duck_lamp/) deterministically.

A recumbent ("lying flat") duck lamp: a loaf-shaped body (a box with 14 mm rounded edges) with a
flat back, folded wings, and a round head resting forward low over the ground with a flat beak (both
ellipsoids), joined by smooth unions into one implicit function and cut flat by the ground plane
z = 0 (a small fillet rounds the rim), so that it rests stably on its belly. The back is flat
(z = 0.066 m) over the 8 cm the seed's ball slides along under force control: on a domed back the
seed's admittance law (k_f = 0.05 (m/s)/N) cannot follow the slope at the circle's 0.17 m/s without
losing the force setpoint. No
third-party geometry is used. The pipeline:

1. sample the implicit function on a grid and extract its zero level set (marching cubes,
   scikit-image);
2. clean the surface: weld duplicate vertices, drop degenerate triangles, then relax the vertices
   tangentially and project them back onto the implicit surface (even spacing, shape kept);
3. tetrahedralize the closed surface with TetGen (the `tetgen` package from PyPI), quality mode;
4. improve the worst tets: remove flat "ear" tets that have two faces on the boundary, then
   smooth nodes (interior nodes freely, boundary nodes on the implicit surface) where that raises
   the smallest dihedral angle; the connectivity TetGen made is otherwise kept;
5. check the result (every tetrahedron positively oriented with volume above a threshold, angles,
   closed outward boundary, dimensions, the seed arm's path reaching the top) and write
   `duck_lamp_body.mochi.h5` and `duck_lamp_recumbent.mochi_prefab`.

Deterministic: no randomness anywhere; two runs on one machine give byte-identical files (the
.mochi.h5 is written without timestamps). Other CPUs or library versions may round differently
and so give a slightly different (equally valid) mesh: that is why the outputs are committed.

The mesh is stored in a local frame centred on the duck (bounding box centred at x = y = 0,
bottom at z = 0, beak towards -x); the prefab places it at (-0.30, 0, 0) in the world.

Regenerate (the outputs are committed; users never need the tools group):

    uv run --group tools python tools/build_duck_lamp.py [--render /tmp/duck.png]
"""

from __future__ import annotations

import argparse
import hashlib
import json
import re
import sys
from pathlib import Path

import h5py
import numpy as np

REPO = Path(__file__).resolve().parents[1]
OUT_DIR = REPO / "assets" / "prefabs" / "duck_lamp"
H5_NAME = "duck_lamp_body.mochi.h5"
PREFAB_NAME = "duck_lamp_recumbent.mochi_prefab"  # reduced: the seed's prop
FULL_PREFAB_NAME = "duck_lamp_recumbent_full.mochi_prefab"  # the full nonlinear finite-element model
# The seed's prefab makes the duck a reduced soft body (linear about its rest shape, in this many
# vibration modes plus the static correction): its dents under the seed's 0.5-2 N are about 1 mm
# in a 66 mm body, where linear elasticity holds, and it steps about 100 times faster.
REDUCED_MODES = 24

# Placement of the duck in the prefab (world) frame: the seed's end-effector circle has its centre
# at (-0.30, 0.15) in X-Z and radius 0.08 m, so its lowest point is (-0.30, 0, 0.07).
WORLD_TRANSLATION = (-0.30, 0.0, 0.0)
PATH_LOWEST_POINT_LOCAL = np.array([0.0, 0.0, 0.07])

# Material: silicone-like, soft enough to dent visibly under 0.5-2 N.
YOUNGS_MODULUS = 1.0e5  # Pa
POISSON_RATIO = 0.45
DENSITY = 1100.0  # kg/m^3
DAMPING = 0.01
FRICTION = 0.8

# Bottom layer: nodes within this height of the ground are the .h5's constrained_nodes, and the
# prefab's fixedRegion (an AABB in the local frame) pins exactly these nodes.
CONSTRAINED_HEIGHT = 1.0e-3  # m
FIXED_REGION_MIN = (-0.1, -0.1, -0.001)
FIXED_REGION_MAX = (0.1, 0.1, CONSTRAINED_HEIGHT)

# Meshing parameters.
GRID_SPACING = 0.007  # m, marching-cubes cell (sets the surface edge length, hence the tet count)
RELAX_ITERATIONS = 30
TETGEN_MINRATIO = 2.0  # radius-edge ratio bound
TETGEN_MINDIHEDRAL = 10.0  # degrees (TetGen's target; the smoothing pass below goes further)
TETGEN_OPT_MAXDIHEDRAL = 165.0  # degrees, TetGen's mesh-optimisation target
TETGEN_OPT_ITERATIONS = 10
SMOOTH_SWEEPS = 8  # quality-improving node smoothing sweeps after TetGen
EAR_QUALITY = 25.0  # degrees: flat tets with two boundary faces below this quality are removed
MIN_TET_VOLUME = 1.0e-10  # m^3 (0.1 mm^3); asserted lower bound on every tet volume
MIN_DIHEDRAL = 15.0  # degrees; asserted lower bound on every dihedral angle (upper: 180 - this)

# --------------------------------------------------------------------------------------------
# The implicit shape (metres, local frame before centring; negative inside)
# --------------------------------------------------------------------------------------------

# name: centre, semi-axes, pitch (degrees, rotation about +y: positive tips the +x end down),
# blend radius of the smooth union with the parts before it. Mirror pairs have y = +-.
PARTS = [
    ("head", (-0.038, 0.000, 0.028), (0.024, 0.025, 0.025), 0.0, 0.0),
    ("beak", (-0.063, 0.000, 0.014), (0.016, 0.017, 0.007), 8.0, 0.006),
    ("wing_left", (0.029, 0.030, 0.036), (0.034, 0.012, 0.020), -6.0, 0.006),
    ("wing_right", (0.029, -0.030, 0.036), (0.034, 0.012, 0.020), -6.0, 0.006),
]
# the body: a rounded box whose flat back (z = 0.066) the seed's ball slides along under force control
BODY_CENTRE, BODY_HALF, BODY_ROUNDING, BODY_BLEND = (0.027, 0.0, 0.026), (0.052, 0.036, 0.040), 0.014, 0.008
GROUND_FILLET = 0.005  # m, blend radius of the cut with the ground plane


def sd_ellipsoid(p: np.ndarray, centre, radii, pitch_deg: float = 0.0) -> np.ndarray:
    """Approximate signed distance to an ellipsoid pitched about +y (Quilez' bound), p: (..., 3)."""
    r = np.asarray(radii, dtype=np.float64)
    q = p - np.asarray(centre, dtype=np.float64)
    if pitch_deg:
        a = np.radians(pitch_deg)
        c, s = np.cos(a), np.sin(a)
        # into the ellipsoid's frame (rotate by -pitch about y)
        q = np.stack([c * q[..., 0] - s * q[..., 2], q[..., 1], s * q[..., 0] + c * q[..., 2]], axis=-1)
    k0 = np.linalg.norm(q / r, axis=-1)
    k1 = np.linalg.norm(q / (r * r), axis=-1)
    k1 = np.maximum(k1, 1e-12)
    return k0 * (k0 - 1.0) / k1


def smooth_min(a: np.ndarray, b: np.ndarray, k: float) -> np.ndarray:
    if k <= 0:
        return np.minimum(a, b)
    h = np.maximum(k - np.abs(a - b), 0.0) / k
    return np.minimum(a, b) - h * h * k * 0.25


def smooth_max(a: np.ndarray, b: np.ndarray, k: float) -> np.ndarray:
    return -smooth_min(-a, -b, k)


def sd_round_box(p: np.ndarray, centre, half, rounding: float) -> np.ndarray:
    """Signed distance to a box with rounded edges (exact)."""
    q = np.abs(p - np.asarray(centre)) - np.asarray(half) + rounding
    outside = np.linalg.norm(np.maximum(q, 0.0), axis=-1)
    inside = np.minimum(np.max(q, axis=-1), 0.0)
    return outside + inside - rounding


def duck_sdf(p: np.ndarray) -> np.ndarray:
    f = sd_round_box(p, BODY_CENTRE, BODY_HALF, BODY_ROUNDING)
    for _name, centre, radii, pitch, blend in PARTS:
        f = smooth_min(f, sd_ellipsoid(p, centre, radii, pitch), blend or BODY_BLEND)
    return smooth_max(f, -p[..., 2], GROUND_FILLET)  # keep z >= 0: flat belly on the ground


def sdf_gradient(p: np.ndarray, eps: float = 1e-6) -> np.ndarray:
    g = np.empty_like(p)
    for axis in range(3):
        d = np.zeros(3)
        d[axis] = eps
        g[:, axis] = (duck_sdf(p + d) - duck_sdf(p - d)) / (2 * eps)
    return g


def project_to_surface(p: np.ndarray, iterations: int = 8) -> np.ndarray:
    """Newton steps along the gradient onto the zero level set."""
    p = p.copy()
    for _ in range(iterations):
        f = duck_sdf(p)
        g = sdf_gradient(p)
        g2 = np.maximum(np.einsum("ij,ij->i", g, g), 1e-12)
        p -= (f / g2)[:, None] * g
    return p


# --------------------------------------------------------------------------------------------
# Surface extraction and cleaning
# --------------------------------------------------------------------------------------------


def extract_surface(h: float) -> tuple[np.ndarray, np.ndarray]:
    from skimage.measure import marching_cubes

    lo = np.array([-0.095, -0.060, -0.5 * h - 2 * h])  # z = 0 lies mid-cell: no vertex on a node
    hi = np.array([0.095, 0.060, 0.095])
    n = np.ceil((hi - lo) / h).astype(int) + 1
    axes = [lo[i] + h * np.arange(n[i]) for i in range(3)]
    X, Y, Z = np.meshgrid(*axes, indexing="ij")
    field = duck_sdf(np.stack([X, Y, Z], axis=-1))
    # the shape must not touch the grid boundary, or the surface would be open
    assert field[0].min() > 0 and field[-1].min() > 0 and field[:, 0].min() > 0 and field[:, -1].min() > 0
    assert field[:, :, 0].min() > 0 and field[:, :, -1].min() > 0
    verts, faces, _normals, _values = marching_cubes(field, level=0.0, spacing=(h, h, h), allow_degenerate=False)
    verts = verts.astype(np.float64) + lo
    return verts, faces.astype(np.int64)


def weld(verts: np.ndarray, faces: np.ndarray, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """Merge vertices closer than `tol` (grid snapping), drop degenerate and unused entries."""
    key = np.round(verts / tol).astype(np.int64)
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.reshape(-1)
    faces = inverse[faces]
    verts = verts[first]
    ok = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 0] != faces[:, 2])
    faces = faces[ok]
    used = np.unique(faces)
    remap = -np.ones(len(verts), dtype=np.int64)
    remap[used] = np.arange(len(used))
    return verts[used], remap[faces]


def edge_counts(faces: np.ndarray) -> dict:
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    und = np.sort(e, axis=1)
    uniq, counts = np.unique(und, axis=0, return_counts=True)
    directed = {tuple(x) for x in e.tolist()}
    return {"edges": uniq, "counts": counts, "consistent": len(directed) == len(e)}


def closed_volume(verts: np.ndarray, faces: np.ndarray) -> float:
    a, b, c = verts[faces[:, 0]], verts[faces[:, 1]], verts[faces[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def relax(verts: np.ndarray, faces: np.ndarray, iterations: int) -> np.ndarray:
    """Tangential Laplacian relaxation with projection back onto the implicit surface."""
    n = len(verts)
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    e = np.unique(np.sort(e, axis=1), axis=0)
    i, j = np.concatenate([e[:, 0], e[:, 1]]), np.concatenate([e[:, 1], e[:, 0]])
    degree = np.bincount(i, minlength=n).astype(np.float64)
    v = verts.copy()
    for _ in range(iterations):
        centroid = np.zeros_like(v)
        np.add.at(centroid, i, v[j])
        centroid /= degree[:, None]
        g = sdf_gradient(v)
        nrm = g / np.maximum(np.linalg.norm(g, axis=1), 1e-12)[:, None]
        d = centroid - v
        d -= np.einsum("ij,ij->i", d, nrm)[:, None] * nrm
        v = project_to_surface(v + 0.5 * d, iterations=4)
    return project_to_surface(v)


def triangle_quality(verts: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """4*sqrt(3)*area / sum(edge^2): 1 for equilateral, 0 for degenerate."""
    a, b, c = verts[faces[:, 0]], verts[faces[:, 1]], verts[faces[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    s = ((b - a) ** 2).sum(1) + ((c - b) ** 2).sum(1) + ((a - c) ** 2).sum(1)
    return 4.0 * np.sqrt(3.0) * area / s


# --------------------------------------------------------------------------------------------
# Tetrahedral mesh
# --------------------------------------------------------------------------------------------


def signed_volumes(nodes: np.ndarray, tets: np.ndarray) -> np.ndarray:
    a, b, c, d = (nodes[tets[:, k]] for k in range(4))
    return np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a) / 6.0


def dihedral_angles(nodes: np.ndarray, tets: np.ndarray) -> np.ndarray:
    """The six interior dihedral angles of every tet, in degrees, shape (M, 6)."""
    p = [nodes[tets[:, k]] for k in range(4)]
    # face k is opposite vertex k; its outward normal
    faces = [(1, 2, 3), (0, 3, 2), (0, 1, 3), (0, 2, 1)]
    normals = []
    for f in faces:
        n = np.cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]])
        normals.append(n / np.linalg.norm(n, axis=1)[:, None])
    out = []
    for a in range(4):
        for b in range(a + 1, 4):
            cosang = -np.einsum("ij,ij->i", normals[a], normals[b])
            out.append(np.degrees(np.arccos(np.clip(cosang, -1.0, 1.0))))
    return np.stack(out, axis=1)


def radius_ratio(nodes: np.ndarray, tets: np.ndarray) -> np.ndarray:
    """3 * inradius / circumradius: 1 for the regular tet, 0 for degenerate."""
    a, b, c, d = (nodes[tets[:, k]] for k in range(4))
    vol = np.abs(signed_volumes(nodes, tets))
    area = sum(
        0.5 * np.linalg.norm(np.cross(q - p, r - p), axis=1) for p, q, r in ((b, c, d), (a, c, d), (a, b, d), (a, b, c))
    )
    inr = 3.0 * vol / area
    # circumradius: |l1^2 (u2 x u3) + l2^2 (u3 x u1) + l3^2 (u1 x u2)| / (12 V) with u = edges from a
    u1, u2, u3 = b - a, c - a, d - a
    num = (
        (u1**2).sum(1)[:, None] * np.cross(u2, u3)
        + (u2**2).sum(1)[:, None] * np.cross(u3, u1)
        + (u3**2).sum(1)[:, None] * np.cross(u1, u2)
    )
    circ = np.linalg.norm(num, axis=1) / (12.0 * vol)
    return 3.0 * inr / circ


def boundary_faces(tets: np.ndarray) -> np.ndarray:
    """Faces used by exactly one tet, oriented outward (counter-clockwise seen from outside)."""
    local = np.array([(1, 2, 3), (0, 3, 2), (0, 1, 3), (0, 2, 1)])  # outward for det > 0
    faces = tets[:, local].reshape(-1, 3)
    key = np.sort(faces, axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return faces[counts[inverse.reshape(-1)] == 1]


def tetrahedralize(verts: np.ndarray, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    import tetgen

    tg = tetgen.TetGen(verts, faces.astype(np.int32))
    nodes, tets = tg.tetrahedralize(
        quality=True,
        minratio=TETGEN_MINRATIO,
        mindihedral=TETGEN_MINDIHEDRAL,
        optmaxdihedral=TETGEN_OPT_MAXDIHEDRAL,
        opt_iterations=TETGEN_OPT_ITERATIONS,
        steinerleft=100000,
        quiet=True,
    )[:2]
    return np.asarray(nodes, dtype=np.float64), np.asarray(tets, dtype=np.int64)


def tet_quality(nodes: np.ndarray, tets: np.ndarray) -> np.ndarray:
    """Per tet: the smaller of its smallest dihedral angle and 180 deg minus its largest (degrees);
    small for slivers, needles and caps alike (70.5 for the regular tet)."""
    d = dihedral_angles(nodes, tets)
    return np.minimum(d.min(axis=1), 180.0 - d.max(axis=1))


def remove_boundary_ears(nodes: np.ndarray, tets: np.ndarray, threshold: float) -> tuple[np.ndarray, np.ndarray, int]:
    """Remove flat tets that have two faces on the boundary (a thin "ear" across a sharply curved
    part of the surface; smoothing cannot fix them, since all four nodes are on the surface).
    Removing one exposes its other two faces; it is only done where the surface stays a closed
    2-manifold (the newly exposed edge is not already on the boundary)."""
    removed = 0
    while True:
        tri = boundary_faces(tets)
        boundary_keys = {tuple(f) for f in np.sort(tri, axis=1).tolist()}
        boundary_edges = {tuple(e) for e in edge_counts(tri)["edges"].tolist()}
        q = tet_quality(nodes, tets)
        drop = None
        for k in np.argsort(q, kind="stable"):
            if q[k] >= threshold:
                break
            t = tets[k].tolist()
            faces = [tuple(sorted(t[i] for i in range(4) if i != j)) for j in range(4)]  # face j: opposite node j
            on_b = [f in boundary_keys for f in faces]
            if sum(on_b) != 2:
                continue
            # the exposed edge joins the two nodes opposite the boundary faces
            a, b = sorted(t[j] for j in range(4) if on_b[j])
            if (a, b) in boundary_edges:
                continue
            drop = k
            break
        if drop is None:
            break
        tets = np.delete(tets, drop, axis=0)
        removed += 1
    used = np.unique(tets)
    assert len(used) == len(nodes), "removing an ear tet orphaned a node"
    return nodes, tets, removed


def improve_tets(nodes: np.ndarray, tets: np.ndarray, sweeps: int) -> np.ndarray:
    """Quality-improving node smoothing: TetGen leaves a few slivers (dihedral angles of a few
    degrees). Each sweep visits the nodes of the worst tets and moves a node to the best of a few
    candidate positions (towards its neighbours' centroid, or along the numerical gradient of the
    smallest dihedral angle of its tets) if that raises the smallest dihedral angle of its tets and
    keeps them all positive. Boundary nodes move too, but are projected back onto the implicit
    surface (bottom nodes stay on z = 0). The connectivity does not change."""
    nodes = nodes.copy()
    tri = boundary_faces(tets)
    on_boundary = np.zeros(len(nodes), dtype=bool)
    on_boundary[np.unique(tri)] = True
    incident: list[list[int]] = [[] for _ in range(len(nodes))]
    for k, tet in enumerate(tets.tolist()):
        for v in tet:
            incident[v].append(k)
    inc = [np.array(x, dtype=np.int64) for x in incident]

    def min_angle(tt: np.ndarray) -> float:
        """Worst of the smallest dihedral angle and 180 deg minus the largest (slivers and caps)."""
        if np.any(signed_volumes(nodes, tt) <= MIN_TET_VOLUME):
            return -1.0
        return float(tet_quality(nodes, tt).min())

    def place(v: int, ps: np.ndarray) -> np.ndarray:
        if not on_boundary[v]:
            return ps
        qs = project_to_surface(ps, iterations=6)
        qs[np.abs(qs[:, 2]) < 1e-9, 2] = 0.0
        return qs

    for _sweep in range(sweeps):
        worst = np.argsort(tet_quality(nodes, tets), kind="stable")[:400]
        visit = list(dict.fromkeys(tets[worst].reshape(-1).tolist()))  # unique, in order
        for v in visit:
            tt = tets[inc[v]]
            p0 = nodes[v].copy()
            best_q, best_p = min_angle(tt), p0
            neighbours = np.unique(tt)
            neighbours = neighbours[neighbours != v]
            centroid = nodes[neighbours].mean(axis=0)
            scale = float(np.linalg.norm(nodes[neighbours] - p0, axis=1).mean())
            grad = np.zeros(3)
            eps = 1e-6 * scale / 0.005
            for a in range(3):
                nodes[v] = p0
                nodes[v, a] += eps
                qp = min_angle(tt)
                nodes[v, a] -= 2 * eps
                qm = min_angle(tt)
                grad[a] = (qp - qm) / (2 * eps)
            nodes[v] = p0
            candidates = [p0 + a * (centroid - p0) for a in (1.0, 0.5, 0.25)]
            gn = float(np.linalg.norm(grad))
            if gn > 0:
                candidates += [p0 + s * scale * grad / gn for s in (0.2, 0.1, 0.05, 0.02, 0.01)]
            for p in place(v, np.array(candidates)):
                nodes[v] = p
                q = min_angle(tt)
                if q > best_q + 1e-6:
                    best_q, best_p = q, nodes[v].copy()
            nodes[v] = best_p
    return nodes


# --------------------------------------------------------------------------------------------
# Build, check, write
# --------------------------------------------------------------------------------------------


def build() -> dict:
    verts, faces = extract_surface(GRID_SPACING)
    verts, faces = weld(verts, faces, 1e-3 * GRID_SPACING)
    ec = edge_counts(faces)
    assert np.all(ec["counts"] == 2) and ec["consistent"], "marching cubes surface is not closed/manifold"
    if closed_volume(verts, faces) < 0:
        faces = faces[:, [0, 2, 1]]
    q_mc = triangle_quality(verts, faces)
    verts = relax(verts, faces, RELAX_ITERATIONS)
    verts[np.abs(verts[:, 2]) < 1e-9, 2] = 0.0  # the flat belly lies exactly on z = 0
    q_surf = triangle_quality(verts, faces)
    assert q_surf.min() > 0.05, f"surface has a near-degenerate triangle (quality {q_surf.min():.3f})"

    nodes, tets = tetrahedralize(verts, faces)
    nodes[np.abs(nodes[:, 2]) < 1e-9, 2] = 0.0
    vol = signed_volumes(nodes, tets)
    tets[vol < 0] = tets[vol < 0][:, [0, 2, 1, 3]]  # positive orientation: det[b-a, c-a, d-a] > 0
    used = np.unique(tets)
    assert len(used) == len(nodes), "TetGen left unused nodes"
    tetgen_min_dihedral = float(dihedral_angles(nodes, tets).min())
    nodes, tets, ears = remove_boundary_ears(nodes, tets, EAR_QUALITY)
    nodes = improve_tets(nodes, tets, SMOOTH_SWEEPS)
    # centre the bounding box on x = y = 0 (the bottom is already at z = 0)
    lo, hi = nodes.min(0), nodes.max(0)
    assert lo[2] == 0.0
    nodes = nodes - np.array([(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, 0.0])
    return {
        "nodes": nodes,
        "tets": tets,
        "surface_quality_mc": q_mc,
        "surface_quality": q_surf,
        "tetgen_min_dihedral": tetgen_min_dihedral,
        "ears_removed": ears,
    }


def check(nodes: np.ndarray, tets: np.ndarray) -> dict:
    vol = signed_volumes(nodes, tets)
    assert np.all(vol > MIN_TET_VOLUME), f"inverted or degenerate tet: min signed volume {vol.min():.3e} m^3"
    assert 1000 <= len(tets) <= 5000, f"tet count {len(tets)} outside [1000, 5000]"
    dih = dihedral_angles(nodes, tets)
    assert dih.min() >= MIN_DIHEDRAL and dih.max() <= 180.0 - MIN_DIHEDRAL, f"poor tet: dihedral angles {dih.min():.1f}-{dih.max():.1f} deg"
    rr = radius_ratio(nodes, tets)
    tri = boundary_faces(tets)
    ec = edge_counts(tri)
    assert np.all(ec["counts"] == 2) and ec["consistent"], "boundary surface is not closed and consistently oriented"
    total = float(vol.sum())
    assert abs(closed_volume(nodes, tri) - total) < 1e-9 * max(1.0, total) + 1e-12, "boundary not outward"
    lo, hi = nodes.min(0), nodes.max(0)
    length = hi[0] - lo[0]
    assert 0.12 <= length <= 0.16, f"length {length:.4f} m"
    assert lo[2] == 0.0 and 0.06 <= hi[2] <= 0.08, f"height range [{lo[2]}, {hi[2]}]"
    return {
        "volume": total,
        "min_dihedral": float(dih.min()),
        "max_dihedral": float(dih.max()),
        "min_radius_ratio": float(rr.min()),
        "mean_radius_ratio": float(rr.mean()),
        "min_volume": float(vol.min()),
        "bbox_min": lo,
        "bbox_max": hi,
        "surface_triangles": tri,
    }


def top_height_at(nodes: np.ndarray, tri: np.ndarray, x: float, y: float) -> float:
    """Height of the boundary surface's top above (x, y), by ray casting straight down."""
    a, b, c = nodes[tri[:, 0]], nodes[tri[:, 1]], nodes[tri[:, 2]]
    best = -np.inf
    for k in range(len(tri)):
        p = np.array([[a[k, 0], a[k, 1]], [b[k, 0], b[k, 1]], [c[k, 0], c[k, 1]]])
        m = np.array([p[1] - p[0], p[2] - p[0]]).T
        det = np.linalg.det(m)
        if abs(det) < 1e-18:
            continue
        s, t = np.linalg.solve(m, np.array([x, y]) - p[0])
        if s >= 0 and t >= 0 and s + t <= 1:
            z = a[k, 2] + s * (b[k, 2] - a[k, 2]) + t * (c[k, 2] - a[k, 2])
            best = max(best, z)
    return best


def write_h5(path: Path, nodes: np.ndarray, tets: np.ndarray, tri: np.ndarray, constrained: np.ndarray) -> None:
    surf_nodes = np.unique(tri)
    remap = -np.ones(len(nodes), dtype=np.int64)
    remap[surf_nodes] = np.arange(len(surf_nodes))
    path.parent.mkdir(parents=True, exist_ok=True)
    kw = {"track_times": False}
    with h5py.File(path, "w", track_order=False) as f:
        f.attrs["generator"] = np.bytes_("tools/build_duck_lamp.py")
        f.attrs["units"] = np.bytes_("m")
        m = f.create_group("mesh")
        m.create_dataset("coordinates", data=nodes.astype(np.float64), **kw)
        m.create_dataset("connectivity", data=tets.astype(np.int32), **kw)
        m.create_dataset("constrained_nodes", data=constrained.astype(np.int32), **kw)
        v = f.create_group("visual_mesh")
        v.create_dataset("coordinates", data=nodes[surf_nodes].astype(np.float64), **kw)
        v.create_dataset("connectivity", data=remap[tri].astype(np.int32), **kw)
        # visual vertex i is mesh node node_indices[i]: draw the deformed surface from node positions
        v.create_dataset("node_indices", data=surf_nodes.astype(np.int32), **kw)
        mat = f.create_group("material")
        mat.attrs["type"] = np.bytes_("NeoHookean")
        mat.attrs["density"] = DENSITY
        mat.create_dataset("youngs_modulus", data=np.full(len(tets), YOUNGS_MODULUS), **kw)
        mat.create_dataset("poisson_ratio", data=np.full(len(tets), POISSON_RATIO), **kw)


def write_prefab(path: Path, reduced_modes: int = 0) -> None:
    """The prefab; a reduced soft body when reduced_modes > 0."""
    material = {
        "type": "NeoHookean",
        "youngsModulus": YOUNGS_MODULUS,
        "poissonRatio": POISSON_RATIO,
        "density": DENSITY,
        "damping": DAMPING,
    }
    if reduced_modes > 0:
        material["reducedModes"] = reduced_modes
    prefab = {
        "actors": {
            "rigid": [],
            "soft": [
                {
                    "name": "duck_lamp",
                    "shape": f"./{H5_NAME}",
                    "worldFromLocal": {"rotation": [0.0, 0.0, 0.0, 1.0], "translation": list(WORLD_TRANSLATION)},
                    "material": material,
                    "fixedRegion": {"min": list(FIXED_REGION_MIN), "max": list(FIXED_REGION_MAX)},
                    "contact": {"coulombFrictionCoefficient": FRICTION},
                }
            ],
            "articulated": [],
        },
        "constraints": [],
        "prefabs": [],
        "scene": {
            "gravity": [0.0, 0.0, -9.81],
            "description": (
                "A soft silicone duck lamp lying on its belly on the ground (z = 0) at x = -0.30 m, "
                "where the seed arm's end-effector circle presses into its back. Bottom nodes pinned."
            ),
        },
    }
    text = json.dumps(prefab, indent=2)
    # lists of numbers on one line: "translation": [-0.3, 0.0, 0.0]
    text = re.sub(r"\[[-+0-9.eE,\s]*[0-9]\s*\]", lambda m: json.dumps(json.loads(m.group(0))), text)
    assert json.loads(text) == prefab
    path.write_text(text + "\n")


def render(path: Path, nodes: np.ndarray, tri: np.ndarray) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    fig = plt.figure(figsize=(12, 10))
    light = np.array([0.4, -0.5, 0.8])
    light /= np.linalg.norm(light)
    a, b, c = nodes[tri[:, 0]], nodes[tri[:, 1]], nodes[tri[:, 2]]
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1)[:, None]
    shade = 0.35 + 0.65 * np.clip(n @ light, 0, 1)
    colors = np.clip(np.array([1.0, 0.85, 0.2])[None] * shade[:, None], 0, 1)
    views = [(25, -50, "front-left"), (30, -140, "back-left"), (0, -90, "side (X-Z), seed path in red"), (90, -90, "top (X-Y)")]
    theta = np.linspace(np.pi, 2 * np.pi, 100)
    for k, (elev, azim, title) in enumerate(views):
        ax = fig.add_subplot(2, 2, k + 1, projection="3d")
        pc = Poly3DCollection(nodes[tri], facecolors=colors, edgecolors=(0, 0, 0, 0.25), linewidths=0.3)
        ax.add_collection3d(pc)
        # the seed's end-effector path (lower half), in the local frame
        ax.plot(0.08 * np.cos(theta), 0 * theta, 0.15 + 0.08 * np.sin(theta), "r-", lw=1)
        ax.set_xlim(-0.085, 0.085)
        ax.set_ylim(-0.085, 0.085)
        ax.set_zlim(-0.005, 0.165)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=elev, azim=azim)
        ax.set_title(title)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out-dir", type=Path, default=OUT_DIR)
    ap.add_argument("--render", type=Path, help="also save a PNG rendering of the surface here")
    args = ap.parse_args(argv)

    built = build()
    nodes, tets = built["nodes"], built["tets"]
    info = check(nodes, tets)
    tri = info["surface_triangles"]
    constrained = np.flatnonzero(nodes[:, 2] <= CONSTRAINED_HEIGHT)
    assert len(constrained) >= 3
    in_region = np.all((nodes >= FIXED_REGION_MIN) & (nodes <= FIXED_REGION_MAX), axis=1)
    assert np.array_equal(np.flatnonzero(in_region), constrained), "fixedRegion must pin exactly the bottom layer"
    gap = np.abs(nodes[:, 2] - CONSTRAINED_HEIGHT).min()
    assert gap > 1e-4, f"a node lies {gap:.1e} m from the fixedRegion top: the pinned set would be fragile"
    top_at_path = top_height_at(nodes, tri, PATH_LOWEST_POINT_LOCAL[0], PATH_LOWEST_POINT_LOCAL[1])
    depth = top_at_path - PATH_LOWEST_POINT_LOCAL[2]
    assert -0.005 <= depth <= 0.02, f"path lowest point is {depth * 1000:.1f} mm below the top surface"

    h5_path = args.out_dir / H5_NAME
    write_h5(h5_path, nodes, tets, tri, constrained)
    write_prefab(args.out_dir / PREFAB_NAME, REDUCED_MODES)
    write_prefab(args.out_dir / FULL_PREFAB_NAME)

    lo, hi = info["bbox_min"], info["bbox_max"]
    t = np.array(WORLD_TRANSLATION)
    qs = built["surface_quality"]
    print("duck lamp asset")
    on_ground = int(np.sum(nodes[:, 2] == 0.0))
    print(
        f"  nodes {len(nodes)}, tetrahedra {len(tets)}, surface triangles {len(tri)}, "
        f"bottom (pinned) nodes {len(constrained)} ({on_ground} exactly on z = 0)"
    )
    print(f"  volume {info['volume'] * 1e6:.1f} cm^3, mass {info['volume'] * DENSITY * 1000:.1f} g at {DENSITY:.0f} kg/m^3")
    print(
        f"  dihedral angles min {info['min_dihedral']:.1f} deg, max {info['max_dihedral']:.1f} deg; "
        f"radius ratio min {info['min_radius_ratio']:.3f}, mean {info['mean_radius_ratio']:.3f}; "
        f"min tet volume {info['min_volume']:.3e} m^3"
    )
    print(f"  TetGen's own min dihedral {built['tetgen_min_dihedral']:.1f} deg, raised by removing {built['ears_removed']} flat boundary ear tets and node smoothing ({SMOOTH_SWEEPS} sweeps)")
    print(f"  surface triangle quality: marching cubes min {built['surface_quality_mc'].min():.3f}, after relaxation min {qs.min():.3f}, mean {qs.mean():.3f}")
    print(f"  bbox local  min {np.round(lo, 4).tolist()} max {np.round(hi, 4).tolist()}  size {np.round(hi - lo, 4).tolist()} m")
    print(f"  bbox world  min {np.round(lo + t, 4).tolist()} max {np.round(hi + t, 4).tolist()}")
    print(f"  top surface above the path's lowest point (x=-0.30): z = {top_at_path:.4f} m (path dips {depth * 1000:.1f} mm into it)")
    digest = hashlib.sha256(nodes.tobytes() + tets.astype(np.int64).tobytes()).hexdigest()[:16]
    print(f"  mesh digest {digest}")
    for path in (h5_path, args.out_dir / PREFAB_NAME, args.out_dir / FULL_PREFAB_NAME):
        print(f"  wrote {path.resolve().relative_to(REPO) if path.resolve().is_relative_to(REPO) else path}")
    if args.render:
        render(args.render, nodes, tri)
        print(f"  rendered {args.render}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
