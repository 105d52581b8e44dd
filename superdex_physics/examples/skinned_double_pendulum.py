"""A double pendulum wearing a skin that strikes a ball.

Two box arms hang from a pivot 0.5 m up on revolute joints about z. One triangle surface, a
square tube over both arms (assets/samples/articulations_parts/skin.mochi.json), is bound to the
two links by linear-blend skinning: nodes near the pivot follow the upper arm, nodes past the elbow
the lower arm, and the weights ramp across the elbow so that the tube bends with the joint. The skin
is colliding only: its nodes probe the ball, and each contact pushes on the links by the nodes'
weights. The arms' own box colliders are filtered out, so whatever strikes the ball is the skin.

Released horizontal, the arms swing down and the skin strikes the ball resting on the ground. The
script prints the skin's surface and bounds, then once per simulated second the joint angles, the
skin's lowest point and the force between skin and ball.

Run: uv run python superdex_physics/examples/skinned_double_pendulum.py [--seconds 4] [--dt 0.005]

Add --debugger to watch it in the scene debugger (the skin is drawn as a deforming surface); without
a display, also set SUPERDEX_DEBUGGER_RECORD=skin.jsonl to record the run to a file.
"""

import argparse

import numpy as np

import superdex.physics as sdp
from superdex.physics.paths import resolve_asset

PIVOT_HEIGHT = 0.5                     # m: the arms' axis, y = 0.5, z = 0, along +x at rest
ARM_LENGTH, ARM_WIDTH = 0.25, 0.025    # m
ARM_DENSITY = 1000.0                   # kg/m^3: 0.156 kg per arm
BALL_RADIUS, BALL_DENSITY = 0.05, 500.0
BALL_POSITION = [0.05, BALL_RADIUS, 0.0]  # m: on the ground, in the swinging skin's path
SKIN_ASSET = "samples/articulations_parts/skin.mochi.json"


def build(scene: sdp.Scene):
    """The skinned pendulum, the ball and the ground; returns (pendulum, ball)."""
    arm = sdp.load_shape_from_file(file_path=str(resolve_asset("cube/cube_fine_mesh.mochi.json")),
                                   bake_scale=[ARM_LENGTH, ARM_WIDTH, ARM_WIDTH])
    skin = sdp.load_shape_from_file(file_path=str(resolve_asset(SKIN_ASSET)))
    # the corner-anchored box spans [0, L] x [0, w] x [0, w]: centred on its joint in y and z
    centred = sdp.TransformRT(translation=[0, -ARM_WIDTH / 2, -ARM_WIDTH / 2])
    links = [sdp.ArticulatedLinkParams(name=name, parent_link=parent, parent_joint_from_link=centred, shape=arm,
                                       collider_type=sdp.ColliderType.BOX, layer="arms", density=ARM_DENSITY)
             for name, parent in (("upper_arm", -1), ("lower_arm", 0))]
    joints = [
        sdp.ArticulatedJointParams(name="shoulder", type=sdp.ArticulatedJointType.REVOLUTE, axis=[0, 0, 1],
                                   parent_link_from_joint=sdp.TransformRT(translation=[0, PIVOT_HEIGHT, 0])),
        # the elbow at the upper arm's far end, on its axis (the link frame is the box's corner)
        sdp.ArticulatedJointParams(name="elbow", type=sdp.ArticulatedJointType.REVOLUTE, axis=[0, 0, 1],
                                   parent_link_from_joint=sdp.TransformRT(translation=[ARM_LENGTH, ARM_WIDTH / 2, ARM_WIDTH / 2])),
    ]
    pendulum = scene.create_articulated_actor(name="skinned_pendulum", joints=joints, links=links,
                                              skin=sdp.ArticulatedSkinParams(shape=skin, layer="skin"))
    ball_shape = sdp.create_sphere_shape(center=[0, 0, 0], radius=BALL_RADIUS)
    ball = scene.create_rigid_actor(name="ball", layer="ball", shape=ball_shape, density=BALL_DENSITY,
                                    world_from_local=sdp.TransformRT(translation=BALL_POSITION))
    ground = sdp.create_plane_shape(normal=[0, 1, 0], distance=0)
    scene.create_rigid_actor(name="ground", layer="ground", shape=ground, is_static=True)
    for shape in (arm, skin, ball_shape, ground):
        sdp.release_shape(shape)
    # only the skin touches the ball; the arms touch nothing, the skin not the ground
    for other in ("arms", "skin", "ball", "ground"):
        scene.enable_layer_contact_symmetric("arms", other, False)
    scene.enable_layer_contact_symmetric("skin", "ground", False)
    return pendulum, ball


def describe_skin(pendulum: sdp.Actor) -> None:
    mesh = pendulum.get_surface_mesh()
    query = pendulum.register_query_and_compute(sdp.QueryType.SURFACE_NODE_POSITIONS)
    x = np.asarray(pendulum.get_surface_mesh_node_positions_local()).reshape(-1, 3)
    print(f"skin: {mesh.get_num_nodes()} nodes, {mesh.get_num_elements()} triangles, "
          f"x from {x[:, 0].min():.3f} to {x[:, 0].max():.3f} m")
    beyond_elbow = []
    pendulum.query_nodes_in_volume_local(sdp.Aabb(min=[ARM_LENGTH, 0.4, -0.1], max=[1.0, 0.6, 0.1]), True,
                                         lambda node, _p: beyond_elbow.append(node))
    print(f"skin nodes past the elbow: {len(beyond_elbow)}")
    pendulum.cancel_query(query)


def run(seconds: float = 4.0, dt: float = 0.005, debugger: bool = False, print_every: float = 1.0) -> dict:
    """Steps the scene; returns the ball's positions and the skin-ball force magnitudes per step."""
    sdp.initialize(num_worker_threads=0)
    scene = sdp.create_scene("skinned double pendulum")
    pendulum, ball = build(scene)
    describe_skin(pendulum)
    pendulum.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    if debugger:
        sdp.debugger.attach()
    ball_positions, forces = [], []
    steps = int(round(seconds / dt))
    every = max(1, int(round(print_every / dt)))
    for k in range(steps):
        scene.step(dt)
        ball_positions.append(np.array(ball.get_root_transform().translation, dtype=np.float64))
        forces.append(float(np.linalg.norm(np.asarray(pendulum.get_contact_force_from_actor_world(ball)))))
        if (k + 1) % every == 0:
            q = np.asarray(pendulum.get_articulated_pose())
            low = pendulum.get_aabb_world().min[1]
            print(f"t={(k + 1) * dt:5.2f} s  joints {q.round(2)} rad  skin's lowest point y={low:.3f} m  "
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
    print(f"the ball moved {moved:.3f} m; the largest skin-ball force was {result['forces'].max():.1f} N")


if __name__ == "__main__":
    main()
