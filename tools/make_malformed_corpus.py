"""Writes the corpus of malformed input files and its manifest.

    uv run python tools/make_malformed_corpus.py [--out DIR]

Every file is a small, deliberately broken input for one of the engine's loaders: bot JSON
(`.superdex_bot`), prefab JSON (`.mochi_prefab`), URDF, MJCF, `.mochi.h5`, OBJ, STL, PLY and debugger
recordings (`.jsonl`, read by `superdex view`). `manifest.json` lists, for each file, the loader
that reads it and the error it must raise: always `superdex.physics.Error`, with a message that
names the file and matches `message` (a regular expression naming the field and what was
expected). `superdex_physics/python/tests/test_malformed_corpus.py` runs every entry.

The files are committed; rerun this script after changing a case (the output is deterministic).
A few valid helper files (`*/valid_*`) are referenced by the broken ones; the manifest does not
list them.
"""

import argparse
import json
import shutil
import struct
from pathlib import Path

import h5py
import numpy as np

REPO = Path(__file__).resolve().parents[1]
DEFAULT_OUT = REPO / "superdex_physics" / "python" / "tests" / "malformed_corpus"

CASES = []  # (format folder, file name, writer(path), loader, message regex, extra manifest fields)


def case(folder, name, content, message, loader=None, **extra):
    """Registers a corpus file. `content` is text, bytes, a JSON-able document (dict or list, for the
    JSON formats) or a function writing the file at a given path."""
    CASES.append((folder, name, content, loader or folder, message, extra))


def write_content(path: Path, content):
    if callable(content):
        content(path)
    elif isinstance(content, bytes):
        path.write_bytes(content)
    elif isinstance(content, str):
        path.write_text(content)
    else:
        path.write_text(json.dumps(content, indent=1) + "\n")


# ---------------------------------------------------------------------------------------------
# .superdex_bot

INERTIA = [0.001, 0.0, 0.0, 0.001, 0.0, 0.001]


def bot(**top):
    """A valid 3-link arm (welded base, two revolute joints) with `top` replacing top-level fields."""
    doc = {
        "name": "corpus_arm",
        "links": [
            {"name": "base", "mass": 1.0, "momentOfInertia": INERTIA, "shape": {"box": {"halfExtents": [0.05, 0.05, 0.05]}}},
            {"name": "upper", "parentLink": 0, "mass": 0.5, "centerOfMass": [0.1, 0.0, 0.0], "momentOfInertia": INERTIA,
             "shape": {"sphere": {"radius": 0.03}}},
            {"name": "lower", "parentLink": 1, "mass": 0.3, "centerOfMass": [0.1, 0.0, 0.0], "momentOfInertia": INERTIA,
             "shape": {"capsule": {"radius": 0.02, "halfLength": 0.1}}},
        ],
        "joints": [
            {"name": "weld", "type": "Hard"},
            {"name": "shoulder", "type": "Revolute", "axis": [0, 1, 0],
             "parentLinkFromJoint": {"rotation": [0, 0, 0, 1], "translation": [0, 0, 0.1]}},
            {"name": "elbow", "type": "Revolute", "axis": [0, 1, 0],
             "parentLinkFromJoint": {"rotation": [0, 0, 0, 1], "translation": [0.2, 0, 0]}},
        ],
        "defaultPose": [0.1, -0.2],
    }
    doc.update(top)
    return doc


def bot_edit(fn):
    doc = bot()
    fn(doc)
    return doc


def link(i, **fields):
    return lambda d: d["links"][i].update(fields)


def joint(i, **fields):
    return lambda d: d["joints"][i].update(fields)


