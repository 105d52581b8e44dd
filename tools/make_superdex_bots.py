"""Writes the bot files that SuperDex's public asset tree ships, in its layout, with stand-in shapes:

  assets/bots/hands/revo2/{left,right}/revo2_{left,right}.superdex_bot   BrainCo Revo2 hands
  assets/bots/arm_hand_combos/fr3_v2_revo2/fr3_v2_revo2_{left,right}.superdex_bot
                                        mod-bots: the FR3 v2 arm, a mount and a Revo2 hand
  assets/bots/fun/googly_eyes/googly_eyes_extra_small.superdex_bot         a googly eye
  assets/bots/.superdex_root            the asset root that "//" paths start from

The bot files carry the kinematics, limits, inertials, transmissions, contact parameters and
tactile pads of SuperDex's public bot files (facebookresearch/project_superdex, Apache-2.0). Their
collision and render meshes are not public; each link's `collision/*.mochi.h5` and `render/*.glb`
here is a stand-in of ours: a box with the link's principal axes and inertia proportions, centred
at its centre of mass, scaled to the link's mass at 1000 kg/m^3 (see the README of each folder).
Run from the repository root (h5py is a development dependency):

    uv run python tools/make_superdex_bots.py
"""

import json
import sys
from pathlib import Path

import h5py
import numpy as np

REPO = Path(__file__).resolve().parents[1]
BOTS = REPO / "assets" / "bots"
sys.path.insert(0, str(REPO / "tools"))
from build_render_models import write_glb  # noqa: E402

# Every actuated Revo2 joint: Coulomb and viscous friction, reflected rotor inertia (kg m^2).
FRICTION = {"coulomb": 0.002, "viscous": 0.005}
ROTOR = 2e-05
# The contact of every Revo2 link with a shape; the fingertip pads add a friction coefficient.
CONTACT = {"penaltySmoothingHalfDistance": 0.0005, "penaltyThresholdDefault": 0.0005}
PAD_CONTACT = {"coulombFrictionCoefficient": 1.0, **CONTACT}
# Distal joints follow their proximal joints: (finger, ratio), as [ratio, -1] transmissions.
MIMIC = [("thumb", 1.0945), ("index", 1.131), ("middle", 1.267), ("ring", 1.252), ("pinky", 1.271)]
FINGERS = ["index", "middle", "pinky", "ring"]
STANDIN_DENSITY = 1000.0  # kg/m^3


def rev(axis, upper, effort, rotation=None, translation=None):
    """A Revolute joint from 0 to `upper` (rad) about `axis`; limits as vectors along the axis."""
    k = int(np.argmax(np.abs(axis)))
    hi = [0.0, 0.0, 0.0]
    hi[k] = upper
    return {"type": "Revolute", "axis": [float(a) for a in axis], "effortLimit": effort, "friction": dict(FRICTION),
            "inertia": ROTOR, "maxLimit": hi, "minLimit": [0.0, 0.0, 0.0], "pose": (rotation, translation)}


def hard(rotation, translation):
    return {"type": "Hard", "maxLimit": [0, 0, 0], "minLimit": [0, 0, 0], "pose": (rotation, translation)}


def pad(cols, rotation, translation, size):
    """A TACTILE_PAD: a rows x cols grid of taxels over a size[0] x size[1] m pad."""
    return {"cols": cols, "rows": 8, "rotation": rotation, "translation": translation, "size": size}


