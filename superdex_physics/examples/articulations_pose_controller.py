"""The articulated pose controller driving a two-link arm that hangs from a cart on a rail.

The articulation, built from ArticulatedLinkParams and ArticulatedJointParams:

    housing (welded 1 m up) --prismatic along X--> cart --revolute about Y--> upper_arm
                                                       --revolute about Y--> lower_arm

The arms are boxes whose link frames sit at their centres (half their length below their
joints); at zero angle they hang along -Z. The controller (add_articulated_pose_controller) is a
set of implicit spring-dampers solved with the contacts; its gains are swapped at run time
(set_articulated_pose_controller_params), in three phases:

- 0-2 s, hybrid: joint tracking on the rail and the shoulder, link position and rotation
  tracking on lower_arm, all holding the rest pose (the arm sags a little under gravity);
- 2-5 s, joint only: every joint follows a smooth trajectory (the cart goes 0.2 m and back, the
  arm swings), set every step with set_articulated_target_pose (the controller infers the
  target's velocity from its motion between steps, so the damping does not hold it back);
- after 5 s, link only: only lower_arm is tracked, its target (centre of mass and rotation) on a
  circle in the arm's X-Z plane (the plane the arm moves in) whose radius grows smoothly from 0
  to 5 cm, its rotation kept; the cart and the shoulder follow through the arm. The first target
  is set with reset_articulated_target_link_transforms (at rest), later ones with
  set_articulated_target_link_transforms. The other links' targets (not tracked) come from the
  arm's inverse kinematics, so the target pose the controller reads off them is meaningful.

An ARTICULATED_CONTROLLER_FORCE query reports the generalized force the controller applied in
each step (N on the rail, N m on the hinges); the script prints it with the joint positions and
the tracking errors.

Run: uv run python superdex_physics/examples/articulations_pose_controller.py [--seconds 9] [--dt 0.005]

Add --debugger to watch it in the scene debugger; without a display, also set
SUPERDEX_DEBUGGER_RECORD=pose_controller.jsonl to record the run to a file (superdex.physics.debugger).
"""

import argparse
import math
from collections import Counter

import numpy as np

import superdex.physics as sdp

GRAVITY = 9.81                                # m/s^2
RAIL_HEIGHT = 1.0                             # m, the housing's weld
HOUSING_MASS, CART_MASS = 5.0, 1.0            # kg
HOUSING_HALF = [0.4, 0.03, 0.03]              # m, the rail
CART_HALF = [0.06, 0.05, 0.04]                # m
ARM_WIDTH = 0.04                              # m, the arms' square section
SHOULDER_OFFSET = 0.1                         # m, the arm hangs this far in front (+Y) of the rail
# (name, mass kg, length m) of the two arms, top to bottom
ARMS = [("upper_arm", 0.6, 0.4), ("lower_arm", 0.4, 0.3)]
LINK_NAMES = ["housing", "cart", "upper_arm", "lower_arm"]
LOWER_ARM = 3                                 # link index
REST_POSE = [0.0, 0.7, 0.5]                   # cart x (m), shoulder and elbow angles (rad)

HYBRID_END, JOINT_END = 2.0, 5.0              # s: the phases
RAIL_TRAVEL = 0.2                             # m, the cart's excursion in the joint phase
SHOULDER_SWING, ELBOW_SWING = 0.5, -0.3       # rad, the arm's swing in the joint phase
CIRCLE_RADIUS, CIRCLE_PERIOD = 0.05, 2.0      # m, s: lower_arm's target in the link phase
CIRCLE_RAMP = 1.5                             # s, the radius grows from 0 over this time

# gains (stiffness, damping): each joint about critically damped on the inertia it moves (rail
# 2 kg, shoulder 0.15 kg m^2, elbow 0.012 kg m^2), settling in a few hundredths of a second; the
# implicit spring-dampers are stable at any stiffness, so dt = 0.005 only has to resolve the
# motion. lower_arm's centre of mass drags the whole arm and the cart in the link phase (2 to 8 kg
# in effect): its damping is set for that.
RAIL_GAINS = (2000.0, 120.0)                  # N/m, N s/m
SHOULDER_GAINS = (200.0, 11.0)                # N m/rad, N m s/rad
ELBOW_GAINS = (100.0, 2.2)                    # N m/rad, N m s/rad
LINK_POS_GAINS = (2000.0, 150.0)              # N/m, N s/m (lower_arm's centre of mass)
LINK_ROT_GAINS = (50.0, 1.5)                  # N m/rad, N m s/rad (lower_arm's rotation)


