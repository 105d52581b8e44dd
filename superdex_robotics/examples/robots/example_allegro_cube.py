"""The Allegro hand holding a cube, palm up, under joint PD.

The right Allegro hand of example-robot-data (16 joints; its URDF gives every joint 3 N m s/rad of
damping and 5 to 10 N m of Coulomb friction) is welded to the world palm up, a 5 cm, 100 g cube is
set on its palm, and joint drives close the fingers around the cube while the thumb turns in
against its side. The example then holds for a few seconds and reports how far the cube slipped
relative to the palm.

Run it with

    uv run python superdex_robotics/examples/robots/example_allegro_cube.py [--seconds 5] [--curl 1.0]

Add --debugger to watch it in the scene debugger (with SUPERDEX_DEBUGGER_RECORD=allegro.jsonl and
no display, the run is recorded to a file).
"""

import argparse
import math

import numpy as np

import superdex.physics as physics
import superdex.robotics as robotics
from superdex.robot_files import example_robot_data_file

URDF_NAME = "robots/allegro_hand_description/urdf/allegro_right_hand.urdf"
PALM_SURFACE = 0.0111  # the palm's face along the palm link's +x (its normal), m
CUBE_HALF, CUBE_MASS = 0.025, 0.1  # m, kg
CUBE_ON_PALM = -0.045  # the cube's centre along the palm link's z (fingers point +z), m
THUMB = {12: 1.3, 13: 0.3, 14: 0.5, 15: 0.5}  # rad: turned in against the cube's side
KP, KD = 20.0, 0.5  # N m/rad, N m s/rad: above the joints' 5-10 N m friction


def run(seconds: float = 5.0, settle: float = 1.0, dt: float = 0.002, curl: float = 1.0, debugger: bool = False) -> dict:
    """Closes the hand on the cube for `settle` s, then holds for `seconds`; returns the cube's
    position in the palm's frame at every step of the hold (m) and the final joint positions."""
    physics.initialize(num_worker_threads=0)
    try:
        scene = physics.create_scene("Allegro holding a cube")
        scene.set_gravity([0, 0, -9.81])
        prefab = robotics.load_bot_prefab_from_urdf_file(example_robot_data_file(URDF_NAME), fixed_base=True)
        # palm up: the palm's normal (+x) turned onto the world's +z, the fingers towards -x
        prefab.world_from_root = physics.TransformRT(rotation=physics.Quaternion.from_axis_angle([0, 1, 0], -math.pi / 2))
        bot = robotics.create_bot(scene, prefab, robotics.create_context())
        hand = bot.get_articulated_actor()
        palm = scene.get_actor(hand.get_nested_link_actors()[0])
        # the cube on the palm, in the world: palm (x, y, z) is world (-z, y, x)
        start = [-CUBE_ON_PALM, 0.0, PALM_SURFACE + CUBE_HALF + 0.0005]
        cube = scene.create_rigid_actor(name="cube", shape=physics.create_box_shape(half_extents=[CUBE_HALF] * 3), mass=CUBE_MASS,
                                        world_from_local=physics.TransformRT(translation=start),
                                        contact=physics.ContactParams(coulomb_friction_coefficient=1.0))
        # index, middle and ring curl (no spread); the thumb turns in
        targets = dict(THUMB)
        for finger in (0, 4, 8):
            targets.update({finger: 0.0, finger + 1: curl, finger + 2: curl, finger + 3: curl})
        for dof, target in targets.items():
            hand.set_joint_drive(dof, stiffness=KP, damping=KD, target_position=target)
        if debugger:
            physics.debugger.attach()
        for _ in range(int(round(settle / dt))):
            scene.step(dt)
        in_palm = []
        for _ in range(int(round(seconds / dt))):
            scene.step(dt)
            X_WP, X_WC = palm.get_root_transform(), cube.get_root_transform()
            in_palm.append(np.array((X_WP.inverse() * X_WC).translation, dtype=np.float64))
        result = {"cube_in_palm": np.array(in_palm), "q": np.array(hand.get_articulated_pose(), dtype=np.float64),
                  "cube_height": float(cube.get_root_transform().translation[2])}
        robotics.destroy_bot(scene, bot)
        return result
    finally:
        if debugger:
            physics.debugger.detach()
        physics.shutdown()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=5.0, help="time to hold the cube (s)")
    parser.add_argument("--curl", type=float, default=1.0, help="finger joint targets (rad)")
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    r = run(args.seconds, curl=args.curl, debugger=args.debugger)
    path = r["cube_in_palm"]
    slip = np.linalg.norm(path - path[0], axis=1).max()
    print(f"held {args.seconds:g} s: the cube moved at most {slip * 1000:.3f} mm relative to the palm, "
          f"its centre {r['cube_height']:.4f} m above the palm link's origin (the palm's face is at {PALM_SURFACE} m)")
    print(f"finger joints {np.array2string(r['q'], precision=2)} rad")


if __name__ == "__main__":
    main()
