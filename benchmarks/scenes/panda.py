"""The Franka Panda of example-robot-data as a simulator-neutral description (models.py), read from
its URDF: link masses, centres of mass and inertias, joint frames, axes, limits and damping.

The 7 arm joints are kept; the hand is welded to link 7 (panda_joint8 and panda_hand_joint
composed); the fingers, massless frames and meshes are left out. For contact, two fingertip
spheres (radius 1 cm, 10 g each) are welded to the hand where the fingertips are, 4 cm either side
of the TCP: they are the only collision shapes, so the three simulators collide the same geometry.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from superdex.robot_files import PANDA_URDF, example_robot_data_file

from benchmarks.models import quat_xyzw_to_matrix, rpy_to_quat_xyzw, matrix_to_quat_xyzw

READY = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785]  # the usual "ready" pose (rad)
# joint PD gains (N m/rad, N m s/rad) and the URDF's effort limits as saturation
KP = [600.0, 600.0, 600.0, 600.0, 250.0, 150.0, 50.0]
KD = [30.0, 30.0, 30.0, 30.0, 10.0, 10.0, 5.0]
TIP_RADIUS = 0.01
TIP_MASS = 0.01


def urdf_path() -> Path:
    return example_robot_data_file(PANDA_URDF)


def _origin(el):
    o = el.find("origin")
    xyz = [float(v) for v in (o.get("xyz", "0 0 0").split() if o is not None else [0, 0, 0])]
    rpy = [float(v) for v in (o.get("rpy", "0 0 0").split() if o is not None else [0, 0, 0])]
    return np.array(xyz), rpy_to_quat_xyzw(*rpy)


def _compose(a, b):
    (pa, qa), (pb, qb) = a, b
    Ra = quat_xyzw_to_matrix(qa)
    return pa + Ra @ pb, matrix_to_quat_xyzw(Ra @ quat_xyzw_to_matrix(qb))


def description(name="panda", effort_limits=None):
    """(articulation description, effort limits per arm joint)."""
    root = ET.parse(urdf_path()).getroot()
    links = {l.get("name"): l for l in root.findall("link")}
    joints = {j.get("name"): j for j in root.findall("joint")}

    def link_dict(lname, parent):
        el = links[lname]
        inertial = el.find("inertial")
        com, q = _origin(inertial)
        R = quat_xyzw_to_matrix(q)
        i = {k: float(v) for k, v in inertial.find("inertia").attrib.items()}
        I = np.array([[i["ixx"], i["ixy"], i["ixz"]], [i["ixy"], i["iyy"], i["iyz"]], [i["ixz"], i["iyz"], i["izz"]]])
        I = R @ I @ R.T  # about the COM, in link axes
        d = {"name": lname, "mass": float(inertial.find("mass").get("value")), "centerOfMass": com.tolist(),
             "momentOfInertia": [I[0, 0], I[0, 1], I[0, 2], I[1, 1], I[1, 2], I[2, 2]]}
        if parent is not None:
            d["parentLink"] = parent
        return d

    out_links = [link_dict("panda_link0", None)]
    out_joints = [{"name": "world_weld", "type": "Hard"}]
    efforts = []
    for k in range(1, 8):
        j = joints[f"panda_joint{k}"]
        xyz, q = _origin(j)
        lim = j.find("limit")
        out_links.append(link_dict(f"panda_link{k}", k - 1))
        out_joints.append({"name": f"panda_joint{k}", "type": "Revolute", "axis": [float(v) for v in j.find("axis").get("xyz").split()],
                           "parentLinkFromJoint": {"translation": xyz.tolist(), "rotation": q.tolist()},
                           "minLimit": float(lim.get("lower")), "maxLimit": float(lim.get("upper")),
                           "friction": {"viscous": float(j.find("dynamics").get("damping"))}})
        efforts.append(float(lim.get("effort")))
    X = _compose(_origin(joints["panda_joint8"]), _origin(joints["panda_hand_joint"]))
    out_links.append(link_dict("panda_hand", 7))
    out_joints.append({"name": "hand_weld", "type": "Hard",
                       "parentLinkFromJoint": {"translation": X[0].tolist(), "rotation": X[1].tolist()}})
    tcp_z = float(_origin(joints["panda_hand_tcp_joint"])[0][2])
    hand = len(out_links) - 1
    for side, y in (("left", 0.04), ("right", -0.04)):
        i = TIP_MASS * 0.4 * TIP_RADIUS ** 2
        out_links.append({"name": f"tip_{side}", "parentLink": hand, "mass": TIP_MASS, "momentOfInertia": [i, 0, 0, i, 0, i],
                          "shape": {"sphere": {"radius": TIP_RADIUS}}, "contact": {"coulombFrictionCoefficient": 0.5}})
        out_joints.append({"name": f"tip_{side}_weld", "type": "Hard", "parentLinkFromJoint": {"translation": [0.0, y, tcp_z]}})
    return {"name": name, "links": out_links, "joints": out_joints, "default_pose": list(READY)}, efforts


def forward_kinematics(desc, q):
    """World positions of every link origin at arm joint positions q (base at the world origin)."""
    pos, rot = [], []
    k = 0
    for link, joint in zip(desc["links"], desc["joints"]):
        X = joint.get("parentLinkFromJoint", {})
        p = np.asarray(X.get("translation", [0, 0, 0]), dtype=np.float64)
        R = quat_xyzw_to_matrix(X.get("rotation", [0, 0, 0, 1]))
        if joint["type"] == "Revolute":
            a = np.asarray(joint["axis"], dtype=np.float64)
            th = q[k]
            k += 1
            K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
            R = R @ (np.eye(3) + np.sin(th) * K + (1 - np.cos(th)) * K @ K)
        if "parentLink" in link:
            P, RP = pos[link["parentLink"]], rot[link["parentLink"]]
            p, R = P + RP @ p, RP @ R
        pos.append(p)
        rot.append(R)
    return pos