def bot_cases():
    B = "bot"
    e = ".superdex_bot"
    case(B, "not_json" + e, "{ links: [", r"not valid JSON")
    case(B, "empty" + e, "", r"not valid JSON")
    case(B, "truncated" + e, json.dumps(bot())[:200], r"not valid JSON")
    case(B, "top_level_array" + e, [bot()], r"\(top level\): expected an object, got an array")
    case(B, "invalid_utf8" + e, b'{"name": "arm\xff\xfe", "links": [], "joints": []}', r"not valid JSON: .*UTF-8")
    case(B, "deep_nesting" + e, '{"name": "x", "links": ' + "[" * 20000 + "]" * 20000 + "}", r"joints: required")
    case(B, "no_name" + e, bot_edit(lambda d: d.pop("name")), r"name: required")
    case(B, "name_not_string" + e, bot(name=5), r"name: expected a string, got a number")
    case(B, "links_not_array" + e, bot(links={"base": {}}), r"links: expected an array, got an object")
    case(B, "no_links" + e, bot(links=[], joints=[], defaultPose=[]), r"links: an articulation needs at least one link")
    case(B, "link_not_object" + e, bot_edit(lambda d: d["links"].__setitem__(1, 3)), r"links\[1\]: expected an object, got a number")
    case(B, "massless_link_with_inertia" + e, bot_edit(lambda d: (d["joints"][2].update(type="Hard"), d["links"][2].update(mass=0),
                                                                    d.update(defaultPose=[0.1]))),
         r"links\[2\]\.momentOfInertia: must be zero on a massless link \(mass 0\)")
    case(B, "mod_bot_base_missing" + e, {"base": "nothing.superdex_bot", "modifications": []},
         r"base: 'nothing\.superdex_bot' resolves to '.*nothing\.superdex_bot', which does not exist")
    case(B, "mod_bot_base_not_string" + e, {"base": 5}, r"base: expected the path of the bot to build on")
    case(B, "mod_bot_includes_itself" + e, {"base": "mod_bot_includes_itself.superdex_bot"}, r"the bot includes itself")
    case(B, "mod_bot_root_without_marker" + e, {"base": "//arms/arm.superdex_bot"}, r"base: .* no \.superdex_root marker is in")
    case(B, "negative_mass" + e, bot_edit(link(1, mass=-0.5)), r"links\[1\]\.mass: must be a positive finite number, got -0\.5")
    case(B, "zero_mass" + e, bot_edit(link(2, mass=0)), r"links\[2\]\.mass: must be a positive finite number, got 0")
    case(B, "infinite_mass" + e, '{"name": "a", "links": [{"name": "b", "mass": 1e999}], "joints": [{"name": "j", "type": "Hard"}]}',
         r"not valid JSON: .*number overflow parsing '1e999'")
    case(B, "mass_string" + e, bot_edit(link(0, mass="heavy")), r"links\[0\]\.mass: expected a number, got a string")
    case(B, "mass_null" + e, bot_edit(link(0, mass=None)), r"links\[0\]\.mass: required when momentOfInertia is given")
    case(B, "com_two_values" + e, bot_edit(link(1, centerOfMass=[0.1, 0.0])), r"links\[1\]\.centerOfMass: expected an array of 3 numbers, got an array of 2")
    case(B, "com_string_entry" + e, bot_edit(link(1, centerOfMass=[0.1, "x", 0.0])), r"links\[1\]\.centerOfMass\[1\]: expected a number, got a string")
    case(B, "inertia_five_values" + e, bot_edit(link(1, momentOfInertia=[1, 0, 0, 1, 0])), r"links\[1\]\.momentOfInertia: expected an array of 6 numbers, got an array of 5")
    case(B, "inertia_not_positive_definite" + e, bot_edit(link(2, momentOfInertia=[1, 0, 0, -1, 0, 1])), r"links\[2\]\.momentOfInertia: must be positive definite")
    case(B, "inertia_triangle" + e, bot_edit(link(2, momentOfInertia=[0.001, 0, 0, 0.001, 0, 0.01])), r"links\[2\]\.momentOfInertia: is not physically valid")
    case(B, "parent_out_of_range" + e, bot_edit(link(2, parentLink=7)), r"links\[2\]\.parentLink: refers to link 7, which does not exist")
    case(B, "parent_negative" + e, bot_edit(link(2, parentLink=-1)), r"links\[2\]\.parentLink: refers to link -1, which does not exist")
    case(B, "parent_fractional" + e, bot_edit(link(2, parentLink=1.5)), r"links\[2\]\.parentLink: expected an integer")
    case(B, "parent_missing" + e, bot_edit(lambda d: d["links"][2].pop("parentLink")), r"links\[2\]\.parentLink: missing")
    case(B, "parent_self" + e, bot_edit(link(2, parentLink=2)), r"links\[2\]\.parentLink: a link cannot be its own parent")
    case(B, "cycle" + e, bot_edit(link(1, parentLink=2)), r"links\[1\]\.parentLink: the link tree has a cycle through link 'upper'")
    case(B, "duplicate_link_name" + e, bot_edit(link(2, name="upper")), r"links\[2\]\.name: duplicate link name 'upper'")
    case(B, "link_without_name" + e, bot_edit(lambda d: d["links"][1].pop("name")), r"links\[1\]\.name: must be a non-empty string")
    case(B, "one_joint_missing" + e, bot_edit(lambda d: d["joints"].pop()), r"joints: expected exactly one joint per link \(3 links\), got 2")
    case(B, "joint_not_object" + e, bot_edit(lambda d: d["joints"].__setitem__(1, "Revolute")), r"joints\[1\]: expected an object, got a string")
    case(B, "root_joint_revolute" + e, bot_edit(joint(0, type="Revolute", axis=[0, 0, 1])), r"joints\[0\]\.type: the root joint must be Hard or Free")
    case(B, "free_joint_not_root" + e, bot_edit(joint(2, type="Free")), r"joints\[2\]\.type: only the root joint")
    case(B, "unknown_joint_type" + e, bot_edit(joint(1, type="Hinge")), r"joints\[1\]\.type: unknown joint type 'Hinge'")
    case(B, "joint_without_type" + e, bot_edit(lambda d: d["joints"][1].pop("type")), r"joints\[1\]\.type: required")
    case(B, "zero_axis" + e, bot_edit(joint(1, axis=[0, 0, 0])), r"joints\[1\]\.axis: must be a finite, non-zero vector")
    case(B, "axis_four_values" + e, bot_edit(joint(1, axis=[0, 1, 0, 0])), r"joints\[1\]\.axis: expected an array of 3 numbers, got an array of 4")
    case(B, "limits_inverted" + e, bot_edit(joint(2, minLimit=[0, 1, 0], maxLimit=[0, -1, 0])), r"joints\[2\]\.minLimit: the lower limit 1 exceeds the upper limit -1")
    case(B, "zero_quaternion" + e, bot_edit(joint(1, parentLinkFromJoint={"rotation": [0, 0, 0, 0], "translation": [0, 0, 0]})),
         r"joints\[1\]\.parentLinkFromJoint\.rotation: must be a non-zero quaternion \[x, y, z, w\]")
    case(B, "translation_two_values" + e, bot_edit(joint(2, parentLinkFromJoint={"translation": [0.2, 0]})),
         r"joints\[2\]\.parentLinkFromJoint\.translation: expected an array of 3 numbers, got an array of 2")
    case(B, "negative_armature" + e, bot_edit(joint(1, inertia=-0.1)), r"joints\[1\]\.inertia: must be a finite number >= 0, got -0\.1")
    case(B, "negative_friction" + e, bot_edit(joint(1, friction={"coulomb": -1.0, "viscous": 0.0})), r"joints\[1\]\.friction\.coulomb: must be a finite number >= 0, got -1")
    case(B, "effort_limit_string" + e, bot_edit(joint(1, effortLimit="high")), r"joints\[1\]\.effortLimit: expected a number, got a string")
    case(B, "default_pose_short" + e, bot(defaultPose=[0.0]), r"defaultPose: expected 2 values")
    case(B, "default_pose_string" + e, bot(defaultPose=[0.0, "up"]), r"defaultPose\[1\]: expected a number, got a string")
    case(B, "world_from_root_bad" + e, bot(worldFromRoot={"rotation": [0, 0, 0, 1], "translation": "up"}),
         r"worldFromRoot\.translation: expected an array of 3 numbers, got a string")
    case(B, "sensor_without_type" + e, bot_edit(link(2, sensors=[{"name": "s"}])), r"links\[2\]\.sensors\[0\]\.type: required")
    case(B, "sensors_not_array" + e, bot_edit(link(2, sensors={"type": "X"})), r"links\[2\]\.sensors: expected an array of objects")
    case(B, "actuator_params_number" + e, bot_edit(link(1, actuators=[{"type": "A", "name": "a", "params": 5}])), r"links\[1\]\.actuators\[0\]\.params: expected a string")
    case(B, "duplicate_actuator_name" + e, bot_edit(lambda d: (d["links"][1].update(actuators=[{"type": "A", "name": "m"}]),
                                                               d["links"][2].update(actuators=[{"type": "A", "name": "m"}]))),
         r"links\[2\]\.actuators\[0\]\.name: duplicate name 'm'")
    case(B, "missing_shape_file" + e, bot_edit(link(2, shape="meshes/nothing.obj")), r"links\[2\]\.shape: shape file '.*bot/meshes/nothing\.obj' does not exist")
    case(B, "sphere_negative_radius" + e, bot_edit(link(1, shape={"sphere": {"radius": -0.1}})), r"links\[1\]\.shape: sphere radius must be a positive finite number, got -0\.1")
    # found by mutating the example bot: a required primitive field that is missing
    case(B, "capsule_without_half_length" + e, bot_edit(link(2, shape={"capsule": {"radius": 0.02}})),
         r"links\[2\]\.shape\.capsule\.halfLength: required")
    case(B, "sphere_radius_null" + e, bot_edit(link(1, shape={"sphere": {"radius": None}})), r"links\[1\]\.shape\.sphere\.radius: required")
    case(B, "unknown_primitive" + e, bot_edit(link(1, shape={"cone": {"radius": 0.1}})), r"links\[1\]\.shape: unknown inline shape 'cone' \(expected sphere, box, capsule or plane\)")
    case(B, "box_two_half_extents" + e, bot_edit(link(0, shape={"box": {"halfExtents": [0.1, 0.1]}})), r"links\[0\]\.shape\.box\.halfExtents: expected an array of 3 numbers, got an array of 2")
    case(B, "shape_number" + e, bot_edit(link(0, shape=3)), r"links\[0\]\.shape: expected a shape file path or an inline primitive such as \{\"sphere\": \{\"radius\": r\}\}, got a number")
    case(B, "unknown_collider_type" + e, bot_edit(link(1, colliderType="Blob")), r"links\[1\]\.colliderType: unknown collider type 'Blob'")
    case(B, "render_model_not_glb" + e, bot_edit(link(1, renderModel="valid_params.json")), r"links\[1\]\.renderModel: render models are binary glTF")
    case(B, "contact_override_unknown_link" + e, bot(contactOverrides=[{"linkA": "base", "linkB": "hand", "enable": False}]),
         r"contactOverrides\[0\]\.linkB: no link named 'hand'")
    case(B, "negative_friction_coefficient" + e, bot_edit(link(2, contact={"coulombFrictionCoefficient": -0.5})),
         r"links\[2\]\.contact\.coulombFrictionCoefficient: must be a finite number >= 0, got -0\.5")
    case(B, "params_file_not_json" + e, bot_edit(link(1, actuators=[{"type": "IDEAL_PD", "name": "a", "params": "valid_readme.txt"}])),
         r"links\[1\]\.actuators\[0\] \('a'\): create_actuator\('IDEAL_PD', name 'a'\): IDEAL_PD: params file '.*valid_readme\.txt' is not valid JSON")
    case(B, "params_number_overflow" + e, bot_edit(link(1, actuators=[{"type": "IDEAL_PD", "name": "a", "params": '{"kp": 1e999}'}])),
         r"links\[1\]\.actuators\[0\] \('a'\): .*IDEAL_PD: params is not valid JSON: .*number overflow parsing '1e999'")
    case(B, "params_unknown_key" + e, bot_edit(link(1, actuators=[{"type": "IDEAL_PD", "name": "a", "params": '{"gain": 1}'}])),
         r"links\[1\]\.actuators\[0\] \('a'\): .*IDEAL_PD: unknown parameter 'gain' \(known: rate, kp, kd, effort_limit, default_position\)")
    case(B, "params_wrong_type" + e, bot_edit(link(1, actuators=[{"type": "IDEAL_PD", "name": "a", "params": '{"kp": "stiff"}'}])),
         r"links\[1\]\.actuators\[0\] \('a'\): .*IDEAL_PD: params\.kp: expected a number, got \"stiff\"")


# ---------------------------------------------------------------------------------------------
# .mochi_prefab

def box_actor(name="box", **extra):
    return {"name": name, "shape": {"box": {"halfExtents": [0.1, 0.1, 0.1]}},
            "worldFromLocal": {"rotation": [0, 0, 0, 1], "translation": [0, 0, 0.5]}, "mass": 1.0, **extra}


