"""The Unitree G1 humanoid standing on the ground under joint PD.

The G1 (example-robot-data's g1_29dof_rev_1_0.urdf: 29 joints, 33 kg, four contact spheres under
each foot) is loaded on a floating base, placed with its feet on a ground plane, and every joint
is held at its zero position (standing straight) by an implicit joint drive: a PD law the step
solves together with contact, so stiff gains stay stable at 2 ms steps. Nothing holds the pelvis:
the robot balances on its feet. The example reports the pelvis height, how far the pelvis drifts,
and the total contact force under the feet against the robot's weight.

Run it with

    uv run python superdex_robotics/examples/robots/example_g1_standing.py [--seconds 5] [--kp 500] [--kd 20]

Add --debugger to watch it in the scene debugger (with SUPERDEX_DEBUGGER_RECORD=g1.jsonl and no
display, the run is recorded to a file).
"""

import argparse

import numpy as np

import superdex.physics as physics
import superdex.robotics as robotics
from superdex.robot_files import example_robot_data_file

URDF_NAME = "robots/g1_description/urdf/g1_29dof_rev_1_0.urdf"
FOOT_LINKS = ("left_ankle_roll_link", "right_ankle_roll_link")
G = 9.81


def run(seconds: float = 5.0, dt: float = 0.002, kp: float = 500.0, kd: float = 20.0, debugger: bool = False) -> dict:
    """Stands the G1 for `seconds`; returns the pelvis trajectory, the foot and total contact forces
    (N, world z, every step), the robot's weight (N) and the contact force on links other than feet."""
    physics.initialize(num_worker_threads=0)
    try:
        scene = physics.create_scene("G1 standing")
        scene.set_gravity([0, 0, -G])
        scene.create_rigid_actor(name="ground", shape=physics.create_plane_shape([0, 0, 1], 0), is_static=True)
        prefab = robotics.load_bot_prefab_from_urdf_file(example_robot_data_file(URDF_NAME))
        bot = robotics.create_bot(scene, prefab, robotics.create_context())
        g1 = bot.get_articulated_actor()
        links = [scene.get_actor(h) for h in g1.get_nested_link_actors()]
        names = list(g1.get_articulated_shape_info().link_names)
        # feet on the ground: lift the standing robot until its lowest point is at z = 0
        pose = np.zeros(g1.get_num_dofs())
        g1.set_articulated_pose_from_joints(pose)
        pose[2] = -min(link.get_aabb_world().min[2] for link in links)
        g1.set_articulated_pose_from_joints(pose)
        weight = sum(link.get_mass() for link in links) * G
        # joint PD towards zero on every joint after the 6 of the floating base
        for dof in range(6, g1.get_num_dofs()):
            g1.set_joint_drive(dof, stiffness=kp, damping=kd, target_position=0.0)
        for link in links:
            link.register_query(physics.QueryType.TOTAL_CONTACT_FORCE)
        feet = [names.index(n) for n in FOOT_LINKS]
        if debugger:
            physics.debugger.attach()
        pelvis, foot_force, total_force = [], [], []
        for _ in range(int(round(seconds / dt))):
            scene.step(dt)
            forces = np.array([link.get_contact_force_world()[2] for link in links])
            pelvis.append(np.array(g1.get_articulated_pose()[:3], dtype=np.float64))
            foot_force.append(forces[feet].sum())
            total_force.append(forces.sum())
        robotics.destroy_bot(scene, bot)
        return {"weight": weight, "start_height": pose[2], "pelvis": np.array(pelvis), "foot_force": np.array(foot_force),
                "total_force": np.array(total_force), "dt": dt}
    finally:
        if debugger:
            physics.debugger.detach()
        physics.shutdown()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=5.0, help="simulated time (s)")
    parser.add_argument("--kp", type=float, default=500.0, help="joint stiffness (N m/rad)")
    parser.add_argument("--kd", type=float, default=20.0, help="joint damping (N m s/rad)")
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    r = run(args.seconds, kp=args.kp, kd=args.kd, debugger=args.debugger)
    last = r["pelvis"][-1]
    drift = np.linalg.norm(r["pelvis"][:, :2] - r["pelvis"][0, :2], axis=1).max()
    print(f"G1 ({r['weight'] / G:.2f} kg) after {args.seconds:g} s: pelvis at z = {last[2]:.4f} m "
          f"(started at {r['start_height']:.4f} m), horizontal drift at most {drift * 1000:.1f} mm")
    print(f"contact force under the feet {r['foot_force'][-1]:.2f} N, weight {r['weight']:.2f} N "
          f"({100 * (r['foot_force'][-1] / r['weight'] - 1):+.3f} %)")


if __name__ == "__main__":
    main()
