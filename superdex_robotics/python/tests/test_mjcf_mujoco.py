"""The MJCF importer against MuJoCo on the model files that gymnasium, gymnasium-robotics,
dm-control and robosuite ship (every .xml of those packages that MuJoCo compiles): each loads,
its joint-space mass matrix and bias forces (Coriolis, centrifugal and gravity) at a random
configuration and velocity equal MuJoCo's on the same file to 1e-6 relative, and its bots step
in one scene at the model's time step for 1 s (at most MAX_STEPS steps: the fruit fly's 0.1 ms
would take 10,000), finite throughout.

Joints are matched by name (MuJoCo's unnamed joints are imported as "joint<id>"). A free joint's
position is relative to the bot's world_from_root, and its linear velocity is expressed in that
frame: MuJoCo's world-frame velocities are rotated into it.
"""

from __future__ import annotations

import importlib.util
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

try:
    import mujoco
except ImportError as exc:  # a declared dev dependency: missing means a broken environment
    raise ImportError("mujoco (a dev dependency in pyproject.toml) is required by this test; run `uv sync`") from exc

import superdex.physics as sdp
import superdex.robotics as sdr

# the comparison to 1e-6 of MuJoCo's double precision needs the double build; both builds step
COMPARE = sdp.uses_double_precision()

PACKAGES = ("gymnasium", "gymnasium_robotics", "dm_control", "robosuite")
TOLERANCE = 1e-6
MAX_STEPS = 500
FREE, BALL, SLIDE, HINGE = (int(t) for t in (mujoco.mjtJoint.mjJNT_FREE, mujoco.mjtJoint.mjJNT_BALL, mujoco.mjtJoint.mjJNT_SLIDE, mujoco.mjtJoint.mjJNT_HINGE))
LOADED: list[str] = []
MATCHED: list[str] = []
STEPPED: list[str] = []


def package_dir(name: str) -> Path:
    spec = importlib.util.find_spec(name)
    if spec is None or not spec.submodule_search_locations:
        raise ImportError(f"{name} (a dev dependency in pyproject.toml) is required by this test; run `uv sync`")
    return Path(next(iter(spec.submodule_search_locations)))


def compiling_models() -> list[tuple[str, Path]]:
    """Every .xml of the packages that MuJoCo compiles (the others are fragments or need assets
    the packages do not ship)."""
    out = []
    for pkg in PACKAGES:
        root = package_dir(pkg)
        for path in sorted(root.rglob("*.xml")):
            try:
                mujoco.MjModel.from_xml_path(str(path))
            except Exception:  # noqa: BLE001 - MuJoCo rejects it: not a model of its own
                continue
            out.append((f"{pkg}/{path.relative_to(root).as_posix()}", path))
    return out


MODELS = compiling_models()


def random_state(m, rng):
    """A configuration within the joint limits (random orientations for ball and free joints)
    and a random velocity."""
    q = m.qpos0.copy()
    for j in range(m.njnt):
        a = m.jnt_qposadr[j]
        if m.jnt_type[j] in (HINGE, SLIDE):
            lo, hi = m.jnt_range[j] if m.jnt_limited[j] else (-1.0, 1.0)
            q[a] = rng.uniform(max(lo, -2.0), min(hi, 2.0))
        elif m.jnt_type[j] == BALL:
            q[a : a + 4] = unit(rng.normal(size=4))
        else:
            q[a : a + 3] += rng.normal(size=3) * 0.1
            q[a + 3 : a + 7] = unit(rng.normal(size=4))
    return q, rng.normal(size=m.nv) * 0.5


def unit(x):
    return x / np.linalg.norm(x)


def rotation_vector(quat_wxyz):
    out = np.zeros(3)
    mujoco.mju_quat2Vel(out, np.asarray(quat_wxyz, float), 1.0)
    return out


def quat_mul(a, b):
    out = np.zeros(4)
    mujoco.mju_mulQuat(out, np.asarray(a, float), np.asarray(b, float))
    return out


def quat_conj(a):
    return np.array([a[0], -a[1], -a[2], -a[3]])


def quat_rotate(a, v):
    out = np.zeros(3)
    mujoco.mju_rotVecQuat(out, np.asarray(v, float), np.asarray(a, float))
    return out


def quat_matrix(a):
    out = np.zeros(9)
    mujoco.mju_quat2Mat(out, np.asarray(a, float))
    return out.reshape(3, 3)


