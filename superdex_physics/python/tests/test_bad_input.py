"""Every bad input raises superdex.physics.Error naming what was wrong; nothing crashes."""

import math

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import real_dtype, two_link_arm

INERTIA = [0.01, 0, 0, 0.01, 0, 0.01]


def chain(scene, links, joints):
    return scene.create_articulated_actor("bad", links, joints)


def base_links():
    return [
        {"name": "base", "mass": 1.0, "momentOfInertia": INERTIA},
        {"name": "a", "parentLink": 0, "mass": 1.0, "momentOfInertia": INERTIA},
        {"name": "b", "parentLink": 1, "mass": 1.0, "momentOfInertia": INERTIA},
    ]


def base_joints():
    return [
        {"name": "root", "type": "Hard"},
        {"name": "ja", "type": "Revolute", "axis": [0, 0, 1]},
        {"name": "jb", "type": "Revolute", "axis": [0, 0, 1]},
    ]


def other_dtype():
    return np.float32 if sdp.uses_double_precision() else np.float64


def test_out_array_wrong_dtype(scene):
    arm = two_link_arm(scene)
    with pytest.raises(sdp.Error, match=r"out_velocities.*dtype " + np.dtype(real_dtype()).name):
        arm.get_articulated_joint_velocities(out_velocities=np.zeros(2, dtype=other_dtype()))
    with pytest.raises(sdp.Error, match="out_velocities"):
        arm.get_articulated_joint_velocities(out_velocities=np.zeros(2, dtype=np.int64))


def test_out_array_wrong_shape(scene):
    arm = two_link_arm(scene)
    with pytest.raises(sdp.Error, match=r"shape \(2,\)"):
        arm.get_articulated_joint_velocities(out_velocities=np.zeros(3, dtype=real_dtype()))
    with pytest.raises(sdp.Error, match=r"shape \(2,\)"):
        arm.get_articulated_pose(np.zeros((2, 1), dtype=real_dtype()))
    with pytest.raises(sdp.Error, match="out_velocities"):
        arm.get_articulated_joint_velocities(out_velocities=[0.0, 0.0])
    with pytest.raises(sdp.Error, match="non-contiguous|shape|contiguous"):
        arm.get_articulated_joint_velocities(out_velocities=np.zeros(4, dtype=real_dtype())[::2])
    with pytest.raises(sdp.Error, match="one entry per link"):
        arm.get_articulated_link_transforms(sdp.DynamicArrayTransformRT(2))
    with pytest.raises(sdp.Error, match="length 2"):
        arm.get_articulated_pose(sdp.DynamicArrayReal(5))


def test_out_array_read_only(scene):
    arm = two_link_arm(scene)
    a = np.zeros(2, dtype=real_dtype())
    a.flags.writeable = False
    with pytest.raises(sdp.Error, match="read-only"):
        arm.get_articulated_joint_velocities(out_velocities=a)


def test_dof_index_out_of_range(scene):
    arm = two_link_arm(scene)
    with pytest.raises(sdp.Error, match=r"dof_indices\[1\] = 2 is out of range.*2 DOFs"):
        arm.set_external_forces_on_dofs([0, 2], [1.0, 1.0])
    with pytest.raises(sdp.Error, match="out of range"):
        arm.set_external_forces_on_dofs([-1], [1.0])
    with pytest.raises(sdp.Error, match="appears twice"):
        arm.set_external_forces_on_dofs([1, 1], [1.0, 1.0])
    with pytest.raises(sdp.Error, match="2 entries but force_values has 1"):
        arm.set_external_forces_on_dofs([0, 1], [1.0])
    with pytest.raises(sdp.Error, match="integer"):
        arm.set_external_forces_on_dofs([0.5], [1.0])


def test_repeated_dof_on_an_actor_with_many_dofs_changes_nothing(scene):
    # more than 64 DOFs: repeated indices are found by another path than on a small arm
    from test_soft_contact import soft_block

    block, nodes = soft_block(scene, cells=2)
    n = block.get_num_dofs()
    assert n > 64
    block.set_external_forces_on_dofs([n - 1, 0], [2.0, 3.0])
    with pytest.raises(sdp.Error, match=rf"dof_indices\[2\] = {n - 1} appears twice"):
        block.set_external_forces_on_dofs([n - 1, 5, n - 1], [1.0, 1.0, 1.0])
    with pytest.raises(sdp.Error, match=rf"dof_indices\[1\] = {n} is out of range: the actor has {n} DOFs"):
        block.set_external_forces_on_dofs([5, n], [1.0, 1.0])
    expected = np.zeros(n)
    expected[[n - 1, 0]] = [2.0, 3.0]
    np.testing.assert_allclose(block.get_external_forces(), expected)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_forces(scene, bad):
    arm = two_link_arm(scene)
    arm.set_external_forces_on_dofs([0], [1.0])
    with pytest.raises(sdp.Error, match=r"force_values\[1\] is not finite"):
        arm.set_external_forces_on_dofs([0, 1], [0.0, bad])
    # the rejected call changed nothing
    np.testing.assert_allclose(arm.get_external_forces(), [1.0, 0.0])


