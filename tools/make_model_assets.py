#!/usr/bin/env python3
"""Generate the model-data assets (assets/cube/, assets/duck/, assets/sphere/, assets/table/) with
the project's own model API.

- assets/cube/cube_mesh.mochi.json and cube_mesh.mochi.h5: the same tetrahedral unit cube in both
  formats: the cube [-0.5, 0.5]^3 m cut into 2 x 2 x 2 cells of six tetrahedra each (27 nodes,
  48 positively oriented tetrahedra, every cell split along its main diagonal so that the faces of
  neighbouring cells match).
- assets/duck/duck_coarse.mochi.h5: a coarse tetrahedral cage around the duck lamp
  (assets/prefabs/duck_lamp/duck_lamp_body.mochi.h5) with the lamp's surface as its visual mesh,
  embedded in the cage: every visual node follows the four nodes of the cage tetrahedron that holds
  it, with its barycentric coordinates as weights (four weights per node, summing to 1).
- assets/duck/duck_1899.mochi.h5: the same kind of cage with cells of FINE_CAGE_CELL (1842 nodes,
  8166 tetrahedra), under the name scripts use for a finer soft duck.
- assets/sphere/icosphere_3subdiv.1.mochi.json: the unit sphere as a triangle mesh, an icosahedron
  whose faces are split in four three times with the new vertices pushed out onto the sphere (642
  vertices, 1280 triangles, counter-clockwise seen from outside).
- assets/table/table.mochi.h5: a table as one closed triangle mesh, Z up, standing on z = 0: a
  1.2 x 0.8 x 0.04 m top whose upper face is at z = 0.75 m and four 0.05 m square legs under its
  corners (five disjoint boxes); table.mochi_scene places it as the static actor "Table".

The cage is made of the grid cells (CAGE_CELL metres on a side) that hold a surface node of the
duck or whose centre lies inside it, each cut into six tetrahedra as in the cube. Cells are then
added where two of them would touch only along an edge or at a corner, so that the cage's boundary
is a closed 2-manifold surface (a signed-distance grid can be computed from it: model.bake_sdf).

Deterministic: no randomness; two runs give the same meshes. Run from the repository root:

    uv run python tools/make_model_assets.py

(SUPERDEX_PRECISION=float, the default, stores the reals as float32 as SuperDex's default build
does; the files read the same in both precisions.)
"""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np

import superdex.physics as sdp

REPO = Path(__file__).resolve().parents[1]
CUBE_DIR = REPO / "assets" / "cube"
DUCK_DIR = REPO / "assets" / "duck"
DUCK_LAMP = REPO / "assets" / "prefabs" / "duck_lamp" / "duck_lamp_body.mochi.h5"
CAGE_CELL = 0.02  # m: the duck's cage cell side (the duck is 0.157 x 0.084 x 0.066 m)
FINE_CAGE_CELL = 0.008  # m: the finer cage of duck_1899.mochi.h5


def kuhn_tets(cells: np.ndarray, dims: tuple[int, int, int]) -> np.ndarray:
    """The six tetrahedra of each cell (i, j, k) of a grid of dims cells, as indices of the grid's
    (dims + 1) nodes (x fastest), positively oriented. Every tetrahedron runs from the cell's lowest
    corner to its highest one along the cell's edges, one axis at a time."""
    nx, ny, _ = (d + 1 for d in dims)

    def node(c):
        return c[:, 0] + nx * (c[:, 1] + ny * c[:, 2])

    tets = []
    for order in itertools.permutations(range(3)):
        corners = [cells.copy()]
        for axis in order:
            step = corners[-1].copy()
            step[:, axis] += 1
            corners.append(step)
        tet = np.stack([node(c) for c in corners], axis=1)
        # an odd permutation of the axes walks the cell the other way round: swap two nodes
        if np.linalg.det(np.eye(3)[list(order)]) < 0:
            tet[:, [2, 3]] = tet[:, [3, 2]]
        tets.append(tet)
    # cell by cell, the six tetrahedra of a cell together
    return np.stack(tets, axis=1).reshape(-1, 4)


