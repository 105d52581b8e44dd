"""Threads: separate scenes built and stepped concurrently from several Python threads give the
same results, bitwise, as the same scenes stepped one after the other, with and without the
engine's worker threads. Each scene has a bot with Python components, a contact pile and a soft-free
rigid prop, so the step releases and retakes the GIL many times while the others run.

What is not thread-safe (documented on the calls): using one scene from two threads at once,
destroy_scene or shutdown while another thread steps, and initialize/shutdown themselves.
"""

import threading

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from robotics_helpers import EXAMPLE_BOT
from superdex.physics.paths import resolve_asset

THREADS = 4
STEPS = 300


class Sensor:
    def __init__(self, actor, params):
        self.actor = actor
        self.readings = []
        actor.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)

    def reset(self):
        pass

    def update(self, t, dt):
        self.readings.append(float(self.actor.get_contact_force_world()[2]))


class Servo:
    def __init__(self, actor, params):
        self.k = 0.05

    def reset(self):
        pass

    def compute_pipeline_effort(self, commands, dt):
        return self.k * (commands["velocity"] or 0.0)


class Controller:
    def __init__(self, actor):
        self.actor = actor

    def reset(self):
        pass

    def compute(self, t, dt):
        return {"velocity": [np.sin(3 * t), np.cos(2 * t)]}


def fingerprint(scene):
    """Every actor's pose and velocity, and the arm's joint state, as bytes (handles differ between
    runs: they come from one engine-wide counter)."""
    parts = []
    actors = []
    scene.for_each_actor(lambda actor: actors.append(actor) if not actor.is_nested_link_actor() else None)
    for actor in actors:
        t = actor.get_root_transform()
        parts += [np.array(t.translation), np.array(t.rotation)]
        if actor.get_type() == sdp.ActorType.ARTICULATED:
            parts += [actor.get_articulated_pose(), actor.get_articulated_joint_velocities()]
        else:
            parts += [actor.get_linear_velocity(), actor.get_angular_velocity()]
    return np.concatenate([np.asarray(p, dtype=np.float64).ravel() for p in parts]).tobytes()


def run_scene(index):
    """Builds scene `index` (its own shapes, bot and pile), steps it, returns its final state."""
    scene = sdp.create_scene(f"scene {index}")
    scene.set_gravity([0, 0, -9.81])
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    for k in range(3):
        scene.create_rigid_actor(name=f"box{k}", shape=sdp.create_box_shape([0.05, 0.05, 0.05]), mass=0.2 + 0.1 * index,
                                 world_from_local=sdp.TransformRT(translation=[0.4, 0.01 * k, 0.06 + 0.11 * k]))
    ctx = sdr.create_context()
    sdr.register_python_sensor(ctx, "MY_CONTACT_FORCE_SENSOR", Sensor)
    sdr.register_python_actuator(ctx, "MY_VELOCITY_SERVO_ACTUATOR", Servo)
    sdr.register_python_controller(ctx, "PY", Controller)
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(resolve_asset(EXAMPLE_BOT))), ctx)
    bot.create_controller("PY", "py")
    sensor = sdr.get_python_sensor(ctx, bot.find_sensors_by_name("force_sensor")[0])
    scene.register_post_step_callback("count", lambda info: None)
    for _ in range(STEPS):
        scene.step(0.005 + 0.001 * index)
    state = fingerprint(scene)
    readings = list(sensor.readings)
    sdr.destroy_bot(scene, bot)
    sdp.destroy_scene(scene)
    return state, readings


@pytest.mark.parametrize("worker_threads", [0, 2])
def test_scenes_stepped_from_several_python_threads_match_sequential(worker_threads):
    sdp.initialize(num_worker_threads=worker_threads)
    try:
        sequential = [run_scene(i) for i in range(THREADS)]
        results = [None] * THREADS
        errors = []
        start = threading.Barrier(THREADS)

        def work(i):
            try:
                start.wait()
                results[i] = run_scene(i)
            except BaseException as e:  # reported below, with the thread's index
                errors.append((i, e))

        threads = [threading.Thread(target=work, args=(i,)) for i in range(THREADS)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        assert not errors, errors
        for i in range(THREADS):
            assert results[i][0] == sequential[i][0], f"scene {i}: the state differs from the sequential run"
            assert results[i][1] == sequential[i][1], f"scene {i}: the sensor readings differ"
        assert len({r[0] for r in results}) == THREADS, "the scenes differ from each other (the test compares something)"
    finally:
        sdp.shutdown()
