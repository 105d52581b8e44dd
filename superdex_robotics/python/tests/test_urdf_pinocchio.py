"""SuperDex's URDF import checked against Pinocchio's URDF parser on real robots.

The Franka Panda and the UR5 of the `example-robot-data` package (a dev dependency), and a
seeded synthetic URDF that exercises what those two leave out (joint and inertial origins
with arbitrary rpy, full inertia tensors, non-unit and unaligned axes, continuous and
prismatic joints, a branching tree), are imported with `sdr.load_bot_prefab_from_urdf_file`
and built with `sdr.create_bot`, and loaded independently with `pinocchio.buildModelFromUrdf`. At random configurations within
the joint limits, random velocities and torques, the test compares to 1e-9 relative:

* the world pose of every link against Pinocchio's BODY frame of the same name;
* every link's Jacobian (world axes, at the link origin) against
  `getFrameJacobian(..., LOCAL_WORLD_ALIGNED)`;
* the mass matrix (`crba`), the bias forces with gravity (`nonLinearEffects`) and the
  forward-dynamics accelerations (`aba`).

DOFs are matched by joint name (SuperDex orders DOFs by link, Pinocchio by joint id).
The importer's joint data (types, limits, effort limits, damping) is also checked against
what Pinocchio read from the same file.

Two modelling differences are accounted for, both documented in urdf_import.cpp:
* Massless URDF links (frames such as `tool0`, `panda_hand_tcp`) are kept as links with
  a negligible mass (1e-9 kg, inertia 1e-12 kg m^2 at their origin) because the engine
  needs positive masses. Pinocchio gets exactly the same inertias added at those links'
  frames, so the two models are identical and the comparison stays exact.
* `<mimic>` (the Panda's second finger): Pinocchio's model keeps each finger its own DOF; the
  importer does too, and holds the relation with a coupling in the step, so the mass matrices
  are the same.

URDFs have no armature, so the mass matrices carry none on either side.

Also: bad URDFs (missing mesh, unknown joint type, cycle) raise `sdp.Error`.

Runs only in double precision (SUPERDEX_PRECISION=double); skipped in float builds.
"""

from __future__ import annotations

import importlib.metadata
import warnings
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

try:
    import pinocchio as pin
except ImportError as exc:  # a declared dev dependency: missing means a broken environment, not a skip
    raise ImportError(
        "pinocchio (PyPI package 'pin', a dev dependency in pyproject.toml) is required by this test; "
        "run `uv sync` to install it"
    ) from exc

import superdex.physics as sdp
import superdex.robotics as sdr

if not sdp.uses_double_precision():
    pytest.skip(
        "the Pinocchio comparison needs double precision (run with SUPERDEX_PRECISION=double)",
        allow_module_level=True,
    )

GRAVITY = np.array([0.0, 0.0, -9.81])
RTOL = 1e-9
NUM_STATES = 5
# what the importer gives links that have no mass in the URDF (urdf_import.cpp)
MASSLESS_LINK_MASS = 1e-9
MASSLESS_LINK_INERTIA = 1e-12

# robot -> URDF path inside example-robot-data's `robots/` folder
ROBOTS = {
    "panda": "panda_description/urdf/panda.urdf",
    "ur5": "ur_description/urdf/ur5_robot.urdf",
}
# import warnings each robot must give (substrings); any other warning fails the test
EXPECTED_WARNINGS = {
    "panda": [
        "link 'panda_rightfinger': the <origin> of the visual mesh is ignored",
        # joint 4's range [-3.0718, -0.0698] rad excludes zero
        "<joint name='panda_joint4'>: zero lies outside the joint's limits [-3.0718, -0.0698]: the robot starts with the joint at -0.0698",
        # the wrist's and fingers' collision meshes overlap in the robot's start pose
        "3 pair(s) of links whose collision shapes overlap at the zero configuration do not collide with each other: "
        "('panda_link5', 'panda_link7'), ('panda_link5', 'panda_hand'), ('panda_leftfinger', 'panda_rightfinger')",
    ],
    "ur5": [],
    "synthetic": [],
}


