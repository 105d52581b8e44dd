"""The physics examples (superdex_physics/examples/), run as a user would and checked against
independent references: statics of a resting stack, the duck's weight from its mesh file, an RK4
integration of the cart-double-pendulum's equations of motion derived here, and what contact
filters promise.

Each example is imported from its file and its run() called in-process (it initializes and shuts
down the engine itself); the numbers compared are engine state read through the public API, the
references are computed here. test_runs_as_a_script runs each one as a subprocess, headless,
recording to a file through the debugger, and checks that it exits cleanly with nothing on stderr.
"""

import importlib.util
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

import superdex.physics as sdp

REPO = Path(__file__).resolve().parents[3]
EXAMPLES = REPO / "superdex_physics" / "examples"
G = 9.81


def load_example(name: str):
    spec = importlib.util.spec_from_file_location(f"example_{name}", EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def float_or_double(double: float, single: float) -> float:
    return double if sdp.uses_double_precision() else single


def yaw_of(q) -> float:
    """Rotation angle about z of a quaternion [x, y, z, w] that turns about z only."""
    x, y, z, w = q
    return 2.0 * math.atan2(z, w)


# --------------------------------------------------------------------------------------------
# falling_and_stacking.py


def test_falling_boxes_settle_into_a_standing_stack():
    """After 3 s the five cubes stand where a rigid stack would put them: cube i at height
    (2 i + 1) h (within 1 mm: contact compliance sinks the stack by well under that), at the x, y
    and yaw they were released with (within 1 mm and 0.01 rad: they fell straight), at rest
    (|v| < 1 mm/s, |w| < 0.01 rad/s); the balls rest on the ground at z = r. Statics: each cube
    carries the weight of the cubes above it from the one on top of it, and the ground carries the
    total weight, within 1 %, with no horizontal force."""
    ex = load_example("falling_and_stacking")
    result = ex.run(seconds=3.0, dt=0.005)
    h, n = ex.HALF, ex.NUM_BOXES
    for i, (start, end) in enumerate(zip(result["initial"], result["final"])):
        if i < n:
            assert end["position"][2] == pytest.approx((2 * i + 1) * h, abs=1e-3), end["name"]
            np.testing.assert_allclose(end["position"][:2], ex.SHIFTS[i], atol=1e-3, err_msg=end["name"])
            assert yaw_of(end["rotation"]) == pytest.approx(i * math.radians(15), abs=0.01), end["name"]
            assert abs(end["rotation"][0]) < 1e-3 and abs(end["rotation"][1]) < 1e-3, "no tilt"
        else:
            ball = ex.BALL_STARTS[i - n]
            np.testing.assert_allclose(end["position"], [ball[0], ball[1], ex.BALL_RADIUS], atol=1e-3, err_msg=end["name"])
        assert np.linalg.norm(end["linear_velocity"]) < 1e-3, end["name"]
        assert np.linalg.norm(end["angular_velocity"]) < 1e-2, end["name"]
    # they did fall: every body started higher than where it rests
    assert all(s["position"][2] > e["position"][2] + 0.005 for s, e in zip(result["initial"], result["final"]))

    box_weight = ex.BOX_MASS * G
    for i, force in enumerate(result["force_from_box_above"]):
        above = (n - 1 - i) * box_weight
        np.testing.assert_allclose(force, [0, 0, -above], atol=0.01 * above)
    total_weight = (n * ex.BOX_MASS + len(ex.BALL_STARTS) * ex.BALL_MASS) * G
    np.testing.assert_allclose(result["ground_force"], [0, 0, -total_weight], atol=0.01 * total_weight)


# --------------------------------------------------------------------------------------------
# soft_duck_drop.py


def duck_weight_from_files() -> float:
    """m g with m = density x volume of the tetrahedra, read from the prefab and the mesh file."""
    prefab_path = REPO / "assets" / "prefabs" / "duck_lamp" / "duck_lamp_recumbent_full.mochi_prefab"
    (entry,) = json.loads(prefab_path.read_text())["actors"]["soft"]
    with h5py.File(prefab_path.parent / entry["shape"].removeprefix("./"), "r") as f:
        nodes = f["mesh/coordinates"][()]
        tets = f["mesh/connectivity"][()].astype(np.int64)
    a, b, c, d = (nodes[tets[:, k]] for k in range(4))
    volume = np.abs(np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a)).sum() / 6.0
    return entry["material"]["density"] * volume * G


