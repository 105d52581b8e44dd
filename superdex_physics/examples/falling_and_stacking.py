"""Falling and stacking: rigid boxes and balls dropped onto the ground settle into a stable stack.

Five 10 cm cubes are released one above the other with 1 cm gaps between them, each turned 15
degrees further about the vertical than the one below and some shifted sideways by up to 1 cm, so
they land as a twisted, staggered tower. Three balls drop beside it from different heights. The
bodies fall together, the bottom cube lands first and the others land on it one after another;
friction keeps the tower standing.

At the end the script prints, for every body, where it came to rest and how fast it still moves,
the height a rigid stack would have (cube i rests with its centre at (2 i + 1) h, h the half
size), the force each cube carries from the ones above it, and the total contact force on the
ground against the total weight.

Run it with

    uv run python superdex_physics/examples/falling_and_stacking.py [--seconds 3] [--dt 0.005]

Add --debugger to watch it in the scene debugger. Without a display, set
SUPERDEX_DEBUGGER_RECORD=stack.jsonl as well to record the run to a file (superdex.physics.debugger).
"""

import argparse
import math

import numpy as np

import superdex.physics as sdp

GRAVITY = 9.81  # m/s^2
HALF = 0.05  # m, half size of the cubes
BOX_MASS = 1.0  # kg
NUM_BOXES = 5
GAP = 0.01  # m, between the cubes at release
TWIST = math.radians(15.0)  # rad, each cube turned this much more about z than the one below
SHIFTS = [(0.0, 0.0), (0.01, -0.008), (0.0, 0.0), (0.01, 0.0), (0.0, -0.008)]  # m, x and y of each cube
BALL_RADIUS = 0.04  # m
BALL_MASS = 0.5  # kg
BALL_STARTS = [(0.3, -0.2, 0.2), (0.3, 0.0, 0.3), (0.3, 0.2, 0.4)]  # m
FRICTION = 0.6


def build_scene(scene: sdp.Scene) -> dict:
    """Adds the ground, the cubes and the balls; returns them by role."""
    material = sdp.ContactParams(coulomb_friction_coefficient=FRICTION)
    ground = scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape(normal=[0, 0, 1], distance=0),
                                      is_static=True, contact=material)
    box_shape = sdp.create_box_shape([HALF, HALF, HALF])
    boxes = []
    for i in range(NUM_BOXES):
        x, y = SHIFTS[i]
        z = GAP + HALF + i * (2 * HALF + GAP)
        pose = sdp.TransformRT(rotation=sdp.Quaternion.from_axis_angle([0, 0, 1], i * TWIST), translation=[x, y, z])
        boxes.append(scene.create_rigid_actor(name=f"box_{i}", shape=box_shape, world_from_local=pose, mass=BOX_MASS,
                                              contact=material))
    ball_shape = sdp.create_sphere_shape(center=[0, 0, 0], radius=BALL_RADIUS)
    balls = [scene.create_rigid_actor(name=f"ball_{i}", shape=ball_shape, world_from_local=sdp.TransformRT(translation=list(start)),
                                      mass=BALL_MASS, contact=material)
             for i, start in enumerate(BALL_STARTS)]
    # contact forces are computed for actors that ask for them
    for actor in [ground, *boxes]:
        actor.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    return {"ground": ground, "boxes": boxes, "balls": balls}


def body_state(actor: sdp.Actor) -> dict:
    xf = actor.get_root_transform()
    return {
        "name": actor.get_name(),
        "mass": actor.get_mass(),
        "position": np.array(xf.translation, dtype=np.float64),
        "rotation": np.array(xf.rotation, dtype=np.float64),  # x, y, z, w
        "linear_velocity": np.array(actor.get_linear_velocity(), dtype=np.float64),
        "angular_velocity": np.array(actor.get_angular_velocity(), dtype=np.float64),
    }


def run(seconds: float = 3.0, dt: float = 0.005, debugger: bool = False, on_step=None) -> dict:
    """Drops the bodies and simulates `seconds`; returns the initial and final states of the bodies,
    the contact force on the ground, and the force each cube receives from the cube above it.
    on_step(scene, actors) is called after every step when given."""
    sdp.initialize(num_worker_threads=0)
    try:
        scene = sdp.create_scene("Falling and stacking")
        scene.set_gravity([0, 0, -GRAVITY])
        actors = build_scene(scene)
        bodies = actors["boxes"] + actors["balls"]
        initial = [body_state(a) for a in bodies]
        if debugger:
            sdp.debugger.attach()
        for _ in range(int(round(seconds / dt))):
            scene.step(dt)
            if on_step is not None:
                on_step(scene, actors)
        boxes = actors["boxes"]
        return {
            "time": scene.get_total_simulation_time(),
            "initial": initial,
            "final": [body_state(a) for a in bodies],
            "ground_force": np.array(actors["ground"].get_contact_force_world(), dtype=np.float64),
            "force_from_box_above": [np.array(boxes[i].get_contact_force_from_actor_world(boxes[i + 1]), dtype=np.float64)
                                     for i in range(len(boxes) - 1)],
        }
    finally:
        if debugger:
            sdp.debugger.detach()
        sdp.shutdown()


def print_summary(result: dict) -> None:
    print(f"after {result['time']:.2f} s:")
    print(f"{'body':>7} {'x [m]':>8} {'y [m]':>8} {'z [m]':>8} {'rigid z':>8} {'|v| [m/s]':>10} {'|w| [rad/s]':>11}")
    for i, body in enumerate(result["final"]):
        x, y, z = body["position"]
        rigid = (2 * i + 1) * HALF if i < NUM_BOXES else BALL_RADIUS
        print(f"{body['name']:>7} {x:8.4f} {y:8.4f} {z:8.4f} {rigid:8.4f} {np.linalg.norm(body['linear_velocity']):10.2e} "
              f"{np.linalg.norm(body['angular_velocity']):11.2e}")
    for i, force in enumerate(result["force_from_box_above"]):
        above = (NUM_BOXES - 1 - i) * BOX_MASS * GRAVITY
        print(f"box_{i} carries {-force[2]:7.3f} N from box_{i + 1} (weight above it: {above:.3f} N)")
    weight = sum(body["mass"] for body in result["final"]) * GRAVITY
    print(f"contact force on the ground: {-result['ground_force'][2]:.3f} N down; total weight {weight:.3f} N")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=3.0, help="simulated time (s)")
    parser.add_argument("--dt", type=float, default=0.005, help="time step (s)")
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    print_summary(run(args.seconds, args.dt, args.debugger))


if __name__ == "__main__":
    main()
