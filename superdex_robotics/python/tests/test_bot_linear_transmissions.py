"""SuperDex's `linearTransmissions` in .superdex_bot files, kept in BotPrefab.linear_transmissions:
one that joins two joints, c0 q0 + c1 q1 = targetDisplacement, is held as a coupling (the mimic fingers of hands such as the
Revo2): the second joint follows the first by -c0 / c1 within 1 % while the first is driven, and
the stiffness and damping it cannot model yet are named in a warning. A bad joint index is an
error naming the field.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from robotics_helpers import scene  # noqa: F401


def finger_bot(transmission: dict) -> dict:
    inertia = [1e-4, 0, 0, 1e-4, 0, 1e-4]
    return {
        "name": "finger",
        "links": [
            {"name": "palm", "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01]},
            {"name": "proximal", "parentLink": 0, "mass": 0.05, "centerOfMass": [0, 0, 0.02], "momentOfInertia": inertia},
            {"name": "distal", "parentLink": 1, "mass": 0.03, "centerOfMass": [0, 0, 0.015], "momentOfInertia": inertia},
        ],
        "joints": [
            {"name": "mount", "type": "Hard"},
            {"name": "proximal_joint", "type": "Revolute", "axis": [1, 0, 0], "minLimit": -0.1, "maxLimit": 1.6},
            {"name": "distal_joint", "type": "Revolute", "axis": [1, 0, 0], "minLimit": -0.1, "maxLimit": 1.6,
             "parentLinkFromJoint": {"translation": [0, 0, 0.04]}},
        ],
        "linearTransmissions": [transmission],
    }


def write(tmp_path, doc):
    path = tmp_path / "finger.superdex_bot"
    path.write_text(json.dumps(doc))
    return str(path)


def test_two_joint_transmission_couples_the_distal_joint(scene, tmp_path):  # noqa: F811
    # distal = 1.13 proximal (the Revo2's mimic ratio form: coefficients [ratio, -1], target 0)
    transmission = {"name": "distal_mimic", "jointIndices": [1, 2], "jointCoefficients": [1.13, -1.0], "jointAxisDisps": [0, 0],
                    "targetDisplacement": 0.0, "stiffness": 1000.0, "damping": 1.0, "allowCompressiveForce": True}
    with pytest.warns(UserWarning, match=r"linearTransmissions\[0\]: held as a rigid coupling of joints 'proximal_joint' and "
                                         r"'distal_joint'; its stiffness and damping are not modelled yet"):
        prefab = sdr.load_bot_prefab_from_file(write(tmp_path, finger_bot(transmission)))
    # kept as written (SuperDex's BotPrefab.linear_transmissions); building couples the joints
    (t,) = prefab.linear_transmissions
    assert (t.name, list(t.joint_indices), list(t.joint_coefficients)) == ("distal_mimic", [1, 2], [pytest.approx(1.13), -1.0])
    assert (t.stiffness, t.damping, t.allow_compressive_force) == (1000.0, 1.0, True)
    assert len(prefab.couplings) == 0
    finger = sdr.create_bot(scene, prefab, sdr.create_context()).get_articulated_actor()
    finger.set_joint_drive(0, stiffness=5.0, damping=0.1, target_position=0.9)
    worst = 0.0
    for k in range(1000):
        scene.step(0.002)
        q = np.asarray(finger.get_articulated_pose(), dtype=float)
        if k >= 10:
            worst = max(worst, abs(q[1] - 1.13 * q[0]))
    assert abs(q[1] - 1.13 * q[0]) <= 0.01 * abs(1.13 * q[0])
    assert worst <= 0.01 * 1.13 * 0.9
    assert q[0] > 0.5  # the drive moved the leader (against gravity and the follower's load)


def test_bad_joint_index_names_the_field(tmp_path):
    transmission = {"jointIndices": [1, 7], "jointCoefficients": [1.0, -1.0]}
    with pytest.raises(sdp.Error, match=r"finger.superdex_bot: linearTransmissions\[0\].jointIndices\[1\]: expected the index of a joint \(0 to 2\)"):
        sdr.load_bot_prefab_from_file(write(tmp_path, finger_bot(transmission)))


def test_transmissions_set_in_code_couple_the_joints(scene, tmp_path):  # noqa: F811
    # a BotLinearTransmissionPrefab added in Python: distal = 0.5 proximal + 0.1
    prefab = sdr.load_bot_prefab_from_file(write(tmp_path, {k: v for k, v in finger_bot({}).items() if k != "linearTransmissions"}))
    prefab.linear_transmissions = [sdr.BotLinearTransmissionPrefab(joint_indices=[1, 2], joint_coefficients=[0.5, -1.0],
                                                                   target_displacement=-0.1)]
    finger = sdr.create_bot(scene, prefab, sdr.create_context()).get_articulated_actor()
    finger.set_joint_drive(0, stiffness=5.0, damping=0.1, target_position=0.8)
    for _ in range(500):
        scene.step(0.002)
    q = np.asarray(finger.get_articulated_pose(), dtype=float)
    assert q[0] > 0.5 and q[1] == pytest.approx(0.5 * q[0] + 0.1, abs=0.01 * (0.5 * q[0] + 0.1))
    prefab.linear_transmissions = [sdr.BotLinearTransmissionPrefab(joint_indices=[1, 2], joint_coefficients=[0.5, 0.0])]
    with pytest.raises(sdp.Error, match=r"linearTransmissions\[0\]\.jointCoefficients\[1\]: must not be zero"):
        sdr.create_bot(scene, prefab, sdr.create_context())


def test_transmission_arrays_are_edited_in_place():
    # the joint arrays are the struct's own arrays: appending or assigning an element changes it
    t = sdr.BotLinearTransmissionPrefab(joint_indices=[1, 2], joint_coefficients=[0.5, -1.0])
    t.joint_indices.append(3)
    t.joint_coefficients[0] = 2.0
    t.joint_axis_disps.resize(3)
    assert list(t.joint_indices) == [1, 2, 3]
    assert list(t.joint_coefficients) == [2.0, -1.0]
    assert list(t.joint_axis_disps) == [0.0, 0.0, 0.0]
    assert t != sdr.BotLinearTransmissionPrefab(joint_indices=[1, 2], joint_coefficients=[0.5, -1.0])
    t.joint_indices = (4, 5)
    assert list(t.joint_indices) == [4, 5]
    with pytest.raises(TypeError):
        t.joint_coefficients = ["a"]