# Per hand: joints and links in file order (the tree in depth-first order, siblings by name).
# A joint: rev(...) / hard(...); a link: (parent, mass kg, centre of mass m, inertia about it
# [xx, xy, xz, yy, yz, zz] kg m^2, tactile pad or None). Massless tip links carry no shape.
LEFT = {
    "joints": {
        "index_proximal": rev([0, 1, 0], 1.41, 2.0, [0.052280683, 0.078365246, 0.082278934, 0.992147063], [-0.0021349, -0.029578, 0.080876]),
        "index_distal": rev([0, 1, 0], 1.69297, 2.0, None, [0.0, 0.0, 0.032]),
        "index_tip": hard([0.0, 0.241212452, 0.0, 0.970472335], [0.011097, 0.0, 0.035739]),
        "index_touch": hard([0.0, 0.235565109, 0.0, 0.97185857], [0.014497, 0.0, 0.023303]),
        "middle_proximal": rev([0, 1, 0], 1.41, 2.0, [0.017523494, 0.074606879, 0.027436944, 0.996681471], [-0.0045935, -0.010061, 0.084993]),
        "middle_distal": rev([0, 1, 0], 1.69297, 2.0, [0.0, 0.063227796, 0.0, 0.997999121], [0.0, 0.0, 0.037]),
        "middle_tip": hard([0.0, 0.173650221, 0.0, 0.984807393], [0.0073534, 0.0, 0.041703]),
        "middle_touch": hard([0.0, 0.173650221, 0.0, 0.984807393], [0.012493, 0.0, 0.028393]),
        "pinky_proximal": rev([0, 1, 0], 1.41, 2.0, [-0.052386955, 0.077106528, -0.082213567, 0.992245494], [-0.0023733, 0.029356, 0.078694]),
        "pinky_distal": rev([0, 1, 0], 1.69297, 2.0, None, [0.0, 0.0, 0.029]),
        "pinky_tip": hard([0.0, 0.235565109, 0.0, 0.97185857], [0.010221, 0.0, 0.032918]),
        "pinky_touch": hard([0.0, 0.235565109, 0.0, 0.97185857], [0.01401, 0.0, 0.021124]),
        "ring_proximal": rev([0, 1, 0], 1.41, 2.0, [-0.01753864, 0.074063264, -0.027427623, 0.996722005], [-0.0046877, 0.010026, 0.083982]),
        "ring_distal": rev([0, 1, 0], 1.69297, 2.0, [0.0, 0.063227796, 0.0, 0.997999121], [0.0, 0.0, 0.035]),
        "ring_tip": hard([0.0, 0.173650221, 0.0, 0.984807393], [0.0071824, 0.0, 0.040734]),
        "ring_touch": hard([0.0, 0.173650221, 0.0, 0.984807393], [0.012028, 0.0, 0.027796]),
        "thumb_metacarpal": rev([0, 0, 1], 1.55334, 0.5, [0.0, 0.0, 0.109892605, 0.993943467], [0.0045, -0.019, 0.027825]),
        "thumb_proximal": rev([-1, 0, 0], -1.0472, 1.1, [-0.153479077, 0.130103768, -0.062637345, 0.977544754], [0.0, -0.014227, 0.0]),
        "thumb_distal": rev([-1, 0, 0], -1.15192, 1.1, [0.052336079, 0.0, 0.0, 0.998629528], [0.0, -0.052, 0.0]),
        "thumb_tip": hard([0.033368804, 0.0, 0.0, 0.999443106], [0.0, -0.026529, -0.0017734]),
        "thumb_touch": hard([0.087328618, 0.0, 0.0, 0.996179558], [0.0, -0.013836, 0.0076686]),
    },
    "links": {
        "base": (None, 0.238, [-0.005262508, 0.003392559, 0.052137917], [2.1090221724e-05, -3.9138247e-08, 9.2095467e-08, 1.4459244699e-05, 1.100006253e-06, 7.997820518e-06], None),
        "index_proximal": (0, 0.009, [-0.002235387, -3.805e-06, 0.017643942], [2.51863527e-07, -3.1093e-11, -6.369013e-09, 2.36343211e-07, -1.71664e-10, 9.3039754e-08], None),
        "index_distal": (1, 0.009, [0.003301659, 6.3e-08, 0.01420758], [3.39958467e-07, -2e-14, -8.7500944e-08, 3.62235424e-07, 2.213e-12, 9.1033906e-08], None),
        "index_tip": (2, 0.0, None, None, None),
        "index_touch": (2, 0.002, [-0.002999182, 7e-09, 0.002523698], [6.777298e-09, 1.9e-14, 1.515116e-09, 5.414854e-09, 7.55e-13, 3.191575e-09],
                        pad(6, [0.43161881, 0.393679103, 0.594647831, 0.552372992], [-9.0093e-05, 1.474e-05, 0.002590291], [0.01175984, 0.018026602])),
        "middle_proximal": (0, 0.009, [-0.002224194, -3.62e-06, 0.020304953], [3.66885321e-07, -3.643e-11, -9.779953e-09, 3.52521387e-07, -2.58098e-10, 1.12242284e-07], None),
        "middle_distal": (5, 0.009, [0.00189418, -2.3e-08, 0.016871115], [5.40534109e-07, 2.941e-12, -8.3516293e-08, 5.49812279e-07, 7.85e-13, 9.5560671e-08], None),
        "middle_tip": (6, 0.0, None, None, None),
        "middle_touch": (6, 0.002, [-0.003192889, -2.9e-08, 0.002978599], [1.0048692e-08, -5.4e-14, 2.259181e-09, 8.232311e-09, 1.98e-13, 4.412725e-09],
                         pad(6, [0.426518406, 0.410120305, 0.57660748, 0.56338903], [-7.1025e-05, -9.75e-07, 0.00291076], [0.01219834, 0.019859962])),
        "pinky_proximal": (0, 0.009, [-0.002132666, -7.023e-06, 0.016068035], [1.97554078e-07, -1.3413e-11, -4.586018e-09, 1.82022483e-07, -1.01838e-10, 8.2175816e-08], None),
        "pinky_distal": (9, 0.009, [0.00307951, -1.23e-07, 0.013023892], [2.70011722e-07, -3.87e-13, -6.7065247e-08, 2.85232999e-07, 2.311e-12, 7.9073805e-08], None),
        "pinky_tip": (10, 0.0, None, None, None),
        "pinky_touch": (10, 0.002, [-0.002891417, -2.12e-07, 0.001653881], [6.919144e-09, 1.05e-13, 1.427465e-09, 5.343607e-09, -7.7e-14, 3.282921e-09],
                        pad(6, [0.41827021, 0.423035164, 0.55949759, 0.577108073], [3.497e-05, -6.7094e-05, 0.001641211], [0.011849051, 0.018020914])),
        "ring_proximal": (0, 0.009, [-0.002344614, -5.321e-06, 0.019178593], [3.14182211e-07, -3.4483e-11, -7.780119e-09, 2.97623388e-07, -2.45024e-10, 1.02120946e-07], None),
        "ring_distal": (13, 0.009, [0.001770536, 6.4e-08, 0.016388959], [4.97910633e-07, -7.13e-13, -7.8333106e-08, 5.06076323e-07, -3.127e-12, 8.9649659e-08], None),
        "ring_tip": (14, 0.0, None, None, None),
        "ring_touch": (14, 0.002, [-0.00302346, -4.1e-08, 0.00304076], [8.201804e-09, -4.5e-14, 1.832114e-09, 6.636513e-09, 6e-14, 3.619258e-09],
                       pad(6, [0.423485314, 0.410130451, 0.577645731, 0.564604828], [-8.0844e-05, 1.5558e-05, 0.002984606], [0.011855516, 0.019128519])),
        "thumb_metacarpal": (0, 0.01, [1.523e-05, -0.007072403, -0.004208398], [1.59238866e-07, 4.691146e-09, 4.93234e-10, 1.60911967e-07, 1.4814495e-08, 5.1354426e-08], None),
        "thumb_proximal": (17, 0.05, [-3.69e-07, -0.027701579, -0.002026683], [2.404508293e-06, 1.70279e-10, 1.2163e-11, 5.12299191e-07, 2.890235e-08, 2.56255683e-06], None),
        "thumb_distal": (18, 0.01, [1.66e-07, -0.011755089, 1.1367e-05], [1.67809286e-07, 1.9186e-11, 2.695e-12, 1.1535724e-07, -1.2518256e-08, 2.19566152e-07], None),
        "thumb_tip": (19, 0.0, None, None, None),
        "thumb_touch": (19, 0.002, [1.36e-07, 0.000717207, -0.007902525], [1.67809287e-07, 1.9362e-11, -6.84e-13, 1.14222234e-07, 6.094321e-09, 2.2070116e-07],
                        pad(8, [-0.008260114, -0.012158912, 0.993886362, 0.109425003], [-0.001176411, -0.001877699, 8.0668e-05], [0.020484576, 0.024388359])),
    },
}

