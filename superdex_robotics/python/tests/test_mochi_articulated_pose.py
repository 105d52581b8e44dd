"""MOCHI_ARTICULATED_POSE: the engine's pose controller on a bot, aimed by compute_output.

- Joint targets (pose_dofs): the Panda-like arm settles where each joint spring balances
  gravity, K (q* - q) = g(q), with g(q) the arm's gravity torques (get_articulated_bias_forces at
  rest, checked against Pinocchio by the physics tests), within 1e-6 of K's scale.
- Link targets (local_to_parent_transforms): the transforms of a posed twin give the same
  target pose as its joint values.
- Params round-trip through .superdex_controller JSON and set the engine controller's gains;
  errors name what is wrong; the engine controller goes with the component.
"""

import json

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from pipeline_helpers import PANDA_READY, create_bot_from_json, panda_bot_json, step
from robotics_helpers import scene  # noqa: F401

TARGET = np.array(PANDA_READY) + np.array([0.2, 0.15, -0.2, 0.25, 0.3, -0.2, 0.3])
K, D = 2000.0, 80.0


def joint_gains(num_links: int) -> sdr.ControllerMochiArticulatedPoseParams:
    pose = sdp.PoseControllerParams(num_links)
    for i in range(1, num_links - 1):  # the seven revolute joints (the base and hand are welded)
        pose.joint_tracking[i] = sdp.PoseTrackingParams(stiffness=K, damping=D)
    return sdr.ControllerMochiArticulatedPoseParams(pose_controller_params=pose)


def make(scene, tmp_path):
    ctx, bot, arm = create_bot_from_json(scene, tmp_path, panda_bot_json())
    handle = bot.create_controller("MOCHI_ARTICULATED_POSE", "pose")
    controller = ctx.get_controller(handle)
    assert isinstance(controller, sdr.ControllerMochiArticulatedPose)
    return ctx, bot, arm, controller, handle


def test_joint_targets_settle_where_the_springs_balance_gravity(scene, tmp_path):
    ctx, bot, arm, controller, handle = make(scene, tmp_path)
    num_links = len(arm.get_nested_link_actors())
    controller.set_params(joint_gains(num_links))
    controller.initialize(True)
    assert arm.has_articulated_pose_controller()
    target = sdr.ControllerMochiArticulatedPoseTarget(world_from_root=arm.get_root_transform(), pose_dofs=TARGET.tolist())
    for _ in range(600):
        controller.compute_output(sdr.ControllerMochiArticulatedPoseObsv(), target)
        scene.step(0.005)
    q = np.asarray(arm.get_articulated_pose(), dtype=float)
    np.testing.assert_allclose(arm.get_articulated_target_pose(), TARGET, atol=1e-9 if sdp.uses_double_precision() else 1e-5)
    # at rest the bias forces are the gravity torques: the springs hold them
    arm.set_articulated_joint_velocities(np.zeros(q.size))
    gravity = np.asarray(arm.get_articulated_bias_forces(), dtype=float)
    np.testing.assert_allclose(K * (TARGET - q), gravity, atol=1e-6 * K if sdp.uses_double_precision() else 1e-3 * K)
    assert np.abs(TARGET - q).max() > 1e-3  # gravity visibly sags it


def test_link_transform_targets_give_the_twin_pose(scene, tmp_path):
    ctx, bot, arm, controller, handle = make(scene, tmp_path)
    twin_scene = sdp.create_scene("twin")
    _, _, twin = create_bot_from_json(twin_scene, tmp_path, panda_bot_json(), "twin.superdex_bot")
    twin.set_articulated_pose_from_joints(TARGET)
    world = twin.get_articulated_link_transforms()
    parents = list(twin.get_articulated_shape_info().parents)
    local = [world[i] if p < 0 else world[p].inverse() * world[i] for i, p in enumerate(parents)]
    controller.set_params(joint_gains(len(parents)))
    controller.initialize(False)
    target = sdr.ControllerMochiArticulatedPoseTarget(world_from_root=sdp.TransformRT(), local_to_parent_transforms=local)
    controller.compute_output(sdr.ControllerMochiArticulatedPoseObsv(), target)
    np.testing.assert_allclose(arm.get_articulated_target_pose(), TARGET, atol=1e-9 if sdp.uses_double_precision() else 1e-4)
    sdp.destroy_scene(twin_scene)


def test_params_json_gains_errors_and_removal(scene, tmp_path):
    ctx, bot, arm, controller, handle = make(scene, tmp_path)
    num_links = len(arm.get_nested_link_actors())
    params = joint_gains(num_links)
    path = tmp_path / "pose.superdex_controller"
    params.save_to_file(str(path))
    doc = json.loads(path.read_text())
    assert doc["poseControllerParams"]["jointTracking"][1] == {"stiffness": K, "damping": D, "saturation": -1.0}
    assert sdr.ControllerMochiArticulatedPoseParams.load_from_file(str(path)) == params
    bad = tmp_path / "bad.superdex_controller"
    bad.write_text('{"poseControllerParams": {"jointTracking": [{"stifness": 1}]}}')
    with pytest.raises(sdp.Error, match="jointTracking\\[0\\].stifness: unknown key"):
        sdr.ControllerMochiArticulatedPoseParams.load_from_file(str(bad))
    with pytest.raises(sdp.Error, match="call initialize"):
        controller.compute_output(sdr.ControllerMochiArticulatedPoseObsv(), sdr.ControllerMochiArticulatedPoseTarget(pose_dofs=TARGET.tolist()))
    # without params: zero gains on every link's position and rotation
    controller.initialize()
    gains = sdp.PoseControllerParams(num_links)
    arm.get_articulated_pose_controller_params(gains)
    assert all(g.stiffness == 0 for g in gains.link_pos_tracking)
    with pytest.raises(sdp.Error, match="remove_existing"):
        controller.initialize(False)
    # set_params reaches the live engine controller
    controller.set_params(params)
    arm.get_articulated_pose_controller_params(gains)
    assert [g.stiffness for g in gains.joint_tracking] == [0.0] + [K] * 7 + [0.0]
    with pytest.raises(sdp.Error, match="exactly one"):
        controller.compute_output(sdr.ControllerMochiArticulatedPoseObsv(), sdr.ControllerMochiArticulatedPoseTarget())
    with pytest.raises(sdp.Error, match="the 7 DOFs below the root"):
        controller.compute_output(sdr.ControllerMochiArticulatedPoseObsv(), sdr.ControllerMochiArticulatedPoseTarget(pose_dofs=[0.0]))
    # the engine controller goes with the component
    ctx.destroy_controller(handle)
    assert not arm.has_articulated_pose_controller()


def test_configured_from_a_scene_entry(scene, tmp_path):
    ctx, bot, arm, controller, handle = make(scene, tmp_path)
    num_links = len(arm.get_nested_link_actors())
    controller.configure_from_scene_entry('{"poseControllerParams": {"jointTracking": [{"stiffness": 5, "damping": 1}]}}', "")
    gains = sdp.PoseControllerParams(num_links)
    arm.get_articulated_pose_controller_params(gains)
    # one entry for every joint with DOFs; the welds have none
    assert [g.stiffness for g in gains.joint_tracking] == [0.0] + [5.0] * 7 + [0.0]
