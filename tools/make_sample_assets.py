#!/usr/bin/env python3
"""Generate the assets the articulation examples look up by path, with the project's own API.

- assets/cube/cube_fine_mesh.mochi.json: a finer tetrahedral unit cube, corner-anchored: the cube
  [0, 1]^3 m cut into 4 x 4 x 4 cells of six tetrahedra each (125 nodes, 384 positively oriented
  tetrahedra, cut as in cube_mesh.mochi.json so that neighbouring cells' faces match). Scripts bake a
  scale into it to make box-shaped links: baked by [sx, sy, sz] it spans [0, sx] x [0, sy] x [0, sz].
- assets/sphere/icosphere_4subdiv.1.mochi.json: the unit sphere as a triangle mesh, an icosahedron
  whose faces are split in four four times (2562 vertices, 5120 triangles, counter-clockwise seen
  from outside), for balls (bake the radius as a scale, use the Sphere collider).
- assets/samples/articulations_double_pendulum_on_rail.mochi_scene: a prefab, +Y up, of a double
  pendulum hanging from a cart on a rail (the articulated actor DoublePendulumOnRail), a ball on the
  ground in front of it (Ball) and the ground (Ground). Its links and joints, in order:

      0: RailHousing / CeilingWeld (Hard)      -> no DoFs (welded 0.75 m up)
      1: Cart        / Rail        (Prismatic) -> DoF 0 (along +X, limited to +-0.2 m)
      2: UpperArm    / UpperSwing  (Revolute)  -> DoF 1 (about -Z)
      3: LowerArm    / LowerSwing  (Spherical) -> DoFs 2-4

  The links are inline boxes whose link frames sit at their centres; at zero pose the arms hang
  straight down and the tip of the lower arm is 5 cm above the ground. The scene's contact filter
  lets only the lower arm (layer EndEffector) touch the ball, and the ball the ground.

- assets/articulated/mixed/mixed_articulation.mochi_prefab: an actor prefab of one articulation
  (MixedArticulation) of five box links in a chain along +X, each joint of another kind:

      0: Base     / BaseFree    (Free)      -> DoFs 0-5
      1: Link1    / Hinge1      (Revolute)  -> DoF 6  (about +Z, +-2 rad)
      2: Link2    / Slider      (Prismatic) -> DoF 7  (along +X, 0 to 5 cm)
      3: Link3    / Ball        (Spherical) -> DoFs 8-10
      4: EndEffector / Hinge2   (Revolute)  -> DoF 11 (about +Y, +-2 rad)

  Each link is a 0.1 x 0.03 x 0.03 m box (1000 kg/m^3) whose link frame is its centre; a child's
  joint sits at the centre of its parent's +X end face, and its box reaches 0.1 m on from there.
  All links are on layer RigidLink. Made for the IK example (scaled by 2, the base pinned at
  its +X end).

- assets/samples/articulations_parts/skin.mochi.json: the skin of the skinned double pendulum, a
  square tube (0.03 m side, open ends) along +X from x = 0 to 0.5 m on the arms' centreline
  (y = 0.5, z = 0), rings of eight nodes every 12.5 mm (328 nodes, 640 triangles, counter-clockwise
  seen from outside). mesh.skinning binds each node to links 0 and 1 (weights_per_node 2): weight 1
  on link 0 up to x = 0.225, on link 1 from x = 0.275, linear between (the elbow at x = 0.25).
- assets/samples/articulations_parts/soft.mochi.json: the soft arm of the soft-skinned double
  pendulum, a tetrahedral bar from x = 0.375 to 0.475 m, 0.025 m square on the same centreline,
  8 cells of six tetrahedra (36 nodes, 48 tetrahedra), nodes numbered along X; constrainedNodes
  [0, 1, 2, 3] are the four corners at x = 0.375, where it attaches to the second arm.

Reuses the mesh builders of tools/make_model_assets.py; writes only the files above (and
assets/samples/), then loads each back through the engine (model loader, load_shape_from_file,
prefab.add_to_scene) and steps the scene to check it. Deterministic: two runs give the same files.
Run from the repository root:

    uv run python tools/make_sample_assets.py

(SUPERDEX_PRECISION=float, the default, writes the reals as float32 values, as
tools/make_model_assets.py does; the files read the same in both precisions.)
"""