def test_non_finite_pose_and_velocities(scene):
    arm = two_link_arm(scene)
    with pytest.raises(sdp.Error, match=r"pose\[0\] is not finite"):
        arm.set_articulated_pose_from_joints([math.nan, 0])
    with pytest.raises(sdp.Error, match=r"expected 2 values, got 3|must have 2 values"):
        arm.set_articulated_joint_velocities([0, 0, 0])
    with pytest.raises(sdp.Error, match="sequence of numbers"):
        arm.set_articulated_joint_velocities("fast")


def test_unknown_handle(scene):
    arm = two_link_arm(scene)
    handle = arm.get_handle()
    with pytest.raises(sdp.Error, match=r"actor 123456 does not exist"):
        scene.get_actor(123456)
    scene.destroy_actor(arm)
    with pytest.raises(sdp.Error, match=f"actor {handle} does not exist"):
        arm.get_num_dofs()
    with pytest.raises(sdp.Error, match="does not exist"):
        scene.destroy_actor(handle)


def test_handles_are_never_reused(scene):
    seen = set()
    for k in range(5):
        arm = two_link_arm(scene, name=f"a{k}")
        handles = {arm.get_handle(), *arm.get_nested_link_actors()}
        assert not handles & seen
        seen |= handles
        scene.destroy_actor(arm)


def test_link_actor_misuse(scene):
    arm = two_link_arm(scene)
    link = scene.get_actor(arm.get_nested_link_actors()[1])
    with pytest.raises(sdp.Error, match="link actor; call it on its articulation"):
        link.set_external_forces_on_dofs([0], [1.0])
    with pytest.raises(sdp.Error, match="destroy the articulation"):
        scene.destroy_actor(link)
    with pytest.raises(sdp.Error, match="not a link actor"):
        arm.get_articulated_actor()


def test_negative_mass(scene):
    links = base_links()
    links[2]["mass"] = -1.0
    with pytest.raises(sdp.Error, match=r"links\[2\]\.mass: must be a positive finite number, got -1"):
        chain(scene, links, base_joints())
    with pytest.raises(sdp.Error, match=r"mass: must be a positive"):
        scene.create_rigid_actor("r", sdp.create_sphere_shape([0, 0, 0], 1), mass=-2.0)


def test_non_positive_definite_inertia(scene):
    links = base_links()
    links[1]["momentOfInertia"] = [1.0, 0, 0, -1.0, 0, 1.0]
    with pytest.raises(sdp.Error, match=r"links\[1\]\.momentOfInertia: must be positive definite"):
        chain(scene, links, base_joints())
    links[1]["momentOfInertia"] = [1.0, 0, 0, 1.0, 0, 5.0]
    with pytest.raises(sdp.Error, match=r"links\[1\]\.momentOfInertia: is not physically valid"):
        chain(scene, links, base_joints())


def test_cycle_in_link_tree(scene):
    links = base_links()
    links[1]["parentLink"] = 2
    with pytest.raises(sdp.Error, match=r"cycle"):
        chain(scene, links, base_joints())


def test_missing_parent(scene):
    links = base_links()
    del links[2]["parentLink"]
    with pytest.raises(sdp.Error, match=r"links\[2\]\.parentLink: missing"):
        chain(scene, links, base_joints())
    links[2]["parentLink"] = 7
    with pytest.raises(sdp.Error, match=r"links\[2\]\.parentLink: refers to link 7, which does not exist"):
        chain(scene, links, base_joints())