RIGHT = {
    "joints": {
        "index_proximal": rev([0, 1, 0], 1.41, 2.0, [-0.052280683, 0.078365246, -0.082278934, 0.992147063], [-0.0021181, 0.029568, 0.080876]),
        "index_distal": rev([0, 1, 0], 1.69297, 2.0, None, [0.0, 0.0, 0.032]),
        "index_tip": hard([0.0, 0.235565109, 0.0, 0.97185857], [0.011097, 0.0, 0.035739]),
        "index_touch": hard([0.734769295, 0.154181855, -0.17809794, 0.636099963], [0.014497, 0.0, 0.023303]),
        "middle_proximal": rev([0, 1, 0], 1.41, 2.0, [-0.017523494, 0.074606879, -0.027436944, 0.996681471], [-0.0045767, 0.010051, 0.084993]),
        "middle_distal": rev([0, 1, 0], 1.69297, 2.0, None, [0.0, 0.0, 0.037]),
        "middle_tip": hard([0.0, 0.235565109, 0.0, 0.97185857], [0.012558, 0.0, 0.040442]),
        "middle_touch": hard([0.0, 0.235566189, 0.0, 0.971858308], [0.015975872, 0.0, 0.026589427]),
        "pinky_proximal": rev([0, 1, 0], 1.41, 2.0, [0.052386955, 0.077106528, 0.082213567, 0.992245494], [-0.0023566, -0.029366, 0.078694]),
        "pinky_distal": rev([0, 1, 0], 1.69297, 2.0, None, [0.0, 0.0, 0.029]),
        "pinky_tip": hard([0.0, 0.235565109, 0.0, 0.97185857], [0.010221, 0.0, 0.032918]),
        "pinky_touch": hard([0.0, 0.235565109, 0.0, 0.97185857], [0.01401, 0.0, 0.021124]),
        "ring_proximal": rev([0, 1, 0], 1.41, 2.0, [0.01753864, 0.074063264, 0.027427623, 0.996722005], [-0.0046709, -0.010037, 0.083982]),
        "ring_distal": rev([0, 1, 0], 1.69297, 2.0, None, [0.0, 0.0, 0.035]),
        "ring_tip": hard([0.0, 0.235565109, 0.0, 0.97185857], [0.012266, 0.0, 0.039501]),
        "ring_touch": hard([0.0, 0.235566189, 0.0, 0.971858308], [0.015439232, 0.0, 0.026056104]),
        "thumb_metacarpal": rev([0, 0, -1], -1.55334, 0.5, [0.0, 0.0, -0.109892605, 0.993943467], [0.005619, 0.019867, 0.027825]),
        "thumb_proximal": rev([1, 0, 0], 1.0472, 1.1, [0.153479077, 0.130103768, 0.062637345, 0.977544754], [0.0, 0.014227, 0.0]),
        "thumb_distal": rev([1, 0, 0], 1.15192, 1.1, [-0.052336079, 0.0, 0.0, 0.998629528], [0.0, 0.052, 0.0]),
        "thumb_tip": hard([-0.03336903, 0.0, 0.0, 0.999443099], [0.0, 0.026528781, -0.001773443]),
        "thumb_touch": hard([-0.03336903, 0.0, 0.0, 0.999443099], [0.0, 0.013792752, 0.007676599]),
    },
    "links": {
        "base": (None, 0.238, [-0.005243781, -0.003403803, 0.052126677], [2.1091166667e-05, 3.8632205e-08, 9.3639915e-08, 1.4462191476e-05, -1.09576502e-06, 7.998114995e-06], None),
        "index_proximal": (0, 0.009, [-0.002234952, 3.159e-06, 0.017640202], [2.51945688e-07, 1.1977e-11, -6.372756e-09, 2.36435336e-07, 1.65019e-10, 9.3035105e-08], None),
        "index_distal": (1, 0.009, [0.0033017, 1.81e-07, 0.01420769], [3.39968051e-07, -2.724e-12, -8.7504119e-08, 3.62244794e-07, -3.692e-12, 9.1034511e-08], None),
        "index_tip": (2, 0.0, None, None, None),
        "index_touch": (2, 0.002, [-0.002999116, 0.002497426, -0.000361458], [6.776917e-09, 1.499251e-09, -2.16894e-10, 3.238013e-09, 3.14647e-10, 5.367915e-09],
                        pad(6, [-0.158927101, 0.709800403, 0.076259081, 0.681989822], [-3.9285e-05, 0.00262083, -0.00044028], [0.011727402, 0.018151911])),
        "middle_proximal": (0, 0.009, [-0.002225111, 5.256e-06, 0.020300778], [3.66996237e-07, 2.6834e-11, -9.798366e-09, 3.52645348e-07, 2.57866e-10, 1.12233933e-07], None),
        "middle_distal": (5, 0.009, [0.004008152, -2.9e-08, 0.016497398], [5.12550472e-07, 2.496e-12, -1.3656937e-07, 5.49827694e-07, 1.151e-12, 1.23560211e-07], None),
        "middle_tip": (6, 0.0, None, None, None),
        "middle_touch": (6, 0.002, [-0.003192892, -1.9e-08, 0.002978604], [1.0048666e-08, -7.9e-14, 2.259178e-09, 8.232281e-09, 1.51e-13, 4.412722e-09],
                         pad(6, [0.426518406, 0.410120305, 0.57660748, 0.56338903], [-7.1025e-05, -9.75e-07, 0.00291076], [0.01219834, 0.019859962])),
        "pinky_proximal": (0, 0.009, [-0.00213212, 7.75e-06, 0.016067158], [1.97563214e-07, 2.234e-11, -4.584257e-09, 1.82023043e-07, 1.08028e-10, 8.2162471e-08], None),
        "pinky_distal": (9, 0.009, [0.003079742, -1.55e-07, 0.013024697], [2.70050429e-07, 1.68e-12, -6.7078025e-08, 2.85275082e-07, 5.106e-12, 7.9079871e-08], None),
        "pinky_tip": (10, 0.0, None, None, None),
        "pinky_touch": (10, 0.002, [-0.002891424, -2.01e-07, 0.00165388], [6.919118e-09, 1.22e-13, 1.427486e-09, 5.343647e-09, 7.2e-14, 3.282897e-09],
                        pad(6, [0.41827021, 0.423035164, 0.55949759, 0.577108073], [3.497e-05, -6.7094e-05, 0.001641211], [0.011849051, 0.018020914])),
        "ring_proximal": (0, 0.009, [-0.002344945, 5.88e-06, 0.019177403], [3.14177685e-07, 3.3438e-11, -7.789818e-09, 2.9761317e-07, 2.41252e-10, 1.02115432e-07], None),
        "ring_distal": (13, 0.009, [0.0038246, 7.8e-08, 0.016034376], [4.71792497e-07, -6.95e-13, -1.26948441e-07, 5.06071999e-07, -2.194e-12, 1.15762768e-07], None),
        "ring_tip": (14, 0.0, None, None, None),
        "ring_touch": (14, 0.002, [-0.003023458, -4.4e-08, 0.00304076], [8.20181e-09, -2.6e-14, 1.832113e-09, 6.63652e-09, 1.13e-13, 3.61926e-09],
                       pad(6, [0.423485314, 0.410130451, 0.577645731, 0.564604828], [-8.0844e-05, 1.5558e-05, 0.002984606], [0.011855516, 0.019128519])),
        "thumb_metacarpal": (0, 0.01, [1.5111e-05, 0.007072425, -0.004208473], [1.59239837e-07, -4.691008e-09, 4.92934e-10, 1.60913457e-07, -1.4814673e-08, 5.1355026e-08], None),
        "thumb_proximal": (17, 0.05, [-4.7e-07, 0.027701501, -0.002026563], [2.404519525e-06, -1.31093e-10, 8.325e-12, 5.12323838e-07, -2.8915475e-08, 2.562542196e-06], None),
        "thumb_distal": (18, 0.01, [-6e-09, 0.011754472, 1.1332e-05], [1.67793545e-07, 7.159e-12, -6.801e-12, 1.15362129e-07, 1.2517499e-08, 2.19553178e-07], None),
        "thumb_tip": (19, 0.0, None, None, None),
        "thumb_touch": (19, 0.002, [-1.2e-08, -0.001522527, -0.007784178], [1.67793545e-07, 7.559e-12, -6.385e-12, 1.14159538e-07, 5.471959e-09, 2.20755769e-07],
                        pad(8, [-0.070619841, 0.000583337, 0.045912308, 0.996445963], [-0.00060451, 0.002418638, -0.000158823], [0.019725424, 0.024117667])),
    },
}

