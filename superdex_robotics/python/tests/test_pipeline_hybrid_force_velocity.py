"""HYBRID_FORCE_VELOCITY, the built-in hybrid force/velocity controller, on the seed's 2-DOF arm
with its servos as the built-in VELOCITY_SERVO, run by the bot pipeline only.

- In free space, towards a constant target, the resolved-rate law moves the ball along the
  straight line to it and arrives within 1 mm.
- Pressed onto a compliant block (contact stiffness 2 kN/m) by a target below its top, the force
  mode settles where its law says, kf (f - force_target) = 0: the contact force equals the
  target (0.5 N within 2 %). (On a rigid block at 250 Hz the seed's law, which leaves force mode
  when the force drops to zero, chatters in and out of contact, as the seed's Python law does.)
- On the seed scene (the reduced duck), following the seed's circle, it matches the seed's own
  Python controller, sensor and servos run by the seed's loop: the same ball path (0.5 mm) and
  contact force (0.02 N) at every step.
- Bad parameters are refused naming the parameter.
"""

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from pipeline_helpers import create_bot_from_json, link_pose, load_bot, step
from robotics_helpers import example_bot_json, scene  # noqa: F401

REPO = Path(__file__).resolve().parents[3]
SEED = REPO / "superdex_robotics" / "examples" / "advanced" / "example_custom_components.py"
BALL = 3
DT = 1 / 250


def builtin_bot_json() -> dict:
    """The example bot with the seed's servos and sensor as the built-in C++ types."""
    doc = example_bot_json()
    for link in doc["links"]:
        for a in link.get("actuators", []):
            a["type"] = "VELOCITY_SERVO"  # the same params as MY_VELOCITY_SERVO_ACTUATOR
        for s in link.get("sensors", []):
            s["type"] = "CONTACT_FORCE"
    return doc


def make_bot(scene, tmp_path):
    return create_bot_from_json(scene, tmp_path, builtin_bot_json())


def test_free_space_moves_along_the_straight_line_to_a_constant_target(scene, tmp_path):
    ctx, bot, arm = make_bot(scene, tmp_path)
    p0, _ = link_pose(arm, BALL)
    target = p0 + np.array([0.05, 0.0, -0.03])
    bot.create_controller("HYBRID_FORCE_VELOCITY", "hybrid", {"link": "ball", "axes": [0, 2], "kp": 5.0, "target_position": target.tolist()})
    path = []
    for _ in range(500):  # 2 s: 10 time constants of kp = 5/s
        scene.step(DT)
        path.append(link_pose(arm, BALL)[0])
    path = np.array(path)
    assert np.linalg.norm(path[-1] - target) < 1e-3, f"final error {np.linalg.norm(path[-1] - target)} m"
    # distance of every point from the line p0 -> target (the servos' lag bends it a little)
    u = (target - p0) / np.linalg.norm(target - p0)
    off_line = np.linalg.norm((path - p0) - np.outer((path - p0) @ u, u), axis=1)
    assert off_line.max() < 2e-3, f"left the straight line by {off_line.max()} m"


def test_force_mode_settles_at_the_force_target_on_a_compliant_block(scene, tmp_path):
    ctx, bot, arm = make_bot(scene, tmp_path)
    p0, _ = link_pose(arm, BALL)
    # a static compliant block whose top lies 5 mm under the ball, and a target 3 cm below the ball
    top = p0[2] - 0.02 - 0.005
    scene.create_rigid_actor(name="block", shape=sdp.create_box_shape(half_extents=[0.05, 0.05, 0.02]),
                             world_from_local=sdp.TransformRT(translation=[p0[0], p0[1], top - 0.02]), is_static=True,
                             contact=sdp.ContactParams(contact_stiffness=2000.0, dissipation_time_scale=0.02))
    target = p0 - np.array([0.0, 0.0, 0.03])
    bot.create_controller("HYBRID_FORCE_VELOCITY", "hybrid",
                          {"link": "ball", "axes": [0, 2], "kp": 5.0, "kf": 0.05, "force_target": 0.5, "target_position": target.tolist()})
    sensor = bot.find_sensors_by_name("force_sensor")[0]
    forces = []
    for _ in range(750):
        scene.step(DT)
        forces.append(ctx.get_sensor_signal(sensor)[2])
    forces = np.array(forces)
    assert forces.max() > 0.5, "the ball never pressed past the entry threshold"
    # the last second: steady at the target force
    np.testing.assert_allclose(forces[-250:], 0.5, rtol=0.02)


def load_seed():
    spec = importlib.util.spec_from_file_location("seed_for_hybrid_test", SEED)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def seed_scene(seed, ctx, prefab):
    scene = sdp.create_scene("seed")
    scene.set_gravity([0, 0, -9.81])
    bot = sdr.create_bot(scene, prefab, ctx)
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape(normal=[0, 0, 1], distance=0), is_static=True)
    sdp.prefab.add_to_scene(prefab_path=str(sdp.paths.resolve_asset(seed.DUCK_LAMP_ASSET)), root_path=str(sdp.paths.get_assets_root()),
                            scene=scene, params=sdp.prefab.PrefabParams(name="duck_lamp"))
    return scene, bot


