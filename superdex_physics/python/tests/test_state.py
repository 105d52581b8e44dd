"""Scene state capture and restore: a restored scene replays bitwise identically.

The scene: a ground plane and a few boxes and a ball, tilted and offset, falling onto the
ground and onto each other, so that the captured moment (after 50 steps of 10 ms) has active
contacts, sliding and rotation. The physics is deterministic, so whatever the solver carries
from step to step (warm starts, contact caches) must be part of the state: replaying the 100
steps after the capture must reproduce every pose and velocity exactly.
"""

import numpy as np
import pytest

import superdex.physics as sdp
from contact_helpers import add_box, add_ground, add_sphere, vec

DT = 0.01
BEFORE = 50
AFTER = 100


def build(scene):
    add_ground(scene, mu=0.6)
    tilt = sdp.Quaternion.from_axis_angle([1, 1, 0], 0.3)
    turn = sdp.Quaternion.from_axis_angle([0, 0, 1], 0.5)
    actors = [
        add_box(scene, "a", [0.0, 0.0, 0.15], mass=1.0, rotation=tilt),
        add_box(scene, "b", [0.05, 0.02, 0.45], mass=2.0, rotation=turn),
        add_box(scene, "c", [0.6, 0.0, 0.3], half=0.08, mass=0.5, rotation=tilt, mu=0.3),
        add_sphere(scene, "ball", [0.3, 0.1, 0.6], radius=0.07, mass=0.8),
    ]
    actors[2].set_velocity([-1.0, 0.0, 0.0], [0.0, 2.0, 1.0])
    actors[3].set_velocity([0.5, -0.3, 0.0], [3.0, 0.0, 0.0])
    return actors


def snapshot(actors):
    parts = []
    for a in actors:
        xf = a.get_root_transform()
        parts += [np.asarray(xf.translation), np.array(xf.rotation), a.get_linear_velocity(), a.get_angular_velocity()]
    return np.concatenate([np.asarray(p) for p in parts])


def run(scene, actors, steps):
    out = []
    for _ in range(steps):
        scene.step(DT)
        out.append(snapshot(actors))
    return np.array(out)


def test_restore_state_replays_bitwise(scene):
    """capture_state after 50 steps, run 100 steps; restore_state, run the same 100 steps: every
    pose and velocity, at every step, is bitwise equal; the clock is restored too."""
    actors = build(scene)
    run(scene, actors, BEFORE)
    assert scene.get_solver_stats().num_contacts > 0, "the scene should be in contact at the capture"
    captured_at = scene.get_total_simulation_time()
    state = scene.capture_state()
    first = run(scene, actors, AFTER)
    scene.restore_state(state, release_immediately=False)
    assert scene.get_total_simulation_time() == captured_at
    second = run(scene, actors, AFTER)
    np.testing.assert_array_equal(second, first)
    # a state kept at restore stays valid: restoring it twice replays the same again
    scene.restore_state(state, release_immediately=True)
    np.testing.assert_array_equal(run(scene, actors, AFTER), first)
    # ... and one released at restore is gone
    with pytest.raises(sdp.Error):
        scene.restore_state(state, release_immediately=False)


def test_restore_puts_back_the_captured_poses(scene):
    """Right after restore_state, the poses and velocities are those at capture time."""
    actors = build(scene)
    run(scene, actors, BEFORE)
    at_capture = snapshot(actors)
    state = scene.capture_state()
    run(scene, actors, 20)
    assert not np.array_equal(snapshot(actors), at_capture)
    scene.restore_state(state, release_immediately=True)
    np.testing.assert_array_equal(snapshot(actors), at_capture)


def test_bytes_round_trip_same_scene_and_fresh_scene(engine):
    """capture_state_to_bytes appends the state's bytes to a bytearray; restoring them into the same scene, or into a fresh
    scene built by the same creation sequence, replays the 100 steps bitwise identically."""
    scene = sdp.create_scene("original")
    scene.set_gravity([0, 0, -9.81])
    actors = build(scene)
    run(scene, actors, BEFORE)
    blob = bytearray()
    scene.capture_state_to_bytes(blob)
    assert len(blob) > 0
    first = run(scene, actors, AFTER)

    scene.restore_state_from_bytes(blob)
    np.testing.assert_array_equal(run(scene, actors, AFTER), first)

    fresh = sdp.create_scene("fresh")
    fresh.set_gravity([0, 0, -9.81])
    fresh_actors = build(fresh)
    fresh.restore_state_from_bytes(blob)
    assert fresh.get_total_simulation_time() == pytest.approx(BEFORE * DT)
    np.testing.assert_array_equal(run(fresh, fresh_actors, AFTER), first)


def test_corrupt_bytes_raise(scene):
    """Bytes that are not a captured state (empty, truncated, garbage of the same length) are
    refused with sdp.Error, and the scene keeps stepping afterwards."""
    actors = build(scene)
    run(scene, actors, 10)
    blob = bytearray()
    scene.capture_state_to_bytes(blob)
    blob = bytes(blob)
    garbage = np.random.default_rng(0).integers(0, 256, len(blob), dtype=np.uint8).tobytes()
    for bad in (b"", blob[: len(blob) // 2], blob[:-1], garbage, b"superdex" * 4):
        with pytest.raises(sdp.Error):
            scene.restore_state_from_bytes(bad)
    run(scene, actors, 10)


def test_state_of_a_different_scene_is_refused(engine):
    """A state captured from a scene with other actors cannot describe this one: restoring it
    raises sdp.Error instead of silently scrambling bodies."""
    scene = sdp.create_scene("s")
    scene.set_gravity([0, 0, -9.81])
    build(scene)
    scene.step(DT)
    other = sdp.create_scene("other")
    other.set_gravity([0, 0, -9.81])
    build(other)
    add_box(other, "extra", [2.0, 0, 0.5])
    other.step(DT)
    blob = bytearray()
    other.capture_state_to_bytes(blob)
    with pytest.raises(sdp.Error):
        scene.restore_state_from_bytes(blob)
