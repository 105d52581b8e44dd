"""Articulated-body dynamics of SuperDex checked against Pinocchio on random kinematic trees.

A seeded generator builds kinematic trees of up to 30 DOFs: a Hard (fixed base) or Free
root, then Revolute, Prismatic, Spherical and Hard (welded) joints on a random topology
with branching, random unit axes, random joint placements (rotation and translation),
random masses, centres of mass and physically valid inertias. Each tree is built in
SuperDex through the Python API and, identically, as a Pinocchio model:

* Revolute / Prismatic -> JointModelRevoluteUnaligned / JointModelPrismaticUnaligned,
  Spherical -> JointModelSpherical, Free root -> JointModelFreeFlyer. A SuperDex Free
  joint's linear velocity is in its parent frame, Pinocchio's in the body frame: with
  v_pin = T v (T rotates the first three DOFs by R^T), the references are mapped exactly:
  M = T^T M_pin T, c = T^T (c_pin + M_pin Tdot v), vdot = T^T (vdot_pin - Tdot v), J = J_pin T.
* Hard joints have no Pinocchio joint: the link's inertia is merged into its nearest moving
  ancestor joint (appendBodyToJoint at the composed placement) and its children attach to
  that joint with the composed placement. A Hard root is a fixed base: link 0 is attached
  to the universe (joint 0).
* Every link gets a Pinocchio frame at its origin, so its Jacobian can be queried.
* Joints are added to Pinocchio in depth-first order (its crba needs every subtree on
  consecutive indices) and its results are permuted back to SuperDex's DOF order (joints
  in link order, which the generator leaves non-depth-first on purpose).

For a few random states (q, v, tau) per tree the test compares the joint-space mass
matrix, the bias forces c(q, v) (gravity included), forward-dynamics accelerations and the
world-aligned Jacobian of every link, to 1e-9 relative.

A second test checks the reference itself: the merged Pinocchio model must agree with
the one pinocchio.buildReducedModel makes when the Hard joints are modelled as locked
revolute joints, so a disagreement with SuperDex is not a mistake of the reference.

Runs only in double precision (SUPERDEX_PRECISION=double); skipped in float builds.
"""

from __future__ import annotations

from dataclasses import dataclass, field

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
from conftest import articulation, joint, link

if not sdp.uses_double_precision():
    pytest.skip(
        "Pinocchio comparison needs double precision (run with SUPERDEX_PRECISION=double)",
        allow_module_level=True,
    )

GRAVITY = np.array([0.0, 0.0, -9.81])
RTOL = 1e-9
STATES_PER_TREE = 3

# (seed, root joint type, DOF budget including the root's, probability of a Hard joint,
#  probability that a new link hangs from the previous one (deep chains) instead of a random link)
TREE_CASES = [
    (0, "Free", 30, 0.15, 0.5),
    (1, "Hard", 30, 0.15, 0.5),
    (2, "Free", 14, 0.30, 0.3),
    (3, "Hard", 8, 0.30, 0.3),
    (4, "Free", 30, 0.45, 0.4),
    (5, "Hard", 24, 0.45, 0.2),
    (6, "Free", 6, 0.50, 0.5),  # a single free body with welded links only
    (7, "Hard", 30, 0.10, 0.85),  # deep, mostly serial chain
    (8, "Free", 22, 0.25, 0.0),  # bushy: parents drawn uniformly
    (9, "Hard", 1, 0.60, 0.5),  # one moving joint among welded links
]

JOINT_DOFS = {"Hard": 0, "Free": 6, "Revolute": 1, "Prismatic": 1, "Spherical": 3}


# --------------------------------------------------------------------------------------
# random trees


@dataclass
class Tree:
    root_type: str
    parents: list[int] = field(default_factory=list)  # -1 for link 0
    types: list[str] = field(default_factory=list)
    axes: list[np.ndarray] = field(default_factory=list)  # unit axes (unused for Hard/Spherical/Free)
    parent_from_joint: list[pin.SE3] = field(default_factory=list)
    quats: list[np.ndarray] = field(default_factory=list)  # rotation of parent_from_joint, x y z w
    masses: list[float] = field(default_factory=list)
    coms: list[np.ndarray] = field(default_factory=list)
    inertias: list[np.ndarray] = field(default_factory=list)  # 3x3 about the COM, link frame
    world_from_root: pin.SE3 = field(default_factory=pin.SE3.Identity)
    world_from_root_quat: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, 0.0, 1.0]))

    @property
    def num_links(self) -> int:
        return len(self.types)

    @property
    def num_dofs(self) -> int:
        return sum(JOINT_DOFS[t] for t in self.types)


