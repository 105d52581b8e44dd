"""Writes the seed corpora of the libFuzzer targets (fuzz/corpus/<target>/).

    uv run python tools/make_fuzz_seeds.py

Each target starts from a few valid inputs (the example bot, the duck-lamp prefab, the tabletop
URDF, an MJCF model, small meshes, shapes and a recording written here) and the malformed corpus of the test
suite (tools/make_malformed_corpus.py), so that the fuzzer begins both inside and at the edges of
each format. To keep the corpora small, the valid seeds come first and the malformed files follow
in corpus order while the target's folder stays under 48 KB (files over 8 KB are left out). The output is deterministic;
the files are committed.
"""

import json
import shutil
import struct
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import make_malformed_corpus as mc  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
OUT = REPO / "fuzz" / "corpus"
BUDGET_BYTES = 48 * 1024  # per target
MAX_FILE_BYTES = 8 * 1024
# malformed-corpus folder -> fuzz target
TARGET_OF = {"bot": "bot_json", "prefab": "prefab_json", "urdf": "urdf", "mjcf": "mjcf", "h5": "mochi_h5",
             "obj": "obj", "stl": "stl", "ply": "ply", "recording": "recording"}


# an MJCF model touching what the importer reads: compiler settings, nested default classes,
# childclass, an inline mesh, free, multi-joint, slide and ball joints with ref, fromto, cylinders,
# ellipsoids, contact filters, an explicit inertial, a body welded to the world, <exclude>
MJCF_MODEL = """<mujoco model="corpus_mjcf">
  <compiler angle="degree" autolimits="true"/>
  <option timestep="0.005" gravity="0 0 -9.81"/>
  <default>
    <joint damping="0.1" armature="0.01"/>
    <geom density="800" friction="0.8 0.01 0.001"/>
    <default class="limb">
      <geom type="capsule" size="0.04"/>
      <joint range="-60 60"/>
    </default>
  </default>
  <asset>
    <mesh name="wedge" vertex="0 0 0  0.1 0 0  0 0.1 0  0 0 0.1" face="0 2 1  0 1 3  0 3 2  1 2 3"/>
  </asset>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="torso" pos="0 0 0.6" childclass="limb">
      <freejoint name="root"/>
      <geom type="box" size="0.1 0.08 0.05"/>
      <body name="hip" pos="0.1 0 0" euler="0 0 30">
        <joint name="hip_x" axis="1 0 0" pos="0 0 0.02"/>
        <joint name="hip_y" axis="0 1 0" ref="10"/>
        <geom fromto="0 0 0 0 0 -0.3"/>
        <body name="shin" pos="0 0 -0.3">
          <joint name="knee" type="slide" axis="0 0 1" range="-0.05 0.05"/>
          <geom type="cylinder" size="0.03 0.1" pos="0 0 -0.1"/>
          <geom type="mesh" mesh="wedge" pos="0 0 -0.2" contype="2" conaffinity="2"/>
        </body>
      </body>
      <body name="head" pos="0 0 0.1">
        <joint name="neck" type="ball" range="0 45"/>
        <geom type="ellipsoid" size="0.05 0.04 0.06"/>
        <inertial pos="0 0 0.02" mass="0.5" diaginertia="0.001 0.001 0.0008"/>
      </body>
    </body>
    <body name="shelf" pos="1 0 0.3">
      <geom type="box" size="0.2 0.2 0.02"/>
      <body name="lid" pos="0 0 0.05">
        <joint name="lid_hinge" axis="0 1 0" pos="-0.2 0 0"/>
        <geom type="box" size="0.2 0.2 0.01"/>
      </body>
    </body>
  </worldbody>
  <contact>
    <exclude body1="shelf" body2="lid"/>
  </contact>
  <actuator>
    <motor joint="hip_x" gear="10"/>
  </actuator>
</mujoco>
"""


