"""save_to_urdf_string / save_to_urdf_file: a bot written as URDF is the same robot to Pinocchio
and to the importer. A URDF read and written back gives Pinocchio the mass matrix of the original
file; the MJCF humanoid (links offset from their joints, several joints per body) written as URDF
gives Pinocchio the joint-space mass matrix the engine has; joints, limits, friction and mimic
couplings come back through the importer; meshes are written beside the file; what URDF cannot
hold is named in a warning or an error.
"""

from __future__ import annotations

import importlib.util
import json
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
from superdex.robot_files import example_robot_data_file

TOL = 1e-9 if sdp.uses_double_precision() else 1e-4
# a file written from the float build carries float-rounded values
ROUND_TRIP = 1e-7 if sdp.uses_double_precision() else 1e-5


def quiet(fn, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fn(*args, **kwargs)


def random_configuration(model, rng):
    q = pin.neutral(model)
    for j in range(1, model.njoints):
        iq = model.idx_qs[j]
        if model.nqs[j] == 1:
            lo, hi = max(model.lowerPositionLimit[iq], -np.pi), min(model.upperPositionLimit[iq], np.pi)
            q[iq] = rng.uniform(lo, hi)
        elif model.nqs[j] == 2:  # continuous
            a = rng.uniform(-np.pi, np.pi)
            q[iq : iq + 2] = np.cos(a), np.sin(a)
    return q


@pytest.mark.parametrize("tail", ["panda_description/urdf/panda.urdf", "ur_description/urdf/ur5_robot.urdf"])
def test_a_urdf_written_back_is_the_same_robot_to_pinocchio(tail):
    urdf = example_robot_data_file("robots/" + tail)
    prefab = quiet(sdr.load_bot_prefab_from_urdf_file, urdf, fixed_base=True)
    original = pin.buildModelFromUrdf(str(urdf))
    written = pin.buildModelFromXML(quiet(sdr.save_to_urdf_string, prefab))
    assert written.nv == original.nv
    rng = np.random.default_rng(3)
    for _ in range(5):
        q = random_configuration(original, rng)
        # same joint names, maybe another order: map by name
        q_written = pin.neutral(written)
        for j in range(1, original.njoints):
            k = written.getJointId(original.names[j])
            q_written[written.idx_qs[k] : written.idx_qs[k] + written.nqs[k]] = q[original.idx_qs[j] : original.idx_qs[j] + original.nqs[j]]
        M0 = pin.crba(original, original.createData(), q)
        M1 = pin.crba(written, written.createData(), q_written)
        perm = [written.idx_vs[written.getJointId(original.names[j])] for j in range(1, original.njoints) if original.nvs[j] > 0]
        # massless links carry the importer's negligible 1e-9 kg in the written file
        assert np.abs(np.triu(M1)[np.ix_(perm, perm)] - np.triu(M0)).max() <= ROUND_TRIP * np.abs(M0).max()


def test_mjcf_humanoid_as_urdf_has_the_engines_mass_matrix():
    path = Path(importlib.util.find_spec("gymnasium").submodule_search_locations[0]) / "envs" / "mujoco" / "assets" / "humanoid.xml"
    model = quiet(sdr.load_mjcf_file, path)
    prefab = next(b for b in model.bots if b.joints[0].type == sdp.ArticulatedJointType.FREE)
    written = pin.buildModelFromXML(quiet(sdr.save_to_urdf_string, prefab))
    sdp.initialize(num_worker_threads=0)
    scene = sdp.create_scene("humanoid")
    try:
        art = sdr.create_bot(scene, prefab, sdr.create_context()).get_articulated_actor()
        info = art.get_articulated_shape_info()
        names = [n for n, d in zip(info.joint_names, info.dof_info) if d.rot_size + d.trans_size > 0][1:]  # after the free root
        rng = np.random.default_rng(5)
        for _ in range(3):
            pose = np.zeros(art.get_num_dofs())
            pose[6:] = rng.uniform(-0.5, 0.5, len(names))
            art.set_articulated_pose_from_joints(pose)
            q = pin.neutral(written)
            for name, value in zip(names, pose[6:]):
                q[written.idx_qs[written.getJointId(name)]] = value
            perm = [written.idx_vs[written.getJointId(n)] for n in names]
            M_ref = pin.crba(written, written.createData(), q)
            M_ref = np.triu(M_ref) + np.triu(M_ref, 1).T
            # the joints' block: the same whatever coordinates the floating base uses; armature aside
            M = np.asarray(art.get_articulated_mass_matrix())[6:, 6:]
            armature = np.array([j.armature for j in prefab.joints if j.type != sdp.ArticulatedJointType.HARD][1:])
            assert np.abs(M - np.diag(armature) - M_ref[np.ix_(perm, perm)]).max() <= TOL * np.abs(M_ref).max()
    finally:
        sdp.destroy_scene(scene)
        sdp.shutdown()


def finger_bot(tmp_path):
    bot = {
        "name": "finger",
        "links": [
            {"name": "palm", "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01],
             "shape": {"capsule": {"radius": 0.02, "halfLength": 0.05}}},
            {"name": "proximal", "parentLink": 0, "mass": 0.05, "centerOfMass": [0, 0, 0.02], "momentOfInertia": [1e-4, 0, 0, 1e-4, 0, 1e-5],
             "shape": {"box": {"halfExtents": [0.01, 0.01, 0.02], "center": [0, 0, 0.02]}}},
            {"name": "distal", "parentLink": 1, "mass": 0.03, "centerOfMass": [0, 0, 0.015], "momentOfInertia": [5e-5, 0, 0, 5e-5, 0, 5e-6]},
            {"name": "tip", "parentLink": 2, "mass": 0.0},
        ],
        "joints": [
            {"name": "mount", "type": "Hard"},
            {"name": "proximal_joint", "type": "Revolute", "axis": [1, 0, 0], "minLimit": -0.1, "maxLimit": 1.6,
             "friction": {"coulomb": 0.01, "viscous": 0.02}, "inertia": 1e-4, "effortLimit": 2.0},
            {"name": "distal_joint", "type": "Revolute", "axis": [1, 0, 0], "minLimit": -0.1, "maxLimit": 1.6,
             "parentLinkFromJoint": {"rotation": [0.0, 0.0, 0.38268343, 0.92387953], "translation": [0, 0, 0.04]}},
            {"name": "tip_weld", "type": "Hard", "parentLinkFromJoint": {"translation": [0, 0, 0.03]}},
        ],
        "linearTransmissions": [{"jointIndices": [1, 2], "jointCoefficients": [1.2, -1.0]}],
    }
    path = tmp_path / "finger.superdex_bot"
    path.write_text(json.dumps(bot))
    return quiet(sdr.load_bot_prefab_from_file, path)


def test_joints_limits_friction_and_couplings_come_back(tmp_path):
    prefab = finger_bot(tmp_path)
    with pytest.warns(UserWarning, match=r"URDF has no rotor inertia \(armature\): left out for joints proximal_joint"):
        sdr.save_to_urdf_file(prefab, tmp_path / "finger.urdf")
    back = quiet(sdr.load_bot_prefab_from_urdf_file, tmp_path / "finger.urdf", fixed_base=True)
    assert [l.name for l in back.links] == ["palm", "proximal", "distal", "tip"]
    assert [j.name for j in back.joints[1:]] == ["proximal_joint", "distal_joint", "tip_weld"]
    j = back.joints[1]
    assert (j.min_limit[0], j.max_limit[0]) == (pytest.approx(-0.1), pytest.approx(1.6))
    assert (j.coulomb_friction, j.viscous_friction, j.effort_limit) == (pytest.approx(0.01), pytest.approx(0.02), pytest.approx(2.0))
    assert [(c.joint, c.leader, c.ratio) for c in back.couplings] == [("distal_joint", "proximal_joint", pytest.approx(1.2))]
    # the frames: the tip 3 cm along the distal link, which is turned 45 degrees about z
    np.testing.assert_allclose(list(back.joints[2].parent_link_from_joint.translation), [0, 0, 0.04], atol=TOL)
    np.testing.assert_allclose(back.joints[2].parent_link_from_joint.rotation.tolist(), [0.0, 0.0, 0.38268343, 0.92387953], atol=TOL)
    # the capsule is a cylinder and two balls
    root = __import__("xml.etree.ElementTree", fromlist=["parse"]).parse(tmp_path / "finger.urdf").getroot()
    palm = root.find("link[@name='palm']")
    assert sorted(c.find("geometry")[0].tag for c in palm.findall("collision")) == ["cylinder", "sphere", "sphere"]
    assert root.find("link[@name='tip']").find("inertial") is None, "a massless frame has no inertial"


def aabb_values(box):
    return np.array(list(box.min) + list(box.max), float)


def test_meshes_are_written_beside_the_file(tmp_path):
    urdf = example_robot_data_file("robots/ur_description/urdf/ur5_robot.urdf")
    prefab = quiet(sdr.load_bot_prefab_from_urdf_file, urdf, fixed_base=True)
    sdr.save_to_urdf_file(prefab, tmp_path / "ur5.urdf")
    meshes = sorted((tmp_path / "ur5_meshes").glob("*.obj"))
    assert len(meshes) >= 6
    back = quiet(sdr.load_bot_prefab_from_urdf_file, tmp_path / "ur5.urdf", fixed_base=True)
    assert [l.name for l in back.links] == [l.name for l in prefab.links]
    # the hulls come back as they were written: the same collision AABBs in every link
    sdp.initialize(num_worker_threads=0)
    try:
        boxes = []
        for p in (prefab, back):
            scene = sdp.create_scene("ur5")
            art = sdr.create_bot(scene, p, sdr.create_context()).get_articulated_actor()
            boxes.append([aabb_values(scene.get_actor(h).get_aabb_local()) for h in art.get_nested_link_actors()])
            sdp.destroy_scene(scene)
        np.testing.assert_allclose(np.array(boxes[0]), np.array(boxes[1]), atol=1e-6)
    finally:
        sdp.shutdown()
    with pytest.warns(UserWarning, match=r"mesh collision shape\(s\) left out"):
        sdr.save_to_urdf_string(prefab)


def test_what_urdf_cannot_hold_is_an_error(tmp_path):
    bot = {"name": "ball_joint", "links": [{"name": "a", "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01]},
                                           {"name": "b", "parentLink": 0, "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01]}],
           "joints": [{"name": "root", "type": "Hard"}, {"name": "shoulder", "type": "Spherical"}]}
    (tmp_path / "ball.superdex_bot").write_text(json.dumps(bot))
    prefab = sdr.load_bot_prefab_from_file(tmp_path / "ball.superdex_bot")
    with pytest.raises(sdp.Error, match=r"save_to_urdf: joints\[1\]\.type: URDF has no Spherical joint below the root \(joint 'shoulder'\)"):
        sdr.save_to_urdf_string(prefab)


def test_a_scaled_primitive_is_written_at_its_scale(tmp_path):
    """A link's box with shapeScale (2, 1, 0.5) and a density, no mass: the URDF box is the scaled
    one, and its mass and inertia are the scaled box's (m = rho * volume, I = m (b^2 + c^2) / 12)."""
    bot = {
        "name": "slab",
        "links": [{"name": "base", "density": 500.0, "shapeScale": [2.0, 1.0, 0.5],
                   "shape": {"box": {"halfExtents": [0.1, 0.05, 0.04]}}}],
        "joints": [{"name": "root", "type": "Free"}],
    }
    path = tmp_path / "slab.superdex_bot"
    path.write_text(json.dumps(bot))
    prefab = quiet(sdr.load_bot_prefab_from_file, path)
    import xml.etree.ElementTree as ET

    link = ET.fromstring(quiet(sdr.save_to_urdf_string, prefab)).find("link")
    size = [float(x) for x in link.find("collision/geometry/box").get("size").split()]
    np.testing.assert_allclose(size, [0.4, 0.1, 0.04], rtol=ROUND_TRIP)
    a, b, c = size
    mass = 500.0 * a * b * c
    assert float(link.find("inertial/mass").get("value")) == pytest.approx(mass, rel=ROUND_TRIP)
    inertia = link.find("inertial/inertia")
    expected = {"ixx": mass * (b * b + c * c) / 12, "iyy": mass * (a * a + c * c) / 12, "izz": mass * (a * a + b * b) / 12}
    for name, value in expected.items():
        assert float(inertia.get(name)) == pytest.approx(value, rel=ROUND_TRIP)


def test_tendons_are_named_when_left_out(tmp_path):
    # URDF cannot hold an MJCF model's tendons or joint springs: the writer names each one
    prefab = finger_bot(tmp_path)
    prefab.fixed_tendons = [sdr.FixedTendon(name="coupling", joints=["proximal_joint", "distal_joint"], coefficients=[1.0, -1.0]),
                            sdr.FixedTendon(name="distal_joint/spring", joints=["distal_joint"], coefficients=[1.0], stiffness=2.0)]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        text = sdr.save_to_urdf_string(prefab)
    assert any("URDF has no tendons or joint springs: left out coupling, distal_joint/spring" in str(w.message) for w in caught)
    assert "<robot" in text