def test_soft_duck_comes_to_rest_on_the_ground():
    """The duck, released 3 cm up, has landed and come to rest by 0.32 s: all numbers finite, every
    node slower than 5 mm/s, its lowest node on the ground within the contact's compliance (1 mm;
    it was 30 mm up), its shape kept (it sank by no more than 3 mm at the top and its footprint
    did not spread by more than 3 mm), and the ground's contact force equals its weight, from the
    mesh volume and the material density, within 2 % (and the duck's own contact force the
    opposite)."""
    ex = load_example("soft_duck_drop")
    result = ex.run(seconds=0.32, dt=0.004, height=0.03)
    released, final = result["released_nodes"], result["final_nodes"]
    assert np.isfinite(final).all() and np.isfinite(result["final_node_velocities"]).all()
    assert released[:, 2].min() == pytest.approx(0.03, abs=1e-6)
    assert np.linalg.norm(result["final_node_velocities"], axis=1).max() < 5e-3
    assert abs(final[:, 2].min()) < 1e-3
    rigid_drop = released - [0, 0, 0.03]
    assert abs(final[:, 2].max() - rigid_drop[:, 2].max()) < 3e-3
    spread = np.abs(final[:, :2]).max(axis=0) - np.abs(rigid_drop[:, :2]).max(axis=0)
    assert np.abs(spread).max() < 3e-3
    weight = duck_weight_from_files()
    assert result["mass"] * G == pytest.approx(weight, rel=1e-3), "the engine's mass is the mesh's"
    np.testing.assert_allclose(result["ground_force"], [0, 0, -weight], atol=0.02 * weight)
    np.testing.assert_allclose(result["duck_contact_force"], -result["ground_force"], rtol=1e-4, atol=1e-4)


# --------------------------------------------------------------------------------------------
# double_pendulum_on_rail.py


class CartDoublePendulum:
    """The cart-double-pendulum's equations of motion, derived here independently of the engine.

    Coordinates q = (x, t1, t2): cart position along X, shoulder angle, elbow angle (relative), both
    about +Y; at zero angle the rods hang along -Z, and a rotation t about +Y takes -Z to
    (-sin t, 0, -cos t). Rod i is uniform, mass m_i, length L_i, centre a_i = L_i / 2 from its
    joint, inertia I_i about its centre (about Y). In the X-Z plane, with p = t1 + t2:

        c1 = (x - a1 sin t1,                 -a1 cos t1)
        c2 = (x - L1 sin t1 - a2 sin p,      -L1 cos t1 - a2 cos p)

    so the centre velocities are J_i qdot with
        J1 = [[1, -a1 cos t1, 0], [0, a1 sin t1, 0]]
        J2 = [[1, -L1 cos t1 - a2 cos p, -a2 cos p], [0, L1 sin t1 + a2 sin p, a2 sin p]]
    and the rods turn at w1 = t1dot, w2 = t1dot + t2dot. Kinetic energy
    T = 1/2 qdot^T M qdot with M = mc e0 e0^T + sum_i (m_i J_i^T J_i + I_i W_i^T W_i), W1 = [0, 1, 0],
    W2 = [0, 1, 1]. Lagrange's equations (equivalently Kane's: project each body's Newton
    equation on its J_i) give M qddot = sum_i J_i^T (m_i g_vec - m_i Jdot_i qdot), with the
    velocity-product accelerations Jdot_i qdot:
        Jdot1 qdot = (a1 sin t1 w1^2, a1 cos t1 w1^2)
        Jdot2 qdot = (L1 sin t1 w1^2 + a2 sin p w2^2, L1 cos t1 w1^2 + a2 cos p w2^2)
    Energy E = T + g (m1 c1_z + m2 c2_z); x is cyclic, so p_x = (M qdot)[0] is conserved.
    """

    def __init__(self, cart_mass, rods, rod_inertia):
        (_, self.m1, self.L1), (_, self.m2, self.L2) = rods
        self.mc = cart_mass
        self.a1, self.a2 = self.L1 / 2, self.L2 / 2
        # inertia about the rod's centre, about Y (the joint axis), from the example's tensor
        self.I1 = rod_inertia(self.m1, self.L1)[3]
        self.I2 = rod_inertia(self.m2, self.L2)[3]

    def terms(self, q, v):
        _, t1, t2 = q
        s1, c1, sp, cp = math.sin(t1), math.cos(t1), math.sin(t1 + t2), math.cos(t1 + t2)
        J1 = np.array([[1, -self.a1 * c1, 0], [0, self.a1 * s1, 0]])
        J2 = np.array([[1, -self.L1 * c1 - self.a2 * cp, -self.a2 * cp], [0, self.L1 * s1 + self.a2 * sp, self.a2 * sp]])
        W1, W2 = np.array([0.0, 1, 0]), np.array([0.0, 1, 1])
        M = np.zeros((3, 3))
        M[0, 0] = self.mc
        M += self.m1 * J1.T @ J1 + self.m2 * J2.T @ J2 + self.I1 * np.outer(W1, W1) + self.I2 * np.outer(W2, W2)
        w1, w2 = v[1], v[1] + v[2]
        b1 = np.array([self.a1 * s1 * w1**2, self.a1 * c1 * w1**2])
        b2 = np.array([self.L1 * s1 * w1**2 + self.a2 * sp * w2**2, self.L1 * c1 * w1**2 + self.a2 * cp * w2**2])
        gravity = np.array([0.0, -G])
        force = J1.T @ (self.m1 * gravity - self.m1 * b1) + J2.T @ (self.m2 * gravity - self.m2 * b2)
        z1, z2 = -self.a1 * c1, -self.L1 * c1 - self.a2 * cp
        energy = 0.5 * v @ M @ v + G * (self.m1 * z1 + self.m2 * z2)
        return M, force, energy

    def energy(self, q, v):
        return self.terms(q, v)[2]

    def momentum_x(self, q, v):
        return float((self.terms(q, v)[0] @ v)[0])

    def rk4(self, q0, seconds, dt, substeps=10):
        """Positions after every dt (RK4 with dt / substeps)."""
        def f(y):
            M, force, _ = self.terms(y[:3], y[3:])
            return np.concatenate([y[3:], np.linalg.solve(M, force)])

        y, h, out = np.concatenate([q0, np.zeros(3)]), dt / substeps, []
        for _ in range(int(round(seconds / dt))):
            for _ in range(substeps):
                k1 = f(y)
                k2 = f(y + h / 2 * k1)
                k3 = f(y + h / 2 * k2)
                k4 = f(y + h * k3)
                y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            out.append(y[:3].copy())
        return np.array(out)


