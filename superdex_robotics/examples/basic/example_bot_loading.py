"""Loading a robot from a .superdex_bot file and looking at what it is made of.

A .superdex_bot file (JSON, FORMATS.md) lists a robot's links and joints, one joint per link
(joints[i] attaches links[i] to its parent), its default pose, and the sensors and actuators
declared on its links by type name. This example

1. loads the file into a BotPrefab (robotics.load_bot_prefab_from_file) and lists its links
   (parent, mass) and joints (type, axis, limits) as the file declares them;
2. builds the bot in a scene (robotics.create_bot) and lists what the engine made of it: the
   articulation's link and joint names, its degrees of freedom (DOFs: one per revolute or
   prismatic joint, none for a welded "Hard" joint) and their index ranges, the pose, and the
   world position of every link;
3. lists the declared components and which of them were built. create_bot builds a component
   only when its type is registered in the robotics context, either a built-in C++ type
   (BASIC_JSC_PD, IDEAL_PD, JOINT_STATE, ...) or a Python class registered with
   robotics.register_python_sensor/actuator/controller. A declared type that nobody registered
   is skipped with a warning; this example collects those warnings and lists the skipped ones.
   (The default bot declares the seed example's Python components, which only
   superdex_robotics/examples/advanced/example_custom_components.py registers.)

Run it with

    uv run python superdex_robotics/examples/basic/example_bot_loading.py [path/to/robot.superdex_bot]

Without a path it loads assets/bots/fun/example_bot_2dof/example_bot_2dof.superdex_bot. Add
--debugger --seconds 2 to watch the bot in the scene debugger (it hangs under gravity with its
joints free); without a display, also set SUPERDEX_DEBUGGER_RECORD=bot.jsonl to record to a file.
"""

import argparse
import warnings

import numpy as np

import superdex.physics as physics
import superdex.robotics as robotics

DEFAULT_BOT_ASSET = "bots/fun/example_bot_2dof/example_bot_2dof.superdex_bot"


def get_default_bot_path() -> str:
    return str(physics.paths.resolve_asset(DEFAULT_BOT_ASSET))


def joint_type_name(joint_type) -> str:
    return str(joint_type).split(".")[-1].capitalize()


def describe_prefab(prefab) -> dict:
    """What the file declares, read from the BotPrefab."""
    links = [{"name": link.name, "parent": link.parent_link, "mass": link.mass} for link in prefab.links]
    joints = []
    for joint in prefab.joints:
        entry = {"name": joint.name, "type": joint_type_name(joint.type), "axis": np.array(joint.axis, dtype=float)}
        if joint.min_limit is not None:
            entry["limits"] = (float(np.dot(joint.axis, joint.min_limit)), float(np.dot(joint.axis, joint.max_limit)))
        joints.append(entry)
    components = []
    for kind, per_link in (("sensor", prefab.sensors), ("actuator", prefab.actuators)):
        for link_index, declared in enumerate(per_link):
            for decl in declared:
                components.append({"kind": kind, "type": decl.type, "name": decl.name,
                                   "link": prefab.links[link_index].name})
    return {"name": prefab.name, "links": links, "joints": joints, "components": components,
            "default_pose": np.array(prefab.default_pose, dtype=float)}


def describe_bot(scene, bot) -> dict:
    """What create_bot built: the articulation's structure, DOFs, pose and link positions."""
    actor = bot.get_articulated_actor()
    info = actor.get_articulated_shape_info()
    dofs = [(int(d.offset), int(d.get_size())) for d in info.dof_info]
    num_links = len(info.link_names)
    xforms = physics.DynamicArrayTransformRT(num_links)
    actor.get_articulated_link_transforms(xforms)
    return {
        "link_names": list(info.link_names),
        "joint_names": list(info.joint_names),
        "joint_types": [joint_type_name(t) for t in info.joint_types],
        "parents": list(info.parents),
        "dofs_per_joint": dofs,  # (first DOF index, number of DOFs) of each joint
        "num_dofs": actor.get_num_dofs(),
        "pose": np.array(actor.get_articulated_pose(), dtype=float),
        "link_positions": np.array([np.array(xforms[i].translation, dtype=float) for i in range(num_links)]),
        "num_sensors": len(bot.get_sensor_handles()),
        "num_actuators": len(bot.get_actuator_handles()),
    }