def random_unit(rng: np.random.Generator) -> np.ndarray:
    while True:
        u = rng.normal(size=3)
        n = np.linalg.norm(u)
        if n > 1e-3:
            return u / n


def random_quat(rng: np.random.Generator) -> np.ndarray:
    """Uniform random unit quaternion, x y z w."""
    while True:
        q = rng.normal(size=4)
        n = np.linalg.norm(q)
        if n > 1e-3:
            return q / n


def quat_to_matrix(q_xyzw: np.ndarray) -> np.ndarray:
    return pin.Quaternion(q_xyzw[3], q_xyzw[0], q_xyzw[1], q_xyzw[2]).toRotationMatrix()


def random_placement(rng: np.random.Generator, max_offset: float) -> tuple[pin.SE3, np.ndarray]:
    q = random_quat(rng)
    return pin.SE3(quat_to_matrix(q), rng.uniform(-max_offset, max_offset, 3)), q


def random_inertia(rng: np.random.Generator, mass: float) -> np.ndarray:
    """Rotational inertia about the COM of a physical mass distribution: from positive
    second moments s of the mass along principal axes, the principal moments
    a = s_y + s_z, b = s_x + s_z, c = s_x + s_y satisfy the (strict) triangle inequality."""
    s = mass * rng.uniform(0.002, 0.03, 3)
    principal = np.array([s[1] + s[2], s[0] + s[2], s[0] + s[1]])
    R = quat_to_matrix(random_quat(rng))
    inertia = R @ np.diag(principal) @ R.T
    return 0.5 * (inertia + inertia.T)


def generate_tree(seed: int, root_type: str, dof_budget: int, p_hard: float, p_chain: float) -> Tree:
    rng = np.random.default_rng(seed)
    tree = Tree(root_type=root_type)
    tree.world_from_root, tree.world_from_root_quat = random_placement(rng, 0.5)

    def add_link(parent: int, joint_type: str) -> None:
        tree.parents.append(parent)
        tree.types.append(joint_type)
        tree.axes.append(random_unit(rng))
        X, q = random_placement(rng, 0.4 if parent >= 0 else 0.2)
        tree.parent_from_joint.append(X)
        tree.quats.append(q)
        mass = float(rng.uniform(0.3, 3.0))
        tree.masses.append(mass)
        tree.coms.append(rng.uniform(-0.15, 0.15, 3))
        tree.inertias.append(random_inertia(rng, mass))

    def pick_parent() -> int:
        n = tree.num_links
        if rng.random() < p_chain:
            return n - 1
        return int(rng.integers(0, n))

    add_link(-1, root_type)
    dofs = JOINT_DOFS[root_type]
    while dofs < dof_budget and tree.num_links < 45:
        remaining = dof_budget - dofs
        if rng.random() < p_hard:
            joint_type = "Hard"
        else:
            choices = ["Revolute", "Prismatic"] + (["Spherical"] if remaining >= 3 else [])
            weights = np.array([0.45, 0.25, 0.30][: len(choices)])
            joint_type = str(rng.choice(choices, p=weights / weights.sum()))
        add_link(pick_parent(), joint_type)
        dofs += JOINT_DOFS[joint_type]
    # a few welded links after the DOF budget is spent (leaves, or parents of nothing)
    for _ in range(int(rng.integers(1, 4))):
        add_link(pick_parent(), "Hard")
    assert tree.num_dofs == dof_budget
    return tree


# --------------------------------------------------------------------------------------
# the tree in SuperDex


def superdex_description(tree: Tree) -> tuple[list, list]:
    """The tree's ArticulatedLinkParams and ArticulatedJointParams."""
    links, joints = [], []
    for i in range(tree.num_links):
        I = tree.inertias[i]
        links.append(link(
            f"link{i}", parent=tree.parents[i] if i > 0 else -1, mass=float(tree.masses[i]),
            center_of_mass=tree.coms[i].tolist(),
            moment_of_inertia=[I[0, 0], I[0, 1], I[0, 2], I[1, 1], I[1, 2], I[2, 2]]))
        fields = {}
        if tree.types[i] in ("Revolute", "Prismatic"):
            fields["axis"] = tree.axes[i].tolist()
        joints.append(joint(
            f"joint{i}", tree.types[i],
            parent_link_from_joint=sdp.TransformRT(rotation=sdp.Quaternion(tree.quats[i].tolist()),
                                                   translation=tree.parent_from_joint[i].translation.tolist()),
            **fields))
    return links, joints


def world_from_root_desc(tree: Tree):
    return sdp.TransformRT(
        rotation=sdp.Quaternion(tree.world_from_root_quat.tolist()), translation=tree.world_from_root.translation.tolist()
    )


