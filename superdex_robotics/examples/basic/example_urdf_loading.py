"""Loading a robot arm from a URDF file, and its forward kinematics.

robotics.load_bot_prefab_from_urdf_file turns a URDF (links, joints, inertials, collision shapes)
into the same BotPrefab that a .superdex_bot file gives, so the rest of the SDK does not care where
a robot came from. Each URDF joint becomes the joint of its child link (revolute, continuous ->
Revolute, prismatic -> Prismatic, fixed -> Hard). A URDF's root link floats on a free joint named
"world_joint" unless fixed_base=True welds it to the world, as this arm is.

This example loads the bundled 4-DOF arm (assets/bots/urdf/tabletop_arm_4dof, a base yaw and
three pitch joints, see its README), builds it with robotics.create_bot, prints its links, joints
and DOFs, then sets a joint configuration and prints where every link is (world frame), in
particular the tool at the end of the chain. Those poses are the arm's forward kinematics, computed
by the engine from the URDF's joint origins and axes.

Run it with

    uv run python superdex_robotics/examples/basic/example_urdf_loading.py [--urdf path/to/robot.urdf] \
        [--pose 0.5 0.4 0.8 -0.3]

--pose gives the joint angles (rad) in DOF order; the default is a bent pose of the bundled arm.
Add --debugger --seconds 2 to watch the arm in the scene debugger afterwards (its joints are free:
it falls from that pose under gravity); without a display, also set SUPERDEX_DEBUGGER_RECORD=arm.jsonl
to record the run to a file.
"""

import argparse

import numpy as np

import superdex.physics as physics
import superdex.robotics as robotics

DEFAULT_URDF_ASSET = "bots/urdf/tabletop_arm_4dof/tabletop_arm_4dof.urdf"
DEFAULT_POSE = [0.5, 0.4, 0.8, -0.3]  # rad: base yaw, shoulder, elbow, wrist


def get_default_urdf_path() -> str:
    return str(physics.paths.resolve_asset(DEFAULT_URDF_ASSET))


def link_poses(actor) -> list[tuple[np.ndarray, np.ndarray]]:
    """(position [3], quaternion [x, y, z, w]) of every link in the world, link order."""
    xforms = physics.DynamicArrayTransformRT(len(actor.get_nested_link_actors()))
    actor.get_articulated_link_transforms(xforms)
    return [(np.array(xforms[i].translation, dtype=np.float64), np.array(xforms[i].rotation, dtype=np.float64))
            for i in range(len(xforms))]


def run(urdf_path: str | None = None, pose=None, seconds: float = 0.0, dt: float = 0.002, debugger: bool = False) -> dict:
    """Loads the URDF, builds the bot, sets `pose` (joint angles in DOF order; default DEFAULT_POSE
    for the bundled arm, zeros otherwise) and returns the names, joint types, DOF layout and the
    world pose of every link at that configuration. Then simulates `seconds` with the joints free."""
    urdf_path = urdf_path or get_default_urdf_path()
    physics.initialize(num_worker_threads=0)
    try:
        scene = physics.create_scene("URDF loading example")
        scene.set_gravity([0, 0, -9.81])
        prefab = robotics.load_bot_prefab_from_urdf_file(urdf_path, fixed_base=True)
        bot = robotics.create_bot(scene, prefab, robotics.create_context())
        try:
            actor = bot.get_articulated_actor()
            info = actor.get_articulated_shape_info()
            num_dofs = actor.get_num_dofs()
            if pose is None:
                pose = DEFAULT_POSE if urdf_path == get_default_urdf_path() else [0.0] * num_dofs
            if len(pose) != num_dofs:
                raise ValueError(f"--pose: the robot has {num_dofs} DOFs, got {len(pose)} values")
            actor.set_articulated_pose_from_joints(list(pose))
            joints = []
            for joint in prefab.joints:
                entry = {"name": joint.name, "type": str(joint.type).split(".")[-1].capitalize(),
                         "axis": np.array(joint.axis, dtype=np.float64), "effort_limit": joint.effort_limit}
                if joint.min_limit is not None:
                    entry["limits"] = (float(np.dot(joint.axis, joint.min_limit)), float(np.dot(joint.axis, joint.max_limit)))
                joints.append(entry)
            result = {
                "path": urdf_path,
                "name": prefab.name,
                "link_names": list(info.link_names),
                "joint_names": list(info.joint_names),
                "joints": joints,
                "masses": [link.mass for link in prefab.links],
                "dofs_per_joint": [(int(d.offset), int(d.get_size())) for d in info.dof_info],
                "num_dofs": num_dofs,
                "pose": np.array(actor.get_articulated_pose(), dtype=np.float64),
                "link_poses": link_poses(actor),
            }
            if debugger:
                physics.debugger.attach()
            for _ in range(int(round(seconds / dt))):
                scene.step(dt)
        finally:
            robotics.destroy_bot(scene, bot)
        return result
    finally:
        if debugger:
            physics.debugger.detach()
        physics.shutdown()


def print_summary(result: dict) -> None:
    print(f"robot '{result['name']}' from {result['path']}")
    print(f"{len(result['link_names'])} links, {len(result['joint_names'])} joints, {result['num_dofs']} DOFs")
    print(f"\n{'link':<12} {'mass [kg]':>9}   joint to its parent")
    for link, mass, joint, (first, size) in zip(result["link_names"], result["masses"], result["joints"],
                                                result["dofs_per_joint"]):
        text = f"{joint['name']} ({joint['type']}"
        if size:
            text += f", DOF {first}, axis {np.array2string(joint['axis'], precision=2)}"
            if "limits" in joint:
                text += f", limits [{joint['limits'][0]:+.2f}, {joint['limits'][1]:+.2f}] rad"
            if joint["effort_limit"] > 0:
                text += f", effort {joint['effort_limit']:g} N m"
        print(f"{link:<12} {mass:9.3f}   {text})")
    print(f"\nforward kinematics at q = {np.array2string(result['pose'], precision=3)} rad:")
    print(f"{'link':<12} {'position [m]':>26}   {'orientation [x, y, z, w]':>34}")
    for link, (p, q) in zip(result["link_names"], result["link_poses"]):
        print(f"{link:<12} {np.array2string(p, precision=4, floatmode='fixed', sign=' '):>26}   "
              f"{np.array2string(q, precision=4, floatmode='fixed', sign=' '):>34}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--urdf", default=None, help="a URDF file (default: the bundled 4-DOF arm)")
    parser.add_argument("--pose", type=float, nargs="+", default=None, help="joint angles (rad), DOF order")
    parser.add_argument("--seconds", type=float, default=0.0, help="simulated time afterwards (s)")
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    try:
        result = run(args.urdf, args.pose, args.seconds, debugger=args.debugger)
    except ValueError as error:
        parser.error(str(error))
    print_summary(result)


if __name__ == "__main__":
    main()
