"""Contact of mesh shapes, per-bot contact overrides, and threaded stepping with contact.

- A closed triangle-mesh cube (its contact comes from surface samples against the other
  shape's distance field, and the other shape's samples against the cube's grid) rests on
  the ground like a box: the contact force carries m g and the cube sits at its half extent.
- A box dropped on a static mesh cube comes to rest on its top face.
- An actor contact rule (Scene.enable_actor_contact_symmetric on two link actors) re-enables
  contact between two links joined by a joint, which by default never collide.
- Stepping with worker threads (islands in parallel) gives bitwise the results of one thread.
"""

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import articulation, joint, link
from contact_helpers import G, add_box, add_ground, position, step_for

HALF = 0.1


def cube_mesh(h):
    v = np.array([[x, y, z] for z in (-h, h) for y in (-h, h) for x in (-h, h)], dtype=float)
    # outward, counter-clockwise triangles of the 6 faces
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    t = []
    for a, b, c, d in quads:
        t += [(a, b, c), (a, c, d)]
    return v, np.array(t, dtype=np.int64)


def test_mesh_cube_rests_on_the_ground(scene, tmp_path, monkeypatch):
    monkeypatch.setenv("SUPERDEX_CACHE_DIR", str(tmp_path))
    add_ground(scene)
    v, t = cube_mesh(HALF)
    cube = scene.create_rigid_actor(name="mesh_cube", shape=sdp.create_tri_mesh_shape(v, t), mass=2.0,
                                    world_from_local=sdp.TransformRT(translation=[0, 0, HALF + 0.02]))
    cube.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    step_for(scene, 0.005, 1.5)
    p = position(cube)
    assert p[2] == pytest.approx(HALF, abs=2e-3)
    assert abs(p[0]) < 1e-3 and abs(p[1]) < 1e-3
    np.testing.assert_allclose(cube.get_contact_force_world(), [0, 0, 2.0 * G], atol=0.02 * 2.0 * G)


def test_box_rests_on_a_static_mesh_cube(scene, tmp_path, monkeypatch):
    monkeypatch.setenv("SUPERDEX_CACHE_DIR", str(tmp_path))
    v, t = cube_mesh(0.2)
    scene.create_rigid_actor(name="pedestal", shape=sdp.create_tri_mesh_shape(v, t), is_static=True)
    box = add_box(scene, "box", [0.02, -0.03, 0.2 + HALF + 0.01], half=HALF, mass=1.0)
    box.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    step_for(scene, 0.005, 1.5)
    p = position(box)
    # the box's samples meet the pedestal's distance grid: rest within a fraction of a grid cell
    assert p[2] == pytest.approx(0.2 + HALF, abs=0.01)
    np.testing.assert_allclose(box.get_contact_force_world(), [0, 0, G], atol=0.03 * G)
    assert np.linalg.norm(box.get_linear_velocity()) < 1e-3


def overlapping_pair(scene):
    """Two links joined by a prismatic joint whose spheres overlap by 5 cm at rest."""
    links = [
        link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
        link("a", parent=0, mass=1.0, shape=sdp.create_sphere_shape([0, 0, 0], 0.1)),
        link("b", parent=1, mass=1.0, shape=sdp.create_sphere_shape([0, 0, 0], 0.1)),
    ]
    joints = [
        joint("weld", "hard", at=[0, 0, 1]),
        joint("ja", "prismatic", axis=[1, 0, 0]),
        joint("jb", "prismatic", at=[0.15, 0, 0], axis=[1, 0, 0]),
    ]
    return articulation(scene, "pair", links, joints)


@pytest.mark.parametrize("enable", [False, True])
def test_actor_contact_rule_enables_joined_links(scene, enable):
    scene.set_gravity([0, 0, 0])
    art = overlapping_pair(scene)
    link_a, link_b = (scene.get_actor(h) for h in list(art.get_nested_link_actors())[1:])
    if enable:
        scene.enable_actor_contact_symmetric(link_a, link_b, True, sdp.IncludeNestedActors.NO)
    link_b.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    scene.step(0.01)
    force = link_b.get_contact_force_world()
    if enable:
        # b lies at +x of a: pushed apart along +x
        assert force[0] > 1.0, "an enabled override makes the joined links push apart"
    else:
        np.testing.assert_allclose(force, 0, atol=1e-9)


