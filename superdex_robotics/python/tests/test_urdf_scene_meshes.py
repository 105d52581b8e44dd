"""COLLADA meshes (.dae), read through Assimp, as robots ship them: example-robot-data's kinova,
baxter, hyq, tiago and romeo collide with .dae meshes in millimetres or metres, z up or y up.
Each mesh's bounds must equal those of the same file loaded by Pinocchio's geometry loader (an
independent reading of the file's node tree, units and axes), and a robot built from them must
load without dropping a collision element.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

try:
    import pinocchio as pin
except ImportError as exc:  # a declared dev dependency: missing means a broken environment
    raise ImportError("pin (a dev dependency in pyproject.toml) is required by this test; run `uv sync`") from exc

import superdex.physics as sdp
import superdex.robotics as sdr
from robotics_helpers import scene  # noqa: F401
from superdex.robot_files import example_robot_data_file

ROBOTS = ["kinova_description/robots/kinova.urdf", "baxter_description/urdf/baxter.urdf", "hyq_description/robots/hyq_no_sensors.urdf",
          "tiago_description/robots/tiago.urdf", "romeo_description/urdf/romeo_small.urdf"]


def robot_file(relative: str) -> Path:
    return example_robot_data_file("robots/" + relative)


@pytest.mark.parametrize("relative", ROBOTS, ids=lambda r: Path(r).stem)
def test_dae_meshes_match_pinocchio(scene, relative):
    urdf = robot_file(relative)
    share = next(p for p in urdf.parents if p.name == "example-robot-data").parent  # where package:// resolves
    _, collision, _ = pin.buildModelsFromUrdf(str(urdf), package_dirs=[str(share)])
    meshes = {g.meshPath: g for g in collision.geometryObjects if g.meshPath.lower().endswith(".dae")}
    assert meshes, f"{relative}: no .dae collision meshes"
    for k, (path, g) in enumerate(sorted(meshes.items())):
        V = np.asarray(g.geometry.vertices()) / np.asarray(g.meshScale)  # Pinocchio bakes the URDF scale in
        actor = scene.create_rigid_actor(name=f"mesh{k}", shape=sdp.load_shape_from_file(file_path=path), is_static=True)
        box = actor.get_aabb_local()
        size = float(np.max(V.max(0) - V.min(0)))
        np.testing.assert_allclose(np.asarray(box.min), V.min(0), atol=1e-6 * size, err_msg=path)
        np.testing.assert_allclose(np.asarray(box.max), V.max(0), atol=1e-6 * size, err_msg=path)


def test_a_robot_of_dae_meshes_keeps_every_collision_element(scene):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        prefab = sdr.load_bot_prefab_from_urdf_file(str(robot_file(ROBOTS[0])))
    dropped = [str(w.message) for w in caught if "no collider" in str(w.message)]
    assert not dropped, dropped
    scene.set_gravity([0, 0, -9.81])
    ground = scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    ground.register_query(sdp.QueryType.CONTACT_POINTS)
    prefab.world_from_root = sdp.TransformRT(translation=[0, 0, 0.3])
    art = sdr.create_bot(scene, prefab, sdr.create_context()).get_articulated_actor()
    links = set(art.get_nested_link_actors())
    lift, deepest, touching = [], 0.0, set()
    for step in range(700):
        scene.step(0.005)
        contacts = list(ground.get_contact_points_world())
        if step >= 600:
            lift.append(abs(sum(c.force[2] for c in contacts)))
            deepest = min([deepest] + [c.distance for c in contacts])
            touching |= {c.actor_a if c.actor_b == ground.get_handle() else c.actor_b for c in contacts}
    # it fell, its unactuated joints flailed and came to rest (after about 2.5 s): mesh links lie on
    # the plane, none sunk into it deeper than the contact solve's millimetre-scale penetration,
    # and over the last 0.5 s they carry its weight
    assert touching and touching <= links, touching
    assert deepest > -0.003
    assert np.mean(lift) == pytest.approx(9.81 * art.get_mass(), rel=0.01)


def test_a_malformed_dae_is_a_clear_error(tmp_path):
    bad = tmp_path / "broken.dae"
    bad.write_text("<?xml version='1.0'?><COLLADA><library_geometries><geometry><mesh>")
    with pytest.raises(sdp.Error, match=r"broken\.dae: cannot read"):
        sdp.load_shape_from_file(file_path=str(bad))
    with pytest.raises(sdp.Error, match=r"missing\.glb: file not found"):
        sdp.load_shape_from_file(file_path=str(tmp_path / "missing.glb"))