def example_robot_data_file(relative: str) -> Path:
    """A file of the installed example-robot-data distribution (its robots live under
    cmeel.prefix/share/example-robot-data/robots; there is no Python module to ask)."""
    try:
        dist = importlib.metadata.distribution("example-robot-data")
    except importlib.metadata.PackageNotFoundError as exc:
        raise ImportError(
            "example-robot-data (a dev dependency in pyproject.toml) is required by this test; run `uv sync`"
        ) from exc
    suffix = "robots/" + relative
    for f in dist.files or []:
        if str(f).replace("\\", "/").endswith(suffix):
            return Path(dist.locate_file(f)).resolve()
    raise FileNotFoundError(f"{suffix} is not part of example-robot-data {dist.version}")


def synthetic_urdf(path: Path, seed: int = 7) -> Path:
    """A branching fixed-base robot with every kind of URDF joint the importer maps, random
    joint origins (xyz and rpy), non-unit unaligned axes, inertials with random origins and
    full inertia tensors, one massless welded frame and one massless link whose welded child
    carries its mass. Numbers are written with repr(), so both parsers read the same values."""
    rng = np.random.default_rng(seed)

    def num(x) -> str:
        return repr(float(x))  # shortest round-trip form

    def vec(x) -> str:
        return " ".join(num(c) for c in x)

    def inertial() -> str:
        a, b, c = rng.uniform(0.01, 0.1, 3)
        Q = pin.exp3(rng.normal(size=3))
        I = Q @ np.diag([b + c, a + c, a + b]) @ Q.T  # principal moments of a physical body
        return (
            f'<inertial><origin xyz="{vec(rng.uniform(-0.2, 0.2, 3))}" rpy="{vec(rng.uniform(-np.pi, np.pi, 3))}"/>'
            f'<mass value="{num(rng.uniform(0.5, 3.0))}"/>'
            f'<inertia ixx="{num(I[0, 0])}" ixy="{num(I[0, 1])}" ixz="{num(I[0, 2])}" iyy="{num(I[1, 1])}" iyz="{num(I[1, 2])}" '
            f'izz="{num(I[2, 2])}"/></inertial>'
        )

    types = ["revolute", "prismatic", "continuous", "fixed", "revolute", "continuous", "prismatic", "revolute"]
    links = ['<link name="base">' + inertial() + "</link>"]
    joints = []
    for i, jtype in enumerate(types, start=1):
        parent = "base" if i == 1 else f"l{rng.integers(1, i)}"
        links.append(f'<link name="l{i}">{inertial()}<collision><geometry><box size="0.1 0.2 0.3"/></geometry></collision></link>')
        body = f'<origin xyz="{vec(rng.uniform(-0.5, 0.5, 3))}" rpy="{vec(rng.uniform(-np.pi, np.pi, 3))}"/>'
        if jtype != "fixed":
            body += f'<axis xyz="{vec(rng.normal(size=3) * rng.uniform(0.5, 2.0))}"/>'
            span = 0.3 if jtype == "prismatic" else 2.0
            body += (
                f'<limit lower="{num(-rng.uniform(0.1, span))}" upper="{num(rng.uniform(0.1, span))}" '
                f'effort="{num(rng.uniform(1, 100))}" velocity="1"/>'
                f'<dynamics damping="{num(rng.uniform(0, 1))}" friction="{num(rng.uniform(0, 1))}"/>'
            )
        joints.append(
            f'<joint name="j{i}" type="{jtype}"><parent link="{parent}"/><child link="l{i}"/>{body}</joint>'
        )
    # a massless tool frame, and a massless moving link that carries a welded massive one
    links.append('<link name="tool"/>')
    joints.append(f'<joint name="j_tool" type="fixed"><parent link="l{len(types)}"/><child link="tool"/>'
                  f'<origin xyz="0 0 0.1" rpy="0.1 0.2 0.3"/></joint>')
    links.append('<link name="carrier"/>')
    joints.append('<joint name="j_carrier" type="continuous"><parent link="l2"/><child link="carrier"/>'
                  f'<origin xyz="0.1 0 0"/><axis xyz="0 0 1"/><limit effort="5" velocity="1"/></joint>')
    links.append(f'<link name="payload">{inertial()}</link>')
    joints.append('<joint name="j_payload" type="fixed"><parent link="carrier"/><child link="payload"/>'
                  f'<origin xyz="0.2 0 0" rpy="0 0.5 0"/></joint>')
    path.write_text('<?xml version="1.0"?>\n<robot name="synthetic">\n' + "\n".join(links + joints) + "\n</robot>\n")
    return path


def urdf_types(urdf: Path) -> dict[str, str]:
    """Joint name -> URDF joint type."""
    return {j.get("name"): j.get("type") for j in ET.parse(urdf).getroot().iter("joint")}


