"""Contact filtering: choose which bodies touch. Balls drop onto pedestals and a shelf; the filtered
ones fall through to the ground, their twins land on top.

Two filters (API.md, "Scene"):

- by actor pair: scene.enable_actor_contact_symmetric(a, b, False, IncludeNestedActors.NO) switches
  contact off between two actors. The ball "ghost_ball" falls through its pedestal and lands on the ground inside it;
  "solid_ball", dropped the same way onto an identical pedestal without the filter, comes to rest
  on top of it.
- by layer: every actor has a contact layer, named by a string (create_rigid_actor(..., layer="..."),
  "" the default layer), and scene.enable_layer_contact_symmetric(la, lb, False) switches contact off
  between two layers. A static shelf sits on layer "shelf" and contact between layers "ghost" and
  "shelf" is off: the balls on layer "ghost" fall through the shelf to the ground (the default
  layer), the ball on layer "solid" stays on the shelf.

Everything else keeps touching: the pedestals and every ball still rest on the ground. (In a bot file,
"contactOverrides": [{"linkA", "linkB", "enable": false}] does the same for two links of a robot,
say a finger and its own palm.)

The summary prints where each ball came to rest, where it would rest on what it was dropped onto,
and the largest contact force seen between each filtered pair during the run (zero).

Run it with

    uv run python superdex_physics/examples/contact_filtering.py [--seconds 1.5] [--dt 0.005]

Add --debugger to watch it in the scene debugger; without a display, also set
SUPERDEX_DEBUGGER_RECORD=filtering.jsonl to record the run to a file (superdex.physics.debugger).
"""

import argparse

import numpy as np

import superdex.physics as sdp

GRAVITY = 9.81  # m/s^2
RADIUS = 0.05  # m, every ball
BALL_MASS = 0.2  # kg
PEDESTAL_HALF = 0.1  # m, cubes resting on the ground
PEDESTAL_MASS = 2.0  # kg
SHELF_TOP = 0.4  # m
SHELF_HALF = [0.25, 0.25, 0.02]  # m
DROP_HEIGHT = 0.8  # m, every ball starts with its centre here
GHOST_LAYER, SHELF_LAYER, SOLID_LAYER = "ghost", "shelf", "solid"
FRICTION = 0.5


def build_scene(scene: sdp.Scene) -> dict:
    material = sdp.ContactParams(coulomb_friction_coefficient=FRICTION)
    ground = scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape(normal=[0, 0, 1], distance=0),
                                      is_static=True, contact=material)
    ball_shape = sdp.create_sphere_shape(center=[0, 0, 0], radius=RADIUS)
    cube = sdp.create_box_shape([PEDESTAL_HALF] * 3)

    def ball(name, x, y, layer=""):
        return scene.create_rigid_actor(name=name, shape=ball_shape, mass=BALL_MASS, layer=layer, contact=material,
                                        world_from_local=sdp.TransformRT(translation=[x, y, DROP_HEIGHT]))

    def pedestal(name, x, y):
        return scene.create_rigid_actor(name=name, shape=cube, mass=PEDESTAL_MASS, contact=material,
                                        world_from_local=sdp.TransformRT(translation=[x, y, PEDESTAL_HALF]))

    # 1. by actor pair
    ghost_pedestal = pedestal("ghost_pedestal", 0.0, -0.3)
    ghost_ball = ball("ghost_ball", 0.0, -0.3)
    scene.enable_actor_contact_symmetric(ghost_ball, ghost_pedestal, False, sdp.IncludeNestedActors.NO)
    solid_pedestal = pedestal("solid_pedestal", 0.0, 0.3)
    solid_ball = ball("solid_ball", 0.0, 0.3)

    # 2. by layer: the shelf is static, on layer "shelf"; layers "ghost" and "shelf" do not touch
    scene.enable_layer_contact_symmetric(GHOST_LAYER, SHELF_LAYER, False)
    shelf = scene.create_rigid_actor(name="shelf", shape=sdp.create_box_shape(SHELF_HALF), is_static=True, layer=SHELF_LAYER,
                                     contact=material,
                                     world_from_local=sdp.TransformRT(translation=[0.8, 0.0, SHELF_TOP - SHELF_HALF[2]]))
    layer_balls = [ball("layer1_ball_a", 0.7, -0.1, GHOST_LAYER), ball("layer1_ball_b", 0.9, 0.1, GHOST_LAYER),
                   ball("layer3_ball", 0.8, 0.0, SOLID_LAYER)]

    actors = {"ground": ground, "ghost_pedestal": ghost_pedestal, "ghost_ball": ghost_ball,
              "solid_pedestal": solid_pedestal, "solid_ball": solid_ball, "shelf": shelf}
    actors.update({a.get_name(): a for a in layer_balls})
    for actor in actors.values():
        actor.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    return actors


# (ball, what it was dropped onto, whether contact between them is filtered out)
DROPS = [("ghost_ball", "ghost_pedestal", True), ("solid_ball", "solid_pedestal", False),
         ("layer1_ball_a", "shelf", True), ("layer1_ball_b", "shelf", True), ("layer3_ball", "shelf", False)]
REST_HEIGHT = {"ghost_pedestal": 2 * PEDESTAL_HALF + RADIUS, "solid_pedestal": 2 * PEDESTAL_HALF + RADIUS,
               "shelf": SHELF_TOP + RADIUS, "ground": RADIUS}


def run(seconds: float = 1.5, dt: float = 0.005, debugger: bool = False, on_step=None) -> dict:
    """Drops the balls and simulates `seconds`. Returns the final position of every dynamic actor and,
    per drop in DROPS, the largest contact force magnitude between the ball and its target seen after
    any step. on_step(scene, actors) is called after every step when given."""
    sdp.initialize(num_worker_threads=0)
    try:
        scene = sdp.create_scene("Contact filtering")
        scene.set_gravity([0, 0, -GRAVITY])
        actors = build_scene(scene)
        largest = {ball: 0.0 for ball, _, _ in DROPS}
        if debugger:
            sdp.debugger.attach()
        for _ in range(int(round(seconds / dt))):
            scene.step(dt)
            for ball, target, _ in DROPS:
                force = actors[ball].get_contact_force_from_actor_world(actors[target])
                largest[ball] = max(largest[ball], float(np.linalg.norm(force)))
            if on_step is not None:
                on_step(scene, actors)
        positions = {name: np.array(a.get_root_transform().translation, dtype=np.float64)
                     for name, a in actors.items() if name not in ("ground", "shelf")}
        return {"time": scene.get_total_simulation_time(), "positions": positions, "largest_pair_force": largest}
    finally:
        if debugger:
            sdp.debugger.detach()
        sdp.shutdown()


def print_summary(result: dict) -> None:
    print(f"after {result['time']:.2f} s:")
    print(f"{'ball':>14} {'dropped onto':>15} {'filtered':>9} {'rests at z [m]':>15} {'on target':>10} {'on ground':>10} "
          f"{'max force from target [N]':>26}")
    for ball, target, filtered in DROPS:
        z = result["positions"][ball][2]
        print(f"{ball:>14} {target:>15} {str(filtered):>9} {z:15.4f} {REST_HEIGHT[target]:10.3f} {REST_HEIGHT['ground']:10.3f} "
              f"{result['largest_pair_force'][ball]:26.3f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=1.5, help="simulated time (s)")
    parser.add_argument("--dt", type=float, default=0.005, help="time step (s)")
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    print_summary(run(args.seconds, args.dt, args.debugger))


if __name__ == "__main__":
    main()