def soft_actor(**extra):
    return {"name": "jelly", "shape": "./valid_tet.mochi.h5",
            "material": {"type": "NeoHookean", "youngsModulus": 1e5, "poissonRatio": 0.3, "density": 1000.0}, **extra}


def prefab(rigid=(), soft=(), articulated=(), **top):
    doc = {"actors": {"rigid": list(rigid), "soft": list(soft), "articulated": list(articulated)}, "constraints": [], "prefabs": []}
    doc.update(top)
    return doc


def prefab_cases():
    P = "prefab"
    e = ".mochi_prefab"
    case(P, "not_json" + e, '{"actors": ', r"not valid JSON")
    case(P, "empty" + e, "", r"not valid JSON")
    case(P, "top_level_string" + e, '"rigid"', r"\(top level\): expected an object")
    case(P, "actors_array" + e, {"actors": []}, r"actors: expected an object with lists rigid, soft and articulated")
    case(P, "rigid_not_array" + e, {"actors": {"rigid": {"name": "a"}}}, r"actors\.rigid: expected an array")
    case(P, "rigid_entry_number" + e, prefab(rigid=[7]), r"actors\.rigid\[0\]: expected an object")
    case(P, "rigid_without_name" + e, prefab(rigid=[{k: v for k, v in box_actor().items() if k != "name"}]), r"actors\.rigid\[0\]\.name: required")
    case(P, "rigid_without_shape" + e, prefab(rigid=[{k: v for k, v in box_actor().items() if k != "shape"}]), r"actors\.rigid\[0\]\.shape: required")
    case(P, "shape_absolute_path" + e, prefab(rigid=[box_actor(shape="/etc/passwd")]), r"actors\.rigid\[0\]\.shape: absolute paths are not allowed \('/etc/passwd'\): use \./ \(prefab folder\) or a path under the root")
    case(P, "shape_dot_dot" + e, prefab(rigid=[box_actor(shape="./../../secret.obj")]), r"actors\.rigid\[0\]\.shape: paths containing '\.\.' are not allowed \('\./\.\./\.\./secret\.obj'\)")
    case(P, "shape_file_missing" + e, prefab(rigid=[box_actor(shape="./missing.obj")]), r"actors\.rigid\[0\]\.shape: shape file '.*prefab/missing\.obj' does not exist")
    case(P, "negative_mass" + e, prefab(rigid=[box_actor(mass=-1.0)]), r"actors\.rigid\[0\]\.mass: must be a positive finite number, got -1")
    # (mass and density together are no defect: SuperDex's mass takes precedence)
    case(P, "negative_density" + e, prefab(rigid=[{k: v for k, v in box_actor(density=-500.0).items() if k != "mass"}]),
         r"actors\.rigid\[0\]\.density: must be a positive finite number, got -500")
    case(P, "rotation_three_values" + e, prefab(rigid=[box_actor(worldFromLocal={"rotation": [0, 0, 1], "translation": [0, 0, 0]})]),
         r"actors\.rigid\[0\]\.worldFromLocal\.rotation: expected an array of 4 numbers, got an array of 3")
    case(P, "translation_string" + e, prefab(rigid=[box_actor(worldFromLocal={"rotation": [0, 0, 0, 1], "translation": [0, "z", 0]})]),
         r"actors\.rigid\[0\]\.worldFromLocal\.translation\[1\]: expected a number, got a string")
    case(P, "is_static_string" + e, prefab(rigid=[box_actor(isStatic="yes")]), r"actors\.rigid\[0\]\.isStatic: expected a boolean, got \"yes\"")
    case(P, "unknown_collider" + e, prefab(rigid=[box_actor(colliderType="Cone")]), r"actors\.rigid\[0\]\.colliderType: unknown collider type \"Cone\"")
    case(P, "dynamic_plane" + e, prefab(rigid=[box_actor(shape={"plane": {"normal": [0, 0, 1], "distance": 0}})]),
         r"actors\.rigid\[0\]: create_rigid_actor\('corpus/box'\): params\.shape: a plane is unbounded and can only carry a static actor \(is_static=True\)")
    case(P, "layer_not_a_name" + e, prefab(rigid=[box_actor(layer=99)]), r"actors\.rigid\[0\]\.layer: expected a contact layer name \(a string\), got 99")
    case(P, "soft_triangle_mesh" + e, prefab(soft=[soft_actor(shape="./valid_cube.obj")]), r"actors\.soft\[0\]\.shape: '.*prefab/valid_cube\.obj' has no tetrahedral mesh \(soft actors need one\)")
    case(P, "soft_unknown_material" + e, prefab(soft=[soft_actor(material={"type": "Jelly", "youngsModulus": 1e5, "poissonRatio": 0.3})]),
         r"actors\.soft\[0\]\.material\.type: unknown material type 'Jelly' \(expected NeoHookean, StVK or Linear\)")
    case(P, "soft_poisson_half" + e, prefab(soft=[soft_actor(material={"type": "NeoHookean", "youngsModulus": 1e5, "poissonRatio": 0.5})]),
         r"actors\.soft\[0\]\.material\.poissonRatio: must be in \(-1, 0\.5\), got 0\.5")
    case(P, "soft_negative_youngs" + e, prefab(soft=[soft_actor(material={"type": "NeoHookean", "youngsModulus": -1.0, "poissonRatio": 0.3})]),
         r"actors\.soft\[0\]\.material\.youngsModulus: must be positive \(Pa\), got -1")
    case(P, "soft_fixed_node_out_of_range" + e, prefab(soft=[soft_actor(fixedNodes=[0, 999])]), r"actors\.soft\[0\]\.fixed_nodes\[1\]: node 999 is out of range \(the mesh has 5 nodes\)")
    case(P, "soft_fixed_region_inverted" + e, prefab(soft=[soft_actor(fixedRegion={"min": [1, 1, 1], "max": [0, 0, 0]})]),
         r"actors\.soft\[0\]\.fixedRegion: min must not exceed max")
    case(P, "nested_without_path" + e, prefab(prefabs=[{"name": "inner"}]), r"prefabs\[0\]\.path: required")
    case(P, "nested_missing_file" + e, prefab(prefabs=[{"name": "inner", "path": "./absent.mochi_prefab"}]),
         r"prefabs\[0\]\.path: prefab file '.*prefab/absent\.mochi_prefab' does not exist")
    case(P, "nested_includes_itself" + e, prefab(prefabs=[{"name": "me", "path": "./nested_includes_itself.mochi_prefab"}]),
         r"nest more than 16 deep")
    # found by the prefab_json fuzz target (issue 9): a file name longer than the system allows made
    # std::filesystem throw from the existence check instead of the loader naming the field
    long_name = "./" + "v" * 300 + ".mochi_prefab"
    case(P, "nested_path_too_long" + e, prefab(prefabs=[{"name": "inner", "path": long_name}]),
         r"prefabs\[0\]\.path: prefab file '.*prefab/v{300}\.mochi_prefab' does not exist")
    case(P, "shape_path_too_long" + e, prefab(rigid=[box_actor(shape="./" + "s" * 300 + ".obj")]),
         r"actors\.rigid\[0\]\.shape: shape file '.*prefab/s{300}\.obj' does not exist")
    case(P, "nested_negative_scale" + e, prefab(prefabs=[{"name": "inner", "path": "./valid_box.mochi_prefab", "scale": -2}]),
         r"prefabs\[0\]\.scale: must be positive")
    case(P, "scene_gravity_two_values" + e, prefab(rigid=[box_actor()], scene={"gravity": [0, -9.81]}),
         r"scene\.gravity: expected 3 numbers, got \[0,-9\.81\]", apply_scene_settings=True)
    case(P, "contact_filter_unknown_actor" + e, prefab(rigid=[box_actor()], contactFilter={"disabledPairs": [["box", "ghost"]]}),
         r"contact_filter\.actor_contact_symmetric\[0\]: no actor named 'ghost' in this prefab")
    case(P, "articulated_bot_missing" + e, prefab(articulated=[{"name": "arm", "bot": "./no_such.superdex_bot"}]),
         r"actors\.articulated\[0\]\.bot: .*prefab/no_such\.superdex_bot: cannot open the bot file \(does it exist\?\)")
    case(P, "articulated_inline_bad_mass" + e, prefab(articulated=[{**bot(), "links": [dict(bot()["links"][0], mass=-3.0)] + bot()["links"][1:]}]),
         r"actors\.articulated\[0\]: links\[0\]\.mass: must be a positive finite number, got -3")
    case(P, "constraints_not_array" + e, prefab(rigid=[box_actor()], constraints={"a": 1}), r"constraints: constraints are not supported yet")


