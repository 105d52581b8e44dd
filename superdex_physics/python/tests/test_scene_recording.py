"""Scene recordings to HDF5 (Scene.start_recording, RecordingParams; docs/recording_format.md,
"Scene recordings"), read back with h5py, independently of the engine:

- a cube in free fall: one frame per step, with the step's time, and a vertical velocity of
  -g t (a constant force gives the same velocity under any one-step integrator); the recorded
  poses are the ones the actor reported after each step;
- the actors' descriptions: names, types, static flags, meshes in the actor frame (the soft
  cube's nodes are the ones it was made from), the DOF map (every actor's DOFs in creation
  order), the mass matrix of a rigid cube (diag(m, m, m, m a^2 / 6) for edge a, about its centre)
  and a soft actor's node masses (adding up to density x volume);
- a cube resting on the ground: contact points on the plane, normals +z, forces adding up to the
  weight, signed gaps; a soft cube's node contact forces add up to its weight;
- drive targets as set; static actors only when asked; what each flag leaves out;
- the session: stop, restart replaces the file, a scene destroyed while recording leaves a
  readable file, an unwritable path raises Error naming it.
"""

import copy
import pickle

import h5py
import numpy as np
import pytest

import superdex.physics as sdp
from conftest import soft_actor, soft_material
from contact_helpers import G, add_box, add_ground
from test_joint_drives import arm

FIELDS = ["record_actor_meshes", "record_actor_local_to_global_map", "record_actor_mass_matrix", "record_target_state",
          "record_dynamic_actor_state", "record_static_actor_state", "record_contact_points", "record_node_contact_forces",
          "record_sdf_distances"]
DEFAULTS = [True, False, False, True, True, False, False, False, False]

# a cube of edge 0.2 m centred on its origin, as five tetrahedra
CUBE_NODES = np.array([[x, y, z] for z in (-0.1, 0.1) for y in (-0.1, 0.1) for x in (-0.1, 0.1)])
CUBE_TETS = np.array([[0, 1, 2, 4], [6, 7, 4, 2], [5, 4, 7, 1], [3, 2, 1, 7], [1, 2, 4, 7]])


def frames(f):
    return [f["frames"][k] for k in sorted(f["frames"].keys())]


def test_params_defaults_round_trips_and_all():
    p = sdp.RecordingParams()
    assert [getattr(p, n) for n in FIELDS] == DEFAULTS
    flipped = sdp.RecordingParams(**{n: not d for n, d in zip(FIELDS, DEFAULTS)})
    assert [getattr(flipped, n) for n in FIELDS] == [not d for d in DEFAULTS]
    assert flipped != p
    assert pickle.loads(pickle.dumps(flipped)) == flipped
    assert copy.deepcopy(flipped) == flipped
    assert all(getattr(sdp.RecordingParams.all(), n) for n in FIELDS)
    assert not any(getattr(sdp.RecordingParams.all(enabled=False), n) for n in FIELDS)
    with pytest.raises(TypeError, match="record_everything"):
        sdp.RecordingParams(record_everything=True)


def test_free_fall(scene, tmp_path):
    path = tmp_path / "fall.h5"
    box = add_box(scene, "box", [0, 0, 1], mass=2.0)
    dt = 0.01
    reported = []
    scene.register_post_step_callback("poses", lambda info: reported.append(
        (np.array(box.get_root_transform().translation), np.array(box.get_linear_velocity()))))
    scene.start_recording(file_path=str(path), params=sdp.RecordingParams())
    assert scene.is_recording()
    for _ in range(20):
        scene.step(dt)
    scene.stop_recording()
    assert not scene.is_recording()
    with h5py.File(path, "r") as f:
        assert f.attrs["format"] == b"superdex-scene-recording" or f.attrs["format"] == "superdex-scene-recording"
        np.testing.assert_allclose(f.attrs["gravity"], [0, 0, -9.81])
        fs = frames(f)
        assert len(fs) == 20
        tol = 1e-5 if sdp.uses_double_precision() else 1e-4
        for k, frame in enumerate(fs):
            t = (k + 1) * dt
            assert frame.attrs["time"] == pytest.approx(t, rel=1e-6)
            assert frame.attrs["time_step"] == pytest.approx(dt)
            assert list(frame["bodies/actors"][()]) == [box.get_handle().value]
            v = frame["bodies/linear_velocities"][0]
            np.testing.assert_allclose(v, [0, 0, -9.81 * t], atol=tol)
            np.testing.assert_allclose(frame["bodies/translations"][0], reported[k][0], atol=1e-6)
            np.testing.assert_allclose(frame["bodies/rotations"][0], [0, 0, 0, 1], atol=1e-6)
            np.testing.assert_allclose(frame["bodies/angular_velocities"][0], [0, 0, 0], atol=1e-6)
            # contacts, static actors and soft actors were not asked for or are absent
            assert "contacts" not in frame and "soft" not in frame