# The mount between the FR3 v2 flange and a Revo2 (a disc, 0.1 kg), and its pose on the flange.
MOUNT = (0.101062, [0.0, 0.0, 0.006573505], [2.2777813e-05, 0.0, 0.0, 2.2777813e-05, 0.0, 4.2041285e-05])
MOUNT_ROTATION = [0.0, 0.0, -0.382683432, 0.923879533]  # -45 degrees about the flange's z
HAND_ON_MOUNT = [0.0, 0.0, 0.015]

# The googly eye (extra small): a base and an eye spinning about y, modelled at 10x and scaled 0.1.
GOOGLY_SCALE = 0.10000000149011612
GOOGLY = {
    "base": (3.5865487006958574e-05, [-2.9475605956008621e-08, 0.00033987965434789658, 9.5836639957269654e-08],
             [2.0657385524369687e-10, 4.2048663677482154e-16, -5.0999874930005105e-15, 4.1167086406446174e-10, -1.1665837499025104e-15, 2.0655796517665692e-10]),
    "eye": (3.9939318412507419e-06, [-0.002499838825315237, 0.00023841779329814017, -6.4023950585578859e-08],
            [4.3397889448737459e-12, -4.466698379989382e-18, -4.8021149898598369e-17, 8.621595624924705e-12, 2.2583581686346192e-18, 4.3391982715301758e-12]),
}
GOOGLY_SPIN_LIMIT = 628.31854248046875  # rad: 100 turns either way