def valid_seeds():
    """(target, file name, content) of the valid inputs."""
    assets = REPO / "assets"
    yield "bot_json", "example_bot_2dof.superdex_bot", (assets / "bots/fun/example_bot_2dof/example_bot_2dof.superdex_bot").read_bytes()
    yield "bot_json", "corpus_arm.superdex_bot", mc.bot()
    yield "prefab_json", "duck_lamp_recumbent.mochi_prefab", (assets / "prefabs/duck_lamp/duck_lamp_recumbent.mochi_prefab").read_bytes()
    yield "prefab_json", "box.mochi_prefab", mc.prefab(rigid=[mc.box_actor()])
    yield "urdf", "tabletop_arm_4dof.urdf", (assets / "bots/urdf/tabletop_arm_4dof/tabletop_arm_4dof.urdf").read_bytes()
    yield "urdf", "corpus_urdf.urdf", mc.urdf()
    yield "mjcf", "corpus_mjcf.xml", MJCF_MODEL
    yield "obj", "cube.obj", mc.obj_text()
    yield "obj", "cube_slashes.obj", mc.obj_text().replace("f 1 2 3", "f 1/1/1 2//2 3/3")
    yield "stl", "cube_binary.stl", mc.stl_binary(mc.CUBE_T)
    ascii_facets = "".join("facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {x} {y} {z}\n" for x, y, z in mc.CUBE_V[t])
                           + "endloop\nendfacet\n" for t in mc.CUBE_T)
    yield "stl", "cube_ascii.stl", f"solid cube\n{ascii_facets}endsolid cube\n"
    yield "off", "cube.off", "OFF\n8 12 0\n" + "".join(f"{x} {y} {z}\n" for x, y, z in mc.CUBE_V) + "".join(
        f"3 {a} {b} {c}\n" for a, b, c in mc.CUBE_T)
    yield "off", "square_with_colours.off", "OFF # a quad with a colour\n4 1 4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n"
    yield "model_json", "cube_mesh.mochi.json", (assets / "cube/cube_mesh.mochi.json").read_bytes()
    yield "model_json", "box.mochi.json", '{"box": {"center": [0, 0, 0.5], "halfExtents": [0.5, 0.5, 0.5], "rotation": [0, 0, 0, 1]}}'
    yield "model_json", "flat.json", json.dumps({"element_size": 4, "coordinates": [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1],
                                                 "connectivity": [0, 1, 2, 3], "constrained_nodes": [0]})
    yield "model_h5", "tets.mochi.h5", mc.h5(mc.mesh(v=mc.TET_V, t=mc.TET_T))
    yield "model_h5", "box.mochi.h5", mc.h5(attrs={"box": {"center": [0.0, 0.0, 0.5], "half_extents": [0.1, 0.2, 0.3],
                                                           "rotation": [0.0, 0.0, 0.0, 1.0]}})
    yield "ply", "cube_ascii.ply", mc.ply_header(8, 12) + mc.ply_body_ascii()
    little = b"".join(struct.pack("<3f", *p) for p in mc.CUBE_V) + b"".join(struct.pack("<B3i", 3, *t) for t in mc.CUBE_T)
    yield "ply", "cube_binary_le.ply", mc.ply_header(8, 12, fmt="binary_little_endian") + little
    big = b"".join(struct.pack(">3d", *p) for p in mc.CUBE_V) + b"".join(struct.pack(">B3i", 3, *t) for t in mc.CUBE_T)
    yield "ply", "cube_binary_be_double.ply", mc.ply_header(8, 12, fmt="binary_big_endian", vprops="property double x\nproperty double y\nproperty double z\n") + big
    sdf = {"sdf": {"grid_min": [-1.0] * 3, "grid_max": [1.0] * 3}}
    for name, writer in [("cube", mc.h5(mc.mesh())), ("tets", mc.h5(mc.mesh(v=mc.TET_V, t=mc.TET_T))),
                         ("cube_sdf", mc.h5({**mc.mesh(), "sdf/grid": np.ones((3, 3, 3))}, sdf)),
                         ("box", mc.h5(attrs={"box": {"half_extents": [0.1, 0.2, 0.3]}})),
                         ("sphere", mc.h5(attrs={"sphere": {"radius": 0.1, "center": [0.0, 0.0, 0.1]}})),
                         ("plane", mc.h5(attrs={"plane": {"normal": [0.0, 0.0, 1.0], "distance": 0.0}}))]:
        yield "mochi_h5", name + ".mochi.h5", writer
    actor = {"type": "actor", "scene": 1, "handle": 2, "name": "box", "kind": "rigid"}
    frame = {**mc.FRAME, "links": {"2": [0, 0, 1, 0, 0, 0, 1]}, "soft": {}}
    yield "recording", "valid.jsonl", mc.jsonl(mc.HEADER, mc.SCENE, actor, frame, {**frame, "step": 2, "t": 0.02}, {"type": "destroy", "scene": 1, "handle": 2})
    # the page's messages (docs/debugger_protocol.md), one per line
    for action in ("pause", "play", "fast", "step", "restore"):
        yield "debugger_message", f"control_{action}.txt", json.dumps({"type": "control", "action": action})
    yield "debugger_message", "ack.txt", '{"type":"ack"}'
    yield "debugger_message", "session.txt", '{"type":"control","action":"pause"}\n{"type":"control","action":"step"}\n{"type":"ack"}\n{"type":"ack"}\n{"type":"control","action":"restore"}\n'


def main():
    for make in (mc.bot_cases, mc.prefab_cases, mc.urdf_cases, mc.mjcf_cases, mc.h5_cases, mc.mesh_cases, mc.recording_cases):
        make()
    if OUT.exists():
        shutil.rmtree(OUT)
    seeds = list(valid_seeds())
    for folder, name, content, *_ in mc.CASES:
        if folder == "prefab" and not name.endswith(".mochi_prefab"):
            continue
        seeds.append((TARGET_OF[folder], "malformed_" + name, content))
    used = {}
    for target, name, content in seeds:
        path = OUT / target / name
        path.parent.mkdir(parents=True, exist_ok=True)
        # JSON documents compact: the fuzzer mutates fewer bytes of layout
        mc.write_content(path, json.dumps(content, separators=(",", ":")) if isinstance(content, (dict, list)) else content)
        size = path.stat().st_size
        if size > MAX_FILE_BYTES or used.get(target, 0) + size > BUDGET_BYTES:
            path.unlink()
        else:
            used[target] = used.get(target, 0) + size
    for target in sorted(p.name for p in OUT.iterdir()):
        files = list((OUT / target).iterdir())
        print(f"{target}: {len(files)} seeds, {sum(f.stat().st_size for f in files)} bytes")


if __name__ == "__main__":
    main()