def test_matches_the_seeds_own_components_on_the_seed_scene(scene, tmp_path):
    seed = load_seed()
    steps = 750  # one period of the circle: the ball presses on the duck from 1.9 s on
    # the seed's loop with its Python components (as in its main(), without the debugger)
    ctx = sdr.create_context()
    seed.register_component_types(ctx)
    seed_scene_, bot = seed_scene(seed, ctx, sdr.load_bot_prefab_from_file(seed.get_default_bot_path()))
    arm = bot.get_articulated_actor()
    controller = sdr.get_python_controller(ctx, ctx.create_controller("MY_VELOCITY_FORCE_CONTROLLER", None, arm, "c"))
    sensor = sdr.get_python_sensor(ctx, bot.find_sensors_by_name(seed.SENSOR_NAME)[0])
    actuators = [sdr.get_python_actuator(ctx, bot.find_actuators_by_name(n)[0]) for n in seed.ACTUATOR_NAMES]
    f = np.zeros(3, dtype=seed.np_real)
    seed_path, seed_fz = [], []
    for _ in range(steps):
        t = seed_scene_.get_total_simulation_time()
        obsv = controller.get_current_observations()
        obsv["f_contact"] = f
        q_dot_des = controller.compute_output(obsv, seed.compute_trajectory_target(t))
        efforts = np.array([a.compute_effort(a.get_current_observations(), w, dt=DT) for a, w in zip(actuators, q_dot_des)], dtype=seed.np_real)
        arm.set_external_forces_on_dofs(dof_indices=[a.dof_index for a in actuators], force_values=efforts)
        seed_scene_.step(DT)
        f = sensor.compute_signal()
        seed_path.append(link_pose(arm, BALL)[0])
        seed_fz.append(float(f[2]))

    # the built-in components, run by the pipeline, following the seed's circle sampled at 250 Hz
    ctx = sdr.create_context()
    scene2, bot = seed_scene(seed, ctx, load_bot(tmp_path, builtin_bot_json()))
    arm = bot.get_articulated_actor()
    times = [k * DT for k in range(steps + 1)]
    targets = [seed.compute_trajectory_target(t) for t in times]
    bot.create_controller("HYBRID_FORCE_VELOCITY", "hybrid", {
        "link": "ball", "axes": [0, 2], "kp": 5.0, "kf": 0.05, "force_target": 0.5, "exit_margin": 0.005,
        "trajectory": {"times": times, "positions": [g["x"].tolist() for g in targets], "velocities": [g["x_dot"].tolist() for g in targets]}})
    sensor = bot.find_sensors_by_name(seed.SENSOR_NAME)[0]
    path, fz = [], []
    for _ in range(steps):
        scene2.step(DT)
        path.append(link_pose(arm, BALL)[0])
        fz.append(float(ctx.get_sensor_signal(sensor)[2]))

    seed_fz, fz = np.array(seed_fz), np.array(fz)
    assert seed_fz.max() > 0.5 and fz.max() > 0.5, "the ball pressed on the duck past the entry threshold"
    gap = np.linalg.norm(np.array(path) - np.array(seed_path), axis=1)
    assert gap.max() < 5e-4, f"ball paths apart by {gap.max()} m at step {gap.argmax()}"
    assert np.abs(fz - seed_fz).max() < 0.02, f"contact forces apart by {np.abs(fz - seed_fz).max()} N"


@pytest.mark.parametrize("params, message", [
    ({"axes": [0, 3]}, r"params.axes: expected distinct world axis indices"),
    ({"axes": []}, r"params.axes: expected a non-empty list"),
    ({"force_axis": [0, 0, 0]}, r"params.force_axis: expected a non-zero vector"),
    ({"link": "no_such_link"}, r"params.link"),
    ({"trajectory": {"times": [0.0, 0.0], "positions": [[0, 0, 0], [0, 0, 0]]}}, r"params.trajectory.times: must be strictly ascending"),
    ({"trajectory": {"times": [0.0, 1.0], "positions": [[0, 0, 0]]}}, r"params.trajectory.positions: 1 entries for 2 times"),
    ({"trajectory": {"times": [0.0], "positions": [[0, 0]]}}, r"params.trajectory.positions\[0\]: expected \[x, y, z\]"),
    ({"trajectory": {"times": [0.0], "positions": [[0, 0, 0]], "speeds": []}}, r"params.trajectory.speeds: unknown key"),
    ({"kpp": 1.0}, r"unknown parameter 'kpp'"),
])
def test_bad_parameters_are_refused_naming_them(scene, tmp_path, params, message):
    ctx, bot, arm = make_bot(scene, tmp_path)
    with pytest.raises(sdp.Error, match=message):
        bot.create_controller("HYBRID_FORCE_VELOCITY", "hybrid", params)


def test_run_time_configuration_keeps_the_old_values_on_error(scene, tmp_path):
    ctx, bot, arm = make_bot(scene, tmp_path)
    p0, _ = link_pose(arm, BALL)
    hybrid = bot.create_controller("HYBRID_FORCE_VELOCITY", "hybrid", {"link": "ball", "axes": [0, 2]})
    with pytest.raises(sdp.Error, match=r"params.link: the link is chosen at creation"):
        ctx.configure_controller(hybrid, {"link": "link_1"})
    # a bad trajectory leaves the target untouched: the ball holds where it was created
    with pytest.raises(sdp.Error, match=r"params.trajectory.times"):
        ctx.configure_controller(hybrid, {"target_position": (p0 + 0.05).tolist(), "trajectory": {"times": []}})
    step(scene, DT, 250)
    assert np.linalg.norm(link_pose(arm, BALL)[0] - p0) < 1e-3
    # a trajectory given at run time is followed (held at its last sample after its end)
    goal = p0 + np.array([-0.04, 0.0, 0.02])
    t0 = scene.get_total_simulation_time()
    ctx.configure_controller(hybrid, {"trajectory": {"times": [t0, t0 + 0.5], "positions": [p0.tolist(), goal.tolist()]}})
    step(scene, DT, 500)
    assert np.linalg.norm(link_pose(arm, BALL)[0] - goal) < 1e-3
    assert math.isfinite(scene.get_total_simulation_time())
