"""The robotics examples (superdex_robotics/examples/basic and control/), run as a user would and
checked against independent references: the bot file's JSON read here, the URDF's joint origins
chained here in numpy and Pinocchio's model of the same URDF, the target poses and the analytic
circle the controllers are given, and the statics of the arm at rest.

Each example is imported from its file and its run() called in-process (it initializes and shuts
down the engine itself); the numbers compared are engine state and sensor signals read through the
public API. test_runs_as_a_script runs each one as a subprocess, headless, recording through the
debugger, and checks that it exits cleanly with nothing on stderr.
"""

import importlib.util
import json
import math
import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import superdex.physics as sdp

REPO = Path(__file__).resolve().parents[3]
EXAMPLES = REPO / "superdex_robotics" / "examples"
BOT_FILE = REPO / "assets" / "bots" / "fun" / "example_bot_2dof" / "example_bot_2dof.superdex_bot"
ARM_URDF = REPO / "assets" / "bots" / "urdf" / "tabletop_arm_4dof" / "tabletop_arm_4dof.urdf"
G = 9.81
DOFS_OF_JOINT = {"Hard": 0, "Revolute": 1, "Prismatic": 1, "Spherical": 3, "Free": 6}


def load_example(relative: str):
    path = EXAMPLES / relative
    spec = importlib.util.spec_from_file_location(f"example_{path.stem}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def float_or_double(double: float, single: float) -> float:
    return double if sdp.uses_double_precision() else single


def quaternion_matrix(q) -> np.ndarray:
    x, y, z, w = np.asarray(q, dtype=np.float64) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


# --------------------------------------------------------------------------------------------
# the URDF arm, read here with ElementTree: forward kinematics and mass properties in numpy


def rpy_matrix(r, p, y) -> np.ndarray:
    """URDF fixed-axis roll-pitch-yaw: Rz(y) Ry(p) Rx(r)."""
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    Rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    Ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    Rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return Rz @ Ry @ Rx


def axis_angle_matrix(axis, angle) -> np.ndarray:
    k = np.asarray(axis, dtype=np.float64) / np.linalg.norm(axis)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def homogeneous(R, p) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, p
    return T


def numbers(element, attribute, default):
    return [float(v) for v in (element.get(attribute) if element is not None and element.get(attribute) else default).split()]


class UrdfChain:
    """A serial URDF (every link has at most one child), parsed with ElementTree."""

    def __init__(self, path: Path):
        root = ET.parse(path).getroot()
        self.name = root.get("name")
        self.links = {link.get("name"): link for link in root.findall("link")}
        joints = root.findall("joint")
        children = {j.find("child").get("link") for j in joints}
        (self.root_link,) = [name for name in self.links if name not in children]
        by_parent = {j.find("parent").get("link"): j for j in joints}
        self.link_order, self.joints = [self.root_link], []
        while self.link_order[-1] in by_parent:
            joint = by_parent[self.link_order[-1]]
            self.joints.append(joint)
            self.link_order.append(joint.find("child").get("link"))
        self.moving = [j for j in self.joints if j.get("type") != "fixed"]

    def link_transforms(self, q) -> list[np.ndarray]:
        """World-from-link 4 x 4 transforms in link order, the root link at the world origin."""
        transforms, i = [np.eye(4)], 0
        for joint in self.joints:
            origin = joint.find("origin")
            T = transforms[-1] @ homogeneous(rpy_matrix(*numbers(origin, "rpy", "0 0 0")), numbers(origin, "xyz", "0 0 0"))
            if joint.get("type") != "fixed":
                T = T @ homogeneous(axis_angle_matrix(numbers(joint.find("axis"), "xyz", "1 0 0"), q[i]), np.zeros(3))
                i += 1
            transforms.append(T)
        return transforms

    def mass_and_com(self, link_name):
        inertial = self.links[link_name].find("inertial")
        return float(inertial.find("mass").get("value")), np.array(numbers(inertial.find("origin"), "xyz", "0 0 0"))


@pytest.fixture(scope="module")
def arm_chain():
    return UrdfChain(ARM_URDF)


# --------------------------------------------------------------------------------------------
# basic/example_bot_loading.py


def expected_from_bot_json(path: Path) -> dict:
    doc = json.loads(path.read_text())
    components = [(kind, c["type"], c["name"], link["name"]) for link in doc["links"]
                  for kind, key in (("sensor", "sensors"), ("actuator", "actuators")) for c in link.get(key, [])]
    return {
        "name": doc["name"],
        "links": [link["name"] for link in doc["links"]],
        "joints": [joint["name"] for joint in doc["joints"]],
        "joint_types": [joint["type"] for joint in doc["joints"]],
        "num_dofs": sum(DOFS_OF_JOINT[joint["type"]] for joint in doc["joints"]),
        "components": sorted(components),
        "default_pose": doc["defaultPose"],
    }


def check_loaded(result: dict, expected: dict) -> None:
    declared, built = result["declared"], result["built"]
    assert declared["name"] == expected["name"]
    assert [link["name"] for link in declared["links"]] == expected["links"]
    assert [joint["name"] for joint in declared["joints"]] == expected["joints"]
    assert [joint["type"] for joint in declared["joints"]] == expected["joint_types"]
    assert built["link_names"] == expected["links"]
    assert built["joint_names"] == expected["joints"]
    assert built["num_dofs"] == expected["num_dofs"]
    assert sum(size for _, size in built["dofs_per_joint"]) == expected["num_dofs"]
    assert sorted((c["kind"], c["type"], c["name"], c["link"]) for c in declared["components"]) == expected["components"]


def test_bot_loading_lists_what_the_file_declares():
    """The example's default bot: names, joint types, DOF count (2: two revolute joints, two welds)
    and declared components as read from the JSON here; the pose after create_bot is the file's
    defaultPose; its Python component types are not registered in this example, so none is built
    and create_bot's warning for each one is collected (nothing reaches stderr)."""
    ex = load_example("basic/example_bot_loading.py")
    result = ex.run()
    expected = expected_from_bot_json(BOT_FILE)
    assert expected["num_dofs"] == 2
    check_loaded(result, expected)
    np.testing.assert_allclose(result["built"]["pose"], expected["default_pose"], atol=1e-6)
    assert result["built_components"] == []
    assert len(result["warnings"]) == len(expected["components"])
    for _, type_name, name, _ in expected["components"]:
        assert any(type_name in w and name in w and "not registered" in w for w in result["warnings"])


def test_bot_loading_of_another_file_with_built_in_components(tmp_path):
    """A bot written here with a Free root (6 DOFs), a prismatic and a revolute joint (8 DOFs), a
    built-in JOINT_STATE sensor (built) and an unregistered actuator type (skipped with a warning).
    The positions create_bot gives the links follow from the joint origins and the default pose."""
    inertia = [0.01, 0, 0, 0.01, 0, 0.01]
    doc = {
        "name": "slider_bot",
        "links": [{"name": "body", "mass": 2.0, "momentOfInertia": inertia},
                  {"name": "carriage", "parentLink": 0, "mass": 0.5, "momentOfInertia": inertia,
                   "sensors": [{"type": "JOINT_STATE", "name": "carriage_state", "params": ""}]},
                  {"name": "arm", "parentLink": 1, "mass": 0.3, "momentOfInertia": inertia,
                   "actuators": [{"type": "NOBODY_REGISTERED_THIS", "name": "mystery_drive", "params": ""}]}],
        "joints": [{"name": "float", "type": "Free"},
                   {"name": "slide", "type": "Prismatic", "axis": [1, 0, 0],
                    "parentLinkFromJoint": {"rotation": [0, 0, 0, 1], "translation": [0, 0, 0.1]}},
                   {"name": "turn", "type": "Revolute", "axis": [0, 0, 1],
                    "parentLinkFromJoint": {"rotation": [0, 0, 0, 1], "translation": [0.2, 0, 0]}}],
        "defaultPose": [0.05, 0.3],
        "worldFromRoot": {"rotation": [0, 0, 0, 1], "translation": [1.0, 2.0, 3.0]},
    }
    path = tmp_path / "slider_bot.superdex_bot"
    path.write_text(json.dumps(doc))
    result = load_example("basic/example_bot_loading.py").run(str(path))
    expected = expected_from_bot_json(path)
    assert expected["num_dofs"] == 8
    check_loaded(result, expected)
    assert result["built_components"] == ["carriage_state"]
    (warning,) = result["warnings"]
    assert "NOBODY_REGISTERED_THIS" in warning and "mystery_drive" in warning
    # body at worldFromRoot; carriage 0.1 up and slid 0.05 along x; arm 0.2 further along x
    np.testing.assert_allclose(result["built"]["link_positions"], [[1, 2, 3], [1.05, 2, 3.1], [1.25, 2, 3.1]], atol=1e-6)


# --------------------------------------------------------------------------------------------
# basic/example_urdf_loading.py


def test_urdf_loading_names_dofs_and_forward_kinematics(arm_chain):
    """Link and joint names and the DOF count equal the URDF's (read here; the root gets a welded
    joint '<root>_root'); at the zero pose the tool is 0.1 + 0.12 + 0.35 + 0.3 + 0.1 = 0.97 m up;
    at the example's pose and at random poses every link's world pose equals the chain of the
    URDF's joint origins and axes multiplied here (homogeneous transforms, URDF rpy convention), to
    1e-5 m and 1e-5 (rotation matrices), 1e-9 in double precision."""
    ex = load_example("basic/example_urdf_loading.py")
    tol = float_or_double(1e-9, 1e-5)
    rng = np.random.default_rng(3)
    poses = [None, [0.0, 0.0, 0.0, 0.0]] + [rng.uniform(-1.8, 1.8, 4).tolist() for _ in range(3)]
    for pose in poses:
        result = ex.run(pose=pose)
        assert result["name"] == arm_chain.name
        assert result["link_names"] == arm_chain.link_order
        assert result["joint_names"] == ["world_joint"] + [j.get("name") for j in arm_chain.joints]
        assert result["num_dofs"] == len(arm_chain.moving) == 4
        q = ex.DEFAULT_POSE if pose is None else pose
        np.testing.assert_allclose(result["pose"], q, atol=1e-6)
        for (p, quat), T in zip(result["link_poses"], arm_chain.link_transforms(q)):
            np.testing.assert_allclose(p, T[:3, 3], atol=tol)
            np.testing.assert_allclose(quaternion_matrix(quat), T[:3, :3], atol=tol)
        if pose == [0.0, 0.0, 0.0, 0.0]:
            np.testing.assert_allclose(result["link_poses"][-1][0], [0, 0, 0.97], atol=1e-6)


def test_urdf_forward_kinematics_against_pinocchio():
    """The tool's world pose at the example's default pose and random poses equals Pinocchio's
    frame placement for the same URDF (pin.buildModelFromUrdf; both order the DOFs depth-first)."""
    ex = load_example("basic/example_urdf_loading.py")
    model = pin.buildModelFromUrdf(str(ARM_URDF))
    data = model.createData()
    tool = model.getFrameId("tool")
    tol = float_or_double(1e-9, 1e-5)
    rng = np.random.default_rng(4)
    for q in [ex.DEFAULT_POSE] + [rng.uniform(-1.8, 1.8, 4).tolist() for _ in range(2)]:
        result = ex.run(pose=q)
        pin.framesForwardKinematics(model, data, np.array(q))
        p, quat = result["link_poses"][-1]
        np.testing.assert_allclose(p, data.oMf[tool].translation, atol=tol)
        np.testing.assert_allclose(quaternion_matrix(quat), data.oMf[tool].rotation, atol=tol)


# --------------------------------------------------------------------------------------------
# control/example_jsc_control.py


def test_jsc_reaches_each_target_pose_without_overshoot():
    """BASIC_JSC_PD moves the arm through three target poses, 2 s each. For every move and joint:
    within 1.2 s the joint is within 2 % of the move from its target; at the end of the 2 s it is
    within 0.1 mrad of it and the arm is still (< 1 mrad/s); at no time does it go past its target
    by more than 1 % of the move (+ 0.1 mrad)."""
    ex = load_example("control/example_jsc_control.py")
    result = ex.run(seconds_per_pose=2.0)
    n, dt = result["steps_per_pose"], ex.CONTROL_DT
    start = np.array(ex.START_POSE, dtype=np.float64)
    for k, target in enumerate(np.array(ex.TARGET_POSES, dtype=np.float64)):
        q, v = result["q"][k * n:(k + 1) * n], result["v"][k * n:(k + 1) * n]
        move = target - start
        for j in range(len(target)):
            past = (q[:, j] - target[j]) * np.sign(move[j])
            assert past.max() <= 0.01 * abs(move[j]) + 1e-4, f"move {k + 1}, joint {j}: overshoot {past.max():.2e} rad"
            close = np.flatnonzero(np.abs(q[:, j] - target[j]) <= 0.02 * abs(move[j]))
            assert close.size and (close[0] + 1) * dt <= 1.2, f"move {k + 1}, joint {j}: slow"
        np.testing.assert_allclose(q[-1], target, atol=1e-4)
        assert np.abs(v[-1]).max() < 1e-3
        start = q[-1]


# --------------------------------------------------------------------------------------------
# control/example_osc_control.py


def test_osc_tool_tracks_the_circle(arm_chain):
    """The Python OSC loop: the tool, whose position is also checked against the URDF chain
    multiplied here from the joint angles (1e-5 m), follows the minimum-jerk approach and then the
    circle written here from its definition (centre, radius, period, counter-clockwise from
    centre + r x, entered after the approach): RMS error under 0.5 mm and largest under 1 mm from
    1 s after entering the circle, under 5 mm during the entry transient; no joint reaches its limit
    (the posture spring keeps the wrist clear)."""
    ex = load_example("control/example_osc_control.py")
    result = ex.run(laps=1.5)
    t, x, q = result["t"], result["x"], result["q"]
    for k in range(0, len(t), 250):
        np.testing.assert_allclose(x[k], arm_chain.link_transforms(q[k])[-1][:3, 3], atol=float_or_double(1e-9, 1e-5))

    w = 2 * math.pi / ex.CIRCLE_PERIOD
    tc = t - ex.APPROACH_SECONDS
    circle = np.asarray(ex.CIRCLE_CENTER) + ex.CIRCLE_RADIUS * np.stack([np.cos(w * tc), np.sin(w * tc), 0 * tc], axis=1)
    error = np.linalg.norm(x - circle, axis=1)
    entered = tc > 0
    settled = tc >= 1.0
    assert settled.sum() * ex.CONTROL_DT >= 4.9, "more than a lap after the transient"
    assert error[entered].max() < 5e-3
    assert math.sqrt(np.mean(error[settled] ** 2)) < 5e-4
    assert error[settled].max() < 1e-3
    # the tool went round: its angle about the centre covers the whole circle
    angle = np.unwrap(np.arctan2(x[settled, 1] - ex.CIRCLE_CENTER[1], x[settled, 0] - ex.CIRCLE_CENTER[0]))
    assert np.ptp(angle) > 2 * math.pi
    limits = np.array([[float(j.find("limit").get("lower")), float(j.find("limit").get("upper"))] for j in arm_chain.moving])
    assert (q > limits[:, 0] + 0.05).all() and (q < limits[:, 1] - 0.05).all()


# --------------------------------------------------------------------------------------------
# control/example_cpp_pipeline.py


def test_cpp_pipeline_reaches_holds_and_senses(arm_chain):
    """Only C++ components run (BASIC_OSC_PD, DC_MOTOR x 4, JOINT_STATE, FORCE_TORQUE, IMU). After
    3 s, from the JOINT_STATE sensor's angles and the URDF chain multiplied here:
    - the tool is at the target within 1 mm, and the arm is still (|v| < 1e-3 rad/s);
    - FORCE_TORQUE at the base reads the statics of the arm at rest: force (0, 0, m g) with m the
      URDF's total mass, torque about the base origin sum_i c_i x (0, 0, m_i g) with the centres
      of mass c_i from the URDF's inertial origins, within 1e-3 of m g (N) and m g x 1 m (N m);
    - the IMU on the tool reads R_tool^T (0, 0, g) and no rotation;
    - the motors deliver the gravity torques of that pose, from Pinocchio's
      computeGeneralizedGravity on the same URDF, within 2e-3 N m."""
    ex = load_example("control/example_cpp_pipeline.py")
    result = ex.run(seconds=3.0)
    n = result["num_dofs"]
    q, v = result["joint_state"][:n], result["joint_state"][n:]
    transforms = arm_chain.link_transforms(q)
    np.testing.assert_allclose(transforms[-1][:3, 3], ex.TARGET, atol=1e-3)
    np.testing.assert_allclose(result["tool_position"], transforms[-1][:3, 3], atol=float_or_double(1e-9, 1e-5))
    assert np.abs(v).max() < 1e-3

    masses, moment = 0.0, np.zeros(3)
    for name, T in zip(arm_chain.link_order, transforms):
        m, com_local = arm_chain.mass_and_com(name)
        masses += m
        moment += np.cross(T[:3, :3] @ com_local + T[:3, 3], [0, 0, m * G])
    weight = masses * G
    assert masses == pytest.approx(result["total_mass"])
    np.testing.assert_allclose(result["base_ft"][:3], [0, 0, weight], atol=1e-3 * weight)
    np.testing.assert_allclose(result["base_ft"][3:], moment, atol=1e-3 * weight)
    assert np.linalg.norm(result["base_ft"][3:5]) > 1.0, "the arm reaches out: its weight has a moment"

    R_tool = transforms[-1][:3, :3]
    np.testing.assert_allclose(result["tool_imu"][:3], R_tool.T @ [0, 0, G], atol=float_or_double(1e-6, 2e-3))
    np.testing.assert_allclose(result["tool_imu"][3:], 0, atol=1e-3)

    model = pin.buildModelFromUrdf(str(ARM_URDF))
    model.gravity.linear = np.array([0, 0, -G])
    gravity = pin.computeGeneralizedGravity(model, model.createData(), q)
    np.testing.assert_allclose(result["efforts"], gravity, atol=2e-3)
    assert np.abs(gravity).max() > 1.0


# --------------------------------------------------------------------------------------------
# every example as a script


@pytest.mark.parametrize("relative, args", [
    ("basic/example_bot_loading.py", ["--seconds", "0.2"]),
    ("basic/example_urdf_loading.py", ["--seconds", "0.2"]),
    ("control/example_jsc_control.py", ["--seconds-per-pose", "0.3"]),
    ("control/example_osc_control.py", ["--laps", "0.1"]),
    ("control/example_cpp_pipeline.py", ["--seconds", "0.3"]),
])
def test_runs_as_a_script(relative, args, tmp_path):
    """python <example> --debugger exits 0 with nothing on stderr (the bot-loading example's
    skipped components are reported on stdout) and prints its summary; SUPERDEX_DEBUGGER_RECORD
    makes the debugger record the run (header and frames)."""
    recording = tmp_path / "run.jsonl"
    env = dict(os.environ, SUPERDEX_DEBUGGER_RECORD=str(recording))
    proc = subprocess.run([sys.executable, str(EXAMPLES / relative), *args, "--debugger"], env=env,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    assert len(proc.stdout.splitlines()) >= 5
    lines = [json.loads(line) for line in recording.read_text().splitlines()]
    assert lines[0]["type"] == "header"
    assert any(line["type"] == "frame" for line in lines)
