"""Bots built from link/joint dicts for the pipeline tests: a Panda-like 7-DOF arm, a one-joint
rotor, and helpers to write them as .superdex_bot files and step a scene.

The arm follows the Franka Panda: the kinematics of its URDF (joint origins, alternating
axes made by +-90 degree rotations about x, all joint axes z in their frames), the masses,
centres of mass and inertias of its identified dynamic model, and an armature of 0.1 kg m^2
per joint (MuJoCo Menagerie's Panda). No collision shapes, no joint friction.
"""

import json
import math
from pathlib import Path

import numpy as np

import superdex.physics as sdp
import superdex.robotics as sdr

S = math.sqrt(0.5)
ROT_X_NEG = [-S, 0.0, 0.0, S]  # rpy (-pi/2, 0, 0)
ROT_X_POS = [S, 0.0, 0.0, S]  # rpy (+pi/2, 0, 0)
IDENTITY = [0.0, 0.0, 0.0, 1.0]

# (name, mass kg, centre of mass m, inertia about the COM [Ixx, Ixy, Ixz, Iyy, Iyz, Izz] kg m^2)
PANDA_LINKS = [
    ("panda_link0", 0.629769, [-0.041018, -0.00014, 0.049974], [0.00315, 8.2904e-07, 0.00015, 0.00388, 8.2299e-06, 0.004285]),
    ("panda_link1", 4.970684, [0.003875, 0.002081, -0.04762], [0.70337, -0.000139, 0.006772, 0.70661, 0.019169, 0.009117]),
    ("panda_link2", 0.646926, [-0.003141, -0.02872, 0.003495], [0.007962, -0.003925, 0.010254, 0.02811, 0.000704, 0.025995]),
    ("panda_link3", 3.228604, [0.027518, 0.039252, -0.066502], [0.037242, -0.004761, -0.011396, 0.036155, -0.012805, 0.01083]),
    ("panda_link4", 3.587895, [-0.05317, 0.104419, 0.027454], [0.025853, 0.007796, -0.001332, 0.019552, 0.008641, 0.028323]),
    ("panda_link5", 1.225946, [-0.011953, 0.041065, -0.038437], [0.035549, -0.002117, -0.004037, 0.029474, 0.000229, 0.008627]),
    ("panda_link6", 1.666555, [0.060149, -0.014117, -0.010517], [0.001964, 0.000109, -0.001158, 0.004354, 0.000341, 0.005433]),
    ("panda_link7", 0.735522, [0.010517, -0.004252, 0.061597], [0.012516, -0.000428, -0.001196, 0.010027, -0.000741, 0.004815]),
    ("panda_hand", 0.73, [0.0, 0.0, 0.05], [0.0025, 0.0, 0.0, 0.0025, 0.0, 0.0017]),
]
# (name, type, parent-from-joint rotation, translation)
PANDA_JOINTS = [
    ("panda_base", "Hard", IDENTITY, [0.0, 0.0, 0.0]),
    ("panda_joint1", "Revolute", IDENTITY, [0.0, 0.0, 0.333]),
    ("panda_joint2", "Revolute", ROT_X_NEG, [0.0, 0.0, 0.0]),
    ("panda_joint3", "Revolute", ROT_X_POS, [0.0, -0.316, 0.0]),
    ("panda_joint4", "Revolute", ROT_X_POS, [0.0825, 0.0, 0.0]),
    ("panda_joint5", "Revolute", ROT_X_NEG, [-0.0825, 0.384, 0.0]),
    ("panda_joint6", "Revolute", ROT_X_POS, [0.0, 0.0, 0.0]),
    ("panda_joint7", "Revolute", ROT_X_POS, [0.088, 0.0, 0.0]),
    ("panda_hand_weld", "Hard", IDENTITY, [0.0, 0.0, 0.107]),
]
PANDA_READY = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785]
ARMATURE = 0.1  # kg m^2


def panda_bot_json() -> dict:
    links, joints = [], []
    for i, ((name, mass, com, inertia), (jname, jtype, rot, trans)) in enumerate(zip(PANDA_LINKS, PANDA_JOINTS)):
        link = {"name": name, "mass": mass, "centerOfMass": com, "momentOfInertia": inertia}
        if i > 0:
            link["parentLink"] = i - 1
        links.append(link)
        joint = {"name": jname, "type": jtype, "parentLinkFromJoint": {"rotation": rot, "translation": trans}}
        if jtype == "Revolute":
            joint["axis"] = [0.0, 0.0, 1.0]
            joint["inertia"] = ARMATURE
        joints.append(joint)
    return {"name": "panda_like", "links": links, "joints": joints, "defaultPose": PANDA_READY}


def rotor_bot_json(izz: float = 0.02, armature: float = 0.08) -> dict:
    """A welded base and one link turning about the vertical z axis through its centre of mass:
    no gravity torque and no velocity-dependent forces, so the joint obeys I dv/dt = tau with
    I = izz + armature."""
    return {
        "name": "rotor",
        "links": [
            {"name": "base", "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01]},
            {"name": "wheel", "parentLink": 0, "mass": 1.0, "momentOfInertia": [0.015, 0, 0, 0.015, 0, izz]},
        ],
        "joints": [
            {"name": "weld", "type": "Hard"},
            {"name": "spin", "type": "Revolute", "axis": [0, 0, 1], "inertia": armature,
             "parentLinkFromJoint": {"rotation": IDENTITY, "translation": [0, 0, 0.2]}},
        ],
        "defaultPose": [0.0],
    }


def load_bot(tmp_path: Path, doc: dict, name: str = "bot.superdex_bot"):
    path = tmp_path / name
    path.write_text(json.dumps(doc, indent=1))
    return sdr.load_bot_prefab_from_file(str(path))


def create_bot_from_json(scene, tmp_path: Path, doc: dict, name: str = "bot.superdex_bot"):
    """A new context and, in it, a bot made from `doc`: (context, bot, the bot's articulation)."""
    ctx = sdr.create_context()
    bot = sdr.create_bot(scene, load_bot(tmp_path, doc, name), ctx)
    return ctx, bot, bot.get_articulated_actor()


def link_actors(scene, bot):
    return [scene.get_actor(h) for h in bot.get_articulated_actor().get_nested_link_actors()]


def step(scene, dt: float, n: int):
    for _ in range(n):
        scene.step(dt)


def link_pose(arm, index: int):
    """World position (3,) and rotation matrix (3, 3) of link `index`."""
    n = len(arm.get_nested_link_actors())
    xforms = sdp.DynamicArrayTransformRT(n)
    arm.get_articulated_link_transforms(xforms)
    x, y, z, w = np.array(xforms[index].rotation, dtype=float)
    R = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])
    return np.array(xforms[index].translation, dtype=float), R


def tolerance(double: float, single: float) -> float:
    return double if sdp.uses_double_precision() else single
