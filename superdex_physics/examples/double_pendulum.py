"""A double pendulum released from horizontal, falling under gravity; prints its state.

Run: uv run python superdex_physics/examples/double_pendulum.py [--seconds 3] [--dt 0.001]

Add --debugger to watch it in the scene debugger; without a display, also set
SUPERDEX_DEBUGGER_RECORD=pendulum.jsonl to record the run to a file (superdex.physics.debugger).
"""

import argparse

import numpy as np

import superdex.physics as sdp


def inertia_of_rod(mass: float, length: float, radius: float = 0.02) -> list[float]:
    """Ixx, Ixy, Ixz, Iyy, Iyz, Izz of a solid rod along x, about its centre of mass."""
    i_axial = 0.5 * mass * radius**2
    i_trans = mass * (3 * radius**2 + length**2) / 12
    return [i_axial, 0, 0, i_trans, 0, i_trans]


def create_double_pendulum(scene: sdp.Scene, length: float = 0.5, mass: float = 1.0) -> sdp.Actor:
    """Two rods hanging from a fixed pivot 2 m above the ground, hinged about Y."""
    links = [
        sdp.ArticulatedLinkParams(name="base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
        sdp.ArticulatedLinkParams(name="upper", parent_link=0, mass=mass, center_of_mass=[length / 2, 0, 0],
                                  moment_of_inertia=inertia_of_rod(mass, length)),
        sdp.ArticulatedLinkParams(name="lower", parent_link=1, mass=mass, center_of_mass=[length / 2, 0, 0],
                                  moment_of_inertia=inertia_of_rod(mass, length)),
    ]
    joints = [
        sdp.ArticulatedJointParams(name="weld", type=sdp.ArticulatedJointType.HARD,
                                   parent_link_from_joint=sdp.TransformRT(translation=[0, 0, 2.0])),
        sdp.ArticulatedJointParams(name="shoulder", type=sdp.ArticulatedJointType.REVOLUTE, axis=[0, 1, 0]),
        sdp.ArticulatedJointParams(name="elbow", type=sdp.ArticulatedJointType.REVOLUTE, axis=[0, 1, 0],
                                   parent_link_from_joint=sdp.TransformRT(translation=[length, 0, 0])),
    ]
    return scene.create_articulated_actor(name="double_pendulum", links=links, joints=joints)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--dt", type=float, default=0.001)
    parser.add_argument("--print-every", type=float, default=0.25, help="seconds between printed lines")
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()

    sdp.initialize(num_worker_threads=0)
    scene = sdp.create_scene("double pendulum")
    scene.set_gravity([0, 0, -9.81])
    pendulum = create_double_pendulum(scene)
    links = pendulum.get_nested_link_actors()
    tip_link = scene.get_actor(links[-1])

    n = pendulum.get_num_dofs()
    q = np.zeros(n, dtype=np.float64 if sdp.uses_double_precision() else np.float32)
    v = np.zeros_like(q)
    xforms = sdp.DynamicArrayTransformRT(len(links))
    if args.debugger:
        sdp.debugger.attach()
    steps = int(round(args.seconds / args.dt))
    every = max(1, int(round(args.print_every / args.dt)))
    print(f"{'t [s]':>7} {'q1 [rad]':>9} {'q2 [rad]':>9} {'v1 [rad/s]':>10} {'v2 [rad/s]':>10}   elbow position [m]")
    for k in range(steps + 1):
        if k % every == 0:
            pendulum.get_articulated_pose(q)
            pendulum.get_articulated_joint_velocities(out_velocities=v)
            pendulum.get_articulated_link_transforms(xforms)
            p = np.array(xforms[2].translation)
            print(f"{scene.get_total_simulation_time():7.3f} {q[0]:9.4f} {q[1]:9.4f} {v[0]:10.4f} {v[1]:10.4f}   "
                  f"[{p[0]:+.3f}, {p[1]:+.3f}, {p[2]:+.3f}]")
        if k < steps:
            scene.step(args.dt)
    print(f"tip link '{tip_link.get_name()}' at {np.array(tip_link.get_root_transform().translation).round(4)}")
    if args.debugger:
        sdp.debugger.detach()
    sdp.shutdown()


if __name__ == "__main__":
    main()