def box_inertia(mass: float, half) -> list[float]:
    """Ixx, Ixy, Ixz, Iyy, Iyz, Izz of a solid box about its centre."""
    x, y, z = (2 * h for h in half)
    return [mass * (y * y + z * z) / 12, 0, 0, mass * (x * x + z * z) / 12, 0, mass * (x * x + y * y) / 12]


def arm_half(length: float) -> list[float]:
    return [ARM_WIDTH / 2, ARM_WIDTH / 2, length / 2]


def build(scene: sdp.Scene) -> sdp.Actor:
    """The ground and the cart with its arm, posed at REST_POSE."""
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape(normal=[0, 0, 1], distance=0), is_static=True)
    (_, _, upper_length), _ = ARMS

    def joint(name, type, axis=(0, 0, 0), at=(0, 0, 0)):
        return sdp.ArticulatedJointParams(name=name, type=type, axis=list(axis),
                                          parent_link_from_joint=sdp.TransformRT(translation=list(at)))

    links = [
        sdp.ArticulatedLinkParams(name="housing", mass=HOUSING_MASS, center_of_mass=[0, 0, 0],
                                  moment_of_inertia=box_inertia(HOUSING_MASS, HOUSING_HALF), shape=sdp.create_box_shape(HOUSING_HALF)),
        sdp.ArticulatedLinkParams(name="cart", parent_link=0, mass=CART_MASS, center_of_mass=[0, 0, 0],
                                  moment_of_inertia=box_inertia(CART_MASS, CART_HALF), shape=sdp.create_box_shape(CART_HALF)),
    ]
    # an arm's link frame is at its centre, half its length below its joint: its centre of mass
    # is the frame's origin, its box centred there
    for i, (name, mass, length) in enumerate(ARMS):
        links.append(sdp.ArticulatedLinkParams(
            name=name, parent_link=i + 1, parent_joint_from_link=sdp.TransformRT(translation=[0, 0, -length / 2]),
            mass=mass, center_of_mass=[0, 0, 0], moment_of_inertia=box_inertia(mass, arm_half(length)),
            shape=sdp.create_box_shape(arm_half(length))))
    joints = [
        joint("weld", sdp.ArticulatedJointType.HARD, at=[0, 0, RAIL_HEIGHT]),
        joint("rail", sdp.ArticulatedJointType.PRISMATIC, axis=[1, 0, 0]),
        joint("shoulder", sdp.ArticulatedJointType.REVOLUTE, axis=[0, 1, 0], at=[0, SHOULDER_OFFSET, 0]),
        # the upper arm's end: half its length below its centre
        joint("elbow", sdp.ArticulatedJointType.REVOLUTE, axis=[0, 1, 0], at=[0, 0, -upper_length / 2]),
    ]
    arm = scene.create_articulated_actor(name="cart_arm", links=links, joints=joints)
    # links joined by a joint never collide; keep the others from touching too
    link_actors = dict(zip(LINK_NAMES, arm.get_nested_link_actors()))
    for a, b in [("housing", "upper_arm"), ("housing", "lower_arm"), ("cart", "lower_arm")]:
        scene.enable_actor_contact_symmetric(link_actors[a], link_actors[b], False, sdp.IncludeNestedActors.NO)
    arm.set_articulated_pose_from_joints(REST_POSE)
    return arm


def tracking(stiffness_damping) -> sdp.PoseTrackingParams:
    stiffness, damping = stiffness_damping
    return sdp.PoseTrackingParams(stiffness=stiffness, damping=damping, saturation=-1)


def hybrid_gains() -> sdp.PoseControllerParams:
    """The rail and the shoulder by their joints, lower_arm by its centre of mass and rotation."""
    params = sdp.PoseControllerParams(len(LINK_NAMES))
    params.joint_tracking[1] = tracking(RAIL_GAINS)
    params.joint_tracking[2] = tracking(SHOULDER_GAINS)
    params.link_pos_tracking[LOWER_ARM] = tracking(LINK_POS_GAINS)
    params.link_rot_tracking[LOWER_ARM] = tracking(LINK_ROT_GAINS)
    return params


def joint_gains() -> sdp.PoseControllerParams:
    """Every joint by its target value, no link tracking."""
    params = sdp.PoseControllerParams(len(LINK_NAMES))
    for i, gains in ((1, RAIL_GAINS), (2, SHOULDER_GAINS), (3, ELBOW_GAINS)):
        params.joint_tracking[i] = tracking(gains)
    return params