def test_actor_descriptions(scene, tmp_path):
    path = tmp_path / "actors.h5"
    ground = add_ground(scene)
    density = 500.0
    jelly = soft_actor(scene, "jelly", sdp.create_tet_mesh_shape(CUBE_NODES, CUBE_TETS),
                       material=soft_material(density=density), recentering=False)
    box = add_box(scene, "box", [1, 0, 0.5], half=0.1, mass=3.0)
    params = sdp.RecordingParams(record_actor_local_to_global_map=True, record_actor_mass_matrix=True)
    scene.start_recording(str(path), params)
    scene.stop_recording()
    with h5py.File(path, "r") as f:
        actors = f["actors"]
        g, j, b = (actors[str(a.get_handle().value)] for a in (ground, jelly, box))
        assert [g.attrs["type"], j.attrs["type"], b.attrs["type"]] in (
            [b"rigid", b"soft", b"rigid"], ["rigid", "soft", "rigid"])
        assert (g.attrs["is_static"], j.attrs["is_static"], b.attrs["is_static"]) == (1, 0, 0)
        assert j.attrs["name"] in (b"jelly", "jelly")
        # the soft cube's simulation mesh is the tetrahedral mesh it was made from
        np.testing.assert_allclose(j["mesh/coordinates"][()], CUBE_NODES, atol=1e-6)
        np.testing.assert_array_equal(j["mesh/connectivity"][()], CUBE_TETS)
        assert j["surface/connectivity"].shape == (12, 3)  # two triangles per face
        # the rigid box's collision shape: a box of half extent 0.1 at its origin; the ground's plane
        (box_shape,) = b["colliders"].values()
        assert box_shape.attrs["shape"] in (b"box", "box")
        np.testing.assert_allclose(box_shape.attrs["half_extents"], [0.1] * 3, atol=1e-7)
        np.testing.assert_allclose(box_shape.attrs["link_from_shape"], [0, 0, 0, 0, 0, 0, 1], atol=1e-7)
        (plane,) = g["colliders"].values()
        assert plane.attrs["shape"] in (b"plane", "plane")
        np.testing.assert_allclose(plane.attrs["normal"], [0, 0, 1], atol=1e-7)
        # the DOF map: the ground has none, then the soft cube's 24, then the box's 6
        assert len(g["local_to_global"]) == 0
        np.testing.assert_array_equal(j["local_to_global"][()], np.arange(24))
        np.testing.assert_array_equal(b["local_to_global"][()], np.arange(24, 30))
        # a cube about its centre: m on the translations, m a^2 / 6 on the rotations
        M = b["mass_matrix"][()]
        np.testing.assert_allclose(M, np.diag([3.0] * 3 + [3.0 * 0.2 ** 2 / 6] * 3), atol=1e-6)
        assert np.sum(j["node_masses"][()]) == pytest.approx(density * 0.2 ** 3, rel=1e-5)
        assert len(f["frames"]) == 0


def test_contacts_and_node_contact_forces(scene, tmp_path):
    path = tmp_path / "contacts.h5"
    add_ground(scene)
    mass = 2.0
    box = add_box(scene, "box", [0, 0, 0.1 + 1e-3], half=0.1, mass=mass)
    density = 500.0
    jelly = soft_actor(scene, "jelly", sdp.create_tet_mesh_shape(CUBE_NODES + [1.0, 0, 0.1 + 1e-3], CUBE_TETS),
                       material=soft_material(youngs_modulus=1e5, density=density, stiffness_damping=0.01))
    for _ in range(100):  # both settle within a second
        scene.step(0.01)
    params = sdp.RecordingParams(record_contact_points=True, record_sdf_distances=True, record_node_contact_forces=True,
                                 record_static_actor_state=True)
    scene.start_recording(str(path), params)
    scene.step(0.01)
    scene.stop_recording()
    with h5py.File(path, "r") as f:
        (frame,) = frames(f)
        c = frame["contacts"]
        pairs, points, normals, forces = c["actors"][()], c["positions"][()], c["normals"][()], c["forces"][()]
        on_box = pairs[:, 0] == box.get_handle().value
        assert on_box.any()
        np.testing.assert_allclose(points[on_box][:, 2], 0, atol=2e-3)
        assert np.all(np.abs(points[on_box][:, :2]) <= 0.1 + 1e-3)
        np.testing.assert_allclose(normals[on_box], np.tile([0, 0, 1], (on_box.sum(), 1)), atol=1e-6)
        np.testing.assert_allclose(forces[on_box].sum(axis=0), [0, 0, mass * G], rtol=5e-3, atol=0.05)
        assert c["distances"].shape == (len(pairs),)
        assert np.all(np.abs(c["distances"][()]) < 5e-3)
        # the soft cube's nodes on the ground carry its weight
        f_nodes = frame["soft"][str(jelly.get_handle().value)]["node_contact_forces"][()]
        assert f_nodes.shape == (8, 3)
        np.testing.assert_allclose(f_nodes.sum(axis=0)[2], density * 0.2 ** 3 * G, rtol=0.02)
        # static actors were asked for: the ground is among the bodies
        assert len(frame["bodies/actors"]) == 2


