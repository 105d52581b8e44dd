"""The mass matrix of every example-robot-data URDF the importer takes as written (no inertia
repaired, no mass computed from geometry), with a fixed base at random configurations within the
joint limits, against Pinocchio's composite rigid body algorithm on the same file: equal to 1e-8
relative to the matrix's largest entry. Pinocchio is given the importer's negligible mass for
massless links (1e-9 kg, 1e-12 kg m^2, at the link origin; on a link of mass 0 with a rotational
inertia, 1e-9 kg at its inertial origin). Robots whose inertias the importer repaired (or computed
from collision shapes) are compared with Pinocchio given the repaired model, exported to URDF by
sdr.save_to_urdf_string.
"""

from __future__ import annotations

import warnings
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

try:
    import pinocchio as pin
except ImportError as exc:  # a declared dev dependency: missing means a broken environment
    raise ImportError("pin (a dev dependency in pyproject.toml) is required by this test; run `uv sync`") from exc

import superdex.physics as sdp
import superdex.robotics as sdr
from superdex.robot_files import example_robot_data_urdfs

pytestmark = pytest.mark.skipif(not sdp.uses_double_precision(), reason="compares to 1e-8: double build only")

MASSLESS_MASS = 1e-9
MASSLESS_INERTIA = 1e-12
REPAIRS = ("using the nearest physical inertia", "computed from its collision shape")
COMPARED: list[str] = []


def name_of(path: Path) -> str:
    return str(path).split("example-robot-data/robots/")[-1]


def pinocchio_model(urdf: Path) -> pin.Model:
    model = pin.buildModelFromUrdf(str(urdf))
    for link in ET.parse(urdf).getroot().findall("link"):
        inertial = link.find("inertial")
        mass = float(inertial.find("mass").get("value")) if inertial is not None else 0.0
        if mass > 0 or not model.existFrame(link.get("name"), pin.FrameType.BODY):
            continue
        frame = model.frames[model.getFrameId(link.get("name"), pin.FrameType.BODY)]
        inertia = inertial.find("inertia") if inertial is not None else None
        rotational = inertia is not None and any(float(inertia.get(k, 0)) != 0 for k in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz"))
        if rotational:  # Pinocchio keeps it; the importer puts it on the negligible mass, at the inertial origin
            xyz = [float(x) for x in (inertial.find("origin").get("xyz", "0 0 0") if inertial.find("origin") is not None else "0 0 0").split()]
            extra = pin.Inertia(MASSLESS_MASS, np.array(xyz), np.zeros((3, 3)))
        else:
            extra = pin.Inertia(MASSLESS_MASS, np.zeros(3), MASSLESS_INERTIA * np.eye(3))
        model.inertias[frame.parentJoint] = model.inertias[frame.parentJoint] + frame.placement.act(extra)
    return model


@pytest.mark.parametrize("urdf", example_robot_data_urdfs(), ids=name_of)
def test_mass_matrix_matches_pinocchio(urdf):
    name = name_of(urdf)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            prefab = sdr.load_bot_prefab_from_urdf_file(str(urdf), fixed_base=True)
    except sdp.Error:
        pytest.skip("makes no robot (test_example_robot_data checks its error)")
    repairs = [str(w.message) for w in caught if any(r in str(w.message) for r in REPAIRS)]
    if repairs:
        # the model the importer built, massless links' negligible masses included, as URDF
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # mesh shapes are left out of a URDF string
            model = pin.buildModelFromXML(sdr.save_to_urdf_string(prefab))
    else:
        model = pinocchio_model(urdf)
    if model.nv == 0:
        pytest.skip("no joints: nothing to compare with a fixed base")
    sdp.initialize(num_worker_threads=0)
    scene = sdp.create_scene("mass_matrix")
    try:
        art = sdr.create_bot(scene, prefab, sdr.create_context()).get_articulated_actor()
        info = art.get_articulated_shape_info()
        # our DOF k is Pinocchio's velocity index perm[k], matched by joint name
        perm = [model.idx_vs[model.getJointId(n)] for n, d in zip(info.joint_names, info.dof_info) if d.rot_size + d.trans_size > 0]
        assert sorted(perm) == list(range(model.nv)), name
        data = model.createData()
        rng = np.random.default_rng(7)
        lower = np.maximum(model.lowerPositionLimit, -np.pi)
        upper = np.minimum(model.upperPositionLimit, np.pi)
        for _ in range(3):
            q = np.zeros(model.nq)
            pose = np.zeros(model.nv)
            for j in range(1, model.njoints):
                iq, iv = model.idx_qs[j], model.idx_vs[j]
                if model.nqs[j] == 1:  # revolute, prismatic
                    pose[iv] = q[iq] = rng.uniform(lower[iq], upper[iq])
                else:  # continuous: (cos, sin)
                    pose[iv] = rng.uniform(-np.pi, np.pi)
                    q[iq : iq + 2] = np.cos(pose[iv]), np.sin(pose[iv])
            art.set_articulated_pose_from_joints(pose[perm])
            M_ref = np.array(pin.crba(model, data, q))
            M_ref = np.triu(M_ref) + np.triu(M_ref, 1).T
            M = np.asarray(art.get_articulated_mass_matrix())
            scale = np.abs(M_ref).max()
            assert np.abs(M - M_ref[np.ix_(perm, perm)]).max() <= 1e-8 * scale, name
        COMPARED.append(name)
    finally:
        sdp.destroy_scene(scene)
        sdp.shutdown()


def test_most_robots_were_compared():
    """Runs after the comparisons (pytest keeps file order): every robot of example-robot-data
    6.0.0 that the importer builds and that has joints was compared, repaired ones included."""
    if not COMPARED:
        pytest.skip("run with the comparisons above")
    assert len(COMPARED) >= 60, COMPARED