def link_gains() -> sdp.PoseControllerParams:
    """lower_arm by its centre of mass and rotation only; the cart and the shoulder follow."""
    params = sdp.PoseControllerParams(len(LINK_NAMES))
    params.link_pos_tracking[LOWER_ARM] = tracking(LINK_POS_GAINS)
    params.link_rot_tracking[LOWER_ARM] = tracking(LINK_ROT_GAINS)
    return params


def joint_trajectory(t: float) -> np.ndarray:
    """The joint phase's target (m, rad): from REST_POSE and back to it, with zero velocity at both ends."""
    s = min(max((t - HYBRID_END) / (JOINT_END - HYBRID_END), 0.0), 1.0)
    bump = math.sin(math.pi * s) ** 2                              # 0 -> 1 -> 0
    swing = math.sin(2 * math.pi * s) * math.sin(math.pi * s)      # 0 -> + -> - -> 0
    return np.array(REST_POSE) + np.array([RAIL_TRAVEL * bump, SHOULDER_SWING * swing, ELBOW_SWING * bump])


def circle_offset(t: float) -> np.ndarray:
    """lower_arm's target centre of mass in the link phase, relative to where it rests (m, world):
    a circle in the X-Z plane, its radius growing smoothly (zero slope and curvature at both
    ends) from 0 to CIRCLE_RADIUS over CIRCLE_RAMP."""
    s = min(max((t - JOINT_END) / CIRCLE_RAMP, 0.0), 1.0)
    radius = CIRCLE_RADIUS * s**3 * (10 - 15 * s + 6 * s * s)
    w = 2 * math.pi / CIRCLE_PERIOD
    return radius * np.array([math.cos(w * (t - JOINT_END)), 0.0, math.sin(w * (t - JOINT_END))])


def vec(a) -> np.ndarray:
    return np.array(a, dtype=np.float64)  # a copy


def row(values, decimals: int = 4) -> str:
    return "[" + " ".join(f"{v:{decimals + 4}.{decimals}f}" for v in values) + "]"


def down(angle: float) -> np.ndarray:
    """Where a rotation by `angle` about +Y turns the arm's hanging direction -Z."""
    return np.array([-math.sin(angle), 0.0, -math.cos(angle)])


def link_frames(pose) -> list[sdp.TransformRT]:
    """World-from-link transforms of the four links at a pose (m, rad): the arm's planar forward
    kinematics (the arm's link frames are at its centres)."""
    x, shoulder, elbow = (float(v) for v in pose)
    (_, _, l1), (_, _, l2) = ARMS
    S = np.array([x, SHOULDER_OFFSET, RAIL_HEIGHT])  # the shoulder's axis
    y = sdp.Quaternion.from_axis_angle

    def frame(angle, at):
        return sdp.TransformRT(rotation=y([0, 1, 0], angle), translation=list(at))

    return [frame(0.0, [0, 0, RAIL_HEIGHT]), frame(0.0, [x, 0, RAIL_HEIGHT]), frame(shoulder, S + l1 / 2 * down(shoulder)),
            frame(shoulder + elbow, S + l1 * down(shoulder) + l2 / 2 * down(shoulder + elbow))]


def pose_placing_lower_arm(com, angle: float) -> np.ndarray:
    """The pose (m, rad) that puts lower_arm's centre of mass at `com` (world), turned by `angle`
    about +Y: the arm's inverse kinematics, on the branch with the shoulder turned towards +angle."""
    (_, _, l1), (_, _, l2) = ARMS
    elbow = vec(com) - l2 / 2 * down(angle)  # the elbow's axis
    shoulder = math.acos((RAIL_HEIGHT - elbow[2]) / l1)
    return np.array([elbow[0] + l1 * math.sin(shoulder), shoulder, angle - shoulder])