from __future__ import annotations

import json
import math
import re
import sys
from pathlib import Path

import numpy as np

import superdex.physics as sdp

sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_model_assets import compact, grid_nodes, kuhn_tets, make_icosphere, signed_volumes, tet_mesh  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
ASSETS = REPO / "assets"
FINE_CUBE = ASSETS / "cube" / "cube_fine_mesh.mochi.json"
FINE_SPHERE = ASSETS / "sphere" / "icosphere_4subdiv.1.mochi.json"
RAIL_SCENE = ASSETS / "samples" / "articulations_double_pendulum_on_rail.mochi_scene"
MIXED_PREFAB = ASSETS / "articulated" / "mixed" / "mixed_articulation.mochi_prefab"

SKIN_MODEL = ASSETS / "samples" / "articulations_parts" / "skin.mochi.json"
SOFT_MODEL = ASSETS / "samples" / "articulations_parts" / "soft.mochi.json"

# ---- the skinned double pendulums' parts (m; the skeleton's rest frame, +Y up) -------------------
PIVOT_HEIGHT = 0.5  # the arms' centreline: y = 0.5, z = 0, along +X from the pivot at x = 0
SKIN_ARM_LENGTH = 0.25  # each arm of the skinned pendulum; the elbow at x = 0.25
SKIN_SIDE = 0.03  # the skin tube's square cross-section (the arms are 0.025 thick)
SKIN_STATION = 0.0125  # spacing of the tube's rings along X
SKIN_BLEND = 0.025  # the weights ramp from link 0 to link 1 over elbow -+ this
SOFT_START, SOFT_LENGTH, SOFT_SIDE = 0.375, 0.1, 0.025  # the soft arm beyond the shorter second arm
SOFT_CELLS = 8  # cells along the soft arm (one across)

FINE_CUBE_CELLS = 4  # cells along each side of the fine cube (0.25 m cells: exact in float32)

# ---- the double pendulum on a rail (m, kg/m^3, +Y up) ------------------------------------------
ARTICULATION_NAME = "DoublePendulumOnRail"
RAIL_HEIGHT = 0.75  # the weld: the centre of the rail housing
HOUSING_SIZE = (0.5, 0.05, 0.05)  # the rail housing, long along X
CART_SIZE = (0.075, 0.075, 0.075)
ARM_SIZE = (0.03, 0.3, 0.03)  # each arm, a rod along Y
RAIL_LIMIT = 0.2  # the cart slides +-0.2 m from the middle of the rail
LINK_DENSITY = 1000.0
TIP_DENSITY = 2000.0  # the lower arm, heavier, strikes the ball
SEED_JOINT_VELOCITIES = [0.3, 4.2, 0.0, 0.0, 0.0]  # m/s on the rail, rad/s on the hinges
BALL_RADIUS = 0.05
BALL_POSITION = [0.15, BALL_RADIUS, 0.0]  # resting on the ground, in reach of the tip
BALL_DENSITY = 500.0

# ---- the mixed-joint chain (m, kg/m^3) ----------------------------------------------------------
MIXED_NAME = "MixedArticulation"
MIXED_LINK_SIZE = (0.1, 0.03, 0.03)  # each link, long along X
MIXED_LINKS = ["Base", "Link1", "Link2", "Link3", "EndEffector"]
HINGE_LIMIT = 2.0  # rad, both hinges
SLIDER_TRAVEL = 0.05  # m


# ------------------------------------------------------------------------------------ model files