def test_targets_and_flags_that_leave_parts_out(scene, tmp_path):
    path = tmp_path / "targets.h5"
    a = arm(scene)
    a.set_joint_drive(0, stiffness=200.0, damping=5.0, target_position=0.25)
    scene.start_recording(str(path), sdp.RecordingParams(record_actor_meshes=False, record_dynamic_actor_state=False))
    scene.step(0.01)
    a.set_joint_drive(0, stiffness=300.0, damping=6.0, target_position=-0.5)
    scene.step(0.01)
    scene.stop_recording()
    with h5py.File(path, "r") as f:
        first, second = frames(f)
        drives = [fr["targets"][str(a.get_handle().value)]["joint_drives"][()] for fr in (first, second)]
        np.testing.assert_allclose(drives[0][0, :3], [200.0, 5.0, 0.25])
        np.testing.assert_allclose(drives[1][0, :3], [300.0, 6.0, -0.5])
        assert "bodies" not in first and "articulated" not in first
        assert all("mesh" not in g and "colliders" not in g for g in f["actors"].values())
        # the arm and its links are described (the links name their articulation)
        links = [g for g in f["actors"].values() if "articulation" in g.attrs]
        assert len(links) == 2 and all(g.attrs["articulation"] == a.get_handle().value for g in links)


def test_articulated_state(scene, tmp_path):
    path = tmp_path / "arm.h5"
    a = arm(scene)
    scene.start_recording(str(path), sdp.RecordingParams())
    states = []
    for _ in range(3):
        scene.step(0.01)
        states.append((np.array(a.get_articulated_pose()), np.array(a.get_articulated_joint_velocities())))
    scene.stop_recording()
    with h5py.File(path, "r") as f:
        for frame, (q, v) in zip(frames(f), states):
            g = frame["articulated"][str(a.get_handle().value)]
            np.testing.assert_allclose(g["joint_positions"][()], q, atol=1e-7)
            np.testing.assert_allclose(g["joint_velocities"][()], v, atol=1e-7)
            assert len(frame["bodies/actors"]) == 2  # the base is welded, not static: both links


def test_session(scene, tmp_path, engine):
    first, second = tmp_path / "first.h5", tmp_path / "second.h5"
    add_box(scene, "box", [0, 0, 1])
    scene.start_recording(str(first), sdp.RecordingParams())
    scene.step(0.01)
    # starting again stops the first recording: it stays complete, the second starts empty
    scene.start_recording(str(second), sdp.RecordingParams())
    scene.step(0.01)
    scene.step(0.01)
    scene.stop_recording()
    scene.stop_recording()  # no effect
    scene.step(0.01)  # not recorded
    with h5py.File(first, "r") as f, h5py.File(second, "r") as g:
        assert len(f["frames"]) == 1 and len(g["frames"]) == 2
        assert frames(g)[0].attrs["time"] == pytest.approx(0.02, rel=1e-6)
    # replacing a file
    scene.start_recording(str(first), sdp.RecordingParams())
    scene.step(0.01)
    # a scene destroyed while recording closes the file
    sdp.destroy_scene(scene)
    with h5py.File(first, "r") as f:
        assert len(f["frames"]) == 1
    other = sdp.create_scene("other")
    missing = tmp_path / "no_such_dir" / "run.h5"
    with pytest.raises(sdp.Error, match="no_such_dir"):
        other.start_recording(str(missing), sdp.RecordingParams())
    assert not other.is_recording()