def inertia_box(mass, com, inertia):
    """(centre, axes 3x3 columns, half extents) of the box with the link's mass and inertia."""
    xx, xy, xz, yy, yz, zz = inertia
    moments, axes = np.linalg.eigh(np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]))
    # a box of half extents h has I_k = m/3 (h_i^2 + h_j^2): h_k^2 = 3/(2m) (I_i + I_j - I_k)
    h2 = np.array([moments.sum() - 2 * moments[k] for k in range(3)]) * 1.5 / mass
    return np.asarray(com, float), axes, np.sqrt(np.maximum(h2, 1e-3 * h2.max()))


def density_scale(mass, h):
    """The factor that brings a box of half extents h to STANDIN_DENSITY at the given mass."""
    return max(1.0, ((mass / STANDIN_DENSITY) / (8 * h.prod())) ** (1 / 3))


def corners_of(centre, axes, h):
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], float)
    return (signs * h) @ axes.T + centre


def boxes_overlap(a, b, margin):
    """Separating-axis test of two oriented boxes (centre, axes, half extents), grown by `margin`."""
    (ca, Ra, ha), (cb, Rb, hb) = a, b
    d = cb - ca
    candidates = [Ra[:, i] for i in range(3)] + [Rb[:, i] for i in range(3)]
    candidates += [np.cross(Ra[:, i], Rb[:, j]) for i in range(3) for j in range(3)]
    for n in candidates:
        if np.linalg.norm(n) < 1e-9:
            continue
        n = n / np.linalg.norm(n)
        ra = np.abs(Ra.T @ n) @ ha + margin
        rb = np.abs(Rb.T @ n) @ hb + margin
        if abs(d @ n) > ra + rb:
            return False
    return True