def make_fine_cube(cells: int = FINE_CUBE_CELLS) -> sdp.ModelData:
    """The unit cube [0, 1]^3 cut into cells^3 cells of six tetrahedra each."""
    dims = (cells, cells, cells)
    grid = np.array([(i, j, k) for k in range(cells) for j in range(cells) for i in range(cells)])
    nodes, tets = compact(grid_nodes(np.zeros(3), 1.0 / cells, dims), kuhn_tets(grid, dims))
    volumes = signed_volumes(nodes, tets)
    assert len(nodes) == (cells + 1) ** 3 and len(tets) == 6 * cells**3
    assert np.all(volumes > 0) and np.isclose(volumes.sum(), 1.0)
    assert nodes.min() == 0.0 and nodes.max() == 1.0
    return sdp.ModelData(mesh=tet_mesh(nodes, tets))


def save_model(model: sdp.ModelData, path: Path) -> None:
    sdp.model.validate(model)
    path.parent.mkdir(parents=True, exist_ok=True)
    sdp.model.save_to_file(model, str(path), sdp.FileFormat.JSON)
    back = sdp.model.load_from_file(str(path))
    assert back.mesh.nodes_per_element == model.mesh.nodes_per_element
    assert list(back.mesh.connectivity) == list(model.mesh.connectivity)
    np.testing.assert_allclose(back.mesh.coordinates, model.mesh.coordinates, atol=1e-7)


def make_skin() -> sdp.ModelData:
    """A square tube along +X over both arms of the skinned double pendulum, rings of eight nodes
    (corners and side midpoints) every SKIN_STATION, open at its ends, each node skinned to link 0
    (UpperArm) and link 1 (LowerArm) with weights ramping linearly across the elbow."""
    h = SKIN_SIDE / 2
    ring = [(-h, -h), (0, -h), (h, -h), (h, 0), (h, h), (0, h), (-h, h), (-h, 0)]  # (y, z) around +X
    stations = round(2 * SKIN_ARM_LENGTH / SKIN_STATION) + 1
    nodes, indices, weights, triangles = [], [], [], []
    for i in range(stations):
        x = i * SKIN_STATION
        w1 = min(max((x - (SKIN_ARM_LENGTH - SKIN_BLEND)) / (2 * SKIN_BLEND), 0.0), 1.0)
        for y, z in ring:
            nodes += [x, PIVOT_HEIGHT + y, z]
            indices += [0, 1]
            weights += [1.0 - w1, w1]
    n = len(ring)
    for i in range(stations - 1):
        for k in range(n):
            a, b = i * n + k, i * n + (k + 1) % n
            c, d = a + n, b + n
            # counter-clockwise seen from outside the tube
            triangles += [a, b, d, a, d, c]
    mesh = sdp.MeshData(nodes_per_element=3, coordinates=nodes, connectivity=triangles,
                        skinning=sdp.SkinningData(weights_per_node=2, indices=indices, weights=weights))
    return sdp.ModelData(mesh=mesh)


def make_soft_arm() -> sdp.ModelData:
    """A tetrahedral bar from x = SOFT_START to SOFT_START + SOFT_LENGTH, SOFT_SIDE square on the
    arms' centreline, SOFT_CELLS cells along X of six tetrahedra each; its nodes numbered along X,
    so that nodes 0-3 are the four corners at x = SOFT_START, its constrained (attached) nodes."""
    dims = (SOFT_CELLS, 1, 1)
    grid = np.array([(i, 0, 0) for i in range(SOFT_CELLS)])
    unit = grid_nodes(np.zeros(3), 1.0, dims)
    tets = kuhn_tets(grid, dims)
    # numbered by X first (stable: y then z within a cross-section)
    order = np.lexsort((unit[:, 1], unit[:, 2], unit[:, 0]))
    remap = np.empty(len(order), dtype=np.int64)
    remap[order] = np.arange(len(order))
    scale = np.array([SOFT_LENGTH / SOFT_CELLS, SOFT_SIDE, SOFT_SIDE])
    nodes = unit[order] * scale + np.array([SOFT_START, PIVOT_HEIGHT - SOFT_SIDE / 2, -SOFT_SIDE / 2])
    tets = remap[tets]
    assert np.all(signed_volumes(nodes, tets) > 0)
    assert np.allclose(nodes[:4, 0], SOFT_START) and np.all(nodes[4:, 0] > SOFT_START)
    return sdp.ModelData(mesh=tet_mesh(nodes, tets), constrained_nodes=[0, 1, 2, 3])