def massless_links(urdf: Path) -> set[str]:
    """Links of the URDF without an <inertial> or with mass 0."""
    out = set()
    for link in ET.parse(urdf).getroot().iter("link"):
        inertial = link.find("inertial")
        if inertial is None or float(inertial.find("mass").get("value")) == 0.0:
            out.add(link.get("name"))
    return out


def assert_close(actual, reference, what: str) -> None:
    actual = np.asarray(actual, dtype=float)
    reference = np.asarray(reference, dtype=float)
    assert actual.shape == reference.shape, f"{what}: shape {actual.shape}, expected {reference.shape}"
    scale = max(1.0, float(np.abs(reference).max())) if reference.size else 1.0
    np.testing.assert_allclose(actual, reference, rtol=RTOL, atol=RTOL * scale, err_msg=what)


def quat_xyzw_to_matrix(q) -> np.ndarray:
    x, y, z, w = (float(c) for c in q)
    return pin.Quaternion(w, x, y, z).normalized().toRotationMatrix()


# --------------------------------------------------------------------------------------
# fixtures


@pytest.fixture(scope="module")
def engine():
    sdp.initialize()
    yield sdp
    sdp.shutdown()


@dataclass
class Robot:
    name: str
    urdf: Path
    prefab: object  # sdr.BotPrefab
    scene: object  # sdp.Scene
    art: object  # the articulated actor
    link_names: list[str]
    model: pin.Model  # Pinocchio's model of the same URDF, massless links given the importer's inertia
    perm: np.ndarray  # SuperDex DOF k is Pinocchio velocity index perm[k]
    frame_ids: list[int]  # Pinocchio BODY frame of each SuperDex link


def pinocchio_model(urdf: Path, massless: set[str], link_names: list[str], floating: bool = False) -> pin.Model:
    model = pin.buildModelFromUrdf(str(urdf), pin.JointModelFreeFlyer()) if floating else pin.buildModelFromUrdf(str(urdf))
    model.gravity = pin.Motion(GRAVITY, np.zeros(3))
    for name in massless & set(link_names):
        # the same negligible inertia as the importer's, at the link origin
        frame = model.frames[model.getFrameId(name, pin.FrameType.BODY)]
        extra = pin.Inertia(MASSLESS_LINK_MASS, np.zeros(3), MASSLESS_LINK_INERTIA * np.eye(3))
        model.inertias[frame.parentJoint] = model.inertias[frame.parentJoint] + frame.placement.act(extra)
    return model


@pytest.fixture(scope="module", params=[*sorted(ROBOTS), "synthetic"])
def robot(request, engine, tmp_path_factory) -> Robot:
    name = request.param
    if name == "synthetic":
        urdf = synthetic_urdf(tmp_path_factory.mktemp("urdf") / "synthetic.urdf")
    else:
        urdf = example_robot_data_file(ROBOTS[name])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        prefab = sdr.load_bot_prefab_from_urdf_file(str(urdf), fixed_base=True)
    messages = [str(w.message) for w in caught]
    for expected in EXPECTED_WARNINGS[name]:
        assert any(expected in m for m in messages), f"{name}: no warning {expected!r} in {messages}"
    assert len(messages) == len(EXPECTED_WARNINGS[name]), f"{name}: unexpected warnings {messages}"
    scene = sdp.create_scene(f"urdf_{name}")
    scene.set_gravity(GRAVITY.tolist())
    bot = sdr.create_bot(scene, prefab, sdr.create_context())
    art = bot.get_articulated_actor()
    info = art.get_articulated_shape_info()
    link_names = list(info.link_names)

    massless = massless_links(urdf)
    model = pinocchio_model(urdf, massless, link_names)
    assert art.get_num_dofs() == model.nv, f"{name}: {art.get_num_dofs()} DOFs, Pinocchio has {model.nv}"

    # DOFs matched by joint name
    perm = np.full(model.nv, -1)
    for i, joint_name in enumerate(info.joint_names):
        d = info.dof_info[i]
        if d.get_size() == 0:
            continue
        assert model.existJointName(joint_name), f"{name}: Pinocchio has no joint {joint_name!r}"
        jid = model.getJointId(joint_name)
        assert model.nvs[jid] == d.get_size(), f"{name}: joint {joint_name!r} DOF count"
        perm[d.offset : d.offset + d.get_size()] = np.arange(model.idx_vs[jid], model.idx_vs[jid] + model.nvs[jid])
    assert sorted(perm) == list(range(model.nv)), f"{name}: DOF map {perm}"

    frame_ids = []
    for link in link_names:
        assert model.existFrame(link, pin.FrameType.BODY), f"{name}: Pinocchio has no BODY frame {link!r}"
        frame_ids.append(model.getFrameId(link, pin.FrameType.BODY))
    return Robot(name, urdf, prefab, scene, art, link_names, model, perm, frame_ids)