def test_actor_contact_rule_actors_must_exist(scene):
    """A rule naming an actor that does not exist (here a destroyed one) raises, naming the
    argument."""
    art = overlapping_pair(scene)
    link_a = scene.get_actor(art.get_nested_link_actors()[1])
    gone = scene.create_rigid_actor(name="gone", shape=sdp.create_sphere_shape([0, 0, 0], 0.1))
    scene.destroy_actor(gone)
    with pytest.raises(sdp.Error, match=r"enable_actor_contact_symmetric: actor_b: actor \d+ does not exist"):
        scene.enable_actor_contact_symmetric(link_a, gone, True, sdp.IncludeNestedActors.NO)
    with pytest.raises(sdp.Error, match=r"enable_actor_contact_symmetric: actor_a: expected an Actor or an ActorHandle"):
        scene.enable_actor_contact_symmetric("a", link_a, True, sdp.IncludeNestedActors.NO)


def pile(scene, n=12):
    add_ground(scene)
    boxes = []
    for k in range(n):
        boxes.append(add_box(scene, f"b{k}", [0.05 * (k % 3) - 0.05, 0.04 * (k % 2), 0.12 + 0.21 * k], half=HALF,
                             mass=1.0 + 0.1 * k))
    return boxes


def test_threaded_stepping_with_contact_matches_one_thread():
    results = []
    for threads in (0, 2):
        sdp.initialize(num_worker_threads=threads)
        scene = sdp.create_scene("pile")
        scene.set_gravity([0, 0, -G])
        boxes = pile(scene)
        # separate piles make islands that the threads solve in parallel; with more than 32
        # collider pairs (every box with the ground, and the touching boxes), the narrow phase
        # also runs in several chunks on the threads
        far = [add_box(scene, f"far{p}_{k}", [5.0 * (p + 1), 0, 0.12 + 0.21 * k], half=HALF) for p in range(6) for k in range(4)]
        for _ in range(150):
            scene.step(0.01)
        assert scene.get_solver_stats().num_islands >= 7
        results.append(np.concatenate([position(b) for b in boxes + far]))
        sdp.shutdown()
    np.testing.assert_array_equal(results[0], results[1])


OVERLAPPING_STACKS = """
import math, sys
import superdex.physics as sdp
from superdex.physics.paths import resolve_asset
sdp.initialize(num_worker_threads=0)
scene = sdp.create_scene("stacks")
cube = sdp.load_shape_from_file(file_path=str(resolve_asset("cube/cube_mesh.mochi.h5")), bake_scale=[0.3, 0.3, 0.3])
plane = sdp.create_plane_shape(normal=[0, 1, 0], distance=0.0)
scene.create_rigid_actor(name="upper", layer="one", shape=plane, is_static=True, world_from_local=sdp.TransformRT(translation=[0, 0.5, 0]))
scene.create_rigid_actor(name="lower", layer="two", shape=plane, is_static=True)
cubes = {}
for stack, (layer, x) in enumerate([("one", -0.5), ("two", 0.5)]):
    for k in range(3):
        cubes[(stack, k)] = scene.create_rigid_actor(name=f"c{stack}{k}", layer=layer, shape=cube,
                                                     world_from_local=sdp.TransformRT(translation=[x, 0.3 * (k + 0.5) + 0.01 * k + 1.5, 0]))
scene.enable_layer_contact_symmetric("one", "two", enable=False)
scene.enable_actor_contact_symmetric(cubes[(1, 0)].get_handle(), cubes[(1, 1)].get_handle(), enable=False,
                                     include_nested_actors=sdp.IncludeNestedActors.NO)
for _ in range(300):
    scene.step(1 / 60)
assert all(math.isfinite(v) for c in cubes.values() for v in c.get_root_transform().translation)
print("done")
"""


def test_overlapping_hull_stacks_step_in_bounded_time(tmp_path):
    """Two stacks of three hull cubes fall onto two planes, one stack passing through the upper
    plane and its middle cube through its bottom one (contact filters), so that hulls overlap
    deeply: every step ends (EPA on float round-off once grew its polytope without end here)."""
    import os
    import subprocess
    import sys

    script = tmp_path / "stacks.py"
    script.write_text(OVERLAPPING_STACKS)
    proc = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=120, env=dict(os.environ))
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert proc.stdout.strip() == "done"
