"""Newton's method stops at the round-off floor of a float solve instead of repeating it.

The G1 humanoid (example-robot-data) dropped limp from a 0.8 m pelvis height onto the ground and
stepped for 1 s at 2 ms ends in a heap of links pressed against the ground and against each
other. In float, near-rigid contacts that stiff leave the momentum residual a round-off floor
that can lie above the solver's tolerance: without the stall test (within 100 times the
tolerance, three iterations in a row that do not halve the residual end the solve) such solves
ran into the 50-iteration limit, nine steps of this drop at 50 or more. With it no step needs
more than 40. In double the floor lies far below the tolerance and every step converges.
"""

import warnings

import numpy as np

import superdex.physics as sdp
import superdex.robotics as sdr
from superdex.robot_files import example_robot_data_file
from robotics_helpers import ground_scene, scene  # noqa: F401 (fixtures)

G1 = "robots/g1_description/urdf/g1_29dof_rev_1_0.urdf"


def test_a_heap_of_g1_links_settles_without_grinding_at_the_round_off_floor(ground_scene):
    scene = ground_scene
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the G1's meshes are repaired, with warnings
        prefab = sdr.load_bot_prefab_from_urdf_file(str(example_robot_data_file(G1)), fixed_base=False)
    robot = sdr.create_bot(scene, prefab, sdr.create_context()).get_articulated_actor()
    pose = [0.0] * robot.get_num_dofs()
    pose[2] = 0.8
    robot.set_articulated_pose_from_joints(pose)
    iterations, statuses = [], []
    for _ in range(500):
        scene.step(0.002)
        stats = scene.get_solver_stats()
        iterations.append(stats.max_non_linear_iters)
        statuses.append(stats.convergence_status)
    pelvis = robot.get_articulated_link_transforms()[0].translation
    assert np.all(np.isfinite(pelvis)) and pelvis[2] < 0.4, "the G1 fell into a heap"
    assert sdp.ConvergenceStatus.DIVERGED not in statuses
    if sdp.uses_double_precision():
        assert all(s == sdp.ConvergenceStatus.CONVERGED for s in statuses)
    else:
        assert max(iterations) <= 40, sorted(iterations)[-10:]
