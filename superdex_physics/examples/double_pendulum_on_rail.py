"""A double pendulum on a cart that slides freely on a horizontal rail.

The articulation, built from ArticulatedLinkParams and ArticulatedJointParams:

    rail (welded 1.5 m up) --prismatic along X--> cart --revolute about Y--> upper rod
                                                      --revolute about Y--> lower rod

The rods are uniform (a 0.5 m, 1 kg rod and a 0.4 m, 0.8 kg rod) and hang along -Z at zero angle;
the cart has 2 kg. Released from rest at an angle, the pendulum swings chaotically and the cart
moves back and forth under it. Nothing pushes the system horizontally and the joints have no
friction, so two quantities should stay constant:

- the total energy, kinetic (1/2 v^T M v, with the engine's joint-space mass matrix M) plus the
  potential energy of the rods' centres of mass;
- the horizontal momentum, which for the cart's coordinate x is the first entry of M v.

The script prints both along the run, computed from the engine's state through the Python API
(mass matrix, link transforms). The implicit integrator conserves them up to an error that
shrinks with the time step (first order): try --dt 0.0005.

Run it with

    uv run python superdex_physics/examples/double_pendulum_on_rail.py [--seconds 5] [--dt 0.001]

Add --debugger to watch it in the scene debugger; without a display, also set
SUPERDEX_DEBUGGER_RECORD=pendulum.jsonl to record the run to a file (superdex.physics.debugger).
"""

import argparse

import numpy as np

import superdex.physics as sdp

GRAVITY = 9.81  # m/s^2
RAIL_HEIGHT = 1.5  # m
CART_MASS = 2.0  # kg
ROD_RADIUS = 0.02  # m
# (name, mass kg, length m) of the two rods, top to bottom
RODS = [("upper", 1.0, 0.5), ("lower", 0.8, 0.4)]
INITIAL_POSE = [0.0, 1.2, -0.6]  # cart x (m), shoulder and elbow angles (rad)


def rod_inertia(mass: float, length: float) -> list[float]:
    """Ixx, Ixy, Ixz, Iyy, Iyz, Izz of a solid rod along z, about its centre of mass."""
    i_trans = mass * (3 * ROD_RADIUS**2 + length**2) / 12
    return [i_trans, 0, 0, i_trans, 0, 0.5 * mass * ROD_RADIUS**2]


def create_cart_pendulum(scene: sdp.Scene) -> sdp.Actor:
    (upper, m1, l1), (lower, m2, l2) = RODS

    def joint(name, type, axis=(0, 0, 0), at=(0, 0, 0)):
        return sdp.ArticulatedJointParams(name=name, type=type, axis=list(axis), parent_link_from_joint=sdp.TransformRT(translation=list(at)))

    links = [
        sdp.ArticulatedLinkParams(name="rail", mass=10.0, moment_of_inertia=[1, 0, 0, 1, 0, 1],
                                  shape=sdp.create_box_shape([1.5, 0.02, 0.02])),
        sdp.ArticulatedLinkParams(name="cart", parent_link=0, mass=CART_MASS, moment_of_inertia=[0.004, 0, 0, 0.009, 0, 0.009],
                                  shape=sdp.create_box_shape([0.1, 0.06, 0.04])),
    ]
    # a rod's link frame is at its centre, half its length below its joint (a link's shape is
    # centred on its frame): its centre of mass is the frame's origin, its capsule along z
    for i, (name, mass, length) in enumerate(RODS):
        links.append(sdp.ArticulatedLinkParams(
            name=name, parent_link=i + 1, parent_joint_from_link=sdp.TransformRT(translation=[0, 0, -length / 2]),
            mass=mass, center_of_mass=[0, 0, 0], moment_of_inertia=rod_inertia(mass, length),
            shape=sdp.create_capsule_shape(radius=ROD_RADIUS, half_length=length / 2 - ROD_RADIUS)))
    joints = [
        joint("rail_weld", sdp.ArticulatedJointType.HARD, at=[0, 0, RAIL_HEIGHT]),
        joint("slider", sdp.ArticulatedJointType.PRISMATIC, axis=[1, 0, 0]),
        # the pendulum hangs 0.1 m in front of the rail (Y does not enter the planar motion)
        joint("shoulder", sdp.ArticulatedJointType.REVOLUTE, axis=[0, 1, 0], at=[0, 0.1, 0]),
        # the upper rod's end: half its length below its centre
        joint("elbow", sdp.ArticulatedJointType.REVOLUTE, axis=[0, 1, 0], at=[0, 0, -l1 / 2]),
    ]
    actor = scene.create_articulated_actor(name="cart_double_pendulum", links=links, joints=joints)
    # links joined by a joint never collide; keep the others (rail, cart, rods) from touching too
    names = ["rail", "cart"] + [name for name, _, _ in RODS]
    link_actors = dict(zip(names, actor.get_nested_link_actors()))
    for a, b in [("rail", upper), ("rail", lower), ("cart", lower)]:
        scene.enable_actor_contact_symmetric(link_actors[a], link_actors[b], False, sdp.IncludeNestedActors.NO)
    actor.set_articulated_pose_from_joints(INITIAL_POSE)
    return actor


