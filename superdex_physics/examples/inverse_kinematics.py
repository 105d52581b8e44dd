"""Inverse kinematics on a five-link arm of mixed joints, with the experimental IK solver.

The arm is the asset articulated/mixed/mixed_articulation.mochi_prefab, added at twice its size:
five 0.2 m boxes in a chain along +X, joined by a free, a revolute, a prismatic, a spherical and a
revolute joint. Its free base is pinned at its +X end to the world origin by two stiff pivot
constraints (position and rotation); without them the solver would reach a target by moving the
whole arm instead of bending it.

experimental.create_ik_solver(scene) takes the scene over: a target on a link is a stiff pivot
constraint of that scene, and solve_ik() poses the arm where the energy of all the scene's
constraints is least (damped Gauss-Newton on the joint positions, joint limits held). The script
goes through a fixed list of targets for the end effector, each alone: a position for its tip
(the +X end of its box), then a rotation (a rotation vector, rad), and so on. For each it prints
whether the solve converged, whether the target was reached within the thresholds, and the
remaining error.

Run: uv run python superdex_physics/examples/inverse_kinematics.py [--targets 8]

Add --debugger to watch each solution in the scene debugger (solve_ik shows it there, as a step
would); without a display, also set SUPERDEX_DEBUGGER_RECORD=ik.jsonl to record the solutions.
"""

import argparse
import math

import numpy as np

import superdex.physics as sdp
from superdex.physics.paths import resolve_asset, resolve_asset_root

PREFAB = "articulated/mixed/mixed_articulation.mochi_prefab"
SCALE = 2.0                            # the arm at twice the asset's size: 0.2 m links
PIN_LOCAL = [0.1, 0.0, 0.0]            # m, the base's +X end (base frame), pinned to the origin
PIN_STIFFNESS = 1e4                    # N/m and N m/rad
TIP_LOCAL = [0.1, 0.0, 0.0]            # m, the end effector's tip (its frame is the box's centre)
TARGET_WEIGHT = 1.0                    # the targets' stiffness, N/m or N m/rad
POSITION_TOLERANCE = 1e-4              # m: a position target within this is reached
ROTATION_TOLERANCE = 1e-3              # rad
# the end effector's targets, in turn: ("position", world point m) or ("rotation", rotation vector rad)
TARGETS = [
    ("position", [0.4, -0.35, 0.2]),
    ("rotation", [0.3, -0.2, 0.4]),
    ("position", [0.55, 0.3, 0.15]),
    ("rotation", [0.0, 0.0, 1.2]),
    ("position", [0.3, 0.4, -0.2]),
    ("rotation", [-0.5, 0.3, 0.0]),
    ("position", [0.6, -0.1, -0.3]),
    ("rotation", [0.0, 0.8, -0.3]),
]


def quaternion_angle(q_a, q_b) -> float:
    """The angle (rad) of the rotation between two unit quaternions [x, y, z, w]."""
    d = abs(float(np.dot(np.asarray(q_a, dtype=float), np.asarray(q_b, dtype=float))))
    return 2.0 * math.acos(min(1.0, d))


def rotation_matrix(q) -> np.ndarray:
    """The rotation matrix of a unit quaternion [x, y, z, w]."""
    x, y, z, w = (float(v) for v in q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def build(scene):
    """Adds the arm and pins its base; returns (arm, base link, end-effector link) handles."""
    scene.set_gravity([0, 0, 0])
    result = sdp.prefab.add_to_scene(prefab_path=str(resolve_asset(PREFAB)), root_path=str(resolve_asset_root(PREFAB)),
                                     scene=scene, params=sdp.prefab.PrefabParams(scale=SCALE))
    arm = result.actors[0]
    # the boxes overlap at the joints: they must not push each other apart
    scene.enable_layer_contact_symmetric("RigidLink", "RigidLink", enable=False)
    links = arm.get_nested_link_actors()
    base, tip = links[0], links[len(links) - 1]
    scene.create_rigid_pivot_position_constraint(sdp.RigidPivotPositionConstraintParams(
        actor=base, local_position=PIN_LOCAL, target_position=[0, 0, 0], stiffness=PIN_STIFFNESS))
    scene.create_rigid_pivot_rotation_constraint(sdp.RigidPivotRotationConstraintParams(
        actor=base, local_rotation=[0, 0, 0], target_rotation=[0, 0, 0], stiffness=PIN_STIFFNESS))
    return arm, base, tip


def run(num_targets=len(TARGETS), on_solve=None, debugger=False):
    """Solves the first num_targets targets in turn (cycling through TARGETS); returns one dict
    per solve: kind, target, reached, converged, error (m or rad), iterations. on_solve(index,
    scene, base_handle, tip_handle) is called after each solve."""
    sdp.initialize(num_worker_threads=0)
    scene = sdp.create_scene("Inverse kinematics")
    arm, base, tip = build(scene)
    solver = sdp.experimental.create_ik_solver(scene)
    params = solver.get_solver_params()
    params.max_iter = 500
    params.abs_tol = 1e-6  # N or N m: far below what the thresholds need of the targets' unit stiffness
    params.position_error_thres, params.rotation_error_thres = POSITION_TOLERANCE, ROTATION_TOLERANCE
    solver.set_solver_params(params)
    if debugger:
        sdp.debugger.attach()

    results = []
    for i in range(num_targets):
        if debugger and not sdp.debugger.is_attached():
            break
        kind, goal = TARGETS[i % len(TARGETS)]
        solver.clear_position_target(tip)
        solver.clear_rotation_target(tip)
        if kind == "position":
            solver.create_position_target(tip, TIP_LOCAL, goal, TARGET_WEIGHT)
        else:
            solver.create_rotation_target(tip, [0, 0, 0], goal, TARGET_WEIGHT)
        reached = solver.solve_ik()
        stats = scene.get_solver_stats()
        X = scene.get_actor(tip).get_root_transform()
        if kind == "position":
            at = np.asarray(X.translation, dtype=float) + rotation_matrix(X.rotation) @ np.array(TIP_LOCAL)
            error = float(np.linalg.norm(at - np.array(goal)))
        else:
            g = np.array(goal, dtype=float)
            want = sdp.Quaternion.from_axis_angle(list(g / np.linalg.norm(g)), float(np.linalg.norm(g)))
            error = quaternion_angle(list(X.rotation), list(want))
        results.append({"kind": kind, "target": goal, "reached": reached, "error": error,
                        "converged": stats.convergence_status == sdp.ConvergenceStatus.CONVERGED,
                        "iterations": stats.total_non_linear_iters})
        print(f"solve {i + 1}: {kind} target {goal}: {'reached' if reached else 'not reached'}, error "
              f"{error:.2e} {'m' if kind == 'position' else 'rad'}, {stats.total_non_linear_iters} iterations "
              f"({stats.convergence_status.name.lower()})")
        if on_solve:
            on_solve(i, scene, base, tip)

    if debugger:
        sdp.debugger.detach()
    sdp.experimental.destroy_ik_solver(solver)  # destroys its scene too
    sdp.shutdown()
    reached = sum(r["reached"] for r in results)
    print(f"{reached} of {len(results)} targets reached")
    return results


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--targets", type=int, default=len(TARGETS), help="how many targets to solve for")
    parser.add_argument("--debugger", action="store_true", help="show each solution in the scene debugger")
    args = parser.parse_args()
    run(args.targets, debugger=args.debugger)


if __name__ == "__main__":
    main()