# ---------------------------------------------------------------------------------------------
# URDF

def inertial(mass="1.0", inertia='ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"', origin='<origin xyz="0 0 0" rpy="0 0 0"/>'):
    return f'<inertial>{origin}<mass value="{mass}"/><inertia {inertia}/></inertial>'


def urdf(links=None, joints=None, name="corpus_urdf"):
    if links is None:
        links = [f'<link name="base">{inertial()}</link>', f'<link name="arm">{inertial()}</link>',
                 f'<link name="hand">{inertial()}</link>']
    if joints is None:
        joints = [joint_xml("j1", "revolute", "base", "arm"), joint_xml("j2", "prismatic", "arm", "hand")]
    return f'<?xml version="1.0"?>\n<robot name="{name}">\n' + "\n".join(links + joints) + "\n</robot>\n"


def joint_xml(name, type_, parent, child, origin='<origin xyz="0 0 0.1" rpy="0 0 0"/>', axis='<axis xyz="0 1 0"/>',
              limit='<limit lower="-1" upper="1" effort="10" velocity="1"/>', extra=""):
    p = f'<parent link="{parent}"/>' if parent is not None else ""
    c = f'<child link="{child}"/>' if child is not None else ""
    t = f' type="{type_}"' if type_ is not None else ""
    return f'<joint name="{name}"{t}>{p}{c}{origin}{axis}{limit}{extra}</joint>'


def links_with(index, text):
    links = [f'<link name="base">{inertial()}</link>', f'<link name="arm">{inertial()}</link>',
             f'<link name="hand">{inertial()}</link>']
    links[index] = text
    return links


NO_IXX = 'ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"'
NAN_IXX = 'ixx="nan" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"'


def urdf_cases():
    U = "urdf"
    e = ".urdf"
    case(U, "not_xml" + e, "this is not XML <robot", r"not a valid XML file: Error=XML_ERROR_PARSING_ELEMENT")
    case(U, "empty" + e, "", r"not a valid XML file: Error=XML_ERROR_EMPTY_DOCUMENT")
    case(U, "truncated" + e, urdf()[:150], r"not a valid XML file: Error=XML_ERROR_PARSING_ATTRIBUTE")
    case(U, "root_not_robot" + e, '<?xml version="1.0"?>\n<model name="m"><link name="a"/></model>\n', r"<robot>")
    case(U, "no_links" + e, urdf(links=[], joints=[]), r"line 2: <robot name='corpus_urdf'>: the robot has no <link>")
    case(U, "link_without_name" + e, urdf(links=links_with(1, f"<link>{inertial()}</link>")), r"line 4: <link>: missing required attribute 'name'")
    case(U, "duplicate_link_name" + e, urdf(links=links_with(2, f'<link name="arm">{inertial()}</link>')), r"line 5: <link name='arm'>: duplicate link name 'arm'")
    case(U, "joint_without_type" + e, urdf(joints=[joint_xml("j1", None, "base", "arm"), joint_xml("j2", "prismatic", "arm", "hand")]),
         r"line 6: <joint name='j1'>: missing required attribute 'type'")
    case(U, "unknown_joint_type" + e, urdf(joints=[joint_xml("j1", "hinge", "base", "arm"), joint_xml("j2", "prismatic", "arm", "hand")]),
         r"line 6: <joint name='j1'>: unknown joint type 'hinge' \(expected revolute, continuous, prismatic, fixed or floating\)")
    case(U, "planar_joint" + e, urdf(joints=[joint_xml("j1", "planar", "base", "arm"), joint_xml("j2", "prismatic", "arm", "hand")]),
         r"line 6: <joint name='j1'>: unsupported joint type 'planar'")
    case(U, "joint_parent_unknown" + e, urdf(joints=[joint_xml("j1", "revolute", "torso", "arm"), joint_xml("j2", "prismatic", "arm", "hand")]),
         r"line 6: <joint name='j1'>/<parent>: refers to link 'torso', which is not defined")
    case(U, "joint_child_unknown" + e, urdf(joints=[joint_xml("j1", "revolute", "base", "arm"), joint_xml("j2", "prismatic", "arm", "finger")]),
         r"line 7: <joint name='j2'>/<child>: refers to link 'finger', which is not defined")
    case(U, "joint_without_parent" + e, urdf(joints=[joint_xml("j1", "revolute", None, "arm"), joint_xml("j2", "prismatic", "arm", "hand")]),
         r"line 6: <joint name='j1'>: missing required element <parent>")
    case(U, "two_roots" + e, urdf(joints=[joint_xml("j1", "revolute", "base", "arm")]), r"line 2: <robot name='corpus_urdf'>: several root links \(links that are no joint's child\): 'base', 'hand'; a robot must be one tree of links connected by joints")
    case(U, "two_parents" + e, urdf(joints=[joint_xml("j1", "revolute", "base", "hand"), joint_xml("j2", "prismatic", "arm", "hand")]),
         r"line 7: <joint name='j2'>: link 'hand' has two parents: it is the child of joint 'j1' and of joint 'j2'")
    case(U, "cycle" + e, urdf(joints=[joint_xml("j1", "revolute", "base", "arm"), joint_xml("j2", "revolute", "arm", "hand"),
                                      joint_xml("j3", "revolute", "hand", "arm")]), r"line 8: <joint name='j3'>: link 'arm' has two parents: it is the child of joint 'j1' and of joint 'j3'")
    case(U, "negative_mass" + e, urdf(links=links_with(1, f'<link name="arm">{inertial(mass="-2")}</link>')), r"line 4: <link name='arm'>/<inertial>/<mass>: the mass must not be negative, got -2")
    case(U, "mass_not_number" + e, urdf(links=links_with(1, f'<link name="arm">{inertial(mass="heavy")}</link>')), r"line 4: <link name='arm'>/<inertial>/<mass>: attribute 'value': malformed number 'heavy'")
    case(U, "inertia_missing_ixx" + e, urdf(links=links_with(1, '<link name="arm">' + inertial(inertia=NO_IXX) + '</link>')),
         r"line 4: <link name='arm'>/<inertial>/<inertia>: missing required attribute 'ixx'")
    case(U, "inertia_not_a_number" + e,
         urdf(links=links_with(2, '<link name="hand">' + inertial(inertia=NAN_IXX) + '</link>')),
         r"line 5: <link name='hand'>/<inertial>/<inertia>: attribute 'ixx': malformed number 'nan'")
    case(U, "origin_two_numbers" + e, urdf(joints=[joint_xml("j1", "revolute", "base", "arm", origin='<origin xyz="0 0.1"/>'),
                                                   joint_xml("j2", "prismatic", "arm", "hand")]), r"line 6: <joint name='j1'>/<origin>: attribute 'xyz': expected 3 numbers, got \"0 0\.1\"")
    case(U, "rpy_not_numbers" + e, urdf(joints=[joint_xml("j1", "revolute", "base", "arm", origin='<origin xyz="0 0 0" rpy="a b c"/>'),
                                                joint_xml("j2", "prismatic", "arm", "hand")]), r"line 6: <joint name='j1'>/<origin>: attribute 'rpy': malformed number 'a'")
    case(U, "zero_axis" + e, urdf(joints=[joint_xml("j1", "revolute", "base", "arm", axis='<axis xyz="0 0 0"/>'),
                                          joint_xml("j2", "prismatic", "arm", "hand")]), r"line 6: <joint name='j1'>/<axis>: the joint axis must not be zero")
    case(U, "limit_inverted" + e, urdf(joints=[joint_xml("j1", "revolute", "base", "arm", limit='<limit lower="1" upper="-1" effort="1" velocity="1"/>'),
                                               joint_xml("j2", "prismatic", "arm", "hand")]), r"line 6: <joint name='j1'>/<limit>: the lower limit 1 exceeds the upper limit -1")
    case(U, "limit_not_number" + e, urdf(joints=[joint_xml("j1", "revolute", "base", "arm", limit='<limit lower="low" upper="1" effort="1" velocity="1"/>'),
                                                 joint_xml("j2", "prismatic", "arm", "hand")]), r"line 6: <joint name='j1'>/<limit>: attribute 'lower': malformed number 'low'")
    case(U, "mesh_file_missing" + e, urdf(links=links_with(1, f'<link name="arm">{inertial()}<collision><geometry><mesh filename="meshes/none.stl"/></geometry></collision></link>')),
         r"<link name='arm'>/<collision>/<geometry>/<mesh>: link 'arm': collision mesh 'meshes/none\.stl' not found")
    case(U, "package_uri_unresolved" + e, urdf(links=links_with(1, f'<link name="arm">{inertial()}<collision><geometry><mesh filename="package://nowhere/a.stl"/></geometry></collision></link>')),
         r"line 4: <link name='arm'>/<collision>/<geometry>/<mesh>: link 'arm': collision mesh 'package://nowhere/a\.stl' not found \(package 'nowhere'")
    case(U, "empty_geometry" + e, urdf(links=links_with(1, f'<link name="arm">{inertial()}<collision><geometry/></collision></link>')),
         r"<link name='arm'>/<collision>/<geometry>: expected one of <box>, <sphere>, <cylinder> or <mesh>")
    case(U, "cylinder_negative_radius" + e, urdf(links=links_with(1, f'<link name="arm">{inertial()}<collision><geometry><cylinder radius="-0.1" length="0.2"/></geometry></collision></link>')),
         r"<link name='arm'>/<collision>/<geometry>/<cylinder>: attribute 'radius' must be positive, got -0\.1")
    case(U, "box_size_two_numbers" + e, urdf(links=links_with(1, f'<link name="arm">{inertial()}<collision><geometry><box size="0.1 0.1"/></geometry></collision></link>')),
         r"<link name='arm'>/<collision>/<geometry>/<box>: attribute 'size': expected 3 numbers, got \"0\.1 0\.1\"")