def built_component_names(bot, declared: list[dict]) -> list[str]:
    """The declared components that create_bot actually built (looked up by name on the bot)."""
    built = []
    for component in declared:
        find = bot.find_sensors_by_name if component["kind"] == "sensor" else bot.find_actuators_by_name
        if find(component["name"]):
            built.append(component["name"])
    return built


def run(bot_path: str | None = None, seconds: float = 0.0, dt: float = 0.004, debugger: bool = False) -> dict:
    """Loads the bot file, builds the bot, optionally simulates `seconds` (its joints are free, so it
    sags under gravity), and returns what describe_prefab and describe_bot found, the names of the
    components that were built, and the warnings create_bot gave for the skipped ones."""
    bot_path = bot_path or get_default_bot_path()
    physics.initialize(num_worker_threads=0)
    try:
        scene = physics.create_scene("Bot loading example")
        scene.set_gravity([0, 0, -9.81])
        prefab = robotics.load_bot_prefab_from_file(bot_path)
        declared = describe_prefab(prefab)
        context = robotics.create_context()
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            bot = robotics.create_bot(scene, prefab, context)
        skipped_warnings = [str(w.message) for w in caught]
        try:
            built = describe_bot(scene, bot)
            built_names = built_component_names(bot, declared["components"])
            if debugger:
                physics.debugger.attach()
            for _ in range(int(round(seconds / dt))):
                scene.step(dt)
            final_pose = np.array(bot.get_articulated_actor().get_articulated_pose(), dtype=float)
        finally:
            robotics.destroy_bot(scene, bot)
        return {"path": bot_path, "declared": declared, "built": built, "built_components": built_names,
                "warnings": skipped_warnings, "final_pose": final_pose}
    finally:
        if debugger:
            physics.debugger.detach()
        physics.shutdown()


def print_summary(result: dict) -> None:
    declared, built = result["declared"], result["built"]
    print(f"bot '{declared['name']}' from {result['path']}")
    print(f"\nlinks ({len(declared['links'])}):")
    for i, link in enumerate(declared["links"]):
        parent = "-" if link["parent"] is None or link["parent"] < 0 else declared["links"][link["parent"]]["name"]
        position = np.array2string(built["link_positions"][i], precision=3, floatmode="fixed", sign=" ")
        print(f"  {i}: {link['name']:<12} parent {parent:<12} mass {link['mass']:.3f} kg   at {position} m")
    print(f"\njoints ({len(declared['joints'])}):")
    for i, joint in enumerate(declared["joints"]):
        first, size = built["dofs_per_joint"][i]
        dofs = f"DOF {first}" if size == 1 else ("no DOF" if size == 0 else f"DOFs {first}..{first + size - 1}")
        limits = f"  limits [{joint['limits'][0]:+.3f}, {joint['limits'][1]:+.3f}]" if "limits" in joint else ""
        axis = f"  axis {np.array2string(joint['axis'], precision=1)}" if size else ""
        print(f"  {i}: {joint['name']:<12} {joint['type']:<10} {dofs:<8}{axis}{limits}".rstrip())
    pose = np.array2string(built["pose"], precision=3)
    print(f"\nDOFs: {built['num_dofs']}; pose after create_bot (the file's defaultPose): {pose}")
    print(f"\ndeclared components ({len(declared['components'])}):")
    for c in declared["components"]:
        state = "built" if c["name"] in result["built_components"] else "skipped (type not registered)"
        print(f"  {c['kind']:<8} {c['name']:<14} type {c['type']:<28} on {c['link']:<10} {state}")
    if result["warnings"]:
        print("\ncreate_bot said:")
        for message in result["warnings"]:
            print(f"  {message}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("bot_path", nargs="?", default=None, help="a .superdex_bot file (default: the example 2-DOF bot)")
    parser.add_argument("--seconds", type=float, default=0.0, help="simulated time after loading (s)")
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    print_summary(run(args.bot_path, args.seconds, debugger=args.debugger))


if __name__ == "__main__":
    main()
