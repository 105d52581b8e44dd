"""Scene 1: the seed scene (2-DOF arm, ground, soft duck-lamp prop, 250 Hz), SuperDex only (the soft
duck has no counterpart in the peers).

Variants
- seed loop: the seed example's own Python classes and loop (superdex_robotics/examples/advanced/
  example_custom_components.py, imported, its main loop without the debugger).
- C++ pipeline: the seed's three components as their built-in C++ counterparts, run by the bot
  pipeline inside scene.step: CONTACT_FORCE for the sensor, VELOCITY_SERVO (same parameters) for
  the servos, and HYBRID_FORCE_VELOCITY with the seed's gains for its controller, following the
  seed's circle sampled at the control rate. The script's loop only calls scene.step.
- C++ pipeline, Python controller: the same, with the seed's controller law written in Python as
  a pipeline controller (one call per step: compute(t, dt) -> joint velocity commands).
- physics only: the same scene with no components at all (the arm falls onto the duck): the
  floor under both, what the simulation alone costs.
- seed loop, full-FEM duck: the seed loop with the duck's full nonlinear finite-element twin
  (duck_lamp_recumbent_full.mochi_prefab) instead of the seed's reduced duck, for comparison; no
  target applies to it.
"""

from __future__ import annotations

import importlib.util
import json
import warnings

import numpy as np

from benchmarks.harness import Timer
from benchmarks.models import node_positions_world
from benchmarks.scenes import arm

NUMBER = 1
TITLE = "Seed scene: 2-DOF arm, ground, soft duck (250 Hz)"
VARIANTS = ("seed loop", "C++ pipeline", "C++ pipeline, Python controller", "physics only", "seed loop, full-FEM duck")
FULL_DUCK_ASSET = "prefabs/duck_lamp/duck_lamp_recumbent_full.mochi_prefab"


def cases(opts):
    # full: one period of the seed's circle (the ball presses on the duck from t = 1.9 s on); the
    # physics-only floor needs less
    return [{"label": v, "sim": "superdex", "variant": v,
             "seconds": 0.04 if opts.quick else (1.0 if v == "physics only" else 3.0)} for v in VARIANTS]