# ---------------------------------------------------------------------------------------------
# .mochi.h5

CUBE_V = np.array([[(i & 1) - 0.5, ((i >> 1) & 1) - 0.5, ((i >> 2) & 1) - 0.5] for i in range(8)])
CUBE_T = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
                   [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]], dtype=np.int32)
TET_V = np.array([[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1], [0.1, 0.1, 0.1]], dtype=np.float64)
TET_T = np.array([[0, 1, 2, 3], [1, 2, 3, 4]], dtype=np.int32)


def h5(datasets=None, attrs=None):
    """A writer of a .mochi.h5 file: datasets {path: array}, attrs {group: {name: value}}."""
    def write(path):
        with h5py.File(path, "w", track_order=False) as f:
            for name, data in (datasets or {}).items():
                f.create_dataset(name, data=data, track_times=False)
            for group, values in (attrs or {}).items():
                g = f.require_group(group)
                for key, value in values.items():
                    g.attrs[key] = value
    return write


def mesh(v=CUBE_V, t=CUBE_T):
    return {"mesh/coordinates": v, "mesh/connectivity": t}


def truncated_h5(path):
    h5(mesh())(path)
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])


def h5_declared_only(shape, dtype="f8", extra=None):
    """A writer of a file whose mesh/coordinates dataset declares `shape` but stores no data (chunked,
    no chunk written: HDF5 would hand back fill values); `extra` adds datasets."""
    def write(path):
        with h5py.File(path, "w", track_order=False) as f:
            f.create_dataset("mesh/coordinates", shape=shape, dtype=dtype, chunks=(1, 3), track_times=False)
            f.create_dataset("mesh/connectivity", data=CUBE_T, track_times=False)
            for name, data in (extra or {}).items():
                f.create_dataset(name, data=data, track_times=False)
    return write


def h5_cases():
    H = "h5"
    e = ".mochi.h5"
    # found for issue 9 (reading the h5 reader while writing its fuzz target): a shape whose value count overflows 64 bits wrapped to 2 values
    # and the reader then sized the mesh from the shape (std::length_error escaped, not an Error)
    case(H, "coordinates_count_overflows" + e, h5_declared_only((6148914691236517206, 3)),
         r"mesh/coordinates: too large: shape \[6148914691236517206, 3\] holds more than 2147483648 values")
    # found by the mochi_h5 fuzz target (issue 9): a corrupt header makes HDF5 ask malloc for
    # petabytes; the refused allocation must end in sdp.Error (the fuzzer's input is kept as it is)
    case(H, "fuzz_huge_metadata_allocation" + e, (REPO / "fuzz/regressions/mochi_h5/huge_metadata_allocation.mochi.h5").read_bytes(),
         r"box: is not a group")
    # found by the mochi_h5 fuzz target (issue 9): a corrupt datatype of 1.7 GB per value, which HDF5
    # allocated to convert a single value (1.8 GB resident for a 4.7 KB file)
    case(H, "fuzz_huge_value_type" + e, (REPO / "fuzz/regressions/mochi_h5/huge_value_type.mochi.h5").read_bytes(),
         r"mesh/coordinates: wrong type: floating-point numbers of 1768186226 bytes each \(expected at most 16\)")
    # found by the mochi_h5 fuzz target (issue 9): a file on which HDF5 1.10 itself reads through a
    # null pointer; the reader tries every file in a child process first, so it is an error, not a crash
    # (a sanitizer's handler, when present, turns the signal into an exit status)
    case(H, "fuzz_hdf5_null_read" + e, (REPO / "fuzz/regressions/mochi_h5/hdf5_null_read_in_local_heap.mochi.h5").read_bytes(),
         r"the HDF5 library crashed reading the file \((signal 11: Segmentation fault|exit status \d+)\): corrupt file\?")
    # ... and a shape that fits but that the 3 KB file cannot hold: 1.2 GB allocated for fill values
    case(H, "coordinates_not_stored" + e, h5_declared_only((50_000_000, 3)),
         r"mesh/coordinates: shape \[50000000, 3\] declares more values than the file \(\d+ bytes\) can hold \(corrupt file\?\)")
    # a uint64 index beyond the range of long long was converted for the message (undefined)
    case(H, "connectivity_uint64_max" + e, h5(mesh(t=np.where(CUBE_T == 7, np.iinfo(np.uint64).max, CUBE_T).astype(np.uint64))),
         r"mesh/connectivity: index 1\.84467e\+19 at row 3 out of range: the mesh has 8 nodes")
    case(H, "text_file" + e, "mesh: cube\n", r"not an HDF5 file \(or unreadable\)")
    case(H, "empty" + e, b"", r"not an HDF5 file \(or unreadable\)")
    case(H, "truncated" + e, truncated_h5, r"cannot open the HDF5 file \(corrupt or unreadable\)")
    case(H, "no_groups" + e, h5(), r"no shape: expected a mesh/, box/, sphere/ or plane/ group")
    case(H, "no_coordinates" + e, h5({"mesh/connectivity": CUBE_T}), r"mesh/coordinates: missing dataset")
    case(H, "no_connectivity" + e, h5({"mesh/coordinates": CUBE_V}), r"mesh/connectivity: missing dataset")
    case(H, "coordinates_n_by_2" + e, h5(mesh(v=CUBE_V[:, :2])), r"mesh/coordinates: wrong shape: expected N x 3, got \[8, 2\]")
    case(H, "coordinates_1d" + e, h5(mesh(v=CUBE_V.ravel())), r"mesh/coordinates: wrong rank: expected a 2-D dataset N x 3, got \[24\]")
    case(H, "connectivity_5_columns" + e, h5(mesh(t=np.zeros((2, 5), dtype=np.int32))), r"mesh/connectivity: wrong shape: expected M x 2 \(a rod's polyline\), M x 3 \(triangles\) or M x 4 \(tetrahedra\), got \[2, 5\]")
    case(H, "connectivity_out_of_range" + e, h5(mesh(t=np.where(CUBE_T == 7, 70, CUBE_T).astype(np.int32))), r"mesh/connectivity: index 70 at row 3 out of range: the mesh has 8 nodes")
    case(H, "connectivity_negative" + e, h5(mesh(t=np.where(CUBE_T == 3, -3, CUBE_T).astype(np.int32))), r"mesh/connectivity: index -3 at row 1 out of range: the mesh has 8 nodes")
    case(H, "coordinates_nan" + e, h5(mesh(v=np.where(CUBE_V == 0.5, np.nan, CUBE_V))), r"mesh/coordinates: NaN at row 1, column 0")
    case(H, "coordinates_strings" + e, h5({"mesh/coordinates": np.array([b"a", b"b"]), "mesh/connectivity": CUBE_T}),
         r"mesh/coordinates: wrong type: expected numbers, got a string")
    case(H, "mesh_is_dataset" + e, h5({"mesh": np.zeros(3)}), r"mesh: is not a group")
    case(H, "empty_mesh" + e, h5(mesh(v=np.zeros((0, 3)), t=np.zeros((0, 3), dtype=np.int32))), r"mesh/coordinates: empty mesh: no nodes")
    case(H, "tet_inverted" + e, h5(mesh(v=TET_V, t=np.array([[0, 2, 1, 3], [1, 2, 3, 4]], dtype=np.int32))), r"tetrahedron 0 is inverted \(negative volume\)", loader="h5_soft")
    case(H, "sphere_negative_radius" + e, h5(attrs={"sphere": {"radius": -1.0}}), r"sphere/radius: must be positive, got -1\.000000")
    case(H, "sphere_without_radius" + e, h5(attrs={"sphere": {"center": [0.0, 0.0, 0.0]}}), r"sphere/radius: missing attribute")
    case(H, "box_two_half_extents" + e, h5(attrs={"box": {"half_extents": [0.1, 0.2]}}), r"box/half_extents: wrong shape: expected 3 values, got 2")
    case(H, "box_nan_half_extents" + e, h5(attrs={"box": {"half_extents": [0.1, np.nan, 0.1]}}), r"box/half_extents: NaN at index 1")
    case(H, "plane_zero_normal" + e, h5(attrs={"plane": {"normal": [0.0, 0.0, 0.0], "distance": 0.0}}), r"plane/normal: must be non-zero")
    case(H, "sdf_grid_2d" + e, h5({**mesh(), "sdf/grid": np.ones((4, 4))}, {"sdf": {"grid_min": [-1.0] * 3, "grid_max": [1.0] * 3}}),
         r"sdf/grid: wrong rank: expected a 3-D dataset \[nx, ny, nz\], got \[4, 4\]")
    case(H, "sdf_without_bounds" + e, h5({**mesh(), "sdf/grid": np.ones((4, 4, 4))}), r"sdf/grid_min: missing attribute")
    case(H, "sdf_bounds_inverted" + e, h5({**mesh(), "sdf/grid": np.ones((4, 4, 4))}, {"sdf": {"grid_min": [1.0] * 3, "grid_max": [-1.0] * 3}}),
         r"sdf: grid_min must be < grid_max on every axis, got grid_min \[1, 1, 1\] and grid_max \[-1, -1, -1\]")
    case(H, "sdf_grid_nan" + e, h5({**mesh(), "sdf/grid": np.full((4, 4, 4), np.nan)}, {"sdf": {"grid_min": [-1.0] * 3, "grid_max": [1.0] * 3}}),
         r"sdf/grid: NaN at \[0, 0, 0\]")
    case(H, "sdf_grid_one_sample" + e, h5({**mesh(), "sdf/grid": np.ones((1, 1, 1))}, {"sdf": {"grid_min": [-1.0] * 3, "grid_max": [1.0] * 3}}),
         r"sdf/grid: wrong shape: every dimension must be at least 2, got \[1, 1, 1\]")