def run(seconds: float = 9.0, dt: float = 0.005, debugger: bool = False, print_every: float = 0.5) -> dict:
    """Steps the scene through the three phases. Returns, after every step, the time, the joint
    positions and their target, lower_arm's centre of mass and its target (world) and the
    controller's generalized force (float64 arrays, (steps,) and (steps, 3)), and the links'
    world-from-link transforms (translations (steps, 4, 3), rotations [x, y, z, w] (steps, 4, 4))."""
    sdp.initialize(num_worker_threads=0)
    scene = sdp.create_scene("articulations pose controller")
    scene.set_gravity([0, 0, -GRAVITY])
    arm = build(scene)
    arm.add_articulated_pose_controller(hybrid_gains())  # the target: the rest pose, at rest
    query = arm.register_query(sdp.QueryType.ARTICULATED_CONTROLLER_FORCE)
    kinds = Counter(str(c.type).split(".")[-1] for c in arm.get_articulated_pose_constraints())
    print(f"pose controller constraints: {dict(kinds)} (zero gains: inactive)")
    rest_com = vec(arm.get_articulated_target_link_transforms()[LOWER_ARM].translation)  # lower_arm's at rest (m, world)
    if debugger:
        sdp.debugger.attach()
    n = arm.get_num_dofs()
    target = np.zeros(n, dtype=arm.get_articulated_pose().dtype)
    first_link_target = False
    phase = "hybrid"
    print(f"t={0.0:6.3f} s: hybrid tracking, holding {REST_POSE}")
    out = {key: [] for key in ("t", "pose", "target_pose", "lower_arm_com", "lower_arm_target_com", "controller_force",
                               "link_translations", "link_rotations")}
    steps = int(round(seconds / dt))
    every = max(1, int(round(print_every / dt)))
    for k in range(steps):
        t = k * dt
        # the targets are for the end of this step, t + dt; a phase starts with the step that
        # ends after its start
        if phase == "hybrid" and t + dt > HYBRID_END + dt / 2:
            phase = "joint"
            arm.set_articulated_pose_controller_params(joint_gains())
            print(f"t={t:6.3f} s: joint tracking, cart {RAIL_TRAVEL} m and back, arm swinging")
        elif phase == "joint" and t + dt > JOINT_END + dt / 2:
            phase = "link"
            arm.set_articulated_pose_controller_params(link_gains())
            first_link_target = True
            print(f"t={t:6.3f} s: link tracking, lower_arm on a circle (radius up to {CIRCLE_RADIUS} m)")
        if phase == "joint":
            arm.set_articulated_target_pose(joint_trajectory(t + dt))
        elif phase == "link":
            # only lower_arm's target is tracked; the other links' targets, from the inverse
            # kinematics, make the target pose (their projection onto the joints) meaningful
            targets = link_frames(pose_placing_lower_arm(rest_com + circle_offset(t + dt), REST_POSE[1] + REST_POSE[2]))
            if first_link_target:  # the target jumps there, at rest
                arm.reset_articulated_target_link_transforms(targets)
                first_link_target = False
            else:  # the target moves there over the step
                arm.set_articulated_target_link_transforms(targets)
        scene.step(dt)

        X = arm.get_articulated_link_transforms()
        X_target = arm.get_articulated_target_link_transforms()
        arm.get_articulated_target_pose(target)
        # an arm's centre of mass is its link frame's origin
        out["t"].append(scene.get_total_simulation_time())
        out["pose"].append(vec(arm.get_articulated_pose()))
        out["target_pose"].append(vec(target))
        out["lower_arm_com"].append(vec(X[LOWER_ARM].translation))
        out["lower_arm_target_com"].append(vec(X_target[LOWER_ARM].translation))
        out["controller_force"].append(vec(arm.get_articulated_controller_force()))
        out["link_translations"].append([vec(x.translation) for x in X])
        out["link_rotations"].append([vec(x.rotation) for x in X])
        if (k + 1) % every == 0:
            q, q_target, f = out["pose"][-1], out["target_pose"][-1], out["controller_force"][-1]
            com_error = 1e3 * np.linalg.norm(out["lower_arm_com"][-1] - out["lower_arm_target_com"][-1])
            print(f"t={out['t'][-1]:6.3f} s  {phase:6}  q [m, rad] {row(q)}  q - target {row(q - q_target)}  "
                  f"lower_arm com error {com_error:5.2f} mm  controller force [N, N m] {row(f, 3)}")
    arm.cancel_query(query)
    if debugger:
        sdp.debugger.detach()
    sdp.shutdown()
    result = {key: np.array(values) for key, values in out.items()}
    result["dt"] = dt
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=9.0)
    parser.add_argument("--dt", type=float, default=0.005)
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    result = run(args.seconds, args.dt, debugger=args.debugger, print_every=max(args.seconds / 10, args.dt))
    error = 1e3 * np.linalg.norm(result["lower_arm_com"][-1] - result["lower_arm_target_com"][-1])
    print(f"joints at {row(result['pose'][-1])} after {args.seconds} s; lower_arm {error:.2f} mm from its target")


if __name__ == "__main__":
    main()
