"""Built-in sensors against analytic expectations, updated by the pipeline after each step.

CONTACT_FORCE of links resting on a table reads their weight; JOINT_STATE equals the engine's
joint state, and its noise has the configured statistics; an IMU at rest reads the specific
force +g (up) and in free fall reads zero; FORCE_TORQUE of a hanging link reads the weight of
what it carries, of a cantilever the moment of its weight, and about a driven joint's axis the
joint's torque.
"""

import json
import math

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from pipeline_helpers import IDENTITY, PANDA_READY, create_bot_from_json, load_bot, panda_bot_json, rotor_bot_json, step, tolerance
from robotics_helpers import scene  # noqa: F401

G = 9.81
S = math.sqrt(0.5)
ROT_X_90 = [S, 0.0, 0.0, S]


def signal(ctx, bot, name):
    (h,) = bot.find_sensors_by_name(name)
    return np.asarray(ctx.get_sensor_signal(h), dtype=float)


def sensor(type_name, name, params=None):
    return {"type": type_name, "name": name, "params": json.dumps(params) if params else ""}


def box_link(name, sensors, parent=None):
    # 2 kg, 0.2 x 0.1 x 0.2 m in its own frame (lies flat once rotated 90 degrees about x)
    link = {"name": name, "mass": 2.0, "momentOfInertia": [0.0133, 0, 0, 0.0133, 0, 0.0083],
            "shape": {"box": {"halfExtents": [0.1, 0.05, 0.1]}}, "sensors": sensors}
    if parent is not None:
        link["parentLink"] = parent
    return link


def test_contact_force_of_links_resting_on_a_table_is_their_weight(scene, tmp_path):
    scene.create_rigid_actor(name="table", shape=sdp.create_box_shape([1.0, 1.0, 0.1]), is_static=True,
                             world_from_local=sdp.TransformRT(translation=[0, 0, -0.1]))
    # two equal boxes welded side by side, turned 90 degrees about x: each carries half of the
    # bot's weight, by symmetry
    doc = {
        "name": "pair",
        "links": [box_link("a", [sensor("CONTACT_FORCE", "a_world")]),
                  box_link("b", [sensor("CONTACT_FORCE", "b_link", {"frame": "link"})], parent=0)],
        "joints": [{"name": "free", "type": "Free"},
                   {"name": "weld", "type": "Hard", "parentLinkFromJoint": {"rotation": IDENTITY, "translation": [0.3, 0, 0]}}],
        "defaultPose": [],
        "worldFromRoot": {"rotation": ROT_X_90, "translation": [0, 0, 0.0505]},
    }
    ctx, bot, _ = create_bot_from_json(scene, tmp_path, doc)
    assert bot.is_pipeline_active()
    np.testing.assert_array_equal(signal(ctx, bot, "a_world"), 0.0)  # zeros before the first update
    step(scene, 0.002, 250)
    weight = 2.0 * G
    np.testing.assert_allclose(signal(ctx, bot, "a_world"), [0, 0, weight], atol=tolerance(1e-6, 2e-3) * weight)
    # in the link frame of a link turned +90 degrees about x, world up is link +y
    np.testing.assert_allclose(signal(ctx, bot, "b_link"), [0, weight, 0], atol=tolerance(1e-6, 2e-3) * weight)


def test_joint_state_equals_the_engine_state(scene, tmp_path):
    ctx, bot, arm = create_bot_from_json(scene, tmp_path, panda_bot_json())
    # a context-level sensor on the articulation joins its bot's pipeline; a bot sensor on a link
    # reads that link's joint
    whole = ctx.create_sensor("JOINT_STATE", arm, "all")
    elbow = bot.create_sensor("JOINT_STATE", scene.get_actor(arm.get_nested_link_actors()[4]), "elbow")
    target = (np.array(PANDA_READY) + 0.3).tolist()
    bot.create_controller("BASIC_JSC_PD", "jsc", {"kp": 100.0, "kd": 10.0, "target_pose": target})
    v = np.zeros(7, dtype=arm.get_articulated_pose().dtype)
    for _ in range(20):
        scene.step(0.002)
        q = arm.get_articulated_pose()
        arm.get_articulated_joint_velocities(v)
        np.testing.assert_array_equal(ctx.get_sensor_signal(whole), np.concatenate([q, v]))
        np.testing.assert_array_equal(ctx.get_sensor_signal(elbow), [q[3], v[3]])
    assert np.abs(v).max() > 0.1, "the arm is moving"