def test_joint_errors(scene):
    joints = base_joints()
    joints[0]["type"] = "Revolute"
    joints[0]["axis"] = [0, 0, 1]
    with pytest.raises(sdp.Error, match=r"joints\[0\]\.type: the root joint must be Hard or Free"):
        chain(scene, base_links(), joints)
    joints = base_joints()
    joints[1]["type"] = "Free"
    with pytest.raises(sdp.Error, match=r"joints\[1\]\.type: only the root joint"):
        chain(scene, base_links(), joints)
    joints = base_joints()
    joints[2]["axis"] = [0, 0, 0]
    with pytest.raises(sdp.Error, match=r"joints\[2\]\.axis: must be a finite, non-zero vector"):
        chain(scene, base_links(), joints)
    joints = base_joints()
    joints[1]["minLimit"] = [0, 0, 1.0]
    joints[1]["maxLimit"] = [0, 0, -1.0]
    with pytest.raises(sdp.Error, match=r"joints\[1\]\.minLimit: the lower limit 1 exceeds the upper limit -1"):
        chain(scene, base_links(), joints)
    joints = base_joints()
    joints[2]["type"] = "Hinge"
    with pytest.raises(sdp.Error, match=r"joints\[2\]\.type: unknown joint type 'Hinge'"):
        chain(scene, base_links(), joints)
    with pytest.raises(sdp.Error, match=r"joints: expected exactly one joint per link"):
        chain(scene, base_links(), base_joints()[:2])


def test_wrong_types_and_names(scene):
    links = base_links()
    links[1]["mass"] = "heavy"
    with pytest.raises(sdp.Error, match=r"links\[1\]\.mass: expected a number, got a string"):
        chain(scene, links, base_joints())
    links = base_links()
    links[2]["name"] = "a"
    with pytest.raises(sdp.Error, match=r"links\[2\]\.name: duplicate link name 'a'"):
        chain(scene, links, base_joints())
    links = base_links()
    links[0]["centerOfMass"] = [0, math.nan, 0]
    with pytest.raises(sdp.Error, match=r"links\[0\]\.centerOfMass\[1\]: must be finite"):
        chain(scene, links, base_joints())
    with pytest.raises(sdp.Error, match=r"defaultPose: expected 2 values"):
        scene.create_articulated_actor("bad", base_links(), base_joints(), default_pose=[0.0])


def test_unknown_field_warns(scene):
    links = base_links()
    links[0]["colour"] = "red"
    with pytest.warns(UserWarning, match=r"links\[0\]\.colour: unknown field"):
        chain(scene, links, base_joints())


def test_bad_shapes(engine):
    with pytest.raises(sdp.Error, match="sphere radius must be a positive finite number"):
        sdp.create_sphere_shape([0, 0, 0], -1)
    with pytest.raises(sdp.Error, match="radius: must be finite"):
        sdp.create_sphere_shape([0, 0, 0], math.nan)
    with pytest.raises(sdp.Error, match="box halfExtents"):
        sdp.create_box_shape([1, 0, 1])
    with pytest.raises(sdp.Error, match="plane normal must be non-zero"):
        sdp.create_plane_shape([0, 0, 0], 0)
    with pytest.raises(sdp.Error, match=r"half_extents: expected 3 values, got 2"):
        sdp.create_box_shape([1, 1])
    s = sdp.create_scene("s")
    with pytest.raises(sdp.Error, match="plane is unbounded and can only be static"):
        s.create_rigid_actor("p", sdp.create_plane_shape([0, 0, 1], 0))
    with pytest.raises(sdp.Error, match="expected a Shape"):
        s.create_rigid_actor("p", "sphere")
    shape = sdp.create_sphere_shape([0, 0, 0], 1)
    sdp.release_shape(shape)
    with pytest.raises(sdp.Error, match="does not exist"):
        s.create_rigid_actor("r", shape)


def test_bad_step_and_settings(scene):
    for dt in (0.0, -0.01, math.nan):
        with pytest.raises(sdp.Error, match="dt must be a positive finite"):
            scene.step(dt)
    with pytest.raises(sdp.Error, match="gravity"):
        scene.set_gravity([0, math.inf, 0])
    with pytest.raises(sdp.Error, match="num_worker_threads"):
        sdp.shutdown()
        sdp.initialize(-5)
    sdp.initialize(0)


def test_arguments_of_the_wrong_type_name_the_argument(scene):
    ball = scene.create_rigid_actor("ball", sdp.create_sphere_shape([0, 0, 0], 0.1))
    with pytest.raises(sdp.Error, match="step: dt: expected a number of seconds, got str"):
        scene.step("0.01")
    with pytest.raises(sdp.Error, match="get_actor: handle: expected an Actor or an actor handle"):
        scene.get_actor("ball")
    with pytest.raises(sdp.Error, match=r"register_pre_step_callback\('cb'\): fn: expected a callable fn\(scene, dt\), got int"):
        scene.register_pre_step_callback("cb", 5)
    with pytest.raises(sdp.Error, match=r"register_post_step_callback\('cb'\): fn: expected a callable"):
        scene.register_post_step_callback("cb", None)
    with pytest.raises(sdp.Error, match="register_query: query_type: expected a superdex.physics.QueryType, got str"):
        ball.register_query("TOTAL_CONTACT_FORCE")
    with pytest.raises(sdp.Error, match="set_solver_params: params: expected a superdex.physics.SolverParams, got None"):
        scene.set_solver_params(None)
    with pytest.raises(sdp.Error, match=r"restore_state: state: expected a SceneState from capture_state\(\), got bytes"):
        scene.restore_state(b"state")
    assert scene.get_actor(ball.get_handle()) == ball  # ints and actors still work
    scene.step(np.float64(0.01))  # and any real number type for dt
    assert scene.get_total_simulation_time() == pytest.approx(0.01)