def standin_boxes(links, poses, touching_allowed, margin=0.001):
    """Link-frame corners of each link's stand-in box: its inertia box grown towards 1000 kg/m^3,
    all by one factor small enough that no two links that may collide overlap (with `margin`) at
    zero joint positions. `poses` are the links' 4x4 poses at zero; `touching_allowed(i, j)` is
    true for pairs that never collide (parent and child, pairs switched off in the file)."""
    base = {i: inertia_box(m, c, I) for i, (m, c, I) in links.items()}
    limit = {i: density_scale(links[i][0], base[i][2]) for i in base}
    grow = max(limit.values())
    while True:
        boxes = {}
        for i, (c, R, h) in base.items():
            T = poses[i]
            boxes[i] = (T[:3, :3] @ c + T[:3, 3], T[:3, :3] @ R, h * min(grow, limit[i]))
        clash = [(i, j) for i in boxes for j in boxes if i < j and not touching_allowed(i, j)
                 and boxes_overlap(boxes[i], boxes[j], margin)]
        if not clash or grow <= 1.0:
            break
        grow = max(1.0, grow * 0.97)
    return {i: corners_of(c, R, h * min(grow, limit[i])) for i, (c, R, h) in base.items()}


# The 12 outward triangles of corners_of's corners (index = 4 sx + 2 sy + sz, bits for +).
BOX_TRIANGLES = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                          [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])


def oriented_triangles(corners):
    """BOX_TRIANGLES, flipped where the principal axes form a left-handed frame."""
    c = corners.mean(axis=0)
    tris = BOX_TRIANGLES.copy()
    a, b, d = corners[tris[0]]
    if np.dot(np.cross(b - a, d - a), a - c) < 0:
        tris = tris[:, ::-1]
    return tris


