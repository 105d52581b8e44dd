#!/usr/bin/env python3
"""Generate the rod assets the examples look up by path, with the project's own API.

- assets/rods/helix_with_visual.mochi.h5: a helical spring along +X as an elastic rod's model: a
  polyline of 193 nodes (192 elements) on the curve

      x(u) = L u,   y(u) = r(u) cos(2 pi n u),   z(u) = r(u) sin(2 pi n u),   u in [0, 1]

  with L = 0.5 m, n = 8 turns and a coil radius r(u) = R s(u), R = 0.05 m, where the taper
  s(u) = (1 - cos(pi min(1, u / a, (1 - u) / a))) / 2 rises smoothly from 0 to 1 over the first and
  last a = 1/16 of the curve: the spring is one analytic space curve whose two ends lie on the X
  axis (at x = 0 and x = 0.5 m). Each element's frame axis is the coil's radial direction
  (cos, sin of the coil angle in the YZ plane) made normal to the element. Its visual mesh is a
  tube of radius 0.01 m with 8 vertices per ring (generate_tubular_rod_model_data), skinned to the
  elements.

Loads the file back through the engine (load_shape_from_file, create_rod_actor) and steps it to
check it. Deterministic: two runs give the same file. Run from the repository root:

    uv run python tools/make_rod_assets.py

(SUPERDEX_PRECISION=float, the default, writes the reals as float32 values.)
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

import superdex.physics as sdp

REPO = Path(__file__).resolve().parents[1]
HELIX = REPO / "assets" / "rods" / "helix_with_visual.mochi.h5"

HELIX_LENGTH = 0.5  # m, along +X
HELIX_TURNS = 8
HELIX_RADIUS = 0.05  # m, the coil radius away from the tapered ends
HELIX_TAPER = 1.0 / 16.0  # share of the curve over which the coil radius rises from 0, at each end
HELIX_NODES_PER_TURN = 24
TUBE_RADIUS = 0.01  # m, the wire's
TUBE_SEGMENTS = 8


def helix_nodes() -> tuple[np.ndarray, np.ndarray]:
    """The helix's nodes (N x 3) and each element's frame axis (N - 1 x 3)."""
    count = HELIX_TURNS * HELIX_NODES_PER_TURN + 1
    u = np.linspace(0.0, 1.0, count)
    taper = 0.5 * (1.0 - np.cos(math.pi * np.minimum(1.0, np.minimum(u, 1.0 - u) / HELIX_TAPER)))
    angle = 2.0 * math.pi * HELIX_TURNS * u
    radius = HELIX_RADIUS * taper
    nodes = np.stack([HELIX_LENGTH * u, radius * np.cos(angle), radius * np.sin(angle)], axis=1)
    mid = 0.5 * (angle[:-1] + angle[1:])
    radial = np.stack([np.zeros_like(mid), np.cos(mid), np.sin(mid)], axis=1)
    tangent = np.diff(nodes, axis=0)
    tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
    axes = radial - np.sum(radial * tangent, axis=1, keepdims=True) * tangent
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    return nodes, axes


def make_helix() -> sdp.ModelData:
    nodes, axes = helix_nodes()
    return sdp.experimental.generate_tubular_rod_model_data(
        nodes=nodes,
        element_frame_axes=axes,
        radius=TUBE_RADIUS,
        num_cross_section_segments=TUBE_SEGMENTS,
        is_closed_loop=False,
    )


def check_helix(path: Path) -> None:
    """Loads the helix back as a rod, holds its first node and steps it."""
    shape = sdp.load_shape_from_file(str(path), bake_scale=[1.0, 1.0, 1.0])
    scene = sdp.create_scene("helix check")
    rod = sdp.experimental.create_rod_actor(scene, sdp.experimental.RodActorParams(name="Spring", shape=shape))
    coordinates = np.asarray(rod.get_mesh().coordinates).reshape(-1, 3)
    assert len(coordinates) == HELIX_TURNS * HELIX_NODES_PER_TURN + 1
    assert np.allclose(coordinates[0], 0.0, atol=1e-6) and np.allclose(coordinates[-1], [HELIX_LENGTH, 0, 0], atol=1e-6)
    scene.create_deformable_node_position_constraint(actor=rod.get_handle(), node_index=0, position=list(coordinates[0]))
    rod.register_query(sdp.QueryType.NODE_POSITIONS)
    for _ in range(5):
        scene.step(1.0 / 60.0)
    assert np.all(np.isfinite(rod.get_node_positions_local()))
    sdp.destroy_scene(scene)


def main() -> None:
    sdp.initialize(num_worker_threads=0)
    model = make_helix()
    sdp.model.validate(model)
    HELIX.parent.mkdir(parents=True, exist_ok=True)
    sdp.model.save_to_file(model, str(HELIX), sdp.FileFormat.H5)
    back = sdp.model.load_from_file(str(HELIX))
    assert back.mesh.nodes_per_element == 2 and back.visual_mesh is not None
    np.testing.assert_allclose(back.mesh.coordinates, model.mesh.coordinates, atol=1e-6)
    check_helix(HELIX)
    sdp.shutdown()
    print(f"wrote {HELIX.relative_to(REPO)}")


if __name__ == "__main__":
    main()