def test_joint_state_noise_statistics_quantisation_and_seed(scene, tmp_path):
    ctx, bot, rotor = create_bot_from_json(scene, tmp_path, rotor_bot_json())
    wheel = scene.get_actor(rotor.get_nested_link_actors()[1])
    noisy = {"position_noise_std": 0.01, "velocity_noise_std": 0.02, "seed": 7}
    a = bot.create_sensor("JOINT_STATE", wheel, "a", noisy)
    b = bot.create_sensor("JOINT_STATE", wheel, "b", noisy)
    c = bot.create_sensor("JOINT_STATE", wheel, "c", dict(noisy, seed=8, position_resolution=0.005))
    n = 2000
    readings = {h: [] for h in (a, b, c)}
    for _ in range(n):
        scene.step(0.002)
        for h in readings:
            readings[h].append(np.asarray(ctx.get_sensor_signal(h), dtype=float))
    ra, rb, rc = (np.array(readings[h]) for h in (a, b, c))
    # the rotor is at rest at q = 0: the readings are pure noise
    for column, std in ((0, 0.01), (1, 0.02)):
        assert abs(ra[:, column].mean()) < 4 * std / math.sqrt(n), "unbiased (4 standard errors)"
        assert ra[:, column].std() == pytest.approx(std, rel=0.06), "the configured std (3.8 standard errors of a std)"
    np.testing.assert_array_equal(ra, rb)  # the same seed gives the same readings
    assert not np.array_equal(ra[:, 0], rc[:, 0])
    steps = rc[:, 0] / 0.005
    np.testing.assert_allclose(steps, np.round(steps), atol=1e-3)  # quantised to 5 mrad
    # reset() restarts the sequence
    bot.reset()
    scene.step(0.002)
    np.testing.assert_array_equal(ctx.get_sensor_signal(a), ra[0])


def test_imu_reads_plus_g_at_rest_and_zero_in_free_fall(scene, tmp_path):
    ctx = sdr.create_context()
    # at rest: a welded base turned 90 degrees about x reads +g along its +y axis
    doc = rotor_bot_json()
    doc["worldFromRoot"] = {"rotation": ROT_X_90, "translation": [0, 0, 1]}
    doc["links"][0]["sensors"] = [sensor("IMU", "imu")]
    rest = sdr.create_bot(scene, load_bot(tmp_path, doc, "rest.superdex_bot"), ctx)
    # free fall: a free box spinning about its vertical principal axis at 2 rad/s
    doc = {"name": "faller", "links": [box_link("box", [sensor("IMU", "imu")])],
           "joints": [{"name": "free", "type": "Free"}], "defaultPose": [],
           "worldFromRoot": {"rotation": ROT_X_90, "translation": [5, 0, 10]}}
    faller = sdr.create_bot(scene, load_bot(tmp_path, doc, "faller.superdex_bot"), ctx)
    faller.get_articulated_actor().set_velocity([0.0, 0.0, 0.0], [0.0, 0.0, 2.0])
    step(scene, 0.002, 100)
    np.testing.assert_allclose(signal(ctx, rest, "imu"), [0, G, 0, 0, 0, 0], atol=tolerance(1e-9, 1e-4))
    # +90 degrees about x takes link +y to world +z: the spin about world z is about link +y
    np.testing.assert_allclose(signal(ctx, faller, "imu"), [0, 0, 0, 0, 2.0, 0], atol=tolerance(1e-6, 2e-3))


def hanging_bot() -> dict:
    """A welded base 1 m up; an arm on a revolute joint about y hanging straight down (COM 0.3 m
    below the joint) carrying a welded tip (COM 0.6 m below); a cantilever beam welded to the
    base with its COM 0.2 m out along +x."""
    inertia = [0.01, 0, 0, 0.01, 0, 0.01]
    return {
        "name": "hanging",
        "links": [
            {"name": "base", "mass": 5.0, "momentOfInertia": inertia},
            {"name": "arm", "parentLink": 0, "mass": 1.5, "centerOfMass": [0, 0, -0.3], "momentOfInertia": [0.05, 0, 0, 0.05, 0, 0.002],
             "sensors": [sensor("FORCE_TORQUE", "ft_arm")]},
            {"name": "tip", "parentLink": 1, "mass": 0.5, "momentOfInertia": [0.001, 0, 0, 0.001, 0, 0.001],
             "sensors": [sensor("FORCE_TORQUE", "ft_tip", {"frame": "world"})]},
            {"name": "beam", "parentLink": 0, "mass": 2.0, "centerOfMass": [0.2, 0, 0], "momentOfInertia": [0.002, 0, 0, 0.03, 0, 0.03],
             "sensors": [sensor("FORCE_TORQUE", "ft_beam")]},
        ],
        "joints": [
            {"name": "weld", "type": "Hard"},
            {"name": "pivot", "type": "Revolute", "axis": [0, 1, 0], "parentLinkFromJoint": {"rotation": IDENTITY, "translation": [0, 0, 1]}},
            {"name": "tip_weld", "type": "Hard", "parentLinkFromJoint": {"rotation": IDENTITY, "translation": [0, 0, -0.6]}},
            {"name": "beam_weld", "type": "Hard", "parentLinkFromJoint": {"rotation": IDENTITY, "translation": [0, 0, 1]}},
        ],
        "defaultPose": [0.0],
    }