# --------------------------------------------------------------------------------------
# the tree in Pinocchio


@dataclass
class PinTree:
    """A Pinocchio model of a tree. Pinocchio's algorithms (crba in particular) need each
    joint's subtree to occupy consecutive indices, so joints are added in depth-first order,
    which differs from SuperDex's link order in general: `q_index[i]` and `v_index[i]` give
    link i's joint coordinates in Pinocchio's q and v, and `perm` maps SuperDex DOF k to
    Pinocchio's v index perm[k]."""

    model: pin.Model
    frame_ids: list[int]  # frame at each link's origin, in link order
    q_index: list[np.ndarray]
    v_index: list[np.ndarray]
    perm: np.ndarray

    @staticmethod
    def of(model: pin.Model, tree: Tree) -> "PinTree":
        q_index, v_index = [], []
        for i in range(tree.num_links):
            if tree.types[i] == "Hard":
                q_index.append(np.zeros(0, dtype=int))
                v_index.append(np.zeros(0, dtype=int))
                continue
            joint = model.joints[model.getJointId(f"joint{i}")]
            q_index.append(np.arange(joint.idx_q, joint.idx_q + joint.nq))
            v_index.append(np.arange(joint.idx_v, joint.idx_v + joint.nv))
        perm = np.concatenate(v_index)
        assert model.nv == tree.num_dofs and sorted(perm.tolist()) == list(range(model.nv))
        frame_ids = [model.getFrameId(f"link{i}") for i in range(tree.num_links)]
        return PinTree(model, frame_ids, q_index, v_index, perm)


def depth_first_order(tree: Tree) -> list[int]:
    children: list[list[int]] = [[] for _ in range(tree.num_links)]
    for i in range(1, tree.num_links):
        children[tree.parents[i]].append(i)
    order, stack = [], [0]
    while stack:
        i = stack.pop()
        order.append(i)
        stack.extend(reversed(children[i]))
    return order


def pin_inertia(tree: Tree, i: int) -> pin.Inertia:
    return pin.Inertia(tree.masses[i], np.asarray(tree.coms[i], dtype=float), np.asarray(tree.inertias[i]))


def pin_joint_model(tree: Tree, i: int):
    t = tree.types[i]
    if t == "Revolute":
        return pin.JointModelRevoluteUnaligned(tree.axes[i])
    if t == "Prismatic":
        return pin.JointModelPrismaticUnaligned(tree.axes[i])
    if t == "Spherical":
        return pin.JointModelSpherical()
    if t == "Free":
        return pin.JointModelFreeFlyer()
    raise ValueError(t)


def new_pin_model() -> pin.Model:
    model = pin.Model()
    model.gravity = pin.Motion(GRAVITY, np.zeros(3))
    return model


def build_pin_model(tree: Tree) -> PinTree:
    """Hard joints merged into their moving ancestor; a frame at every link origin."""
    model = new_pin_model()
    body_joint: dict[int, int] = {}  # Pinocchio joint that carries link i
    joint_from_link: dict[int, pin.SE3] = {}  # link i's frame in that joint's frame
    for i in depth_first_order(tree):
        p = tree.parents[i]
        if p < 0:  # a Hard root welds link 0 to the universe (joint 0)
            parent_joint, parent_from_joint = 0, tree.world_from_root * tree.parent_from_joint[0]
        else:
            parent_joint, parent_from_joint = body_joint[p], joint_from_link[p] * tree.parent_from_joint[i]
        if tree.types[i] == "Hard":
            jid, placement = parent_joint, parent_from_joint
        else:
            jid = model.addJoint(parent_joint, pin_joint_model(tree, i), parent_from_joint, f"joint{i}")
            placement = pin.SE3.Identity()
        model.appendBodyToJoint(jid, pin_inertia(tree, i), placement)
        body_joint[i] = jid
        joint_from_link[i] = placement
        model.addFrame(pin.Frame(f"link{i}", jid, placement, pin.FrameType.OP_FRAME))
    return PinTree.of(model, tree)