def write_standins(folder: Path, stem: str, corners):
    """collision/<stem>_collision.mochi.h5 (a closed triangle mesh) and render/<stem>_render.glb."""
    tris = oriented_triangles(corners)
    (folder / "collision").mkdir(parents=True, exist_ok=True)
    (folder / "render").mkdir(parents=True, exist_ok=True)
    with h5py.File(folder / "collision" / f"{stem}_collision.mochi.h5", "w") as f:
        f.create_dataset("mesh/coordinates", data=corners.astype(np.float64))
        f.create_dataset("mesh/connectivity", data=tris.astype(np.int32))
    # flat-shaded: three vertices of its own per triangle, with the face normal
    v = corners[tris].reshape(-1, 3)
    n = np.repeat(np.cross(v[1::3] - v[0::3], v[2::3] - v[0::3]), 3, axis=0)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    write_glb(folder / "render" / f"{stem}_render.glb", [(v, n, np.arange(len(v)).reshape(-1, 3), (0.72, 0.74, 0.78, 1.0))])


def pose(rotation, translation):
    out = {}
    if rotation is not None:
        out["rotation"] = rotation
    if translation is not None:
        out["translation"] = translation
    return out


def revo2_geometry(data, side):
    """(links with mass {index: (mass, com, inertia)}, zero-pose link poses, pairs that never collide)."""
    keys, joints = list(data["links"]), [None] + list(data["joints"].values())
    parents = [p for p, *_ in data["links"].values()]
    poses = [np.eye(4)]
    for i in range(1, len(keys)):
        rotation_, translation = joints[i]["pose"]
        T = np.eye(4)
        T[:3, :3] = quat_matrix(rotation_ or [0, 0, 0, 1])
        T[:3, 3] = translation or [0, 0, 0]
        poses.append(poses[parents[i]] @ T)
    # a welded link belongs to its parent's body; contact skips one body and the next along the tree
    body = [0] * len(keys)
    for i in range(1, len(keys)):
        body[i] = body[parents[i]] if joints[i]["type"] == "Hard" else i
    off = {frozenset((0, keys.index("thumb_proximal")))}

    def never(i, j):
        a, b = body[i], body[j]
        adjacent = a == b or (parents[b] is not None and body[parents[b]] == a) or (parents[a] is not None and body[parents[a]] == b)
        return adjacent or frozenset((i, j)) in off

    massive = {i: (m, c, I) for i, (_, m, c, I, _) in enumerate(data["links"].values()) if m > 0}
    return massive, {i: poses[i] for i in massive}, never


def quat_matrix(q):
    x, y, z, w = np.asarray(q, float) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def revo2(side, data):
    folder = BOTS / "hands" / "revo2" / side
    joints = [{"name": "world_joint", "type": "Free"}]
    for key, j in data["joints"].items():
        entry = {k: v for k, v in j.items() if k != "pose"}
        entry["name"] = f"{side}_{key}_joint"
        entry["parentLinkFromJoint"] = pose(*j["pose"])
        joints.append(dict(sorted(entry.items())))
    keys = list(data["links"])
    boxes = standin_boxes(*revo2_geometry(data, side))
    links = []
    for i, (key, (parent, mass, com, inertia, tactile)) in enumerate(data["links"].items()):
        name = f"{side}_{key}_link"
        link = {"name": name}
        if parent is not None:
            link["parentLink"] = parent
        if mass == 0:
            link.update(mass=0.0, centerOfMass=[0.0, 0.0, 0.0], momentOfInertia=[0.0] * 6)
        else:
            link.update(mass=mass, centerOfMass=com, momentOfInertia=inertia)
            link["contact"] = dict(PAD_CONTACT if tactile else CONTACT)
            if not tactile:
                link["boundaryElementType"] = "P1Q1"
            link["shape"] = f"collision/{name}_collision.mochi.h5"
            link["renderModel"] = f"render/{name}_render.glb"
            write_standins(folder, name, boxes[i])
        if tactile:
            where = {"rotation": tactile["rotation"], "translation": tactile["translation"]}
            params = {"cols": tactile["cols"], "pad_from_sensor": where, "rows": tactile["rows"], "size": tactile["size"]}
            link["sensors"] = [{"name": f"{key.split('_')[0]}_tactile", "params": json.dumps(params),
                                "parentFromSensor": where, "type": "TACTILE_PAD"}]
        links.append(dict(sorted(link.items())))
    assert len(keys) == len(joints)
    index = {f"{side}_{key}_joint": i for i, key in enumerate(["world"] + list(data["joints"]))}
    transmissions = [{"allowCompressiveForce": True, "damping": 0.05, "jointAxisDisps": [0.0, 0.0],
                      "jointCoefficients": [ratio, -1.0],
                      "jointIndices": [index[f"{side}_{finger}_proximal_joint"], index[f"{side}_{finger}_distal_joint"]],
                      "name": f"{side}_{finger}_distal_joint_mimic", "stiffness": 50.0} for finger, ratio in MIMIC]
    dofs = sum(1 for j in joints if j["type"] == "Revolute")
    bot = {"contactOverrides": [{"enable": False, "linkA": f"{side}_base_link", "linkB": f"{side}_thumb_proximal_link"}],
           "defaultPose": [0.0] * dofs, "joints": joints, "linearTransmissions": transmissions, "links": links,
           "name": f"revo2_{side}"}
    write_json(folder / f"revo2_{side}.superdex_bot", bot)