# --------------------------------------------------------------------------------------
# the imported model


def test_links_and_joints_match_the_urdf(robot: Robot):
    """Every URDF link is a SuperDex link (the UR5's bare `world` link is the world itself),
    parents come before children, and the joint data is what Pinocchio read."""
    urdf_links = [link.get("name") for link in ET.parse(robot.urdf).getroot().iter("link")]
    expected = [n for n in urdf_links if n != "world"]
    assert sorted(robot.link_names) == sorted(expected)
    parents = [link.parent_link for link in robot.prefab.links]
    assert parents[0] == -1 and all(0 <= p < i for i, p in enumerate(parents) if i > 0), parents

    massless = massless_links(robot.urdf)
    for link in robot.prefab.links:
        if link.name in massless:
            assert link.mass == MASSLESS_LINK_MASS, link.name
            np.testing.assert_array_equal(link.moment_of_inertia, MASSLESS_LINK_INERTIA * np.array([1, 0, 0, 1, 0, 1]))

    model = robot.model
    types = urdf_types(robot.urdf)
    for joint in robot.prefab.joints:
        if not model.existJointName(joint.name):  # fixed joints are frames in Pinocchio
            assert joint.type == sdp.ArticulatedJointType.HARD, joint.name
            continue
        jid = model.getJointId(joint.name)
        k = model.idx_vs[jid]
        axis = np.asarray(joint.axis, dtype=float)
        assert np.linalg.norm(axis) == pytest.approx(1.0, abs=1e-15), joint.name
        assert joint.armature == 0.0
        assert joint.effort_limit == pytest.approx(model.effortLimit[k], rel=1e-12), joint.name
        assert joint.viscous_friction == pytest.approx(model.damping[k], rel=1e-12), joint.name
        assert joint.coulomb_friction == pytest.approx(model.friction[k], rel=1e-12), joint.name
        if types[joint.name] == "continuous":
            assert joint.type == sdp.ArticulatedJointType.REVOLUTE and joint.min_limit is None and joint.max_limit is None
            continue
        expected_type = sdp.ArticulatedJointType.PRISMATIC if types[joint.name] == "prismatic" else sdp.ArticulatedJointType.REVOLUTE
        assert joint.type == expected_type, joint.name
        lower = float(axis @ np.asarray(joint.min_limit, dtype=float))
        upper = float(axis @ np.asarray(joint.max_limit, dtype=float))
        iq = model.idx_qs[jid]
        assert lower == pytest.approx(model.lowerPositionLimit[iq], abs=1e-12), joint.name
        assert upper == pytest.approx(model.upperPositionLimit[iq], abs=1e-12), joint.name


# --------------------------------------------------------------------------------------
# kinematics and dynamics


@dataclass
class State:
    q_pin: np.ndarray
    pose: np.ndarray  # SuperDex DOF order
    v: np.ndarray  # SuperDex DOF order
    tau: np.ndarray  # SuperDex DOF order


def random_state(robot: Robot, rng: np.random.Generator) -> State:
    """Joint values within the limits (continuous joints: any angle), random v and tau."""
    model = robot.model
    q_pin = pin.neutral(model)
    values = np.zeros(model.nv)  # Pinocchio velocity order
    for jid in range(1, model.njoints):
        iq, iv = model.idx_qs[jid], model.idx_vs[jid]
        assert model.nvs[jid] == 1, model.names[jid]
        if model.nqs[jid] == 1:  # revolute, prismatic
            values[iv] = q_pin[iq] = rng.uniform(model.lowerPositionLimit[iq], model.upperPositionLimit[iq])
        else:  # continuous: (cos, sin) in Pinocchio
            values[iv] = rng.uniform(-np.pi, np.pi)
            q_pin[iq : iq + 2] = np.cos(values[iv]), np.sin(values[iv])
    return State(
        q_pin=q_pin,
        pose=values[robot.perm],
        v=rng.normal(0.0, 1.0, model.nv),
        tau=rng.normal(0.0, 5.0, model.nv),
    )


