"""Built-in controllers driving a Panda-like 7-DOF arm through the bot pipeline only.

No Python loop other than scene.step: the controllers are created on the bot, configured at
run time from Python, and run inside each step by the bot's pipeline, which applies their
efforts as the arm's external generalized forces (DOFs without an actuator take the commanded
effort directly).
"""

import numpy as np
import pytest

import superdex.physics as sdp
from pipeline_helpers import PANDA_READY, create_bot_from_json, link_pose, panda_bot_json, step
from robotics_helpers import scene  # noqa: F401
import superdex.robotics as sdr

# a target pose 0.3-0.5 rad away from the ready pose on every joint
TARGET = np.array(PANDA_READY) + np.array([0.3, 0.25, -0.3, 0.35, 0.4, -0.3, 0.5])


def make_panda(scene, tmp_path):
    return create_bot_from_json(scene, tmp_path, panda_bot_json())


def test_basic_jsc_pd_reaches_a_target_pose_within_1_mrad(scene, tmp_path):
    ctx, bot, arm = make_panda(scene, tmp_path)
    assert not bot.is_pipeline_active(), "no component takes part yet"
    jsc = bot.create_controller("BASIC_JSC_PD", "jsc", {"kp": 400.0, "kd": 40.0, "gravity_compensation": True})
    assert bot.is_pipeline_active(), "a pipeline-capable component switches the pipeline on"
    # the default target is the pose at creation: the arm holds still against gravity
    step(scene, 0.002, 50)
    np.testing.assert_allclose(arm.get_articulated_pose(), PANDA_READY, atol=1e-4)
    # run-time configuration from Python
    ctx.configure_controller(jsc, {"target_pose": TARGET})
    step(scene, 0.002, 1250)  # 2.5 s: kp/kd = 10/s, well damped on every joint
    error = np.abs(arm.get_articulated_pose() - TARGET)
    assert error.max() < 1e-3, f"joint errors (rad): {error}"
    v = np.zeros(7, dtype=arm.get_articulated_pose().dtype)
    arm.get_articulated_joint_velocities(v)
    assert np.abs(v).max() < 1e-3


def test_basic_jsc_pd_saturation_and_deadband(scene, tmp_path):
    ctx, bot, arm = make_panda(scene, tmp_path)
    scene.set_gravity([0, 0, 0])
    jsc = bot.create_controller("BASIC_JSC_PD", "jsc", {"kp": 400.0, "kd": 40.0, "saturation": 5.0, "target_pose": TARGET.tolist()})
    scene.step(0.002)
    forces = arm.get_external_forces()
    # every DOF is 0.3 rad or more away: 400 N m/rad x 0.3 rad saturates at 5 N m
    np.testing.assert_allclose(np.abs(forces), 5.0, rtol=1e-6)
    # inside the deadband the position error counts as zero (and the arm is at rest here)
    arm.set_articulated_joint_velocities(np.zeros(7))
    ctx.configure_controller(jsc, {"deadband": 1.0})
    scene.step(0.002)
    np.testing.assert_allclose(arm.get_external_forces(), 0.0, atol=1e-9)
    with pytest.raises(sdp.Error, match=r"params.kp: expected 7 values"):
        ctx.configure_controller(jsc, {"kp": [1.0, 2.0]})
    with pytest.raises(sdp.Error, match=r"unknown parameter 'kpp'"):
        ctx.configure_controller(jsc, {"kpp": 1.0})


def test_basic_osc_pd_moves_the_end_effector_within_1_mm(scene, tmp_path):
    ctx, bot, arm = make_panda(scene, tmp_path)
    hand = 8
    p0, R0 = link_pose(arm, hand)
    # the base link is welded at the world origin: base frame = world frame
    target = p0 + np.array([0.1, -0.15, -0.1])
    osc = bot.create_controller(
        "BASIC_OSC_PD",
        "osc",
        {"base_link": "panda_link0", "end_effector_link": "panda_hand", "kp_p": 100.0, "kd_p": 20.0,
         "kp_r": 100.0, "kd_r": 20.0, "null_space_damping": 2.0, "max_position_error": 0.5},
    )
    ctx.configure_controller(osc, {"target_position": target})
    step(scene, 0.002, 1000)  # 2 s: critically damped at 10 rad/s in task space
    p, R = link_pose(arm, hand)
    assert np.linalg.norm(p - target) < 1e-3, f"end-effector error {np.linalg.norm(p - target)} m"
    # the orientation was held (target orientation: the one at creation)
    assert np.linalg.norm(R - R0) < 1e-3


