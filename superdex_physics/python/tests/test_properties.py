"""Property tests (hypothesis) on random valid scenes: boxes, spheres and capsules with random
sizes, masses, poses and velocities, on the ground or in the air, stepped with random time steps.

- Stepping never produces NaN or infinity, and never raises a numerical fault (under the default
  NumericalFaultPolicy.RAISE a diverged or non-finite step would raise); and no solve runs out
  of Newton iterations unconverged (that raised too before a solve stopped by a limit became
  SuperDex's STOPPED, no fault): each converges, or stops early on a Newton step that can no
  longer move the solution at the working precision (NonLinearSolverParams.rel_step_tol).
- capture_state, then restore_state, then step gives bitwise the same state as stepping on.

CI runs a fixed, derandomized set of examples (profile "ci"); `SUPERDEX_HYPOTHESIS_PROFILE=explore`
searches with fresh random examples and more of them.
"""

import math
import os

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import superdex.physics as sdp

settings.register_profile("ci", max_examples=60, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("explore", max_examples=500, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("SUPERDEX_HYPOTHESIS_PROFILE", "ci"))

size = st.floats(0.02, 0.4)
coordinate = st.floats(-1.0, 1.0)
speed = st.floats(-5.0, 5.0)
spin = st.floats(-10.0, 10.0)

body = st.fixed_dictionaries({
    "kind": st.sampled_from(["box", "sphere", "capsule"]),
    "dims": st.tuples(size, size, size),
    "mass": st.floats(0.05, 20.0),
    "position": st.tuples(coordinate, coordinate, st.floats(0.0, 2.0)),
    "axis": st.tuples(coordinate, coordinate, coordinate),
    "angle": st.floats(-math.pi, math.pi),
    "linear": st.tuples(speed, speed, speed),
    "angular": st.tuples(spin, spin, spin),
})

scene_description = st.fixed_dictionaries({
    "bodies": st.lists(body, min_size=1, max_size=5),
    "ground": st.booleans(),
    "dt": st.floats(0.001, 0.025),
    "friction": st.floats(0.0, 1.5),
})


def shape_of(b):
    a, c, d = b["dims"]
    if b["kind"] == "box":
        return sdp.create_box_shape([a, c, d])
    if b["kind"] == "sphere":
        return sdp.create_sphere_shape([0, 0, 0], a)
    return sdp.create_capsule_shape(a, c)


def build(description):
    scene = sdp.create_scene("random")
    scene.set_gravity([0, 0, -9.81])
    contact = sdp.ContactParams(coulomb_friction_coefficient=description["friction"])
    if description["ground"]:
        scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True, contact=contact)
    actors = []
    for k, b in enumerate(description["bodies"]):
        axis = np.array(b["axis"])
        rotation = (sdp.Quaternion.from_axis_angle(axis, b["angle"]) if np.linalg.norm(axis) > 1e-3
                    else sdp.Quaternion(0, 0, 0, 1))
        a = scene.create_rigid_actor(name=f"{b['kind']}{k}", shape=shape_of(b), mass=b["mass"], contact=contact,
                                     world_from_local=sdp.TransformRT(rotation=rotation, translation=list(b["position"])))
        a.set_velocity(list(b["linear"]), list(b["angular"]))
        actors.append(a)
    return scene, actors


def state_bytes(scene):
    out = bytearray()
    scene.capture_state_to_bytes(out)
    return bytes(out)


def state_of(actors):
    parts = []
    for a in actors:
        t = a.get_root_transform()
        parts += [np.array(t.translation), np.array(t.rotation), a.get_linear_velocity(), a.get_angular_velocity()]
    return np.concatenate([np.asarray(p, dtype=np.float64) for p in parts])


@given(scene_description)
def test_random_scenes_never_produce_nan(description):
    sdp.initialize(0)
    try:
        scene, actors = build(description)
        max_iter = scene.get_solver_params().non_linear_solver.max_iter
        for _ in range(25):
            scene.step(description["dt"])  # raises on a numerical fault
            assert np.all(np.isfinite(state_of(actors)))
            stats = scene.get_solver_stats()
            assert (stats.convergence_status == sdp.ConvergenceStatus.CONVERGED
                    or (stats.convergence_status == sdp.ConvergenceStatus.STOPPED and stats.max_non_linear_iters < max_iter)), stats
        assert scene.get_last_numerical_faults() == []
    finally:
        sdp.shutdown()


@given(scene_description, st.integers(0, 10), st.integers(1, 10))
def test_capture_restore_step_equals_step(description, before, after):
    sdp.initialize(0)
    try:
        scene, actors = build(description)
        dt = description["dt"]
        for _ in range(before):
            scene.step(dt)
        saved = scene.capture_state()
        for _ in range(after):
            scene.step(dt)
        straight = (state_bytes(scene), state_of(actors).tobytes())
        scene.restore_state(saved, release_immediately=True)
        for _ in range(after):
            scene.step(dt)
        replayed = (state_bytes(scene), state_of(actors).tobytes())
        assert replayed == straight
    finally:
        sdp.shutdown()
