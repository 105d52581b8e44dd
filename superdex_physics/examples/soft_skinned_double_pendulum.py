"""A double pendulum carrying a soft arm at its tip, which strikes a ball.

A soft-skinned actor: a skeleton of two box arms (0.25 m and 0.125 m) on revolute joints about z,
hanging from a pivot 0.5 m up, and a soft tetrahedral bar (0.1 m, Neo-Hookean, E = 15 kPa;
assets/samples/articulations_parts/soft.mochi.json) whose four constrained nodes are tied to the
lower arm's end. The bar is a full finite-element body in the same implicit solve as the arms: it
sags under its own weight, swings with the arms, pulls on them through its ties, and bends when it
strikes the ball resting on the ground. Contact between the bar and the arm it hangs from is off.

The script prints the actor's parts, then once per simulated second the joint angles, the bar's
lowest point and the force between bar and ball.

Run: uv run python superdex_physics/examples/soft_skinned_double_pendulum.py [--seconds 4] [--dt 0.005]

Add --debugger to watch it in the scene debugger; without a display, also set
SUPERDEX_DEBUGGER_RECORD=soft_arm.jsonl to record the run to a file.
"""

import argparse

import numpy as np

import superdex.physics as sdp
from superdex.physics.paths import resolve_asset

PIVOT_HEIGHT = 0.5                       # m: the arms' axis at rest, y = 0.5, z = 0, along +x
ARM_LENGTHS, ARM_WIDTH = (0.25, 0.125), 0.025  # m
ARM_DENSITY = 1000.0                     # kg/m^3
SOFT_YOUNGS_MODULUS, SOFT_DENSITY = 1.5e4, 500.0  # Pa, kg/m^3: 0.031 kg bar
BALL_RADIUS, BALL_DENSITY = 0.05, 500.0
BALL_POSITION = [0.05, BALL_RADIUS, 0.0]  # m: on the ground, in the bar's path
SOFT_ASSET = "samples/articulations_parts/soft.mochi.json"


def build(scene: sdp.Scene):
    """The soft-skinned pendulum, the ball and the ground; returns (pendulum, soft arm, ball)."""
    cube = str(resolve_asset("cube/cube_fine_mesh.mochi.json"))
    arms = [sdp.load_shape_from_file(file_path=cube, bake_scale=[length, ARM_WIDTH, ARM_WIDTH]) for length in ARM_LENGTHS]
    bar = sdp.load_shape_from_file(file_path=str(resolve_asset(SOFT_ASSET)))
    centred = sdp.TransformRT(translation=[0, -ARM_WIDTH / 2, -ARM_WIDTH / 2])
    skeleton = sdp.ArticulatedActorParams(name="soft_skinned_pendulum")
    skeleton.links = [sdp.ArticulatedLinkParams(name=name, parent_link=parent, parent_joint_from_link=centred, shape=shape,
                                                collider_type=sdp.ColliderType.BOX, layer="arms", density=ARM_DENSITY)
                      for name, parent, shape in (("upper_arm", -1, arms[0]), ("lower_arm", 0, arms[1]))]
    skeleton.joints = [
        sdp.ArticulatedJointParams(name="shoulder", type=sdp.ArticulatedJointType.REVOLUTE, axis=[0, 0, 1],
                                   parent_link_from_joint=sdp.TransformRT(translation=[0, PIVOT_HEIGHT, 0])),
        sdp.ArticulatedJointParams(name="elbow", type=sdp.ArticulatedJointType.REVOLUTE, axis=[0, 0, 1],
                                   parent_link_from_joint=sdp.TransformRT(translation=[ARM_LENGTHS[0], ARM_WIDTH / 2, ARM_WIDTH / 2])),
    ]
    material = sdp.SoftMaterialParams(type=sdp.SoftMaterialType.NEO_HOOKEAN, density=SOFT_DENSITY)
    material.neo_hookean.youngs_modulus = SOFT_YOUNGS_MODULUS
    soft = sdp.SoftActorParams(name="soft_arm", shape=bar, layer="soft", material=material)
    pendulum = scene.create_soft_skinned_actor(skeleton_params=skeleton, soft_params=[soft], soft_attach_links=["lower_arm"],
                                               enable_colliding_links=True)
    ball_shape = sdp.create_sphere_shape(center=[0, 0, 0], radius=BALL_RADIUS)
    ball = scene.create_rigid_actor(name="ball", layer="ball", shape=ball_shape, density=BALL_DENSITY,
                                    world_from_local=sdp.TransformRT(translation=BALL_POSITION))
    ground = sdp.create_plane_shape(normal=[0, 1, 0], distance=0)
    scene.create_rigid_actor(name="ground", layer="ground", shape=ground, is_static=True)
    for shape in (*arms, bar, ball_shape, ground):
        sdp.release_shape(shape)
    # the arms touch nothing; the bar touches the ball, not the ground
    for other in ("arms", "ball", "ground"):
        scene.enable_layer_contact_symmetric("arms", other, False)
    scene.enable_layer_contact_symmetric("soft", "ground", False)
    soft_arm = scene.get_actor(pendulum.get_nested_soft_actors()[0])
    return pendulum, soft_arm, ball


def run(seconds: float = 4.0, dt: float = 0.005, debugger: bool = False, print_every: float = 1.0) -> dict:
    """Steps the scene; returns the ball's positions and the bar-ball force magnitudes per step."""
    sdp.initialize(num_worker_threads=0)
    scene = sdp.create_scene("soft skinned double pendulum")
    pendulum, soft_arm, ball = build(scene)
    links = [scene.get_actor(h).get_name() for h in pendulum.get_nested_link_actors()]
    print(f"links {links}, soft parts ['{soft_arm.get_name()}'] ({soft_arm.get_mass():.3f} kg), "
          f"{pendulum.get_num_dofs()} joint DoFs")
    soft_arm.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    if debugger:
        sdp.debugger.attach()
    ball_positions, forces = [], []
    steps = int(round(seconds / dt))
    every = max(1, int(round(print_every / dt)))
    for k in range(steps):
        scene.step(dt)
        ball_positions.append(np.array(ball.get_root_transform().translation, dtype=np.float64))
        forces.append(float(np.linalg.norm(np.asarray(soft_arm.get_contact_force_from_actor_world(ball)))))
        if (k + 1) % every == 0:
            q = np.asarray(pendulum.get_articulated_pose())
            low = soft_arm.get_aabb_world().min[1]
            print(f"t={(k + 1) * dt:5.2f} s  joints {q.round(2)} rad  bar's lowest point y={low:.3f} m  "
                  f"force on the ball {forces[-1]:.2f} N")
    if debugger:
        sdp.debugger.detach()
    sdp.shutdown()
    return {"ball_positions": np.array(ball_positions), "forces": np.array(forces), "dt": dt}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seconds", type=float, default=4.0)
    parser.add_argument("--dt", type=float, default=0.005)
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    result = run(args.seconds, args.dt, debugger=args.debugger, print_every=max(args.seconds / 8, args.dt))
    moved = np.linalg.norm(result["ball_positions"][-1] - BALL_POSITION)
    print(f"the ball moved {moved:.3f} m; the largest bar-ball force was {result['forces'].max():.1f} N")


if __name__ == "__main__":
    main()