def energy_and_momentum(actor: sdp.Actor) -> tuple[float, float]:
    """Total energy (J) and horizontal momentum (kg m/s) from the engine's state: kinetic energy
    1/2 v^T M v, potential energy of the rods' centres of mass, momentum (M v)[0] (the cart's x)."""
    n = actor.get_num_dofs()
    v = np.zeros(n, dtype=actor.get_articulated_pose().dtype)
    actor.get_articulated_joint_velocities(v)
    v = v.astype(np.float64)
    M = np.array(actor.get_articulated_mass_matrix(), dtype=np.float64).reshape(n, n)
    xforms = sdp.DynamicArrayTransformRT(2 + len(RODS))
    actor.get_articulated_link_transforms(xforms)
    potential = 0.0
    for i, (_, mass, length) in enumerate(RODS):
        com = np.array(xforms[2 + i].translation, dtype=np.float64)  # a rod's frame is at its centre
        potential += mass * GRAVITY * com[2]
    Mv = M @ v
    return 0.5 * float(v @ Mv) + potential, float(Mv[0])


def run(seconds: float = 5.0, dt: float = 0.001, debugger: bool = False) -> dict:
    """Simulates `seconds` from rest at INITIAL_POSE. Returns the times, joint positions and
    velocities after every step (float64 arrays, [steps, 3]), and energy and momentum after
    every step as computed by energy_and_momentum()."""
    sdp.initialize(num_worker_threads=0)
    try:
        scene = sdp.create_scene("Double pendulum on a rail")
        scene.set_gravity([0, 0, -GRAVITY])
        actor = create_cart_pendulum(scene)
        n = actor.get_num_dofs()
        v = np.zeros(n, dtype=actor.get_articulated_pose().dtype)
        times, poses, velocities, energy, momentum = [], [], [], [], []
        e0, p0 = energy_and_momentum(actor)
        if debugger:
            sdp.debugger.attach()
        for _ in range(int(round(seconds / dt))):
            scene.step(dt)
            actor.get_articulated_joint_velocities(v)
            times.append(scene.get_total_simulation_time())
            poses.append(np.array(actor.get_articulated_pose(), dtype=np.float64))
            velocities.append(v.astype(np.float64))
            e, p = energy_and_momentum(actor)
            energy.append(e)
            momentum.append(p)
        return {"dt": dt, "initial_pose": np.array(INITIAL_POSE), "initial_energy": e0, "initial_momentum": p0,
                "t": np.array(times), "q": np.array(poses), "v": np.array(velocities),
                "energy": np.array(energy), "momentum": np.array(momentum)}
    finally:
        if debugger:
            sdp.debugger.detach()
        sdp.shutdown()


def print_summary(result: dict, print_every: float = 0.5) -> None:
    every = max(1, int(round(print_every / result["dt"])))
    print(f"{'t [s]':>6} {'cart x [m]':>10} {'q1 [rad]':>9} {'q2 [rad]':>9} {'energy [J]':>11} {'momentum x [kg m/s]':>20}")
    print(f"{0.0:6.3f} {result['initial_pose'][0]:10.4f} {result['initial_pose'][1]:9.4f} {result['initial_pose'][2]:9.4f} "
          f"{result['initial_energy']:11.5f} {result['initial_momentum']:20.5f}")
    for k in range(every - 1, len(result["t"]), every):
        q = result["q"][k]
        print(f"{result['t'][k]:6.3f} {q[0]:10.4f} {q[1]:9.4f} {q[2]:9.4f} {result['energy'][k]:11.5f} {result['momentum'][k]:20.5f}")
    drift = result["energy"] - result["initial_energy"]
    print(f"energy: largest change {np.abs(drift).max():.4f} J (from {result['initial_energy']:.4f} J); "
          f"momentum: largest |p_x| {np.abs(result['momentum']).max():.4f} kg m/s")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=5.0, help="simulated time (s)")
    parser.add_argument("--dt", type=float, default=0.001, help="time step (s)")
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    print_summary(run(args.seconds, args.dt, args.debugger))


if __name__ == "__main__":
    main()
