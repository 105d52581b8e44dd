"""BotLinkPrefab, BotSensorPrefab, BotActuatorPrefab, BotJointPrefab: building a bot in code with
components declared on its links."""

import pytest

import superdex.physics as sdp
import superdex.robotics as sdr

CAMERA = sdr.CameraSensor.type_name()


@pytest.fixture
def scene():
    sdp.initialize(num_worker_threads=0)
    s = sdp.create_scene("prefab links")
    s.set_gravity([0, 0, -9.81])
    yield s
    sdp.shutdown()


class Motor:
    def __init__(self, actor, param_args):
        self.actor, self.param_args = actor, param_args

    def reset(self):
        pass


def _pendulum():
    """A welded base and one revolute link carrying a camera and a motor."""
    prefab = sdr.BotPrefab()
    prefab.name = "pendulum"
    prefab.add_link(sdr.BotLinkPrefab(name="base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
                    sdr.BotJointPrefab(name="weld", type=sdp.ArticulatedJointType.HARD))
    camera = sdr.BotSensorPrefab(type=CAMERA, name="tip_cam", parent_from_sensor=sdp.TransformRT(translation=[0.0, 0.0, -0.5]),
                                 params='{"imageWidth": 32, "imageHeight": 24}')
    motor = sdr.BotActuatorPrefab(type="PREFAB_MOTOR", name="motor", params='{"gear": 10}')
    link = sdr.BotLinkPrefab(name="rod", parent_link=0, mass=0.5, center_of_mass=[0.0, 0.0, -0.5],
                             moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.001], sensors=[camera], actuators=[motor])
    prefab.add_link(link, sdr.BotJointPrefab(name="hinge", axis=[0.0, 1.0, 0.0], effort_limit=5.0))
    return prefab


def test_joint_prefab_defaults_and_keywords():
    joint = sdr.BotJointPrefab()
    assert joint.effort_limit == sdr.EFFORT_UNBOUNDED == -1.0
    assert isinstance(sdr.EFFORT_UNBOUNDED, float)
    assert sdr.BotJointPrefab(name="j", effort_limit=0.0).effort_limit == 0.0
    with pytest.raises(sdp.Error, match="unknown field 'effort'"):
        sdr.BotJointPrefab(effort=1.0)


def test_link_prefab_holds_its_components():
    sensor = sdr.BotSensorPrefab(type=CAMERA, name="cam", parent_from_sensor=sdp.TransformRT([1.0, 2.0, 3.0]), params="cam.json")
    link = sdr.BotLinkPrefab(name="l", mass=2.0, sensors=[sensor])
    assert link.mass == 2.0 and link.name == "l"
    assert link.sensors[0] == sensor and len(link.actuators) == 0
    link.sensors[0].name = "renamed"
    assert link.sensors[0].name == "renamed", "the list is the link's own"
    link.actuators = [sdr.BotActuatorPrefab(type="X", name="a")]
    assert link.actuators[0].type == "X"
    with pytest.raises(sdp.Error, match=r"BotLinkPrefab\.sensors\[0\]: expected a BotSensorPrefab"):
        link.sensors = ["cam"]
    with pytest.raises(sdp.Error, match="unknown field 'sensor'"):
        sdr.BotLinkPrefab(sensor=[sensor])


def test_add_link_round_trips_and_checks_parents():
    prefab = _pendulum()
    assert [l.name for l in prefab.links] == ["base", "rod"]
    rod = prefab.get_link_prefab(1)
    assert rod.sensors[0].name == "tip_cam" and rod.actuators[0].params == '{"gear": 10}'
    assert rod.sensors[0].parent_from_sensor == sdp.TransformRT(translation=[0.0, 0.0, -0.5])
    assert len(prefab.get_link_prefab(0).sensors) == 0
    with pytest.raises(sdp.Error, match="out of range"):
        prefab.get_link_prefab(2)
    with pytest.raises(sdp.Error, match=r"link\.parent_link: must be the index of an earlier link \(0\.\.1\), got 5"):
        prefab.add_link(sdr.BotLinkPrefab(name="bad", parent_link=5), sdr.BotJointPrefab())
    with pytest.raises(sdp.Error, match=r"link\.sensors\[0\]\.type: must not be empty"):
        prefab.add_link(sdr.BotLinkPrefab(name="bad", parent_link=1, sensors=[sdr.BotSensorPrefab()]), sdr.BotJointPrefab())
    with pytest.raises(sdp.Error, match="add_link: link: expected a BotLinkPrefab"):
        prefab.add_link(None, sdr.BotJointPrefab())
    assert len(prefab.links) == 2, "rejected links are not added"


def test_declared_components_are_built_with_the_bot(scene):
    ctx = sdr.create_context()
    sdr.register_python_actuator(ctx, "PREFAB_MOTOR", Motor)
    bot = sdr.create_bot(scene, _pendulum(), ctx)
    [cam_handle] = bot.get_sensor_handles()
    camera = ctx.get_sensor(cam_handle)
    assert camera.get_name() == "tip_cam" and camera.get_params().image_width == 32
    assert camera.get_parent_from_sensor() == sdp.TransformRT(translation=[0.0, 0.0, -0.5])
    assert camera.get_owning_bot().get_name() == "pendulum"
    motor = sdr.get_python_actuator(ctx, bot.get_actuator_handles()[0])
    assert motor.param_args == '{"gear": 10}'
    assert motor.actor == camera.get_actor(), "both sit on the rod's link actor"
    # the rod swings from its hinge: the camera at its tip moves with it
    bot.get_articulated_actor().set_articulated_pose_from_joints([0.5])
    before = camera.get_world_transform().translation[0]
    for _ in range(100):
        scene.step(0.005)
    assert abs(camera.get_world_transform().translation[0] - before) > 0.05