def load_seed():
    spec = importlib.util.spec_from_file_location("seed_example", arm.SEED_EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def build(seed, ctx, prefab, duck_asset=None):
    physics, robotics = seed.physics, seed.robotics
    scene = physics.create_scene("Custom Components Example")
    scene.set_gravity([0, 0, -9.81])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # physics only: the declared component types are not registered
        bot = robotics.create_bot(scene, prefab, ctx)
    scene.create_rigid_actor(name="ground", shape=physics.create_plane_shape(normal=[0, 0, 1], distance=0), is_static=True)
    added = physics.prefab.add_to_scene(
        prefab_path=str(physics.paths.resolve_asset(duck_asset or seed.DUCK_LAMP_ASSET)), root_path=str(physics.paths.get_assets_root()),
        scene=scene, params=physics.prefab.PrefabParams(name="duck_lamp"))
    duck = added.actors[0]
    duck.register_query(physics.QueryType.NODE_POSITIONS)  # for the final check on its top
    return scene, bot, duck


def run_seed_loop(seed, steps, duck_asset=None):
    """The seed's main(), its loop run `steps` times instead of while a debugger is attached."""
    physics, robotics = seed.physics, seed.robotics
    physics.initialize(num_worker_threads=0)
    bot_prefab = robotics.load_bot_prefab_from_file(seed.get_default_bot_path())
    robotics_context = robotics.create_context()
    seed.register_component_types(robotics_context)
    scene, bot, duck = build(seed, robotics_context, bot_prefab, duck_asset)
    bot_actor = bot.get_articulated_actor()
    handle = robotics_context.create_controller("MY_VELOCITY_FORCE_CONTROLLER", None, bot_actor, "my_controller")
    controller = robotics.get_python_controller(robotics_context, handle)
    sensor = robotics.get_python_sensor(robotics_context, bot.find_sensors_by_name(seed.SENSOR_NAME)[0])
    actuators = [robotics.get_python_actuator(robotics_context, bot.find_actuators_by_name(name)[0]) for name in seed.ACTUATOR_NAMES]
    dof_indices = [actuator.dof_index for actuator in actuators]
    time_step = 1.0 / seed.CONTROL_RATE_HZ
    contact_force = np.zeros(3, dtype=seed.np_real)
    max_fz = 0.0
    with Timer() as timer:
        for _ in range(steps):
            t = scene.get_total_simulation_time()
            obsv = controller.get_current_observations()
            obsv["f_contact"] = contact_force
            q_dot_des = controller.compute_output(obsv, seed.compute_trajectory_target(t))
            efforts = np.array([actuator.compute_effort(actuator.get_current_observations(), w_goal, dt=time_step)
                                for actuator, w_goal in zip(actuators, q_dot_des)], dtype=seed.np_real)
            bot_actor.set_external_forces_on_dofs(dof_indices=dof_indices, force_values=efforts)
            scene.step(time_step)
            contact_force = sensor.compute_signal()
            max_fz = max(max_fz, float(contact_force[2]))
    return timer.wall, scene, bot_actor, duck, {"max_fz_N": max_fz}


class PipelineSeedController:
    """The seed's MyVelocityForceController law as a pipeline controller: compute(t, dt) returns
    the joint velocity commands the VELOCITY_SERVO actuators follow."""

    def __init__(self, actor):
        self.actor = actor
        self.law = arm.Controller()
        self.ctx = self.sensor = None
        self.max_fz = 0.0
        scene = actor.get_scene()
        self.ball = scene.get_actor(actor.get_nested_link_actors()[arm.BALL_LINK])
        self.xforms = None
        self.f_z = 0.0

    def reset(self):
        self.law.force_mode = False

    def compute(self, t, dt):
        import superdex.physics as sdp

        if self.xforms is None:
            self.xforms = sdp.DynamicArrayTransformRT(len(self.actor.get_nested_link_actors()))
        self.actor.get_articulated_link_transforms(self.xforms)
        x = np.array(self.xforms[arm.BALL_LINK].translation, dtype=np.float64)
        J = np.array(self.ball.get_articulated_jacobian(), dtype=np.float64).reshape(6, -1)[0:3]
        f_z = float(self.ctx.get_sensor_signal(self.sensor)[2]) if self.sensor is not None else 0.0
        self.max_fz = max(self.max_fz, f_z)
        return {"velocity": self.law.compute(x, J, f_z, t)}


def seed_controller_params(seed, steps):
    """HYBRID_FORCE_VELOCITY parameters for the seed's controller: its gains, and its circle
    sampled at the control rate over the run."""
    law = arm.Controller()
    times = [k / seed.CONTROL_RATE_HZ for k in range(steps + 1)]
    targets = [seed.compute_trajectory_target(t) for t in times]
    return json.dumps({
        "link": "ball", "axes": [0, 2], "kp": law.k_p, "kf": law.k_f, "force_target": law.f_z_target,
        "exit_margin": law.exit_margin, "force_axis": [0, 0, 1],
        "trajectory": {"times": times, "positions": [tg["x"].tolist() for tg in targets],
                       "velocities": [tg["x_dot"].tolist() for tg in targets]}})


def run_pipeline(seed, steps, with_components=True, python_controller=True):
    physics, robotics = seed.physics, seed.robotics
    physics.initialize(num_worker_threads=0)
    prefab = robotics.load_bot_prefab_from_file(seed.get_default_bot_path())
    if with_components:  # else the seed's types stay unregistered: create_bot skips them
        for declared in prefab.actuators:
            for d in declared:
                d.type = "VELOCITY_SERVO"  # takes the very params of MY_VELOCITY_SERVO_ACTUATOR
        for declared in prefab.sensors:
            for d in declared:
                d.type = "CONTACT_FORCE"
    ctx = robotics.create_context()
    robotics.register_python_controller(ctx, "SEED_PIPELINE_CONTROLLER", PipelineSeedController)
    scene, bot, duck = build(seed, ctx, prefab)
    controller = None
    if with_components and python_controller:
        handle = bot.create_controller("SEED_PIPELINE_CONTROLLER", "seed_controller")
        controller = robotics.get_python_controller(ctx, handle)
        controller.ctx = ctx
        controller.sensor = bot.find_sensors_by_name(seed.SENSOR_NAME)[0]
    elif with_components:
        bot.create_controller("HYBRID_FORCE_VELOCITY", "seed_controller", seed_controller_params(seed, steps))
    if with_components:
        assert bot.is_pipeline_active()
    dt = 1.0 / seed.CONTROL_RATE_HZ
    with Timer() as timer:
        for _ in range(steps):
            scene.step(dt)  # controller, servos, physics, sensor
    checks = {"max_fz_N": controller.max_fz} if controller else {}
    if controller:
        controller.ctx = None  # no reference cycle through the context
    return timer.wall, scene, bot.get_articulated_actor(), duck, checks


def run_case(case):
    seed = load_seed()
    steps = int(round(case["seconds"] * seed.CONTROL_RATE_HZ))
    if case["variant"].startswith("seed loop"):
        full = case["variant"] == "seed loop, full-FEM duck"
        wall, scene, bot_actor, duck, checks = run_seed_loop(seed, steps, FULL_DUCK_ASSET if full else None)
    else:
        wall, scene, bot_actor, duck, checks = run_pipeline(seed, steps, case["variant"] != "physics only",
                                                            case["variant"] == "C++ pipeline, Python controller")
    xf = seed.physics.DynamicArrayTransformRT(4)
    bot_actor.get_articulated_link_transforms(xf)
    ball = np.array(xf[arm.BALL_LINK].translation, dtype=np.float64)
    checks.update({"ball_x": float(ball[0]), "ball_z": float(ball[2]),
                   "duck_top_z": float(node_positions_world(duck)[:, 2].max())})
    seed.physics.shutdown()
    return {"wall": wall, "steps": steps, "sim_time": steps / seed.CONTROL_RATE_HZ, "checks": checks}