def save_skinned_parts() -> None:
    skin = make_skin()
    save_model(skin, SKIN_MODEL)
    back = sdp.model.load_from_file(str(SKIN_MODEL))
    np.testing.assert_allclose(back.mesh.skinning.weights, skin.mesh.skinning.weights, atol=1e-7)
    print(f"skin: {skin.mesh.get_num_nodes()} nodes, {len(skin.mesh.connectivity) // 3} triangles")
    soft = make_soft_arm()
    save_model(soft, SOFT_MODEL)
    assert list(sdp.model.load_from_file(str(SOFT_MODEL)).constrained_nodes) == [0, 1, 2, 3]
    print(f"soft arm: {soft.mesh.get_num_nodes()} nodes, {len(soft.mesh.connectivity) // 4} tetrahedra")


# ------------------------------------------------------------------------------------- the prefab


def box(size) -> dict:
    """An inline box primitive centred on its link's frame."""
    return {"box": {"halfExtents": [s / 2 for s in size]}}


def rail_scene() -> dict:
    """The prefab of the double pendulum on a rail, the ball and the ground, as JSON."""
    housing_bottom = [0.0, -HOUSING_SIZE[1] / 2, 0.0]
    cart_bottom = [0.0, -CART_SIZE[1] / 2, 0.0]
    arm_bottom = [0.0, -ARM_SIZE[1] / 2, 0.0]

    def link(name, parent, size, joint_from_link, layer, density):
        entry = {"name": name, "parentLink": parent, "shape": box(size), "colliderType": "Box",
                 "jointFromLink": joint_from_link, "layer": layer, "density": density}
        if parent < 0:
            del entry["parentLink"]  # the root
        return entry

    def at(translation):
        return {"rotation": [0.0, 0.0, 0.0, 1.0], "translation": translation}

    # each link frame at the link's centre; a child joint at the bottom centre of its parent
    links = [
        link("RailHousing", -1, HOUSING_SIZE, [0.0, 0.0, 0.0], "Pendulum", LINK_DENSITY),
        link("Cart", 0, CART_SIZE, cart_bottom, "Pendulum", LINK_DENSITY),
        link("UpperArm", 1, ARM_SIZE, arm_bottom, "Pendulum", LINK_DENSITY),
        link("LowerArm", 2, ARM_SIZE, arm_bottom, "EndEffector", TIP_DENSITY),
    ]
    joints = [
        {"name": "CeilingWeld", "type": "Hard"},
        {"name": "Rail", "type": "Prismatic", "axis": [1.0, 0.0, 0.0], "parentLinkFromJoint": at(housing_bottom),
         "minLimit": -RAIL_LIMIT, "maxLimit": RAIL_LIMIT, "limitStiffness": 250.0, "limitDamping": 8.8,
         "friction": {"viscous": 0.018}, "inertia": 0.125},
        # a positive angle swings the arm's lower end towards -X
        {"name": "UpperSwing", "type": "Revolute", "axis": [0.0, 0.0, -1.0], "parentLinkFromJoint": at(cart_bottom)},
        {"name": "LowerSwing", "type": "Spherical", "parentLinkFromJoint": at(arm_bottom)},
    ]
    disabled = [("Pendulum", "Pendulum"), ("Pendulum", "Ball"), ("Pendulum", "EndEffector"),
                ("Pendulum", "Environment"), ("EndEffector", "Environment")]
    return {
        "actors": {
            "rigid": [
                {"name": "Ground", "shape": {"plane": {"normal": [0.0, 1.0, 0.0], "distance": 0.0}},
                 "isStatic": True, "layer": "Environment"},
                {"name": "Ball", "shape": {"sphere": {"radius": BALL_RADIUS}}, "translation": BALL_POSITION,
                 "colliderType": "Sphere", "density": BALL_DENSITY, "layer": "Ball"},
            ],
            "soft": [],
            "articulated": [
                {"name": ARTICULATION_NAME, "translation": [0.0, RAIL_HEIGHT, 0.0],
                 "jointVelocities": SEED_JOINT_VELOCITIES, "links": links, "joints": joints},
            ],
        },
        "prefabs": [],
        "contactFilter": {"layerContactSymmetric": [{"enable": False, "layers": list(pair)} for pair in disabled]},
        "scene": {
            "description": "A double pendulum (UpperArm, LowerArm) hanging from a cart on a rail welded 0.75 m up, "
                           "+Y up; the lower arm's tip swings 5 cm above the ground and strikes a 5 cm ball "
                           "resting at x = 0.15 m. Only the lower arm touches the ball.",
            "gravity": [0.0, -9.8, 0.0],
        },
    }