def test_force_torque_of_hanging_links_is_their_weight(scene, tmp_path):
    ctx, bot, _ = create_bot_from_json(scene, tmp_path, hanging_bot())
    step(scene, 0.002, 50)
    tol = tolerance(1e-8, 2e-3)
    # the joint holds up everything below it: arm and tip, 2 kg, straight below (no moment)
    np.testing.assert_allclose(signal(ctx, bot, "ft_arm"), [0, 0, 2.0 * G, 0, 0, 0], atol=tol * 2 * G)
    np.testing.assert_allclose(signal(ctx, bot, "ft_tip"), [0, 0, 0.5 * G, 0, 0, 0], atol=tol * 2 * G)
    # the cantilever's weld also holds the moment of its weight: -(r x m g) = (0, -0.2 m g, 0)
    np.testing.assert_allclose(signal(ctx, bot, "ft_beam"), [0, 0, 2.0 * G, 0, -0.2 * 2.0 * G, 0], atol=tol * 2 * G)


def test_force_torque_about_a_driven_joint_axis_is_the_joint_torque(scene, tmp_path):
    ctx, bot, _ = create_bot_from_json(scene, tmp_path, hanging_bot())
    # 3 N m on the pivot (no actuator: the commanded effort is applied directly); the arm swings up
    bot.create_controller("JOINT_COMMAND", "drive", {"effort": [3.0]})
    readings = []
    for _ in range(300):
        scene.step(0.001)
        readings.append(signal(ctx, bot, "ft_arm")[4])  # torque about the link's y axis = the joint axis
    assert abs(bot.get_articulated_actor().get_articulated_pose()[0]) > 0.2, "the arm swung"
    # the impulse balance of the step is exact; float32 momenta differenced over 1 ms leave
    # rounding of about eps |H| / dt ~ 1e-4 N m
    np.testing.assert_allclose(readings, 3.0, atol=tolerance(1e-9, 1e-3))


def test_sensors_measure_at_their_parent_from_sensor_frame(scene, tmp_path):
    """Sensors mounted away from the link origin (parentFromSensor) measure there, in their own
    axes. An IMU 0.2 m out along a link spinning at w about z reads the centripetal specific
    force w^2 r towards the axis; a FORCE_TORQUE sensor at the centre of mass of a welded arm reads
    its weight and no torque, and turned 90 degrees about x it sees the weight along its y axis."""
    scene.set_gravity([0, 0, 0])
    w, r = 5.0, 0.2
    doc = {
        "name": "spinner",
        "links": [{"name": "base", "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01]},
                  {"name": "disc", "parentLink": 0, "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.02],
                   "sensors": [{"type": "IMU", "name": "imu", "params": "",
                                "parentFromSensor": {"rotation": IDENTITY, "translation": [r, 0, 0]}}]}],
        "joints": [{"name": "weld", "type": "Hard"}, {"name": "spin", "type": "Revolute", "axis": [0, 0, 1]}],
        "defaultPose": [0.0],
    }
    ctx, bot, spinner = create_bot_from_json(scene, tmp_path, doc)
    spinner.set_articulated_joint_velocities([w])
    step(scene, 0.001, 200)
    f = signal(ctx, bot, "imu")
    np.testing.assert_allclose(f[:3], [-w * w * r, 0, 0], atol=0.01 * w * w * r)
    np.testing.assert_allclose(f[3:], [0, 0, w], atol=1e-3 * w)

    scene.set_gravity([0, 0, -G])
    m, cx = 2.0, 0.3
    arm = {
        "name": "cantilever",
        "links": [{"name": "base", "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01]},
                  {"name": "arm", "parentLink": 0, "mass": m, "centerOfMass": [cx, 0, 0],
                   "momentOfInertia": [0.001, 0, 0, 0.01, 0, 0.01],
                   "sensors": [{"type": "FORCE_TORQUE", "name": "ft_com", "params": "",
                                "parentFromSensor": {"rotation": IDENTITY, "translation": [cx, 0, 0]}},
                               {"type": "FORCE_TORQUE", "name": "ft_turned", "params": "",
                                "parentFromSensor": {"rotation": ROT_X_90, "translation": [cx, 0, 0]}}]}],
        "joints": [{"name": "weld", "type": "Hard", "parentLinkFromJoint": {"rotation": IDENTITY, "translation": [5, 0, 1]}},
                   {"name": "fixed", "type": "Hard"}],
        "defaultPose": [],
    }
    bot2 = sdr.create_bot(scene, load_bot(tmp_path, arm, "cantilever.superdex_bot"), ctx)
    step(scene, 0.001, 5)
    ft = signal(ctx, bot2, "ft_com")
    np.testing.assert_allclose(ft[:3], [0, 0, m * G], atol=1e-3 * m * G)
    np.testing.assert_allclose(ft[3:], 0, atol=1e-3 * m * G * cx)
    # sensor y is link z after turning +90 degrees about x
    np.testing.assert_allclose(signal(ctx, bot2, "ft_turned")[:3], [0, m * G, 0], atol=1e-3 * m * G)