@pytest.fixture(scope="module")
def pendulum():
    ex = load_example("double_pendulum_on_rail")
    model = CartDoublePendulum(ex.CART_MASS, ex.RODS, ex.rod_inertia)
    runs = {dt: ex.run(seconds=1.0, dt=dt) for dt in (1e-3, 5e-4)}
    reference = model.rk4(np.array(ex.INITIAL_POSE, dtype=float), 1.0, 5e-4)  # every 0.5 ms
    return ex, model, runs, reference


def test_cart_pendulum_follows_the_equations_of_motion(pendulum):
    """Over the first second (the pendulum swings through the bottom twice; the cart moves 0.28 m)
    the engine's joint trajectory at dt = 1 ms stays within 0.02 rad (m for the cart) of an RK4
    solution of the equations derived above, and halving dt halves the error (first order: the
    ratio is below 0.6), so the engine converges to that solution."""
    ex, model, runs, reference = pendulum
    errors = {}
    for dt, result in runs.items():
        stride = int(round(dt / 5e-4))
        ref = reference[stride - 1::stride]
        assert len(ref) == len(result["q"])
        errors[dt] = np.abs(result["q"] - ref).max()
    assert np.ptp(runs[1e-3]["q"][:, 0]) > 0.2, "the cart moves"
    assert np.ptp(runs[1e-3]["q"][:, 1]) > 1.5, "the pendulum swings"
    assert errors[1e-3] < 0.02, errors
    assert errors[5e-4] < 0.6 * errors[1e-3], errors


def test_cart_pendulum_conserves_energy_and_horizontal_momentum(pendulum):
    """The mass matrix the engine reports equals the derived one (1e-5 relative); and along the
    run, with E and p_x computed here from the engine's joint state: |E - E0| stays below 1 % of
    the potential-energy swing of the rods, g (m1 a1 + m2 (L1 + a2)), and |p_x| below 3 % of the
    largest momentum the cart alone reaches, mc max|xdot|, both shrinking by half or more with dt
    (they are the integrator's first-order error, not a drift that stays). The example's own
    energy and momentum, computed from the engine's mass matrix and link poses, agree with these."""
    ex, model, runs, _ = pendulum
    scale_e = G * (model.m1 * model.a1 + model.m2 * (model.L1 + model.a2))
    worst = {}
    for dt, result in runs.items():
        e = np.array([model.energy(q, v) for q, v in zip(result["q"], result["v"])])
        p = np.array([model.momentum_x(q, v) for q, v in zip(result["q"], result["v"])])
        e0 = model.energy(np.array(ex.INITIAL_POSE, dtype=float), np.zeros(3))
        scale_p = model.mc * np.abs(result["v"][:, 0]).max()
        worst[dt] = (np.abs(e - e0).max() / scale_e, np.abs(p).max() / scale_p)
        assert worst[dt][0] < 0.01, worst
        assert worst[dt][1] < 0.03, worst
        # the example's own energy and momentum (from the engine's mass matrix and link poses)
        # are these, up to the constant potential energy of the rail's height
        assert np.ptp(result["energy"] - e) < 1e-3 * scale_e
        np.testing.assert_allclose(result["momentum"], p, atol=1e-3 * scale_p)
    assert worst[5e-4][0] < 0.6 * worst[1e-3][0] and worst[5e-4][1] < 0.6 * worst[1e-3][1], worst

    sdp.initialize(num_worker_threads=0)
    try:
        scene = sdp.create_scene("mass matrix")
        actor = ex.create_cart_pendulum(scene)
        for q in ([0.3, 1.2, -0.6], [-0.2, -2.0, 2.5], [0.0, 0.4, 3.0]):
            actor.set_articulated_pose_from_joints(q)
            M = np.array(actor.get_articulated_mass_matrix(), dtype=np.float64).reshape(3, 3)
            expected = model.terms(np.array(q), np.zeros(3))[0]
            np.testing.assert_allclose(M, expected, rtol=1e-5, atol=1e-5 * np.abs(expected).max())
    finally:
        sdp.shutdown()


# --------------------------------------------------------------------------------------------
# contact_filtering.py