def compact(nodes: np.ndarray, tets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Only the nodes that tetrahedra use, renumbered in their order."""
    used = np.unique(tets)
    remap = np.full(len(nodes), -1, dtype=np.int64)
    remap[used] = np.arange(len(used))
    return nodes[used], remap[tets]


def signed_volumes(nodes: np.ndarray, tets: np.ndarray) -> np.ndarray:
    a, b, c, d = (nodes[tets[:, k]] for k in range(4))
    return np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6.0


def grid_nodes(origin: np.ndarray, cell: float, dims: tuple[int, int, int]) -> np.ndarray:
    nx, ny, nz = (d + 1 for d in dims)
    k, j, i = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nx), indexing="ij")
    return origin + cell * np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1)


def tet_mesh(nodes: np.ndarray, tets: np.ndarray) -> sdp.MeshData:
    return sdp.MeshData(
        nodes_per_element=4,
        coordinates=nodes.astype(np.float64).ravel().tolist(),
        connectivity=tets.astype(np.int64).ravel().tolist(),
    )


# ------------------------------------------------------------------------------------------- cube


def make_cube() -> sdp.ModelData:
    dims = (2, 2, 2)
    cells = np.array([(i, j, k) for k in range(2) for j in range(2) for i in range(2)])
    nodes = grid_nodes(np.array([-0.5, -0.5, -0.5]), 0.5, dims)
    nodes, tets = compact(nodes, kuhn_tets(cells, dims))
    volumes = signed_volumes(nodes, tets)
    assert len(tets) == 48 and len(nodes) == 27
    assert np.all(volumes > 0) and np.isclose(volumes.sum(), 1.0)
    return sdp.ModelData(mesh=tet_mesh(nodes, tets))


# ------------------------------------------------------------------------------------ sphere, table


def tri_mesh(nodes: np.ndarray, triangles: np.ndarray) -> sdp.MeshData:
    return sdp.MeshData(nodes_per_element=3, coordinates=nodes.astype(np.float64).ravel().tolist(),
                        connectivity=triangles.astype(np.int64).ravel().tolist())


def make_icosphere(subdivisions: int) -> sdp.ModelData:
    t = (1 + 5 ** 0.5) / 2
    nodes = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
             [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    nodes = [list(np.array(n, dtype=np.float64) / np.linalg.norm(n)) for n in nodes]
    faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6],
             [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10],
             [8, 6, 7], [9, 8, 1]]
    for _ in range(subdivisions):
        midpoint = {}

        def mid(a: int, b: int) -> int:
            key = (min(a, b), max(a, b))
            if key not in midpoint:
                m = (np.array(nodes[a]) + np.array(nodes[b])) / 2
                nodes.append(list(m / np.linalg.norm(m)))
                midpoint[key] = len(nodes) - 1
            return midpoint[key]

        split = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            split += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        faces = split
    nodes, faces = np.array(nodes), np.array(faces)
    # counter-clockwise seen from outside: every face's normal points away from the centre
    normals = np.cross(nodes[faces[:, 1]] - nodes[faces[:, 0]], nodes[faces[:, 2]] - nodes[faces[:, 0]])
    assert np.all(np.einsum("ij,ij->i", normals, nodes[faces].mean(axis=1)) > 0)
    return sdp.ModelData(mesh=tri_mesh(nodes, faces))


def box_surface(lo, hi) -> tuple[np.ndarray, np.ndarray]:
    """The 8 corners (x fastest) and 12 outward triangles of the box [lo, hi]."""
    corners = np.array([[(lo, hi)[i][0], (lo, hi)[j][1], (lo, hi)[k][2]] for k in (0, 1) for j in (0, 1) for i in (0, 1)],
                       dtype=np.float64)
    triangles = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4], [2, 6, 3], [3, 6, 7],
                          [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]])
    return corners, triangles


def make_table() -> sdp.ModelData:
    top_lo, top_hi = np.array([-0.6, -0.4, 0.71]), np.array([0.6, 0.4, 0.75])
    boxes = [(top_lo, top_hi)]
    for sx in (-1, 1):
        for sy in (-1, 1):
            c = np.array([sx * 0.55, sy * 0.35])
            boxes.append((np.array([c[0] - 0.025, c[1] - 0.025, 0.0]), np.array([c[0] + 0.025, c[1] + 0.025, 0.71])))
    nodes, triangles = [], []
    for lo, hi in boxes:
        corners, tris = box_surface(lo, hi)
        triangles.append(tris + 8 * len(nodes))
        nodes.append(corners)
    return sdp.ModelData(mesh=tri_mesh(np.concatenate(nodes), np.concatenate(triangles)))


# ------------------------------------------------------------------------------------------- duck


def inside_tets(points: np.ndarray, nodes: np.ndarray, tets: np.ndarray, tolerance: float) -> tuple[np.ndarray, np.ndarray]:
    """For each point, the tetrahedron holding it (-1 if none) and its barycentric coordinates
    there; the tetrahedron whose smallest coordinate is largest wins."""
    a = nodes[tets[:, 0]]
    frames = np.stack([nodes[tets[:, k]] - a for k in (1, 2, 3)], axis=2)  # columns b-a, c-a, d-a
    inverse = np.linalg.inv(frames)
    best = np.full(len(points), -1)
    best_bary = np.zeros((len(points), 4))
    best_min = np.full(len(points), -np.inf)
    for start in range(0, len(points), 256):
        p = points[start : start + 256]
        local = np.einsum("tij,ptj->pti", inverse, p[:, None, :] - a[None, :, :])  # (points, tets, 3)
        bary = np.concatenate([1.0 - local.sum(axis=2, keepdims=True), local], axis=2)
        smallest = bary.min(axis=2)
        t = smallest.argmax(axis=1)
        rows = np.arange(len(p))
        best_min[start : start + len(p)] = smallest[rows, t]
        best[start : start + len(p)] = np.where(smallest[rows, t] >= -tolerance, t, -1)
        best_bary[start : start + len(p)] = bary[rows, t]
    return best, best_bary


def well_composed(occupied: np.ndarray) -> np.ndarray:
    """Adds cells until no 2 x 2 x 2 block of cells has its occupied or its empty cells in more than
    one face-connected piece: then no two cells meet only along an edge or at a corner, and the
    boundary of their union is a 2-manifold."""
    corners = list(itertools.product((0, 1), repeat=3))
    neighbours = [[b for b, cb in enumerate(corners) if sum(x != y for x, y in zip(ca, cb)) == 1] for ca in corners]

    def pieces(members: list[int]) -> int:
        left, count = set(members), 0
        while left:
            count += 1
            stack = [left.pop()]
            while stack:
                for n in neighbours[stack.pop()]:
                    if n in left:
                        left.remove(n)
                        stack.append(n)
        return count

    grid = np.pad(occupied, 1)  # empty cells all around
    changed = True
    while changed:
        changed = False
        for i, j, k in itertools.product(*(range(n - 1) for n in grid.shape)):
            block = [grid[i + a, j + b, k + c] for a, b, c in corners]
            full = [n for n, v in enumerate(block) if v]
            empty = [n for n, v in enumerate(block) if not v]
            if full and empty and (pieces(full) > 1 or pieces(empty) > 1):
                grid[i : i + 2, j : j + 2, k : k + 2] = True
                changed = True
    return grid[1:-1, 1:-1, 1:-1]


def make_duck(cell: float = CAGE_CELL) -> sdp.ModelData:
    lamp = sdp.model.load_from_file(str(DUCK_LAMP))
    fine_nodes = np.array(lamp.mesh.coordinates, dtype=np.float64).reshape(-1, 3)
    fine_tets = np.array(lamp.mesh.connectivity, dtype=np.int64).reshape(-1, 4)
    surface = np.array(lamp.visual_mesh.coordinates, dtype=np.float64).reshape(-1, 3)
    triangles = np.array(lamp.visual_mesh.connectivity, dtype=np.int64)

    # the cage grid: the duck's box grown to whole cells, centred on it
    low, high = surface.min(axis=0), surface.max(axis=0)
    dims = tuple(int(n) for n in np.ceil((high - low) / cell + 1e-9))
    origin = (low + high) / 2 - cell * np.array(dims) / 2
    occupied = np.zeros(dims, dtype=bool)
    holding = np.clip(np.floor((surface - origin) / cell).astype(int), 0, np.array(dims) - 1)
    occupied[tuple(holding.T)] = True
    centres = np.array(list(itertools.product(*(range(n) for n in dims))))
    inside, _ = inside_tets(origin + cell * (centres + 0.5), fine_nodes, fine_tets, 0.0)
    occupied[tuple(centres[inside >= 0].T)] = True
    occupied = well_composed(occupied)

    cells = np.argwhere(occupied.transpose(2, 1, 0))[:, ::-1]  # x fastest, like the nodes
    nodes, tets = compact(grid_nodes(origin, cell, dims), kuhn_tets(cells, dims))
    assert np.all(signed_volumes(nodes, tets) > 0)

    # the embedding: each surface node in its cage tetrahedron
    holder, bary = inside_tets(surface, nodes, tets, 1e-9)
    assert np.all(holder >= 0), "a surface node lies outside the cage"
    weights = np.clip(bary, 0.0, None)
    weights /= weights.sum(axis=1, keepdims=True)
    skinning = sdp.SkinningData(
        weights_per_node=4, indices=tets[holder].ravel().tolist(), weights=weights.ravel().tolist()
    )
    visual = sdp.MeshData(nodes_per_element=3, coordinates=surface.ravel().tolist(), connectivity=triangles.tolist(), skinning=skinning)
    duck = sdp.ModelData(mesh=tet_mesh(nodes, tets), visual_mesh=visual)
    # the embedded surface is where the cage's nodes put it
    placed = np.einsum("pk,pkj->pj", weights, nodes[tets[holder]])
    assert np.abs(placed - surface).max() < 1e-9
    print(f"duck cage: {dims} cells of {cell} m, {occupied.sum()} used, {len(nodes)} nodes, {len(tets)} tetrahedra; "
          f"visual mesh {len(surface)} nodes, {len(triangles) // 3} triangles")
    return duck


def main() -> None:
    cube = make_cube()
    sdp.model.validate(cube)
    CUBE_DIR.mkdir(parents=True, exist_ok=True)
    sdp.model.save_to_file(cube, str(CUBE_DIR / "cube_mesh.mochi.json"), sdp.FileFormat.JSON)
    sdp.model.save_to_file(cube, str(CUBE_DIR / "cube_mesh.mochi.h5"), sdp.FileFormat.H5)
    for name in ("cube_mesh.mochi.json", "cube_mesh.mochi.h5"):
        assert sdp.model.load_from_file(str(CUBE_DIR / name)) == cube, name
    print("cube: 27 nodes, 48 tetrahedra")

    sphere = make_icosphere(3)
    sdp.model.validate(sphere)
    (REPO / "assets" / "sphere").mkdir(parents=True, exist_ok=True)
    sdp.model.save_to_file(sphere, str(REPO / "assets" / "sphere" / "icosphere_3subdiv.1.mochi.json"), sdp.FileFormat.JSON)
    print(f"sphere: {sphere.mesh.get_num_nodes()} vertices")
    table = make_table()
    sdp.model.validate(table)
    (REPO / "assets" / "table").mkdir(parents=True, exist_ok=True)
    sdp.model.save_to_file(table, str(REPO / "assets" / "table" / "table.mochi.h5"), sdp.FileFormat.H5)

    fine = make_duck(FINE_CAGE_CELL)
    sdp.model.validate(fine)
    sdp.model.save_to_file(fine, str(DUCK_DIR / "duck_1899.mochi.h5"), sdp.FileFormat.H5)

    duck = make_duck()
    sdp.model.validate(duck)
    DUCK_DIR.mkdir(parents=True, exist_ok=True)
    sdp.model.save_to_file(duck, str(DUCK_DIR / "duck_coarse.mochi.h5"), sdp.FileFormat.H5)
    back = sdp.model.load_from_file(str(DUCK_DIR / "duck_coarse.mochi.h5"))
    assert back.mesh == duck.mesh and back.visual_mesh.connectivity == duck.visual_mesh.connectivity
    sdp.model.bake_sdf(back)  # the cage's surface is closed: a distance grid can be made of it


if __name__ == "__main__":
    main()