def mixed_prefab() -> dict:
    """The actor prefab of the mixed-joint chain, as JSON."""
    half = MIXED_LINK_SIZE[0] / 2

    def at(translation):
        return {"rotation": [0.0, 0.0, 0.0, 1.0], "translation": translation}

    links = []
    for i, name in enumerate(MIXED_LINKS):
        entry = {"name": name, "parentLink": i - 1, "shape": box(MIXED_LINK_SIZE), "colliderType": "Box",
                 "jointFromLink": [0.0 if i == 0 else half, 0.0, 0.0], "layer": "RigidLink", "density": LINK_DENSITY}
        if i == 0:
            del entry["parentLink"]
        links.append(entry)
    end = at([half, 0.0, 0.0])  # a child's joint: the parent's +X end face
    joints = [
        {"name": "BaseFree", "type": "Free"},
        {"name": "Hinge1", "type": "Revolute", "axis": [0.0, 0.0, 1.0], "parentLinkFromJoint": end,
         "minLimit": -HINGE_LIMIT, "maxLimit": HINGE_LIMIT},
        {"name": "Slider", "type": "Prismatic", "axis": [1.0, 0.0, 0.0], "parentLinkFromJoint": end,
         "minLimit": 0.0, "maxLimit": SLIDER_TRAVEL},
        {"name": "Ball", "type": "Spherical", "parentLinkFromJoint": end},
        {"name": "Hinge2", "type": "Revolute", "axis": [0.0, 1.0, 0.0], "parentLinkFromJoint": end,
         "minLimit": -HINGE_LIMIT, "maxLimit": HINGE_LIMIT},
    ]
    return {
        "actors": {"rigid": [], "soft": [], "articulated": [{"name": MIXED_NAME, "links": links, "joints": joints}]},
        "constraints": [],
        "prefabs": [],
        "scene": {
            "description": "Five 0.1 m box links in a chain along +X joined by a free, a revolute, a prismatic, a "
                           "spherical and a revolute joint (12 DoFs); all on layer RigidLink.",
        },
    }


def write_json(doc: dict, path: Path) -> None:
    text = json.dumps(doc, indent=2)
    # lists of numbers on one line each
    text = re.sub(r"\[[-+0-9.eE,\s]*[0-9]\s*\]", lambda m: json.dumps(json.loads(m.group(0))), text)
    assert json.loads(text) == doc
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text + "\n")


# ------------------------------------------------------------------------------------------ check