def test_filtered_pairs_never_touch_and_unfiltered_pairs_do():
    """After every step, the solver's contact records (CONTACT_POINTS) hold no contact between a
    filtered pair (ball-pedestal by actor pair, layer-1 balls and the layer-2 shelf by layers) and
    no force between them; the filtered balls fall through and rest on the ground (z = r within
    1 mm) carrying their weight from it. The unfiltered twins touch what they were dropped on: they
    rest on top of it (pedestal top + r, shelf top + r, within 1 mm), carried by it (its contact
    force on them is their weight within 1 %), and they have contact records with it."""
    ex = load_example("contact_filtering")
    filtered = [(ball, target) for ball, target, f in ex.DROPS if f]
    unfiltered = [(ball, target) for ball, target, f in ex.DROPS if not f]
    seen = {pair: 0 for pair in filtered + unfiltered}  # steps with contact records between the pair
    final = {}
    steps = []

    def on_step(scene, actors):
        steps.append(scene.get_total_simulation_time())
        if len(steps) == 1:  # the balls are still high up; the records are there from the next step on
            for actor in actors.values():
                actor.register_query(sdp.QueryType.CONTACT_POINTS)
            return
        for ball, target in filtered + unfiltered:
            other = actors[target].get_handle()
            records = [c for c in actors[ball].get_contact_points_world() if other in (c.actor_a, c.actor_b)]
            seen[(ball, target)] += len(records) > 0
            if (ball, target) in filtered:
                assert np.linalg.norm(actors[ball].get_contact_force_from_actor_world(actors[target])) == 0.0
        for ball, target in filtered + unfiltered:
            final[ball] = (np.array(actors[ball].get_contact_force_from_actor_world(actors[target]), dtype=np.float64),
                           np.array(actors[ball].get_contact_force_from_actor_world(actors["ground"]), dtype=np.float64))

    result = ex.run(seconds=1.5, dt=0.005, on_step=on_step)
    weight = ex.BALL_MASS * G
    for ball, target in filtered:
        assert seen[(ball, target)] == 0, f"{ball} touched {target}"
        assert result["positions"][ball][2] == pytest.approx(ex.RADIUS, abs=1e-3), f"{ball} fell to the ground"
        np.testing.assert_allclose(final[ball][1], [0, 0, weight], atol=0.01 * weight)
    for ball, target in unfiltered:
        assert seen[(ball, target)] > 50, f"{ball} should rest on {target}"
        assert result["positions"][ball][2] == pytest.approx(ex.REST_HEIGHT[target], abs=1e-3), f"{ball} on {target}"
        np.testing.assert_allclose(final[ball][0], [0, 0, weight], atol=0.01 * weight)
        np.testing.assert_allclose(final[ball][1], 0.0, atol=1e-9)
    # the ghost ball lies inside its pedestal, which still rests on the ground
    np.testing.assert_allclose(result["positions"]["ghost_pedestal"], [0, -0.3, ex.PEDESTAL_HALF], atol=1e-3)
    assert np.linalg.norm(result["positions"]["ghost_ball"] - result["positions"]["ghost_pedestal"]) < ex.PEDESTAL_HALF


# --------------------------------------------------------------------------------------------
# inverse_kinematics.py


def test_inverse_kinematics_reaches_every_target():
    """Each of the example's targets, read back from the end effector's pose after its solve:
    positions of the tip within 1e-4 m, rotations within 1e-3 rad, the base still pinned."""
    from contact_helpers import rotation_angle, rotation_matrix

    ex = load_example("inverse_kinematics")
    seen = []

    def on_solve(i, scene, base, tip):
        X = scene.get_actor(tip).get_root_transform()
        B = scene.get_actor(base).get_root_transform()
        base_pin = np.asarray(B.translation, dtype=float) + rotation_matrix(np.asarray(B.rotation, dtype=float)) @ ex.PIN_LOCAL
        seen.append((np.asarray(X.translation, dtype=float), np.asarray(X.rotation, dtype=float), base_pin))

    results = ex.run(on_solve=on_solve)
    assert len(results) == len(seen) == len(ex.TARGETS)
    for (kind, goal), (p, q, base_pin), r in zip(ex.TARGETS, seen, results):
        assert r["reached"] and r["converged"], (kind, goal, r)
        if kind == "position":
            tip = p + rotation_matrix(q) @ np.array(ex.TIP_LOCAL)
            np.testing.assert_allclose(tip, goal, atol=1e-4)
        else:
            g = np.array(goal)
            axis, angle = g / np.linalg.norm(g), np.linalg.norm(g)
            want = np.array([*(math.sin(angle / 2) * axis), math.cos(angle / 2)])
            assert rotation_angle(q, want) < 1e-3, (goal, rotation_angle(q, want))
        np.testing.assert_allclose(base_pin, 0, atol=1e-4)