@pytest.mark.parametrize("bad", [[math.nan, 0, 0], [0, math.inf, 0], [0, 0]])
def test_bad_vectors_name_the_argument(scene, bad):
    ball = scene.create_rigid_actor("ball", sdp.create_sphere_shape([0, 0, 0], 0.1))
    with pytest.raises(sdp.Error, match="set_velocity: (linear|linear and angular velocity)"):
        ball.set_velocity(bad, [0, 0, 0])
    with pytest.raises(sdp.Error, match="set_velocity: (angular|linear and angular velocity)"):
        ball.set_velocity([0, 0, 0], bad)
    with pytest.raises(sdp.Error, match=r"(set_root_transform: transform\.translation: must be finite|TransformRT: translation: expected 3 values)"):
        ball.set_root_transform(sdp.TransformRT(translation=bad))
    with pytest.raises(sdp.Error, match="set_gravity: gravity"):
        scene.set_gravity(bad)
    scene.step(0.01)  # nothing was changed by the rejected calls
    assert np.all(np.isfinite(ball.get_root_transform().translation))


# every Actor method with arguments that would be valid for a live actor
ACTOR_CALLS = {
    "get_name": (), "get_type": (), "get_root_transform": (), "get_mass": (), "get_num_dofs": (),
    "set_root_transform": (sdp.TransformRT(),), "set_velocity": ([0, 0, 0], [0, 0, 0]),
    "get_linear_velocity": (), "get_angular_velocity": (),
    "set_external_forces_on_dofs": ([0], [1.0]), "clear_external_forces": (), "get_external_forces": (),
    "register_query": (sdp.QueryType.TOTAL_CONTACT_FORCE,), "get_contact_force_world": (),
    "get_contact_torque_world": (), "get_contact_points_world": (),
}


@pytest.mark.parametrize("method", sorted(ACTOR_CALLS))
def test_every_method_of_a_destroyed_actor_raises(scene, method):
    ball = scene.create_rigid_actor("ball", sdp.create_sphere_shape([0, 0, 0], 0.1))
    handle = ball.get_handle()
    scene.destroy_actor(ball)
    with pytest.raises(sdp.Error, match=f"actor {handle} does not exist"):
        getattr(ball, method)(*ACTOR_CALLS[method])
    scene.step(0.01)


def test_stale_handles_after_destroy_scene_and_shutdown(engine):
    scene = sdp.create_scene("gone")
    ball = scene.create_rigid_actor("ball", sdp.create_sphere_shape([0, 0, 0], 0.1))
    arm = two_link_arm(scene)
    sdp.destroy_scene(scene)
    for call in (lambda: scene.step(0.01), lambda: ball.get_mass(), lambda: arm.get_articulated_pose(),
                 lambda: scene.capture_state(), lambda: scene.get_actor(ball.get_handle())):
        with pytest.raises(sdp.Error, match="does not exist"):
            call()
    with pytest.raises(sdp.Error, match="destroy_scene: scene .* does not exist"):
        sdp.destroy_scene(scene)
    live = sdp.create_scene("live")
    live_ball = live.create_rigid_actor("ball", sdp.create_sphere_shape([0, 0, 0], 0.1))
    sdp.shutdown()
    with pytest.raises(sdp.Error, match="does not exist"):
        live.step(0.01)
    with pytest.raises(sdp.Error, match="does not exist"):
        live_ball.get_root_transform()
    sdp.initialize(0)
    fresh = sdp.create_scene("fresh")
    fresh.step(0.01)


def test_actor_of_another_scene_is_refused(scene):
    ball = scene.create_rigid_actor("ball", sdp.create_sphere_shape([0, 0, 0], 0.1))
    other = sdp.create_scene("other")
    with pytest.raises(sdp.Error, match=f"destroy_actor: actor {ball.get_handle()} does not exist in scene 'other'"):
        other.destroy_actor(ball)
    with pytest.raises(sdp.Error, match="enable_actor_contact_symmetric: actor .* does not exist in scene 'other'"):
        other.enable_actor_contact_symmetric(ball, ball, False)