def test_articulated_pose_tracks_stiffly_where_an_explicit_pd_diverges(scene, tmp_path):
    # dt sqrt(K / M_min) = 0.005 sqrt(1e5 / 0.106) ~ 4.9: an explicit PD is unstable (> 2)
    gains = {"stiffness": 1e5, "damping": 2e3}
    ctx, bot, arm = make_panda(scene, tmp_path)
    bot.create_controller("ARTICULATED_POSE", "pose", dict(gains, target_pose=TARGET.tolist()))
    step(scene, 0.005, 100)  # 0.5 s; the slowest implicit mode decays at about K/D = 50/s
    assert np.abs(arm.get_articulated_pose() - TARGET).max() < 1e-3

    explicit_scene = sdp.create_scene("explicit")
    explicit_scene.set_gravity([0, 0, -9.81])
    _, bot2, arm2 = make_panda(explicit_scene, tmp_path)
    bot2.create_controller("BASIC_JSC_PD", "jsc", {"kp": gains["stiffness"], "kd": gains["damping"],
                                                  "gravity_compensation": True, "target_pose": TARGET.tolist()})
    step(explicit_scene, 0.005, 5)
    assert np.abs(arm2.get_articulated_pose() - TARGET).max() > 1.0, "the explicit PD blows up at this stiffness"


def planar_arm_json() -> dict:
    """Two 0.3 m links turning about y, hanging from a welded base, and a tip welded at the end of
    the second: the tip moves in x-z only."""
    rod = {"mass": 1.0, "centerOfMass": [0, 0, -0.15], "momentOfInertia": [0.0075, 0, 0, 0.0075, 0, 0.0005]}
    return {
        "name": "planar",
        "links": [{"name": "base", "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01]},
                  dict(rod, name="upper", parentLink=0), dict(rod, name="lower", parentLink=1),
                  {"name": "tip", "parentLink": 2, "mass": 0.1, "momentOfInertia": [1e-4, 0, 0, 1e-4, 0, 1e-4]}],
        "joints": [{"name": "weld", "type": "Hard"},
                   {"name": "shoulder", "type": "Revolute", "axis": [0, 1, 0],
                    "parentLinkFromJoint": {"rotation": [0, 0, 0, 1], "translation": [0, 0, 1]}},
                   {"name": "elbow", "type": "Revolute", "axis": [0, 1, 0],
                    "parentLinkFromJoint": {"rotation": [0, 0, 0, 1], "translation": [0, 0, -0.3]}},
                   {"name": "tip_weld", "type": "Hard",
                    "parentLinkFromJoint": {"rotation": [0, 0, 0, 1], "translation": [0, 0, -0.3]}}],
        "defaultPose": [0.4, 0.8],
    }


def test_basic_osc_pd_position_only_on_a_planar_arm(scene, tmp_path):
    # a 3-row task of rank 2: the pseudo-inverse task inertia ignores the y direction
    ctx, bot, arm = create_bot_from_json(scene, tmp_path, planar_arm_json())
    p0, _ = link_pose(arm, 3)
    target = p0 + np.array([0.05, 0.0, 0.05])
    bot.create_controller("BASIC_OSC_PD", "osc", {"control_orientation": False, "kp_p": 100.0, "kd_p": 20.0,
                                                  "target_position": target.tolist()})
    step(scene, 0.002, 1000)
    assert np.linalg.norm(link_pose(arm, 3)[0] - target) < 1e-3


def test_articulated_pose_link_mode_reaches_a_point(scene, tmp_path):
    """ARTICULATED_POSE with "link": the planar arm's tip is driven (inside the solve) to a
    reachable point in its x-z plane within 1 mm, with gravity compensated."""
    import json

    path = tmp_path / "planar.superdex_bot"
    path.write_text(json.dumps(planar_arm_json()))
    ctx = sdr.create_context()
    bot = sdr.create_bot(scene, sdr.load_bot_prefab_from_file(str(path)), ctx)
    target = [0.35, 0.0, 0.6]
    bot.create_controller("ARTICULATED_POSE", "reach", {"link": "tip", "target_position": target,
                                                        "linear_stiffness": 2e3, "linear_damping": 150,
                                                        "angular_stiffness": 0, "angular_damping": 0})
    step(scene, 0.01, 300)
    tip = scene.get_actor(bot.get_articulated_actor().get_nested_link_actors()[-1])
    np.testing.assert_allclose(np.array(tip.get_root_transform().translation), target, atol=1e-3)
    with pytest.raises(sdp.Error, match="no link named 'hand'"):
        bot.create_controller("ARTICULATED_POSE", "bad", {"link": "hand"})