def build_pin_model_by_reduction(tree: Tree) -> PinTree:
    """The same tree with every Hard joint modelled as a revolute joint, then locked at zero
    by pinocchio.buildReducedModel (an independent construction of the reference)."""
    full = new_pin_model()
    jids: dict[int, int] = {}
    for i in depth_first_order(tree):
        p = tree.parents[i]
        parent_joint = 0 if p < 0 else jids[p]
        placement = tree.parent_from_joint[i]
        if p < 0:
            placement = tree.world_from_root * placement
        jmodel = pin.JointModelRZ() if tree.types[i] == "Hard" else pin_joint_model(tree, i)
        jid = full.addJoint(parent_joint, jmodel, placement, f"joint{i}")
        full.addJointFrame(jid, -1)
        full.appendBodyToJoint(jid, pin_inertia(tree, i), pin.SE3.Identity())
        full.addFrame(pin.Frame(f"link{i}", jid, pin.SE3.Identity(), pin.FrameType.OP_FRAME))
        jids[i] = jid
    locked = [jids[i] for i in range(tree.num_links) if tree.types[i] == "Hard"]
    reduced = pin.buildReducedModel(full, locked, pin.neutral(full))
    reduced.gravity = pin.Motion(GRAVITY, np.zeros(3))
    return PinTree.of(reduced, tree)


# --------------------------------------------------------------------------------------
# states


@dataclass
class State:
    pose: np.ndarray  # SuperDex pose: joint values, rotation vectors, free [p, rotation vector]
    q_parts: list[np.ndarray]  # Pinocchio configuration of each link's joint (quaternions x y z w)
    v: np.ndarray  # SuperDex DOF order
    tau: np.ndarray  # SuperDex DOF order


def random_rotation_vector(rng: np.random.Generator) -> np.ndarray:
    return random_unit(rng) * rng.uniform(0.05, 3.0)


def quat_coeffs_from_rotation_vector(r: np.ndarray) -> np.ndarray:
    return pin.Quaternion(pin.exp3(r)).coeffs()  # x y z w


def random_state(tree: Tree, rng: np.random.Generator) -> State:
    pose, q_parts = [], []
    for t in tree.types:
        if t == "Hard":
            pose_i, q_i = np.zeros(0), np.zeros(0)
        elif t == "Revolute":
            pose_i = q_i = np.array([rng.uniform(-np.pi, np.pi)])
        elif t == "Prismatic":
            pose_i = q_i = np.array([rng.uniform(-0.3, 0.3)])
        elif t == "Spherical":
            pose_i = random_rotation_vector(rng)
            q_i = quat_coeffs_from_rotation_vector(pose_i)
        elif t == "Free":
            p = rng.uniform(-1.0, 1.0, 3)
            r = random_rotation_vector(rng)
            pose_i = np.concatenate([p, r])
            q_i = np.concatenate([p, quat_coeffs_from_rotation_vector(r)])
        pose.append(pose_i)
        q_parts.append(np.asarray(q_i, dtype=float))
    n = tree.num_dofs
    return State(
        pose=np.concatenate(pose).astype(float),
        q_parts=q_parts,
        v=rng.normal(0.0, 1.0, n),
        tau=rng.normal(0.0, 5.0, n),
    )


# --------------------------------------------------------------------------------------
# reference quantities


@dataclass
class Reference:
    M: np.ndarray
    bias: np.ndarray
    accel: np.ndarray
    jacobians: list[np.ndarray]  # (6, nv) per link, LOCAL_WORLD_ALIGNED at the link origin


def pinocchio_reference(pt: PinTree, s: State) -> Reference:
    """Pinocchio's quantities at state s, permuted to SuperDex's DOF order."""
    model, perm = pt.model, pt.perm
    data = model.createData()
    q = pin.neutral(model)
    for idx, part in zip(pt.q_index, s.q_parts):
        q[idx] = part
    v, tau = np.zeros(model.nv), np.zeros(model.nv)
    v[perm], tau[perm] = s.v, s.tau
    M = np.array(pin.crba(model, data, q)).reshape(model.nv, model.nv)
    M = np.triu(M) + np.triu(M, 1).T  # crba fills the upper triangle
    bias = np.array(pin.nonLinearEffects(model, data, q, v)).reshape(model.nv)
    accel = np.array(pin.aba(model, data, q, v, tau)).reshape(model.nv)
    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    jacobians = [  # reshaped: eigenpy returns a 6 x 1 matrix as a vector
        np.array(pin.getFrameJacobian(model, data, fid, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)).reshape(6, model.nv)
        for fid in pt.frame_ids
    ]
    return Reference(
        M=M[np.ix_(perm, perm)], bias=bias[perm], accel=accel[perm], jacobians=[J[:, perm] for J in jacobians]
    )


def free_velocity_map(tree: Tree, s: State) -> tuple[np.ndarray, np.ndarray]:
    """T with v_pin = T v for SuperDex velocities v, and Tdot v (zero without a Free root)."""
    n = tree.num_dofs
    T, Tdot_v = np.eye(n), np.zeros(n)
    if tree.types[0] == "Free":
        R = pin.exp3(s.pose[3:6])  # rotation of the free joint (root DOFs come first)
        T[:3, :3] = R.T
        # d/dt(R^T) v_lin = -w_body x (R^T v_lin)
        Tdot_v[:3] = -np.cross(s.v[3:6], R.T @ s.v[:3])
    return T, Tdot_v