def test_kinematics_and_dynamics_match_pinocchio(robot: Robot):
    model, perm, art, scene = robot.model, robot.perm, robot.art, robot.scene
    data = model.createData()
    n_links = len(robot.link_names)
    link_actors = [scene.get_actor(h) for h in art.get_nested_link_actors()]
    assert len(link_actors) == n_links
    transforms = sdp.DynamicArrayTransformRT(n_links)
    rng = np.random.default_rng({"panda": 1, "ur5": 2, "synthetic": 3}[robot.name])

    for k in range(NUM_STATES):
        s = random_state(robot, rng)
        where = f"{robot.name}, state {k}"
        art.set_articulated_pose_from_joints(s.pose)
        art.set_articulated_joint_velocities(s.v)
        v_pin, tau_pin = np.zeros(model.nv), np.zeros(model.nv)
        v_pin[perm], tau_pin[perm] = s.v, s.tau

        # link poses
        pin.forwardKinematics(model, data, s.q_pin, v_pin)
        pin.updateFramePlacements(model, data)
        art.get_articulated_link_transforms(transforms)
        for i, fid in enumerate(robot.frame_ids):
            X = data.oMf[fid]
            link = robot.link_names[i]
            assert_close(np.asarray(transforms[i].translation), X.translation, f"position of {link}, {where}")
            assert_close(quat_xyzw_to_matrix(np.array(transforms[i].rotation)), X.rotation, f"rotation of {link}, {where}")

        # link Jacobians: world axes at the link origin, linear rows first
        pin.computeJointJacobians(model, data, s.q_pin)
        pin.updateFramePlacements(model, data)
        for i, fid in enumerate(robot.frame_ids):
            J_ref = np.array(pin.getFrameJacobian(model, data, fid, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED))
            J_ref = J_ref.reshape(6, model.nv)[:, perm]
            J = np.asarray(link_actors[i].get_articulated_jacobian()).reshape(6, model.nv)
            assert_close(J, J_ref, f"Jacobian of {robot.link_names[i]}, {where}")

        # dynamics
        M_ref = np.array(pin.crba(model, data, s.q_pin)).reshape(model.nv, model.nv)
        M_ref = np.triu(M_ref) + np.triu(M_ref, 1).T  # crba fills the upper triangle
        bias_ref = np.array(pin.nonLinearEffects(model, data, s.q_pin, v_pin)).reshape(model.nv)
        accel_ref = np.array(pin.aba(model, data, s.q_pin, v_pin, tau_pin)).reshape(model.nv)
        assert_close(art.get_articulated_mass_matrix(), M_ref[np.ix_(perm, perm)], f"mass matrix, {where}")
        assert_close(art.get_articulated_bias_forces(), bias_ref[perm], f"bias forces, {where}")
        assert_close(art.compute_articulated_forward_dynamics(s.tau), accel_ref[perm], f"forward dynamics, {where}")


def test_reference_inertias_are_negligible(robot: Robot):
    """The inertias added to Pinocchio for massless links change its mass matrix by about
    1e-9 of its largest entry: the importer's stand-in mass is physically irrelevant."""
    plain = pin.buildModelFromUrdf(str(robot.urdf))
    rng = np.random.default_rng(4)
    for _ in range(NUM_STATES):
        q = random_state(robot, rng).q_pin
        M_plain = pin.crba(plain, plain.createData(), q)
        M = pin.crba(robot.model, robot.model.createData(), q)
        np.testing.assert_allclose(M, M_plain, rtol=0, atol=1e-8 * np.abs(M_plain).max())