def our_state(m, prefab, art, q):
    """The bot's pose for MuJoCo's qpos `q`, MuJoCo's DOF index of each of its DOFs, and T with
    v_mujoco = T v_ours on those DOFs."""
    x, y, z, w = prefab.world_from_root.rotation.tolist()
    root_q = np.array([w, x, y, z])
    root_p = np.array(prefab.world_from_root.translation.tolist())
    info = art.get_articulated_shape_info()
    pose, dofs, blocks = [], [], []
    for name, dof in zip(info.joint_names, info.dof_info):
        if dof.rot_size + dof.trans_size == 0:
            continue
        j = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, name)
        if j < 0:
            assert name.startswith("joint"), name
            j = int(name[len("joint") :])
        a, d, kind = m.jnt_qposadr[j], m.jnt_dofadr[j], m.jnt_type[j]
        if kind in (HINGE, SLIDE):
            pose.append([q[a]])
            dofs.append(d)
            blocks.append(np.eye(1))
        elif kind == BALL:
            pose.append(rotation_vector(q[a : a + 4]))
            dofs += range(d, d + 3)
            blocks.append(np.eye(3))
        else:  # free: relative to world_from_root, linear velocity in its frame
            inv = quat_conj(root_q)
            pose.append(np.concatenate([quat_rotate(inv, q[a : a + 3] - root_p), rotation_vector(quat_mul(inv, q[a + 3 : a + 7]))]))
            dofs += range(d, d + 6)
            blocks += [quat_matrix(root_q), np.eye(3)]
    if not dofs:
        return None, [], None
    T = np.zeros((len(dofs), len(dofs)))
    k = 0
    for b in blocks:
        T[k : k + len(b), k : k + len(b)] = b
        k += len(b)
    return np.concatenate(pose), dofs, T


class _SkipComparison(Exception):
    """The float build: no comparison with MuJoCo, only loading and stepping."""


@pytest.fixture
def engine():
    sdp.initialize(num_worker_threads=0)
    yield
    sdp.shutdown()


def build(model):
    """A Z-up scene with the model's gravity and its bots."""
    scene = sdp.create_scene("mjcf")
    scene.set_gravity(model.gravity)
    ctx = sdr.create_context()
    return scene, [sdr.create_bot(scene, p, ctx).get_articulated_actor() for p in model.bots]


@pytest.mark.parametrize("name,path", MODELS, ids=[n for n, _ in MODELS])
def test_model_matches_mujoco_and_steps(engine, name, path):
    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # what is not imported (actuators, tendons, ...) is named in warnings
        model = sdr.load_mjcf_file(path)
    LOADED.append(name)
    q, v = random_state(m, np.random.default_rng(3))
    d.qpos[:] = q
    d.qvel[:] = v
    mujoco.mj_forward(m, d)
    M_ref = np.zeros((m.nv, m.nv))
    mujoco.mj_fullM(m, d, M_ref)
    scene, arts = build(model)
    try:
        if not COMPARE:
            raise _SkipComparison
        covered = []
        for prefab, art in zip(model.bots, arts):
            pose, dofs, T = our_state(m, prefab, art, q)
            if not dofs:
                continue
            covered += dofs
            art.set_articulated_pose_from_joints(pose)
            art.set_articulated_joint_velocities(T.T @ v[dofs])
            M = T @ np.asarray(art.get_articulated_mass_matrix()) @ T.T
            bias = T @ np.asarray(art.get_articulated_bias_forces())
            M_mj, bias_mj = M_ref[np.ix_(dofs, dofs)], d.qfrc_bias[dofs]
            assert np.abs(M - M_mj).max() <= TOLERANCE * np.abs(M_mj).max(), f"{name}: mass matrix of bot {prefab.name}"
            assert np.abs(bias - bias_mj).max() <= TOLERANCE * max(np.abs(bias_mj).max(), 1e-9), f"{name}: bias forces of bot {prefab.name}"
        assert sorted(covered) == list(range(m.nv)), f"{name}: every MuJoCo DOF is one of the bots'"
        MATCHED.append(name)
    except _SkipComparison:
        pass
    finally:
        sdp.destroy_scene(scene)
    # from the model's start pose, at rest
    scene, arts = build(model)
    try:
        for _ in range(min(math.ceil(1.0 / model.timestep), MAX_STEPS)):
            scene.step(model.timestep)
        for art in arts:
            assert np.isfinite(np.asarray(art.get_articulated_joint_velocities())).all(), name
            assert all(np.isfinite(t.translation.tolist()).all() for t in art.get_articulated_link_transforms()), name
        STEPPED.append(name)
    finally:
        sdp.destroy_scene(scene)


def test_nearly_every_model_loads_matches_and_steps():
    """Runs after the models above (pytest keeps file order): at least 90 % of the compiling models
    loaded, matched MuJoCo and stepped (150 of 150 with MuJoCo 4.0 and the packages' current files)."""
    if not LOADED:
        pytest.skip("run with the models above")
    assert len(MODELS) >= 140, len(MODELS)
    assert len(STEPPED) >= 0.9 * len(MODELS), sorted(set(n for n, _ in MODELS) - set(STEPPED))
    if COMPARE:
        assert len(MATCHED) >= 0.9 * len(MODELS), sorted(set(n for n, _ in MODELS) - set(MATCHED))