def combos():
    folder = BOTS / "arm_hand_combos" / "fr3_v2_revo2"
    mass, com, inertia = MOUNT
    write_standins(folder, "fr3_revo2_mount", standin_boxes({0: MOUNT}, {0: np.eye(4)}, lambda i, j: True)[0])
    for side in ("left", "right"):
        mount = {"AttachLink": {
            "enabled": True,
            "joint": {"name": "fr3_revo2_mount_joint", "type": "Hard", "parentLinkFromJoint": {"rotation": MOUNT_ROTATION}},
            "link": {"centerOfMass": com, "mass": mass, "momentOfInertia": inertia, "name": "fr3_revo2_mount",
                     "renderModel": "render/fr3_revo2_mount_render.glb", "shape": "collision/fr3_revo2_mount_collision.mochi.h5"},
            "name": "fr3_revo2_mount", "parentLinkName": "fr3_link8"}}
        hand = {"AttachBot": {
            "enabled": True,
            "joint": {"name": f"mount_to_revo2_{side}", "type": "Hard", "parentLinkFromJoint": {"translation": HAND_ON_MOUNT}},
            "name": f"revo2_{side}", "parentLinkName": "fr3_revo2_mount",
            "path": f"//hands/revo2/{side}/revo2_{side}.superdex_bot"}}
        write_json(folder / f"fr3_v2_revo2_{side}.superdex_bot",
                   {"base": "//arms/fr3_v2/fr3_v2.superdex_bot", "modifications": [mount, hand], "name": f"fr3_v2_revo2_{side}"})


def googly_eyes():
    folder = BOTS / "fun" / "googly_eyes"
    scale = [GOOGLY_SCALE] * 3
    links = []
    for i, (key, (mass, com, inertia)) in enumerate(GOOGLY.items()):
        # the shape files are modelled at 1 / scale, like the rest of the file's geometry
        # the eye spins inside the base: parent and child never collide
        box = standin_boxes({0: (mass, com, inertia)}, {0: np.eye(4)}, lambda i, j: True)[0]
        write_standins(folder, key, box / GOOGLY_SCALE)
        link = {"centerOfMass": com, "mass": mass, "momentOfInertia": inertia, "name": key,
                "renderModel": f"render/{key}_render.glb", "renderModelScale": scale,
                "shape": f"collision/{key}_collision.mochi.h5", "shapeScale": scale}
        if i > 0:
            link["parentLink"] = 0
        links.append(link)
    joints = [{"name": "world_joint", "type": "Hard"},
              {"axis": [0, 1, 0], "effortLimit": 0, "maxLimit": [0, GOOGLY_SPIN_LIMIT, 0], "minLimit": [0, -GOOGLY_SPIN_LIMIT, 0],
               "name": "joint_eye", "type": "Revolute"}]
    write_json(folder / "googly_eyes_extra_small.superdex_bot", {"defaultPose": [0], "joints": joints, "links": links, "name": "googly_eyes"})


def write_json(path: Path, doc):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(doc, indent=2) + "\n")
    print(f"wrote {path.relative_to(REPO)}")


def main():
    # an empty marker: "//" paths in bot files start from this folder
    (BOTS / ".superdex_root").write_text("")
    revo2("left", LEFT)
    revo2("right", RIGHT)
    combos()
    googly_eyes()


if __name__ == "__main__":
    main()
