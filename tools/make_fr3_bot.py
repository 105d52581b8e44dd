"""Writes assets/bots/arms/fr3/fr3.superdex_bot and assets/bots/arms/fr3_v2/fr3_v2.superdex_bot:
an FR3-like 7-DOF arm in the .superdex_bot format. The v2 file adds the flange as a massless link,
fr3_link8, welded 0.107 m along link 7's z axis: the link that hands and tools attach to (mod-bots
such as bots/arm_hand_combos/fr3_v2_revo2/ name it as their parent link).

Kinematics, joint limits, efforts and link inertials are Franka Robotics' published FR3 values
(see assets/bots/arms/fr3/README.md); the collision shapes are capsules of our own that join each
joint to the next one. Run from the repository root:  uv run python tools/make_fr3_bot.py
"""

import json
import math
from pathlib import Path

import numpy as np

ARMS = Path(__file__).resolve().parents[1] / "assets" / "bots" / "arms"
OUT = ARMS / "fr3" / "fr3.superdex_bot"
OUT_V2 = ARMS / "fr3_v2" / "fr3_v2.superdex_bot"

HALF_PI = math.pi / 2

# Joint frames in their parent link's frame: (translation m, roll about x rad); every axis is z.
JOINTS = [
    ([0.0, 0.0, 0.333], 0.0),
    ([0.0, 0.0, 0.0], -HALF_PI),
    ([0.0, -0.316, 0.0], HALF_PI),
    ([0.0825, 0.0, 0.0], HALF_PI),
    ([-0.0825, 0.384, 0.0], -HALF_PI),
    ([0.0, 0.0, 0.0], HALF_PI),
    ([0.088, 0.0, 0.0], HALF_PI),
]
# The flange (tool mounting face) in link 7's frame.
FLANGE = [0.0, 0.0, 0.107]

# Position limits (rad) and effort limits (N m) per joint.
LOWER = [-2.7437, -1.7837, -2.9007, -3.0421, -2.8065, 0.5445, -3.0159]
UPPER = [2.7437, 1.7837, 2.9007, -0.1518, 2.8065, 4.5169, 3.0159]
EFFORT = [87.0, 87.0, 87.0, 87.0, 12.0, 12.0, 12.0]
# Joint damping (N m s/rad) of the published dynamics.
DAMPING = 0.003
# Reflected rotor inertia (kg m^2): NOT published by Franka. An estimate of ours of the order of a
# harmonic-drive arm's, so that explicit joint-space controllers stay stable at 1 ms steps.
ARMATURE = [0.1, 0.1, 0.1, 0.1, 0.05, 0.05, 0.05]

# Link inertials: (mass kg, centre of mass m, inertia about the COM: xx, xy, xz, yy, yz, zz kg m^2).
INERTIALS = [
    (2.3966, [-0.0172, 0.0004, 0.0745], [0.0090, 0.0, 0.0020, 0.0115, 0.0, 0.0085]),
    (2.9274653454, [0.0000004128, -0.0181251324, -0.0386035970],
     [0.023927316485107913, 1.3317903455714081e-05, -0.00011404774918616684, 0.0224821613275756,
      -0.0019950320628240115, 0.006350098258530016]),
    (2.9355370338, [0.0031828864, -0.0743221644, 0.0088146084],
     [0.041938946257609425, 0.00020257331521090626, 0.004077784227179924, 0.02514514885014724,
      -0.0042252158006570156, 0.06170214472888839]),
    (2.2449013699, [0.0407015686, -0.0048200565, -0.0289730823],
     [0.02410142547240885, 0.002404694559042109, -0.002856269270114313, 0.01974053266708178,
      -0.002104212683891874, 0.019044494482244823]),
    (2.6155955791, [-0.0459100965, 0.0630492960, -0.0085187868],
     [0.03452998321913202, 0.01322552265982813, 0.01015142998484113, 0.028881621933049058,
      -0.0009762833870704552, 0.04125471171146641]),
    (2.3271207594, [-0.0016039605, 0.0292536262, -0.0972965990],
     [0.051610278463662895, -0.005715173387783472, -0.0035673167625872135, 0.04787729713371481,
      0.010673985108535986, 0.016423625579357254]),
    (1.8170376524, [0.0597131221, -0.0410294666, -0.0101692726],
     [0.005412333594383447, 0.006193456360285834, 0.0014219289306117652, 0.014058329545509979,
      -0.0013140753741120031, 0.016080817924212554]),
    (0.6271432862, [0.0045225817, 0.0086261921, -0.0161633251],
     [0.00021092389150104718, -2.433299114461931e-05, 4.564480393778983e-05, 0.00017718568002411474,
      8.744070223226438e-05, 5.993190599659971e-05]),
]