# ---------------------------------------------------------------------------------------------
# OBJ, STL, PLY

def stl_binary(triangles, count=None, nan=False):
    out = b"\0" * 80 + struct.pack("<I", len(triangles) if count is None else count)
    for tri in triangles:
        verts = [CUBE_V[i] for i in tri]
        if nan:
            verts[0] = [np.nan, 0, 0]
        out += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *p) for p in verts) + struct.pack("<H", 0)
    return out


def ply_header(nv, nf, fmt="ascii", vprops="property float x\nproperty float y\nproperty float z\n",
               fprops="property list uchar int vertex_indices\n", end=True):
    return (f"ply\nformat {fmt} 1.0\nelement vertex {nv}\n{vprops}element face {nf}\n{fprops}" + ("end_header\n" if end else "")).encode()


def ply_body_ascii(v=CUBE_V, t=CUBE_T):
    return ("".join(f"{x} {y} {z}\n" for x, y, z in v) + "".join(f"3 {a} {b} {c}\n" for a, b, c in t)).encode()


def obj_text(v=CUBE_V, t=CUBE_T):
    return "".join(f"v {x} {y} {z}\n" for x, y, z in v) + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in t)


def mesh_cases():
    case("obj", "empty.obj", "", r"empty mesh: no vertices", loader="mesh")
    case("obj", "only_comments.obj", "# nothing here\n\n", r"empty mesh: no vertices", loader="mesh")
    case("obj", "bad_number.obj", "v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n", r"bad_number\.obj:2: malformed number 'x' in vertex", loader="mesh")
    case("obj", "vertex_two_numbers.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", r"vertex_two_numbers\.obj:2: a vertex needs 3 coordinates, got 2", loader="mesh")
    case("obj", "face_index_out_of_range.obj", obj_text() + "f 1 2 99\n", r"face_index_out_of_range\.obj:21: face index 99 out of range: the file has 8 vertices", loader="mesh")
    case("obj", "face_index_zero.obj", obj_text() + "f 0 1 2\n", r"face_index_zero\.obj:21: face index 0 is invalid \(OBJ indices start at 1\)", loader="mesh")
    case("obj", "face_negative_too_far.obj", obj_text() + "f -1 -2 -30\n", r"face_negative_too_far\.obj:21: face index -30 out of range: only 8 vertices precede it", loader="mesh")
    case("obj", "face_two_vertices.obj", obj_text() + "f 1 2\n", r"face_two_vertices\.obj:21: a face needs at least 3 vertices, got 2", loader="mesh")
    case("obj", "nan_vertex.obj", obj_text().replace("v -0.5 -0.5 -0.5", "v nan -0.5 -0.5"), r"nan_vertex\.obj:1: vertex 1 has a non-finite coordinate 'nan'", loader="mesh")
    case("obj", "binary_garbage.obj", bytes(range(256)) * 4, r"empty mesh: no vertices", loader="mesh")
    case("obj", "no_faces.obj", "".join(f"v {x} {y} {z}\n" for x, y, z in CUBE_V), r"empty mesh: no triangles", loader="mesh")
    case("stl", "empty.stl", b"", r"not an STL file: 0 bytes is too short for binary STL and there is no 'solid' header", loader="mesh")
    case("stl", "header_only.stl", b"\0" * 80, r"not an STL file: 80 bytes is too short for binary STL and there is no 'solid' header", loader="mesh")
    case("stl", "binary_zero_triangles.stl", stl_binary([]), r"empty mesh: no vertices", loader="mesh")
    case("stl", "binary_count_too_large.stl", stl_binary(CUBE_T[:2], count=12), r"the binary header announces 12 triangles \(684 bytes\) but the file has 184 bytes", loader="mesh")
    case("stl", "binary_count_huge.stl", stl_binary(CUBE_T[:2], count=0xFFFFFFFF), r"the binary header announces 4294967295 triangles \(214748364834 bytes\) but the file has 184 bytes", loader="mesh")
    case("stl", "binary_nan.stl", stl_binary(CUBE_T, nan=True), r"triangle 0 has a non-finite coordinate \(NaN or infinity\)", loader="mesh")
    case("stl", "ascii_bad_vertex.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 zero 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n",
         r"ascii_bad_vertex\.stl:5: malformed number 'zero' in vertex", loader="mesh")
    case("stl", "ascii_two_vertices.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid s\n",
         r"ascii_two_vertices\.stl:3: a facet needs at least 3 vertices, got 2", loader="mesh")
    case("stl", "ascii_unterminated.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n",
         r"ascii_unterminated\.stl:3: 'outer loop' without 'endloop'", loader="mesh")
    case("ply", "no_magic.ply", b"format ascii 1.0\nend_header\n", r"no_magic\.ply:1: not a PLY file: the first line must be 'ply'", loader="mesh")
    case("ply", "no_end_header.ply", ply_header(8, 12, end=False), r"end_header", loader="mesh")
    case("ply", "unknown_format.ply", ply_header(8, 12, fmt="binary_middle_endian") + ply_body_ascii(), r"unknown_format\.ply:2: unknown PLY format 'binary_middle_endian' \(expected ascii, binary_little_endian or binary_big_endian\)", loader="mesh")
    case("ply", "vertex_count_too_large.ply", ply_header(9, 12) + ply_body_ascii(), r"the file ends early, in element 'face' record 11", loader="mesh")
    case("ply", "vertex_count_huge.ply", ply_header(2**62, 12, fmt="binary_little_endian") + b"\0" * 64, r"the file ends early, in element 'vertex' record 5", loader="mesh")
    case("ply", "vertex_count_negative.ply", ply_header(-8, 12) + ply_body_ascii(), r"vertex_count_negative\.ply:3: malformed element count '-8'", loader="mesh")
    case("ply", "face_index_out_of_range.ply", ply_header(8, 12) + ply_body_ascii(t=np.where(CUBE_T == 7, 40, CUBE_T)), r"face_index_out_of_range\.ply:21: face 3 has vertex index 40 out of range: the file has 8 vertices", loader="mesh")
    case("ply", "face_list_count_255.ply", ply_header(8, 1, fmt="binary_little_endian") + b"".join(struct.pack("<3f", *p) for p in CUBE_V) + struct.pack("<B", 255) + b"\0" * 12,
         r"the file ends early, in element 'face' record 0", loader="mesh")
    # found for issue 9 (reading the PLY reader while writing its fuzz target): list lengths and indices of ASCII files beyond any PLY integer
    # type, or infinite, were converted to integers (undefined behaviour)
    case("ply", "list_length_infinite.ply", ply_header(8, 1) + ply_body_ascii(t=[]) + b"inf 0 1 2\n",
         r"list_length_infinite\.ply:18: expected an integer, got 'inf' in element 'face' record 0", loader="mesh")
    case("ply", "list_length_1e300.ply", ply_header(8, 1) + ply_body_ascii(t=[]) + b"1e300 0 1 2\n",
         r"list_length_1e300\.ply:18: expected an integer, got '1e300' in element 'face' record 0", loader="mesh")
    # faces declared before a huge vertex element: an index past the range of int was converted
    case("ply", "vertex_index_beyond_int.ply",
         b"ply\nformat ascii 1.0\nelement face 1\nproperty list uchar uint vertex_indices\nelement vertex 10000000000\n"
         b"property float x\nproperty float y\nproperty float z\nend_header\n3 0 1 3000000000\n",
         r"vertex_index_beyond_int\.ply:10: face 0 has vertex index 3000000000 out of range: the file has 10000000000 vertices", loader="mesh")
    case("ply", "unknown_property_type.ply", ply_header(8, 12, vprops="property quad x\nproperty float y\nproperty float z\n") + ply_body_ascii(),
         r"unknown_property_type\.ply:4: unknown property type 'quad'", loader="mesh")
    case("ply", "no_x_property.ply", ply_header(8, 12, vprops="property float a\nproperty float y\nproperty float z\n") + ply_body_ascii(),
         r"element 'vertex' has no property 'x'", loader="mesh")
    case("ply", "binary_truncated.ply", ply_header(8, 12, fmt="binary_little_endian") + b"".join(struct.pack("<3f", *p) for p in CUBE_V[:5]),
         r"the file ends early, in element 'vertex' record 5", loader="mesh")
    case("ply", "ascii_malformed_number.ply", ply_header(8, 12) + ply_body_ascii().replace(b"0.5 0.5 0.5", b"0.5 half 0.5"), r"ascii_malformed_number\.ply:16: malformed number 'half' in element 'vertex' record 6", loader="mesh")

    dae_cases()