def test_inverse_kinematics_as_a_script_records_each_solution(tmp_path):
    """python inverse_kinematics.py --targets 3 --debugger, recording: one frame per solution (the
    scene is never stepped: the clock stays at 0), each pose another."""
    recording = tmp_path / "ik.jsonl"
    env = dict(os.environ, SUPERDEX_DEBUGGER_RECORD=str(recording))
    proc = subprocess.run([sys.executable, str(EXAMPLES / "inverse_kinematics.py"), "--targets", "3", "--debugger"], env=env,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    assert "3 of 3 targets reached" in proc.stdout
    frames = [f for f in map(json.loads, recording.read_text().splitlines()) if f["type"] == "frame"]
    assert [f["t"] for f in frames] == [0.0, 0.0, 0.0]
    assert len({json.dumps(f["links"]) for f in frames}) == 3


# --------------------------------------------------------------------------------------------
# every example as a script


@pytest.mark.parametrize("name, args", [
    ("falling_and_stacking", ["--seconds", "0.5"]),
    ("soft_duck_drop", ["--seconds", "0.02"]),
    ("double_pendulum_on_rail", ["--seconds", "0.5"]),
    ("contact_filtering", ["--seconds", "0.5"]),
    ("double_pendulum", ["--seconds", "0.5"]),
    ("constraints_double_pendulum", ["--seconds", "0.5"]),
    ("articulations_pose_controller", ["--seconds", "0.5"]),
    ("skinned_double_pendulum", ["--seconds", "0.5"]),
    ("soft_skinned_double_pendulum", ["--seconds", "0.5"]),
    ("mc_kibben_muscle", ["--hold", "0.25"]),
    ("rod_spring", ["--seconds", "0.25"]),
])
def test_runs_as_a_script(name, args, tmp_path):
    """python <example> --debugger exits 0 with nothing on stderr and prints its summary; with
    SUPERDEX_DEBUGGER_RECORD the debugger records the run (header, frames up to the end)."""
    recording = tmp_path / "run.jsonl"
    env = dict(os.environ, SUPERDEX_DEBUGGER_RECORD=str(recording), SUPERDEX_DEBUGGER_FRAME_INTERVAL="0")
    proc = subprocess.run([sys.executable, str(EXAMPLES / f"{name}.py"), *args, "--debugger"], env=env,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    assert len(proc.stdout.splitlines()) >= 3
    lines = [json.loads(line) for line in recording.read_text().splitlines()]
    assert lines[0]["type"] == "header"
    frames = [line for line in lines if line["type"] == "frame"]
    # the run's simulated length: --seconds, or four pressures held --hold each
    length = float(args[1]) * (4 if args[0] == "--hold" else 1)
    assert frames and frames[-1]["t"] == pytest.approx(length, abs=1e-4)
    if name == "constraints_double_pendulum":
        # the frames carry the constraints' points: the pivot's target on the anchor's circle
        # (5 cm around the anchor), each constraint's two points within a millimetre
        first = frames[0]["constraints"]
        assert [c["type"] for c in first] == ["RIGID_PIVOT_POSITION", "RIGID_SPHERICAL_JOINT"]
        assert np.linalg.norm(np.subtract(first[0]["b"], [0, 0, 1])) < 0.051
        assert all(np.linalg.norm(np.subtract(c["a"], c["b"])) < 1e-3 for c in first)
        assert frames[-1]["constraints"] == []  # the upper box and its pivot are gone by the end
    if name == "articulations_pose_controller":
        # the active pose-controller constraints are in the frames (those without gains are not
        # drawn): in the hybrid phase lower_arm's centre-of-mass and rotation targets, and the
        # rail's and the shoulder's joint targets
        types = [c["type"] for c in frames[-1]["constraints"]]
        assert types == ["RIGID_PIVOT_TO_RIGID_TARGET", "RIGID_PIVOT_ROTATION"] + ["ARTICULATED_SINGLE_DOF_TARGET"] * 2
    if name == "skinned_double_pendulum":
        # the skin is drawn as a deforming surface of its own, its nodes in every frame
        skin = [line for line in lines if line["type"] == "actor" and line["name"] == "skinned_pendulum/skin"]
        assert len(skin) == 1 and len(skin[0]["surfaceTriangles"]) == 640
        moved = [np.asarray(f["soft"][str(skin[0]["handle"])]).reshape(-1, 3) for f in (frames[0], frames[-1])]
        assert moved[0].shape == (328, 3) and np.abs(moved[1] - moved[0]).max() > 0.05


def test_constraints_double_pendulum_swings_as_the_jointed_one():
    """The example's two boxes on stiff pivot and ball-joint constraints (anchor held still) follow
    the same boxes as an articulation with exact revolute joints, released horizontal in one
    plane: the lower box's centre within 1 cm of the articulation's over 0.6 s, a swing across of
    75 cm (the constraints give by force / stiffness, under 1 mm, and the stiff springs' fast
    modes take a little energy out under the implicit step)."""
    example = load_example("constraints_double_pendulum")
    dt, seconds = 0.002, 0.6
    result = example.run(seconds, dt, moving_anchor=False, timeline=False, print_every=seconds)
    L, w = example.LENGTH, example.WIDTH
    mass = example.DENSITY * L * w * w
    sdp.initialize(num_worker_threads=0)
    scene = sdp.create_scene("reference")
    scene.set_gravity([0, 0, -G])
    inertia = [mass * 2 * w * w / 12, 0, 0, mass * (L * L + w * w) / 12, 0, mass * (L * L + w * w) / 12]
    links = [sdp.ArticulatedLinkParams(name="upper", mass=mass, center_of_mass=[L / 2, 0, 0], moment_of_inertia=inertia),
             sdp.ArticulatedLinkParams(name="lower", parent_link=0, mass=mass, center_of_mass=[L / 2, 0, 0], moment_of_inertia=inertia)]
    joints = [sdp.ArticulatedJointParams(name="pivot", type=sdp.ArticulatedJointType.REVOLUTE, axis=[0, 1, 0],
                                         parent_link_from_joint=sdp.TransformRT(translation=list(example.ANCHOR))),
              sdp.ArticulatedJointParams(name="joint", type=sdp.ArticulatedJointType.REVOLUTE, axis=[0, 1, 0],
                                         parent_link_from_joint=sdp.TransformRT(translation=[L, 0, 0]))]
    pendulum = scene.create_articulated_actor(name="pendulum", links=links, joints=joints)
    from contact_helpers import rotation_matrix

    reference = []
    for _ in range(len(result["lower_positions"])):
        scene.step(dt)
        # the lower link's frame is at its joint: the box's centre is L/2 further along the link
        X = pendulum.get_articulated_link_transforms()[1]
        centre = np.asarray(X.translation, dtype=np.float64) + rotation_matrix(np.asarray(X.rotation, dtype=np.float64)) @ [L / 2, 0, 0]
        reference.append(centre)
    sdp.shutdown()
    ours = result["lower_positions"]
    assert float(np.min(ours[:, 2])) < example.ANCHOR[2] - 0.2  # it swung down
    assert float(np.max(np.linalg.norm(ours - np.array(reference), axis=1))) < 0.01


# --------------------------------------------------------------------------------------------
# articulations_pose_controller.py


def arm_model(ex) -> CartDoublePendulum:
    """The example's cart and arms as the cart-double-pendulum above (the arms are uniform boxes of
    square section w, centred half their length below their joints; about Y, m (w^2 + L^2) / 12)."""
    return CartDoublePendulum(ex.CART_MASS, ex.ARMS, lambda m, length: [0, 0, 0, m * (ex.ARM_WIDTH**2 + length**2) / 12])


def force_along(model: CartDoublePendulum, q: np.ndarray, dt: float) -> np.ndarray:
    """M(q) qddot - f(q, qdot) along a trajectory sampled every dt (rates by central differences):
    the generalized force that moves the model along it against gravity, the controller's part."""
    v = np.gradient(q, dt, axis=0)
    a = np.gradient(v, dt, axis=0)
    out = []
    for qi, vi, ai in zip(q, v, a):
        M, f, _ = model.terms(qi, vi)
        out.append(M @ ai - f)
    return np.array(out)


@pytest.fixture(scope="module")
def pose_controller():
    ex = load_example("articulations_pose_controller")
    result = ex.run(seconds=7.0, dt=0.005, print_every=7.0)
    return ex, result


def test_pose_controller_hybrid_phase_holds_the_arm_against_gravity(pose_controller):
    """At the end of the hybrid phase (2 s) the arm rests (its pose unchanged over the last 0.5 s
    within 1e-6), so the controller's generalized force balances gravity's: on the rail none
    (gravity is across it; 0.01 N, 0.1 % of the arms' weight) and on each hinge minus the torque
    about its axis of the weights m g of the arms beyond it, at their centres of mass, from the
    engine's link transforms (an arm's frame is at its centre; the shoulder is SHOULDER_OFFSET
    along the cart's Y, the elbow half the upper arm's length along the upper arm's -Z), within
    2 %."""
    from contact_helpers import rotation_matrix

    ex, result = pose_controller
    t = result["t"]
    k = int(np.argmin(np.abs(t - ex.HYBRID_END)))
    assert t[k] == pytest.approx(ex.HYBRID_END)
    settled = (t > ex.HYBRID_END - 0.5) & (t <= t[k])
    assert np.ptp(result["pose"][settled], axis=0).max() < 1e-6
    T, R = result["link_translations"][k], result["link_rotations"][k]
    (_, m1, l1), (_, m2, _) = ex.ARMS
    cart, upper, lower = 1, 2, 3
    shoulder = T[cart] + rotation_matrix(R[cart]) @ [0, ex.SHOULDER_OFFSET, 0]
    elbow = T[upper] + rotation_matrix(R[upper]) @ [0, 0, -l1 / 2]

    def torque_y(mass, centre, axis_point):
        # ((c - p) x (0, 0, -m g))_y = m g (c_x - p_x)
        return mass * G * (centre[0] - axis_point[0])

    gravity = np.array([0.0,
                        torque_y(m1, T[upper], shoulder) + torque_y(m2, T[lower], shoulder),
                        torque_y(m2, T[lower], elbow)])
    assert abs(gravity[1]) > 1.0 and abs(gravity[2]) > 0.3, "the rest pose is bent: gravity pulls on both hinges"
    force = result["controller_force"][k]
    assert abs(force[0]) < 0.01
    np.testing.assert_allclose(force[1:], -gravity[1:], rtol=0.02)


def test_pose_controller_joint_phase_follows_the_trajectory(pose_controller):
    """From 2 s to 5 s the joints track the target set every step (the cart 0.2 m out and back,
    the shoulder swinging 0.77 rad across). The damping follows the target's motion, so the error
    is the springs' quasi-static one, e* = -K^-1 tau*, with tau* = M qddot* - f(q*, qdot*) the
    force that moves the arm along the target (the equations of motion above, at the target),
    K the joint stiffnesses: the error never exceeds the largest |e*| by more than 25 % (no
    overshoot at the switch from the hybrid gains nor along the way), and once the switch's
    transient has decayed (0.25 s, over seven of the slowest joint's decay time 2 m / D = 2 x
    2 kg / 120 N s/m on the rail) it is e* within the damping's lag D/K max|de*/dt| plus 10 % of
    max|e*| (the error's own inertia, left out by the quasi-static model)."""
    ex, result = pose_controller
    t, dt = result["t"], result["dt"]
    phase = (t > ex.HYBRID_END + dt / 2) & (t < ex.JOINT_END + dt / 2)
    target = result["target_pose"][phase]
    # (the float build's clock is float32: the times are a few microseconds off by 5 s)
    np.testing.assert_allclose(target, [ex.joint_trajectory(s) for s in t[phase]], atol=float_or_double(1e-12, 1e-5))
    assert np.ptp(result["pose"][phase][:, 0]) > 0.19 and np.ptp(result["pose"][phase][:, 1]) > 0.7, "the arm moved"

    K = np.array([ex.RAIL_GAINS[0], ex.SHOULDER_GAINS[0], ex.ELBOW_GAINS[0]])
    D = np.array([ex.RAIL_GAINS[1], ex.SHOULDER_GAINS[1], ex.ELBOW_GAINS[1]])
    expected = -force_along(arm_model(ex), target, dt) / K
    error = result["pose"][phase] - target
    largest = np.abs(expected).max(axis=0)
    assert largest[1] > 0.01, "the shoulder carries the arm: a sag of over 10 mrad"
    assert (np.abs(error) <= 1.25 * largest).all(), (np.abs(error).max(axis=0), largest)
    steady = t[phase] > ex.HYBRID_END + 0.25
    lag = D / K * np.abs(np.gradient(expected, dt, axis=0)[steady]).max(axis=0)
    assert (np.abs(error - expected)[steady] <= lag + 0.1 * largest).all(), (np.abs(error - expected)[steady].max(axis=0), lag, largest)


def test_pose_controller_link_phase_carries_lower_arm_on_its_circle(pose_controller):
    """After 5 s only lower_arm is tracked, its target on a circle in the X-Z plane about where it
    rests (radius growing to 5 cm, rotation kept); the target pose the engine reads off the link
    targets puts lower_arm there (the arm's forward kinematics, written here). The arm is a 3-DOF
    planar chain, so the force F on lower_arm's centre of mass and the torque on it that move the
    arm along the target solve J^T (F, torque) = tau* (tau* as in the joint phase, at the target
    pose; J lower_arm's planar Jacobian), and the spring's quasi-static error is -F / K (at rest
    F is (m1 a1 / L1 + m2) g up, in any pose: 3.4 mm). The centre of mass stays within 1.25 times
    the largest such error of its target, and after the switch's transient (0.3 s) it is within
    25 % of that largest error of the predicted one (what is left: the error's own inertia and
    damping, which the quasi-static model leaves out)."""
    ex, result = pose_controller
    t, dt = result["t"], result["dt"]
    tight = float_or_double(1e-9, 2e-5)  # m, rad: what must agree up to rounding
    (_, m1, l1), (_, m2, l2) = ex.ARMS
    a2 = l2 / 2
    phase = t > ex.JOINT_END + dt / 2
    target_com = result["lower_arm_target_com"][phase]
    rest_com = result["lower_arm_target_com"][0]  # the hybrid phase's target is the rest pose
    offset = target_com - rest_com
    np.testing.assert_allclose(offset[:, 1], 0, atol=tight)
    radius = np.linalg.norm(offset, axis=1)
    assert radius.max() <= ex.CIRCLE_RADIUS + tight and radius[-1] == pytest.approx(ex.CIRCLE_RADIUS, abs=tight)
    q = result["target_pose"][phase]
    x, t1, p = q[:, 0], q[:, 1], q[:, 1] + q[:, 2]
    np.testing.assert_allclose(p, sum(ex.REST_POSE[1:]), atol=tight)
    np.testing.assert_allclose(target_com[:, 0], x - l1 * np.sin(t1) - a2 * np.sin(p), atol=tight)
    np.testing.assert_allclose(target_com[:, 2], ex.RAIL_HEIGHT - l1 * np.cos(t1) - a2 * np.cos(p), atol=tight)

    tau = force_along(arm_model(ex), q, dt)
    expected = []
    for ti, pi, Qi in zip(t1, p, tau):
        J = np.array([[1, -l1 * np.cos(ti) - a2 * np.cos(pi), -a2 * np.cos(pi)],   # centre of mass x
                      [0, l1 * np.sin(ti) + a2 * np.sin(pi), a2 * np.sin(pi)],      # centre of mass z
                      [0, 1, 1]])                                                  # rotation about Y
        wrench = np.linalg.solve(J.T, Qi)
        expected.append(-wrench[:2] / ex.LINK_POS_GAINS[0])
    expected = np.array(expected)
    # the target starts at rest (the radius grows from 0 with zero rate): there the error is the
    # static one, (m1 a1 / L1 + m2) g / K
    static = (m1 * (l1 / 2) / l1 + m2) * G / ex.LINK_POS_GAINS[0]
    assert np.linalg.norm(expected[0]) == pytest.approx(static, rel=0.02)
    error = (result["lower_arm_com"] - result["lower_arm_target_com"])[phase]
    np.testing.assert_allclose(error[:, 1], 0, atol=tight)
    error = error[:, [0, 2]]
    largest = np.linalg.norm(expected, axis=1).max()
    assert np.linalg.norm(error, axis=1).max() <= 1.25 * largest
    steady = t[phase] > ex.JOINT_END + 0.3
    assert np.linalg.norm(error - expected, axis=1)[steady].max() <= 0.25 * largest


# --------------------------------------------------------------------------------------------
# skinned_double_pendulum.py, soft_skinned_double_pendulum.py


@pytest.mark.parametrize("name", ["skinned_double_pendulum", "soft_skinned_double_pendulum"])
def test_the_skinned_pendulums_strike_the_ball_with_their_soft_or_skinned_part(name):
    """The arms' own colliders touch nothing, so the ball is struck by the skin (or the soft bar)
    alone: within 0.5 s a skin-ball (bar-ball) force acts and the ball is knocked more than 10 cm
    along the ground (it stays on it: its centre at y = r within 1 mm once the strike is over)."""
    example = load_example(name)
    result = example.run(seconds=1.0, dt=0.005, print_every=1.0)
    forces, positions = result["forces"], result["ball_positions"]
    first = int(np.flatnonzero(forces > 0)[0])
    assert first * result["dt"] < 0.5
    assert np.linalg.norm(positions[-1] - example.BALL_POSITION) > 0.1
    assert abs(positions[-1][1] - example.BALL_RADIUS) < 1e-3


# --------------------------------------------------------------------------------------------
# mc_kibben_muscle.py


def test_the_muscle_holds_the_forearm_where_the_torques_balance():
    """At each pressure the forearm settles where the muscle's torque T(d) r, T from Chou and
    Hannaford's model written here and d = -r q its length change, balances the forearm's weight
    m g (l / 2) cos q (the root found by bisection here): within 0.5 degree; higher pressures hold
    it higher."""
    example = load_example("mc_kibben_muscle")
    result = example.run(hold=2.0, dt=0.002)
    m, l, r = example.FOREARM_MASS, example.FOREARM_LENGTH, example.MOMENT_ARM
    p = example.MUSCLE

    def tension(pressure, d):
        b, n = p["thread_length"], p["number_of_wraps"]
        L = p["deflated_equilibrium_length"] + d
        t = max(0.0, pressure - p["minimum_pressure"]) * (3 * L * L - b * b) / (4 * math.pi * n * n) + p["deflated_stiffness"] * d
        return max(t, 0.0)

    for pressure, q in zip(result["pressures"], result["angles"]):
        # the net torque raising the forearm falls as it rises: one root in (-pi/2, pi/2)
        lo, hi = -math.pi / 2, math.pi / 2
        for _ in range(80):
            mid = (lo + hi) / 2
            if tension(pressure, -r * mid) * r - m * G * (l / 2) * math.cos(mid) > 0:
                lo = mid
            else:
                hi = mid
        assert math.degrees(abs(q - lo)) < 0.5, (pressure, math.degrees(q), math.degrees(lo))
    assert np.all(np.diff(result["angles"]) > 0.05)


# --------------------------------------------------------------------------------------------
# rod_spring.py


def test_the_rod_spring_stretches_by_its_load_over_the_close_coiled_spring_rate():
    """The block settles where the coil's load over G d^4 / (8 D^3 n) says (the classic
    close-coiled spring rate, from the wire's twisting alone): within 5 %, the remainder being the
    leads' bending, the coil's pitch and its curvature, which the formula leaves out; and it has
    settled (the last tenth of a second moves it by under 1 % of the drop)."""
    example = load_example("rod_spring")
    result = example.run(seconds=2.0, dt=0.005)
    assert result["drop"] == pytest.approx(result["expected"], rel=0.05)
    last = np.asarray(result["drops"][-20:])
    assert np.ptp(last) < 0.01 * result["expected"]