def assert_close(actual, reference, what: str) -> None:
    actual = np.asarray(actual, dtype=float)
    reference = np.asarray(reference, dtype=float)
    assert actual.shape == reference.shape, f"{what}: shape {actual.shape}, expected {reference.shape}"
    scale = max(1.0, float(np.abs(reference).max())) if reference.size else 1.0
    np.testing.assert_allclose(actual, reference, rtol=RTOL, atol=RTOL * scale, err_msg=what)


def describe(tree: Tree) -> str:
    counts = {t: tree.types.count(t) for t in JOINT_DOFS if t in tree.types}
    return f"{tree.num_links} links, {tree.num_dofs} DOFs, root {tree.root_type}, joints {counts}"


# --------------------------------------------------------------------------------------
# tests


@pytest.fixture(scope="module")
def engine():
    sdp.initialize()
    yield sdp
    sdp.shutdown()


CASE_IDS = [f"seed{c[0]}-{c[1]}-{c[2]}dof" for c in TREE_CASES]


@pytest.mark.parametrize("case", TREE_CASES, ids=CASE_IDS)
def test_reference_model_matches_reduced_model(case):
    """The hand-merged Pinocchio model equals Pinocchio's own reduction of locked joints."""
    seed = case[0]
    tree = generate_tree(*case)
    merged, reduced = build_pin_model(tree), build_pin_model_by_reduction(tree)
    rng = np.random.default_rng(10_000 + seed)
    for k in range(STATES_PER_TREE):
        s = random_state(tree, rng)
        a, b = pinocchio_reference(merged, s), pinocchio_reference(reduced, s)
        where = f"tree seed {seed} ({describe(tree)}), state {k}"
        # the reference is self-consistent: M(q) aba(q, v, tau) + c(q, v) = tau
        assert_close(a.M @ a.accel + a.bias, s.tau, f"Pinocchio M a + c = tau, {where}")
        assert_close(a.M, b.M, f"mass matrix, {where}")
        assert_close(a.bias, b.bias, f"bias forces, {where}")
        assert_close(a.accel, b.accel, f"forward dynamics, {where}")
        for i in range(tree.num_links):
            assert_close(a.jacobians[i], b.jacobians[i], f"Jacobian of link{i} ({tree.types[i]}), {where}")


@pytest.mark.parametrize("case", TREE_CASES, ids=CASE_IDS)
def test_dynamics_match_pinocchio(engine, case):
    seed = case[0]
    tree = generate_tree(*case)
    reference_model = build_pin_model(tree)
    n = tree.num_dofs

    scene = sdp.create_scene(f"pinocchio_tree_{seed}")
    scene.set_gravity(GRAVITY.tolist())
    links, joints = superdex_description(tree)
    art = articulation(scene, f"tree{seed}", links, joints, world_from_root=world_from_root_desc(tree))
    assert art.get_num_dofs() == n
    link_handles = list(art.get_nested_link_actors())
    assert len(link_handles) == tree.num_links
    link_actors = [scene.get_actor(h) for h in link_handles]

    rng = np.random.default_rng(20_000 + seed)
    for k in range(STATES_PER_TREE):
        s = random_state(tree, rng)
        art.set_articulated_pose_from_joints(s.pose)
        art.set_articulated_joint_velocities(s.v)
        T, Tdot_v = free_velocity_map(tree, s)
        # T is orthogonal, so tau_pin = T^-T tau = T tau keeps the power tau . v
        ref = pinocchio_reference(reference_model, State(pose=s.pose, q_parts=s.q_parts, v=T @ s.v, tau=T @ s.tau))
        where = f"tree seed {seed} ({describe(tree)}), state {k}"

        M = np.asarray(art.get_articulated_mass_matrix())
        assert_close(M, T.T @ ref.M @ T, f"mass matrix, {where}")
        assert_close(art.get_articulated_bias_forces(), T.T @ (ref.bias + ref.M @ Tdot_v), f"bias forces, {where}")
        assert_close(art.compute_articulated_forward_dynamics(s.tau), T.T @ (ref.accel - Tdot_v),
                     f"forward dynamics, {where}")
        for i, actor in enumerate(link_actors):
            J = np.asarray(actor.get_articulated_jacobian()).reshape(6, n)
            assert_close(J, ref.jacobians[i] @ T, f"Jacobian of link{i} ({tree.types[i]} joint), {where}")