# a tetrahedron as COLLADA (read through Assimp); the cases below break one piece of it
def dae_text(positions="0 0 0 1 0 0 0 1 0 0 0 1", count=12, indices="0 2 1 0 1 3 0 3 2 1 2 3", source="#tet-pos",
             geometries=None, instance='<instance_geometry url="#tet"/>'):
    if geometries is None:
        geometries = (f'<geometry id="tet"><mesh><source id="tet-pos"><float_array id="tet-pos-array" count="{count}">{positions}</float_array>'
                      '<technique_common><accessor source="#tet-pos-array" count="4" stride="3"><param name="X" type="float"/>'
                      '<param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>'
                      f'<vertices id="tet-vtx"><input semantic="POSITION" source="{source}"/></vertices>'
                      f'<triangles count="4"><input semantic="VERTEX" source="#tet-vtx" offset="0"/><p>{indices}</p></triangles></mesh></geometry>')
    return ('<?xml version="1.0" encoding="utf-8"?>\n<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">'
            '<asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>'
            f'<library_geometries>{geometries}</library_geometries>'
            f'<library_visual_scenes><visual_scene id="s"><node id="n">{instance}</node></visual_scene></library_visual_scenes>'
            '<scene><instance_visual_scene url="#s"/></scene></COLLADA>\n')