# The "ready" pose (rad), inside every limit.
READY = [0.0, -math.pi / 4, 0.0, -3 * math.pi / 4, 0.0, math.pi / 2, math.pi / 4]
RADIUS = [0.06, 0.06, 0.06, 0.055, 0.055, 0.05, 0.045, 0.04]
# Links at most this many joints apart do not collide: their capsules meet around the shared
# joints (elbow, wrist) in ordinary poses, where the real arm's shells do not touch.
NO_CONTACT_HOPS = 3


def check_inertia(i, m):
    """A physical inertia: symmetric positive definite, principal moments obeying the triangle inequality."""
    xx, xy, xz, yy, yz, zz = m
    eig = np.linalg.eigvalsh(np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]))
    assert eig.min() > 0, f"link {i}: inertia not positive definite {eig}"
    assert eig[0] + eig[1] >= eig[2] * (1 - 1e-9), f"link {i}: principal moments violate the triangle inequality {eig}"


def quat_roll(angle):
    """[x, y, z, w] of a rotation about x."""
    return [math.sin(angle / 2), 0.0, 0.0, math.cos(angle / 2)]


def quat_between(a, b):
    """[x, y, z, w] rotating unit vector a onto unit vector b."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    c = np.cross(a, b)
    w = 1.0 + float(a @ b)
    if w < 1e-9:  # opposite: half a turn about any axis normal to a
        c, w = np.array([1.0, 0.0, 0.0]) if abs(a[0]) < 0.9 else np.array([0.0, 1.0, 0.0]), 0.0
    q = np.array([*c, w])
    return [round(float(x), 9) for x in q / np.linalg.norm(q)]


def segment_shape(end, radius):
    """A capsule from the link origin to `end` (link frame), or a sphere when they coincide."""
    end = np.asarray(end, float)
    length = float(np.linalg.norm(end))
    if length < 1e-6:
        return {"sphere": {"radius": radius}}
    # capsules run along their local z axis
    return {"capsule": {"radius": radius, "halfLength": round(length / 2, 9),
                        "center": [round(float(x), 9) for x in end / 2],
                        "rotation": quat_between([0, 0, 1], end / length)}}


def arm(name, flange_link):
    """The arm's bot document; with `flange_link`, the massless flange link fr3_link8 on a weld."""
    links, joints = [], []
    for i, (mass, com, inertia) in enumerate(INERTIALS):
        check_inertia(i, inertia)
        # each link's shape joins its origin to the next joint (the flange for link 7)
        end = JOINTS[i][0] if i < len(JOINTS) else FLANGE
        link = {"name": f"fr3_link{i}", "mass": mass, "centerOfMass": com, "momentOfInertia": inertia,
                "shape": segment_shape(end, RADIUS[i]), "contact": {"coulombFrictionCoefficient": 0.6}}
        if i > 0:
            link["parentLink"] = i - 1
        links.append(link)
    joints.append({"name": "fr3_base_weld", "type": "Hard"})
    for j, (translation, roll) in enumerate(JOINTS):
        joints.append({
            "name": f"fr3_joint{j + 1}", "type": "Revolute", "axis": [0.0, 0.0, 1.0],
            "parentLinkFromJoint": {"rotation": quat_roll(roll), "translation": translation},
            "minLimit": [0.0, 0.0, LOWER[j]], "maxLimit": [0.0, 0.0, UPPER[j]],
            "effortLimit": EFFORT[j], "inertia": ARMATURE[j],
            "friction": {"coulomb": 0.0, "viscous": DAMPING},
        })
    overrides = [{"linkA": links[a]["name"], "linkB": links[b]["name"], "enable": False}
                 for a in range(len(links)) for b in range(a + 2, min(a + NO_CONTACT_HOPS, len(links) - 1) + 1)]
    if flange_link:
        # a frame, no body: merged into link 7 by the weld
        links.append({"name": "fr3_link8", "parentLink": len(links) - 1, "mass": 0.0, "centerOfMass": [0.0, 0.0, 0.0],
                      "momentOfInertia": [0.0] * 6})
        joints.append({"name": "fr3_joint8", "type": "Hard", "parentLinkFromJoint": {"translation": FLANGE}})
    return {"name": name, "links": links, "joints": joints, "defaultPose": [round(q, 9) for q in READY],
            "contactOverrides": overrides}


def main():
    for out, bot in ((OUT, arm("fr3", False)), (OUT_V2, arm("fr3_v2", True))):
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(json.dumps(bot, indent=2) + "\n")
        print(f"wrote {out}")


if __name__ == "__main__":
    main()
