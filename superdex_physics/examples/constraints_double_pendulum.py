"""A double pendulum made of two free boxes and two constraints, on a moving anchor.

The upper box hangs from a world anchor by a pivot-position constraint (a ball joint to a point
of the world, whose target moves on a small circle), the lower box from the upper one by a
spherical-joint constraint. Both are stiff spring-dampers solved implicitly with the contacts.
Along the way: the constraints are listed, their forces and the pivot's deviation printed, the
pivot softened and restored, the joint removed (the lower box falls away), and the upper box
destroyed (its pivot goes with it).

Run: uv run python superdex_physics/examples/constraints_double_pendulum.py [--seconds 10] [--dt 0.004]

Add --debugger to watch it in the scene debugger; without a display, also set
SUPERDEX_DEBUGGER_RECORD=pendulum.jsonl to record the run to a file (superdex.physics.debugger).
"""

import argparse
import math

import numpy as np

import superdex.physics as sdp

LENGTH, WIDTH, DENSITY = 0.25, 0.025, 1000.0  # m, m, kg/m^3: 0.156 kg per box
ANCHOR = np.array([0.0, 0.0, 1.0])            # m, world
STIFFNESS, DAMPING = 2.5e4, 3.5               # N/m, N s/m
CIRCLE_RADIUS, CIRCLE_PERIOD = 0.05, 4.0      # m, s: the anchor's motion


def build(scene: sdp.Scene, moving_anchor: bool = True):
    """The two boxes (released horizontal along +x from the anchor) and their constraints."""
    shape = sdp.create_box_shape(half_extents=[LENGTH / 2, WIDTH / 2, WIDTH / 2])
    upper = scene.create_rigid_actor(name="upper", layer="links", shape=shape, density=DENSITY,
                                     world_from_local=sdp.TransformRT(translation=list(ANCHOR + [LENGTH / 2, 0, 0])))
    lower = scene.create_rigid_actor(name="lower", layer="links", shape=shape, density=DENSITY,
                                     world_from_local=sdp.TransformRT(translation=list(ANCHOR + [1.5 * LENGTH, 0, 0])))
    # the boxes overlap at their joint: no contact between them
    scene.enable_layer_contact_symmetric("links", "links", False)
    pivot = scene.create_rigid_pivot_position_constraint(actor=upper.get_handle(), local_position=[-LENGTH / 2, 0, 0],
                                                         target_position=list(ANCHOR), stiffness=STIFFNESS, damping=DAMPING)
    joint = scene.create_rigid_spherical_joint_constraint(actor_a=upper.get_handle(), actor_b=lower.get_handle(),
                                                          local_pos_a=[LENGTH / 2, 0, 0], local_pos_b=[-LENGTH / 2, 0, 0],
                                                          stiffness=STIFFNESS, damping=DAMPING)
    for c in (pivot, joint):
        c.register_query(sdp.QueryType.CONSTRAINT_FORCE)
    return upper, lower, pivot, joint


def anchor_at(t: float, moving: bool) -> np.ndarray:
    if not moving:
        return ANCHOR
    w = 2 * math.pi / CIRCLE_PERIOD
    return ANCHOR + CIRCLE_RADIUS * np.array([math.cos(w * t) - 1, 0.0, math.sin(w * t)])


def run(seconds: float = 10.0, dt: float = 0.004, moving_anchor: bool = True, timeline: bool = True, debugger: bool = False,
        print_every: float = 1.0) -> dict:
    """Steps the scene; returns the lower box's frames over time ((steps, 3) positions, m)."""
    sdp.initialize(num_worker_threads=0)
    scene = sdp.create_scene("constraints double pendulum")
    scene.set_gravity([0, 0, -9.81])
    upper, lower, pivot, joint = build(scene, moving_anchor)
    names = []
    scene.for_each_constraint(lambda c: names.append(str(c.get_type())))
    print(f"constraints: {names}")
    if debugger:
        sdp.debugger.attach()
    # the timeline, as fractions of the run
    events = {"soften": 0.4, "restore": 0.55, "remove joint": 0.7, "destroy upper": 0.9} if timeline else {}
    done = set()
    positions = []
    steps = int(round(seconds / dt))
    every = max(1, int(round(print_every / dt)))
    for k in range(steps):
        t = k * dt
        for name, at in events.items():
            if name in done or t < at * seconds:
                continue
            done.add(name)
            if name == "soften":
                pivot.set_stiffness(stiffness=50.0)  # the anchor now holds 3 N with a 6 cm sag
            elif name == "restore":
                pivot.set_stiffness(stiffness=STIFFNESS)
            elif name == "remove joint":
                scene.destroy_constraint(joint)
                joint = None
            elif name == "destroy upper":
                scene.destroy_actor(upper)
                pivot = upper = None
            print(f"t={t:6.3f} s: {name}")
        if pivot is not None:
            # the target's motion over the step is what the damping follows
            pivot.set_target_position(sdp.Real3(*anchor_at(t + dt, moving_anchor)))
        scene.step(dt)
        positions.append(np.array(lower.get_root_transform().translation, dtype=np.float64))
        if (k + 1) % every == 0:
            pivot_force = np.linalg.norm(np.asarray(pivot.get_force())[:3]) if pivot is not None else 0.0
            joint_force = np.linalg.norm(np.asarray(joint.get_force())[:3]) if joint is not None else 0.0
            sag = 1e3 * np.linalg.norm(np.asarray(pivot.get_deviation())) if pivot is not None else 0.0
            print(f"t={t + dt:6.3f} s  pivot force {pivot_force:6.2f} N  joint force {joint_force:6.2f} N  pivot deviation {sag:6.2f} mm")
    if debugger:
        sdp.debugger.detach()
    sdp.shutdown()
    return {"lower_positions": np.array(positions), "dt": dt}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--dt", type=float, default=0.004)
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    result = run(args.seconds, args.dt, debugger=args.debugger, print_every=max(args.seconds / 10, args.dt))
    print(f"lower box at {result['lower_positions'][-1].round(4)} after {args.seconds} s")


if __name__ == "__main__":
    main()