def dae_cases():
    good = dae_text()
    case("dae", "not_xml.dae", "this is not a COLLADA file\n", r"not_xml\.dae: cannot read: .*malformed XML", loader="mesh")
    case("dae", "empty.dae", "", r"empty\.dae: cannot read: .*malformed XML", loader="mesh")
    case("dae", "truncated.dae", good[: len(good) // 2], r"truncated\.dae: cannot read: .*malformed XML", loader="mesh")
    case("dae", "wrong_root.dae", '<?xml version="1.0"?><COLLADAX></COLLADAX>\n', r"wrong_root\.dae: cannot read: ", loader="mesh")
    case("dae", "no_geometry.dae", dae_text(geometries="", instance=""), r"no_geometry\.dae: no triangles in the file", loader="mesh")
    case("dae", "index_out_of_range.dae", dae_text(indices="0 2 1 0 1 3 0 3 2 1 2 99"), r"index_out_of_range\.dae: cannot read: Invalid data index \(99/4\)", loader="mesh")
    case("dae", "bad_number.dae", dae_text(positions="0 0 0 1 0 0 0 x 0 0 0 1"), r"bad_number\.dae: cannot read: Cannot parse string .* as a real number", loader="mesh")
    case("dae", "short_float_array.dae", dae_text(positions="0 0 0 1 0 0"), r"short_float_array\.dae: cannot read: Expected more values while reading float_array", loader="mesh")
    case("dae", "nan_vertex.dae", dae_text(positions="0 0 0 1 0 0 0 nan 0 0 0 1"), r"nan_vertex\.dae: a vertex has a non-finite coordinate", loader="mesh")
    case("dae", "missing_source.dae", dae_text(source="#nothing"), r"missing_source\.dae: cannot read: Unable to resolve library reference \"nothing\"", loader="mesh")
    case("dae", "count_huge.dae", dae_text().replace('<triangles count="4">', '<triangles count="3000000000">'),
         r"count_huge\.dae:\d+: a count attribute exceeds what a file of \d+ bytes can hold", loader="mesh")
    case("dae", "degenerate_only.dae", dae_text(indices="0 0 1 1 1 2 2 2 3 3 3 0"), r"degenerate_only\.dae: ", loader="mesh")

# ---------------------------------------------------------------------------------------------
# debugger recordings (.jsonl)

HEADER = {"type": "header", "format": "superdex-recording", "version": 1, "units": "SI", "frameInterval": 0}
SCENE = {"type": "scene", "scene": 1, "name": "s", "gravity": [0, 0, -9.81]}
FRAME = {"type": "frame", "scene": 1, "step": 1, "t": 0.01, "links": {}, "contacts": [], "joints": {}, "signals": {}}


def jsonl(*lines):
    return "".join((x if isinstance(x, str) else json.dumps(x)) + "\n" for x in lines)


def recording_cases():
    R = "recording"
    e = ".jsonl"
    case(R, "empty" + e, "", r"is empty")
    case(R, "blank_lines" + e, "\n\n\n", r"is empty")
    case(R, "first_line_not_json" + e, jsonl("superdex recording v1", SCENE), r"line 1: not a SuperDex recording")
    case(R, "wrong_format" + e, jsonl({**HEADER, "format": "other-recording"}, SCENE), r"line 1: not a SuperDex recording")
    case(R, "header_not_first" + e, jsonl(SCENE, HEADER), r"line 1: not a SuperDex recording")
    case(R, "future_version" + e, jsonl({**HEADER, "version": 99}, SCENE, FRAME), r"line 1: header\.version: recording format version 99 is not supported \(this reader reads version 1\)")
    case(R, "version_string" + e, jsonl({**HEADER, "version": "1"}, SCENE, FRAME), r"line 1: header\.version: expected an integer, got \"1\"")
    case(R, "line_not_json" + e, jsonl(HEADER, SCENE, '{"type": "frame", "scene": 1, "t": ', FRAME), r"line 3: not valid JSON")
    case(R, "line_array" + e, jsonl(HEADER, SCENE, [1, 2, 3]), r"line 3: expected a JSON object")
    case(R, "line_without_type" + e, jsonl(HEADER, SCENE, {"scene": 1, "t": 0.0}), r"line 3: type: required")
    case(R, "type_number" + e, jsonl(HEADER, {**SCENE, "type": 4}), r"line 2: type: expected a string, got 4")
    case(R, "frame_time_string" + e, jsonl(HEADER, SCENE, {**FRAME, "t": "soon"}), r"line 3: frame\.t: expected a number, got \"soon\"")
    case(R, "frame_without_scene" + e, jsonl(HEADER, SCENE, {k: v for k, v in FRAME.items() if k != "scene"}), r"line 3: frame\.scene: required")
    case(R, "frame_links_array" + e, jsonl(HEADER, SCENE, {**FRAME, "links": [1, 2]}), r"line 3: frame\.links: expected an object")
    case(R, "frame_link_pose_short" + e, jsonl(HEADER, SCENE, {**FRAME, "links": {"5": [0, 0, 0]}}), r"line 3: frame\.links\.5: expected 7 numbers, got \[0,0,0\]")
    case(R, "frame_unknown_scene" + e, jsonl(HEADER, SCENE, {**FRAME, "scene": 9}), r"line 3: frame\.scene: scene 9 was not described by an earlier scene line")
    case(R, "actor_without_handle" + e, jsonl(HEADER, SCENE, {"type": "actor", "scene": 1, "name": "a", "kind": "rigid"}), r"line 3: actor\.handle: required")
    case(R, "binary_garbage" + e, bytes(range(1, 256)) * 3, r"line 1: not a SuperDex recording")


def helper_files(out: Path):
    """Valid files the broken ones refer to (not in the manifest)."""
    (out / "prefab").mkdir(parents=True, exist_ok=True)
    h5({"mesh/coordinates": TET_V, "mesh/connectivity": TET_T})(out / "prefab" / "valid_tet.mochi.h5")
    (out / "prefab" / "valid_cube.obj").write_text(obj_text())
    (out / "prefab" / "valid_box.mochi_prefab").write_text(json.dumps(prefab(rigid=[box_actor()]), indent=1) + "\n")
    (out / "bot").mkdir(parents=True, exist_ok=True)
    (out / "bot" / "valid_params.json").write_text('{"kp": 1.0}\n')
    (out / "bot" / "valid_readme.txt").write_text("params files are JSON; this one is not\n")
    # a MuJoCo .msh whose header announces 10 vertices and 2 faces, cut after 4 bytes of data
    (out / "mjcf").mkdir(parents=True, exist_ok=True)
    (out / "mjcf" / "valid_truncated.msh").write_bytes(struct.pack("<4i", 10, 0, 0, 2) + bytes(4))

# ---------------------------------------------------------------------------------------------
# MJCF (MuJoCo XML)

def mjcf(body='<body name="arm" pos="0 0 1"><joint name="hinge"/><geom type="capsule" size="0.05 0.2"/></body>', head=""):
    return f'<mujoco model="corpus_mjcf">\n{head}<worldbody>\n<geom type="plane" size="1 1 0.1"/>\n{body}\n</worldbody>\n</mujoco>\n'


def mjcf_cases():
    M = "mjcf"
    e = ".xml"
    case(M, "not_xml" + e, "<mujoco <worldbody>", r"not a valid XML file")
    case(M, "root_not_mujoco" + e, '<robot name="r"><link name="a"/></robot>\n', r"not an MJCF file: the root element is <robot>, expected <mujoco>")
    case(M, "unknown_joint_type" + e, mjcf('<body name="arm"><joint name="j" type="twist"/><geom size="0.1"/></body>'),
         r"line 4: <body name='arm'>/<joint name='j'>: unknown joint type 'twist' \(expected hinge, slide, ball or free\)")
    case(M, "size_not_number" + e, mjcf('<body name="arm"><joint name="j"/><geom type="box" size="0.1 wide 0.1"/></body>'),
         r"line 4: <body name='arm'>/<geom>: attribute 'size': malformed number 'wide'")
    case(M, "capsule_without_size" + e, mjcf('<body name="arm"><joint name="j"/><geom type="capsule"/></body>'),
         r"line 4: <body name='arm'>/<geom>: a capsule geom needs 2 positive size value\(s\)")
    case(M, "undefined_class" + e, mjcf('<body name="arm" childclass="missing"><joint name="j"/><geom size="0.1"/></body>'),
         r"line 4: <body name='arm'>: childclass 'missing' is not a defined default class")
    case(M, "undefined_mesh" + e, mjcf('<body name="arm"><joint name="j"/><geom type="mesh" mesh="hand"/></body>'),
         r"line 4: <body name='arm'>/<geom>: refers to mesh 'hand', which is not defined in <asset>")
    case(M, "missing_mesh_file" + e, mjcf('<body name="arm"><joint name="j"/><geom type="mesh" mesh="hand"/></body>',
                                            head='<asset><mesh name="hand" file="no_such_hand.stl"/></asset>\n'),
         r"<asset>/<mesh name='hand'>: mesh file '.*no_such_hand.stl' not found")
    case(M, "missing_include" + e, mjcf(head='<include file="no_such_part.xml"/>\n'), r"line 2: <mujoco>/<include>: included file '.*no_such_part.xml' not found")
    case(M, "nested_free_joint" + e, mjcf('<body name="arm"><joint name="j"/><geom size="0.1"/><body name="hand"><freejoint/><geom size="0.1"/></body></body>'),
         r"<body name='hand'>/<freejoint>: a free joint must be the only joint of a body that is a child of the world")
    case(M, "range_inverted" + e, mjcf('<body name="arm"><joint name="j" range="30 -30"/><geom size="0.1"/></body>'),
         r"<joint name='j'>: attribute 'range': the lower limit 0.523599 exceeds the upper limit -0.523599")
    arm = '<mujoco model="corpus_mjcf">\n<worldbody>\n<body name="arm"><joint name="j" axis="0 1 0"/><geom size="0.1"/></body>\n</worldbody>\n'
    case(M, "tendon_unknown_joint" + e, arm + '<tendon><fixed name="t"><joint joint="j" coef="1"/><joint joint="missing" coef="-1"/></fixed></tendon>\n</mujoco>\n',
         r"<fixed name='t'>/<joint>: refers to joint 'missing', which is not defined")
    case(M, "tendon_range_inverted" + e, arm + '<tendon><fixed name="t" limited="true" range="0.5 -0.5"><joint joint="j" coef="1"/></fixed></tendon>\n</mujoco>\n',
         r"<fixed name='t'>: attribute 'range': the lower limit 0\.5 exceeds the upper limit -0\.5")
    case(M, "negative_inertial_mass" + e, mjcf('<body name="arm"><joint name="j"/><inertial pos="0 0 0" mass="-1" diaginertia="1 1 1"/></body>'),
         r"<body name='arm'>/<inertial>: missing or negative 'mass'")
    case(M, "coordinate_global" + e, mjcf(head='<compiler coordinate="global"/>\n'), r"coordinate=\"global\" is not supported")
    case(M, "msh_truncated" + e, mjcf('<body name="arm"><joint name="j"/><geom type="mesh" mesh="hand"/></body>',
                                       head='<asset><mesh name="hand" file="valid_truncated.msh"/></asset>\n'),
         r"not a MuJoCo .msh file: 20 bytes where its header announces 160")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT)
    args = parser.parse_args()
    for make in (bot_cases, prefab_cases, urdf_cases, mjcf_cases, h5_cases, mesh_cases, recording_cases):
        make()
    if args.out.exists():
        shutil.rmtree(args.out)
    helper_files(args.out)
    manifest = []
    for folder, name, content, loader, message, extra in CASES:
        path = args.out / folder / name
        path.parent.mkdir(parents=True, exist_ok=True)
        write_content(path, content)
        manifest.append({"file": f"{folder}/{name}", "loader": loader, "exception": "superdex.physics.Error", "message": message, **extra})
    names = [m["file"] for m in manifest]
    assert len(names) == len(set(names)), "corpus file names must be unique"
    (args.out / "manifest.json").write_text(json.dumps(manifest, indent=1) + "\n")
    counts = {}
    for m in manifest:
        counts[m["file"].split("/")[0]] = counts.get(m["file"].split("/")[0], 0) + 1
    print(f"{len(manifest)} files in {args.out}: " + ", ".join(f"{k} {v}" for k, v in counts.items()))


if __name__ == "__main__":
    main()