def check_rail_scene() -> None:
    """Adds the prefab to a scene the way the examples do and steps it."""
    rel = RAIL_SCENE.relative_to(ASSETS)
    scene = sdp.create_scene("check")
    result = sdp.prefab.add_to_scene(prefab_path=str(ASSETS / rel), root_path=str(ASSETS), scene=scene)
    (arm,) = [a for a in result.filter(sdp.ActorType.ARTICULATED) if a.get_name() == ARTICULATION_NAME]
    info = arm.get_articulated_shape_info()
    assert list(info.link_names) == ["RailHousing", "Cart", "UpperArm", "LowerArm"], list(info.link_names)
    assert list(info.joint_names) == ["CeilingWeld", "Rail", "UpperSwing", "LowerSwing"], list(info.joint_names)
    assert arm.get_num_dofs() == 5
    names = sorted(a.get_name() for a in result.filter(sdp.ActorType.RIGID))
    assert names == ["Ball", "Ground"], names
    mass = arm.get_mass()
    expected = LINK_DENSITY * (math.prod(HOUSING_SIZE) + math.prod(CART_SIZE) + math.prod(ARM_SIZE)) + TIP_DENSITY * math.prod(ARM_SIZE)
    assert math.isclose(mass, expected, rel_tol=1e-4), (mass, expected)
    for _ in range(100):
        scene.step(0.01)
    pose = sdp.DynamicArrayReal(5)
    arm.get_articulated_pose(pose)
    assert all(math.isfinite(x) for x in pose) and abs(pose[0]) < RAIL_LIMIT + 0.05
    sdp.destroy_scene(scene)
    print(f"{rel}: {ARTICULATION_NAME} {list(info.link_names)}, 5 DoFs, {mass:.4f} kg; pose after 1 s "
          f"{[round(x, 3) for x in pose]}")


def check_mixed_prefab() -> None:
    """Adds the prefab scaled by 2, as the IK example does, and checks its structure and mass."""
    rel = MIXED_PREFAB.relative_to(ASSETS)
    scene = sdp.create_scene("check")
    result = sdp.prefab.add_to_scene(prefab_path=str(ASSETS / rel), root_path=str(ASSETS), scene=scene,
                                     params=sdp.prefab.PrefabParams(scale=2.0))
    arm = result.actors[0]
    info = arm.get_articulated_shape_info()
    assert list(info.link_names) == MIXED_LINKS, list(info.link_names)
    assert arm.get_num_dofs() == 12
    mass = arm.get_mass()
    expected = LINK_DENSITY * 8 * math.prod(MIXED_LINK_SIZE) * len(MIXED_LINKS)
    assert math.isclose(mass, expected, rel_tol=1e-4), (mass, expected)
    sdp.destroy_scene(scene)
    print(f"{rel}: {MIXED_NAME} {list(info.link_names)}, 12 DoFs, {mass:.4f} kg at scale 2")


def main() -> None:
    sdp.initialize(num_worker_threads=0)

    cube = make_fine_cube()
    save_model(cube, FINE_CUBE)
    print(f"fine cube: {cube.mesh.get_num_nodes()} nodes, {len(cube.mesh.connectivity) // 4} tetrahedra")

    sphere = make_icosphere(4)
    save_model(sphere, FINE_SPHERE)
    print(f"fine sphere: {sphere.mesh.get_num_nodes()} vertices, {len(sphere.mesh.connectivity) // 3} triangles")

    # both load as the examples load them: a baked, corner-anchored box and a baked ball
    shape = sdp.load_shape_from_file(file_path=str(FINE_CUBE), bake_scale=[0.5, 0.05, 0.05])
    x = np.array(sdp.get_shape_mesh(shape).coordinates, dtype=float).reshape(-1, 3)
    assert np.allclose(x.min(axis=0), 0) and np.allclose(x.max(axis=0), [0.5, 0.05, 0.05])
    sdp.release_shape(shape)
    shape = sdp.load_shape_from_file(file_path=str(FINE_SPHERE), bake_scale=[0.05, 0.05, 0.05])
    sdp.release_shape(shape)

    write_json(rail_scene(), RAIL_SCENE)
    check_rail_scene()
    write_json(mixed_prefab(), MIXED_PREFAB)
    check_mixed_prefab()
    save_skinned_parts()
    sdp.shutdown()


if __name__ == "__main__":
    main()
