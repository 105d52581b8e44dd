"""Writes the render models (binary glTF, .glb) of the bundled robots. Run at development time:

    uv run python tools/build_render_models.py

- assets/bots/fun/example_bot_2dof/models/ball.glb: the end effector, a 2 cm sphere in two
  colours (a red cap towards -X, where the ball meets the duck, on a light grey body), so that
  its rotation is visible in the debugger.

glTF 2.0 binary layout: a 12-byte header, a JSON chunk and a BIN chunk (positions, normals,
indices), one mesh with one primitive per colour, metallic-roughness materials.
"""

import json
import struct
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]


def uv_sphere(radius: float, rings: int = 16, segments: int = 32):
    """Vertices (N×3), normals (N×3) and triangles (M×3, counter-clockwise from outside)."""
    theta = np.linspace(0, np.pi, rings + 1)  # from +Z down to -Z
    phi = np.linspace(0, 2 * np.pi, segments + 1)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    normals = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1).reshape(-1, 3)
    tris = []
    for i in range(rings):
        for j in range(segments):
            a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            tris += [[a, b, a + 1], [a + 1, b, b + 1]]
    return radius * normals, normals, np.array(tris)


def write_glb(path: Path, parts):
    """parts: list of (vertices, normals, triangles, rgba)."""
    blob, views, accessors, primitives, materials = b"", [], [], [], []

    def add(data: np.ndarray, target: int, component: int, kind: str, with_bounds: bool):
        nonlocal blob
        raw = data.tobytes()
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(raw), "target": target})
        blob += raw + b"\0" * (-len(raw) % 4)
        acc = {"bufferView": len(views) - 1, "componentType": component, "count": len(data), "type": kind}
        if with_bounds:
            acc["min"], acc["max"] = data.min(axis=0).tolist(), data.max(axis=0).tolist()
        accessors.append(acc)
        return len(accessors) - 1

    for vertices, normals, triangles, rgba in parts:
        position = add(vertices.astype(np.float32), 34962, 5126, "VEC3", True)
        normal = add(normals.astype(np.float32), 34962, 5126, "VEC3", False)
        indices = add(triangles.astype(np.uint16).reshape(-1), 34963, 5123, "SCALAR", False)
        materials.append({"pbrMetallicRoughness": {"baseColorFactor": list(rgba), "metallicFactor": 0.1, "roughnessFactor": 0.5}})
        primitives.append({"attributes": {"POSITION": position, "NORMAL": normal}, "indices": indices,
                           "material": len(materials) - 1})
    gltf = {"asset": {"version": "2.0", "generator": "superdex tools/build_render_models.py"},
            "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": path.stem}],
            "meshes": [{"primitives": primitives}], "materials": materials,
            "accessors": accessors, "bufferViews": views, "buffers": [{"byteLength": len(blob)}]}
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(blob), 0x004E4942) + blob
    path.write_bytes(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)


def split_by(vertices, normals, triangles, mask_of_vertex):
    """Two parts of a mesh: triangles whose vertices all satisfy the mask, and the rest."""
    inside = mask_of_vertex[triangles].all(axis=1)
    parts = []
    for keep in (inside, ~inside):
        used, remap = np.unique(triangles[keep], return_inverse=True)
        parts.append((vertices[used], normals[used], remap.reshape(-1, 3)))
    return parts


def main():
    vertices, normals, triangles = uv_sphere(0.02)
    (cap, body) = split_by(vertices, normals, triangles, vertices[:, 0] < -0.012)
    out = REPO / "assets" / "bots" / "fun" / "example_bot_2dof" / "models" / "ball.glb"
    write_glb(out, [(*cap, (0.85, 0.18, 0.15, 1.0)), (*body, (0.82, 0.84, 0.88, 1.0))])
    print(f"wrote {out.relative_to(REPO)} ({out.stat().st_size} bytes)")


if __name__ == "__main__":
    main()