def test_floating_base_dynamics_match_pinocchio(robot: Robot):
    """Loaded without fixed_base, the root floats on a Free joint named world_joint: the mass
    matrix and gravity forces equal Pinocchio's with a free-flyer root. Pinocchio's free-flyer
    linear velocity is in the body frame, the engine's in the world frame: v_pin = T v with
    T = diag(R^T, I) on the root's six DOFs, so M = T^T M_pin T and g = T^T g_pin."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        prefab = sdr.load_bot_prefab_from_urdf_file(str(robot.urdf))
    urdf_links = [link.get("name") for link in ET.parse(robot.urdf).getroot().iter("link")]
    if "world" in urdf_links:  # the URDF welds its base to a 'world' link itself: it stays fixed
        assert prefab.joints[0].type == sdp.ArticulatedJointType.HARD
        return
    assert (prefab.joints[0].name, prefab.joints[0].type) == ("world_joint", sdp.ArticulatedJointType.FREE)
    scene = sdp.create_scene(f"floating_{robot.name}")
    try:
        scene.set_gravity(GRAVITY.tolist())
        art = sdr.create_bot(scene, prefab, sdr.create_context()).get_articulated_actor()
        model = pinocchio_model(robot.urdf, massless_links(robot.urdf), robot.link_names, floating=True)
        data = model.createData()
        n = model.nv
        assert art.get_num_dofs() == n == robot.model.nv + 6
        # the root's six DOFs come first in both; the joints follow in the fixed-base order
        perm = np.concatenate([np.arange(6), 6 + robot.perm])
        rng = np.random.default_rng(11)
        for k in range(NUM_STATES):
            s = random_state(robot, rng)
            p, r = rng.uniform(-1.0, 1.0, 3), rng.normal(0.0, 1.0, 3)
            R = pin.exp3(r)
            q_pin = np.concatenate([p, pin.Quaternion(R).coeffs(), s.q_pin])  # quaternion as x, y, z, w
            art.set_articulated_pose_from_joints(np.concatenate([p, r, s.pose]))
            art.set_articulated_joint_velocities(np.zeros(n))
            T = np.eye(n)
            T[:3, :3] = R.T
            M_pin = np.array(pin.crba(model, data, q_pin)).reshape(n, n)
            M_pin = (np.triu(M_pin) + np.triu(M_pin, 1).T)[np.ix_(perm, perm)]
            g_pin = np.array(pin.computeGeneralizedGravity(model, data, q_pin)).reshape(n)[perm]
            where = f"{robot.name} floating, state {k}"
            assert_close(art.get_articulated_mass_matrix(), T.T @ M_pin @ T, f"mass matrix, {where}")
            assert_close(art.get_articulated_bias_forces(), T.T @ g_pin, f"gravity forces, {where}")
    finally:
        sdp.destroy_scene(scene)


# --------------------------------------------------------------------------------------
# bad input


def write_urdf(tmp_path: Path, body: str) -> str:
    path = tmp_path / "bad.urdf"
    path.write_text(f'<?xml version="1.0"?>\n<robot name="bad">\n{body}\n</robot>\n')
    return str(path)


LINK = (
    '<link name="{}"><inertial><mass value="1"/>'
    '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>'
)


def test_missing_collision_mesh_is_an_error(engine, tmp_path):
    path = write_urdf(
        tmp_path,
        '<link name="base"><collision><geometry><mesh filename="package://nowhere/meshes/base.stl"/>'
        "</geometry></collision></link>",
    )
    with pytest.raises(sdp.Error, match=r"link 'base': collision mesh 'package://nowhere/meshes/base.stl' not found"):
        sdr.load_bot_prefab_from_urdf_file(path, fixed_base=True)


def test_a_floating_base_needs_mass(engine, tmp_path):
    # a lone link without <inertial> cannot float; welded to the world it is a fixed frame
    path = write_urdf(tmp_path, '<link name="base"/>')
    with pytest.raises(sdp.Error, match=r"<link name='base'>: link 'base' has no inertial but moves on joint 'world_joint'"):
        sdr.load_bot_prefab_from_urdf_file(path)
    fixed = sdr.load_bot_prefab_from_urdf_file(path, fixed_base=True)
    assert (fixed.name, len(fixed.links), fixed.joints[0].name) == ("bad", 1, "world_joint")


def test_unknown_joint_type_is_an_error(engine, tmp_path):
    path = write_urdf(
        tmp_path,
        LINK.format("a") + LINK.format("b")
        + '<joint name="twist" type="screw"><parent link="a"/><child link="b"/></joint>',
    )
    with pytest.raises(sdp.Error, match=r"bad\.urdf: line \d+: <joint name='twist'>: unknown joint type 'screw'"):
        sdr.load_bot_prefab_from_urdf_file(path)


def test_cycle_is_an_error(engine, tmp_path):
    path = write_urdf(
        tmp_path,
        LINK.format("a") + LINK.format("b")
        + '<joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>'
        + '<joint name="j2" type="fixed"><parent link="b"/><child link="a"/></joint>',
    )
    with pytest.raises(sdp.Error, match=r"the joints form a cycle"):
        sdr.load_bot_prefab_from_urdf_file(path)
