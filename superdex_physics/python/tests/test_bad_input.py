"""Every bad input raises superdex.physics.Error naming what was wrong (or, for an argument of the
wrong Python type, the bindings' TypeError naming the argument); nothing crashes."""

import math
import re

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import articulation, joint, link, real_dtype, two_link_arm

INERTIA = [0.01, 0, 0, 0.01, 0, 0.01]


def chain(scene, links, joints, **fields):
    return articulation(scene, "bad", links, joints, **fields)


def base_links():
    return [
        link("base", mass=1.0, moment_of_inertia=INERTIA),
        link("a", parent=0, mass=1.0, moment_of_inertia=INERTIA),
        link("b", parent=1, mass=1.0, moment_of_inertia=INERTIA),
    ]


def base_joints():
    return [
        joint("root", "hard"),
        joint("ja", "revolute", axis=[0, 0, 1]),
        joint("jb", "revolute", axis=[0, 0, 1]),
    ]


def sphere(scene, name="ball"):
    return scene.create_rigid_actor(name=name, shape=sdp.create_sphere_shape([0, 0, 0], 0.1))


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
    with pytest.raises(sdp.Error, match=r"out_velocities: .*got shape \(2,\), not contiguous"):
        arm.get_articulated_joint_velocities(out_velocities=np.zeros(4, dtype=real_dtype())[::2])
    with pytest.raises(sdp.Error, match="out_world_from_links: expected a DynamicArrayTransformRT of length 3, got length 2"):
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
    # SuperDex: looking up an unknown handle gives None, destroying a destroyed actor does nothing
    assert scene.get_actor(sdp.ActorHandle(123456)) is None
    scene.destroy_actor(arm)
    assert scene.get_actor(handle) is None
    with pytest.raises(sdp.Error, match=f"get_num_dofs: actor {handle.value} does not exist"):
        arm.get_num_dofs()
    scene.destroy_actor(handle)
    scene.destroy_actor(arm)
    scene.destroy_actor(None)


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
    link_actor = scene.get_actor(arm.get_nested_link_actors()[1])
    with pytest.raises(sdp.Error, match="link actor; call it on its articulation"):
        link_actor.set_external_forces_on_dofs([0], [1.0])
    with pytest.raises(sdp.Error, match="destroy_actor: actor .* is a link of an articulated actor; destroy the articulated actor"):
        scene.destroy_actor(link_actor)
    with pytest.raises(sdp.Error, match="not a link actor"):
        arm.get_articulated_actor()


def test_negative_mass(scene):
    links = base_links()
    links[2].mass = -1.0
    with pytest.raises(sdp.Error, match=r"params\.links\[2\]\.mass: must be a positive finite number, got -1"):
        chain(scene, links, base_joints())
    with pytest.raises(sdp.Error, match=r"params\.mass: must be a positive"):
        scene.create_rigid_actor(name="r", shape=sdp.create_sphere_shape([0, 0, 0], 1), mass=-2.0)


def test_non_physical_inertia_warns_naming_the_field(scene, log_messages):
    """SuperDex simulates a non-physical inertia as the nearest physical one, with a warning (the
    log's Warning channel) naming the field and what is wrong with it."""
    links = base_links()
    links[1].moment_of_inertia = [1.0, 0, 0, -1.0, 0, 1.0]
    chain(scene, links, base_joints())
    warnings = [m for c, m in log_messages if c == sdp.LogChannel.WARNING]
    assert len(warnings) == 1
    assert re.search(r"params\.links\[1\]\.moment_of_inertia: must be positive definite .*nearest physical inertia",
                     warnings[0])
    log_messages.clear()
    links[1].moment_of_inertia = [1.0, 0, 0, 1.0, 0, 5.0]
    chain(scene, links, base_joints())
    warnings = [m for c, m in log_messages if c == sdp.LogChannel.WARNING]
    assert len(warnings) == 1
    assert re.search(r"params\.links\[1\]\.moment_of_inertia: is not physically valid: .*triangle inequality", warnings[0])
    for _ in range(10):
        scene.step(0.01)


def test_cycle_in_link_tree(scene):
    # parents come first (SuperDex's rule), so a cycle cannot even be written down
    links = base_links()
    links[1].parent_link = 2
    with pytest.raises(sdp.Error, match=r"links\[1\]\.parent_link: must be -1 \(root\) or the index of an earlier link, got 2"):
        chain(scene, links, base_joints())


def test_missing_parent(scene):
    links = base_links()
    links[2].parent_link = -1  # the field's default
    with pytest.raises(sdp.Error, match=r"links\[2\]\.parent_link: only the first link can be the root"):
        chain(scene, links, base_joints())
    links[2].parent_link = 7
    with pytest.raises(sdp.Error, match=r"links\[2\]\.parent_link: must be -1 \(root\) or the index of an earlier link, got 7"):
        chain(scene, links, base_joints())


def test_joint_errors(scene):
    joints = base_joints()
    joints[1].type = sdp.ArticulatedJointType.FREE
    with pytest.raises(sdp.Error, match=r"joints\[1\]\.type: only the root joint"):
        chain(scene, base_links(), joints)
    joints = base_joints()
    joints[2].axis = [0, 0, 0]
    with pytest.raises(sdp.Error, match=r"joints\[2\]\.axis: must be a non-zero vector"):
        chain(scene, base_links(), joints)
    joints = base_joints()
    joints[1].min_limit = [0, 0, 1.0]
    joints[1].max_limit = [0, 0, -1.0]
    with pytest.raises(sdp.Error, match=r"joints\[1\]\.min_limit: the lower limit 1 exceeds the upper limit -1"):
        chain(scene, base_links(), joints)
    # a joint type is an ArticulatedJointType: one left unset is refused, and a name is no type
    joints = base_joints()
    joints[2].type = sdp.ArticulatedJointType.INVALID
    with pytest.raises(sdp.Error, match=r"joints\[2\]\.type: is not set \(INVALID\)"):
        chain(scene, base_links(), joints)
    with pytest.raises(TypeError, match=r"ArticulatedJointParams\(\): type: cannot be set from a value of type str"):
        sdp.ArticulatedJointParams(name="jb", type="Hinge")
    with pytest.raises(sdp.Error, match=r"params\.joints: must hold one joint per link \(3\), got 2"):
        chain(scene, base_links(), base_joints()[:2])
    # SuperDex lets the root joint be any joint: a revolute root turns the whole chain
    joints = base_joints()
    joints[0].type = sdp.ArticulatedJointType.REVOLUTE
    joints[0].axis = [0, 0, 1]
    assert chain(scene, base_links(), joints).get_num_dofs() == 3


def test_wrong_types_and_names(scene):
    with pytest.raises(TypeError, match=r"ArticulatedLinkParams\(\): mass: cannot be set from a value of type str"):
        link("a", parent=0, mass="heavy")
    links = base_links()
    links[2].name = "a"
    with pytest.raises(sdp.Error, match=r"links\[2\]\.name: duplicate link name 'a'"):
        chain(scene, links, base_joints())
    links = base_links()
    links[0].center_of_mass = [0, math.nan, 0]
    with pytest.raises(sdp.Error, match=r"links\[0\]\.center_of_mass: must be finite, got a non-finite entry at index 1"):
        chain(scene, links, base_joints())
    with pytest.raises(sdp.Error, match=r"params\.joint_velocities: expected one value per DOF \(2\), got 1"):
        chain(scene, base_links(), base_joints(), joint_velocities=[0.0])


def test_unknown_field_raises(scene):
    # params structs take their own fields only
    with pytest.raises(TypeError, match=r"ArticulatedLinkParams\(\): unexpected keyword argument 'colour'"):
        link("base", colour="red")
    with pytest.raises(TypeError, match=r"RigidActorParams\(\): unexpected keyword argument 'colour'"):
        scene.create_rigid_actor(name="r", shape=sdp.create_sphere_shape([0, 0, 0], 1), colour="red")


def test_bad_shapes(engine):
    with pytest.raises(sdp.Error, match="sphere radius must be a positive finite number"):
        sdp.create_sphere_shape([0, 0, 0], -1)
    with pytest.raises(sdp.Error, match="radius: must be finite"):
        sdp.create_sphere_shape([0, 0, 0], math.nan)
    with pytest.raises(sdp.Error, match="box halfExtents"):
        sdp.create_box_shape([1, 0, 1])
    with pytest.raises(sdp.Error, match="plane normal must be non-zero"):
        sdp.create_plane_shape([0, 0, 0], 0)
    with pytest.raises(TypeError, match=r"create_box_shape\(half_extents: [\w.]*Real3\)(.|\n)*Invoked with types: list"):
        sdp.create_box_shape([1, 1])
    s = sdp.create_scene("s")
    with pytest.raises(sdp.Error, match="params.shape: a plane is unbounded and can only carry a static actor"):
        s.create_rigid_actor(name="p", shape=sdp.create_plane_shape([0, 0, 1], 0))
    with pytest.raises(TypeError, match=r"RigidActorParams\(\): shape: cannot be set from a value of type str"):
        s.create_rigid_actor(name="p", shape="sphere")
    with pytest.raises(sdp.Error, match=r"params.shape: is not set"):
        s.create_rigid_actor(name="p")
    shape = sdp.create_sphere_shape([0, 0, 0], 1)
    sdp.release_shape(shape)
    with pytest.raises(sdp.Error, match=r"params.shape: shape \d+ does not exist"):
        s.create_rigid_actor(name="r", shape=shape)


def test_bad_step_and_settings(scene):
    for dt in (-0.01, math.nan, math.inf):
        with pytest.raises(sdp.Error, match="step: time_step_sec must be a finite number of seconds >= 0"):
            scene.step(dt)
    scene.step(0.0)  # SuperDex: a zero step runs the callbacks and queries without moving anything
    assert scene.get_total_simulation_time() == 0
    with pytest.raises(sdp.Error, match="gravity"):
        scene.set_gravity([0, math.inf, 0])
    with pytest.raises(sdp.Error, match="num_worker_threads"):
        sdp.shutdown()
        sdp.initialize(-5)
    sdp.initialize(0)


def wrong_type(call, argument, got):
    """The bindings' TypeError for an argument of the wrong type: it names the call's arguments
    with their types, and the types it was given."""
    return pytest.raises(TypeError, match=rf"{call}\(self, (.*, )?{argument}[^\n]*\)(.|\n)*Invoked with types: [^\n]*{got}")


def test_arguments_of_the_wrong_type_name_the_argument(scene):
    ball = sphere(scene)
    with wrong_type("step", r"time_step_sec: float", "str"):
        scene.step("0.01")
    with wrong_type("get_actor", r"actor: [\w.]*ActorHandle", "str"):
        scene.get_actor("ball")
    with pytest.raises(sdp.Error, match=r"register_pre_step_callback\('cb'\): callback must be callable as callback\(info: StepInfo\), got int"):
        scene.register_pre_step_callback("cb", 5)
    with pytest.raises(sdp.Error, match=r"register_post_step_callback\('cb'\): callback must be callable"):
        scene.register_post_step_callback("cb", None)
    with pytest.raises(sdp.Error, match="register_query: type: expected a superdex.physics.QueryType or an int, got str"):
        ball.register_query("TOTAL_CONTACT_FORCE")
    with pytest.raises(sdp.Error, match="register_query: type: 99 is not a QueryType"):
        ball.register_query(99)
    with wrong_type("set_solver_params", r"params: [\w.]*SolverParams", "NoneType"):
        scene.set_solver_params(None)
    with wrong_type("restore_state", r"handle: [\w.]*StateHandle", "bytes"):
        scene.restore_state(b"state", True)
    with pytest.raises(sdp.Error, match=r"restore_state: state \d+ is not a state captured in scene 'test'"):
        scene.restore_state(sdp.StateHandle(12345), True)
    assert scene.get_actor(ball.get_handle()) == ball  # handles and actors still work
    scene.step(np.float64(0.01))  # and any real number type for dt
    assert scene.get_total_simulation_time() == pytest.approx(0.01)


@pytest.mark.parametrize("bad", [[math.nan, 0, 0], [0, math.inf, 0], [0, 0]])
def test_bad_vectors_name_the_argument(scene, bad):
    ball = sphere(scene)
    with pytest.raises(sdp.Error, match="set_velocity: (linear_vel: expected 3 values|linear and angular velocity must be finite)"):
        ball.set_velocity(bad, [0, 0, 0])
    with pytest.raises(sdp.Error, match="set_velocity: (angular_vel: expected 3 values|linear and angular velocity must be finite)"):
        ball.set_velocity([0, 0, 0], bad)
    if len(bad) == 3:
        with pytest.raises(sdp.Error, match=r"set_root_transform: world_from_local\.translation: must be finite"):
            ball.set_root_transform(sdp.TransformRT(translation=bad))
        with pytest.raises(sdp.Error, match="set_gravity: gravity must be finite"):
            scene.set_gravity(bad)
    else:  # a Real3 from two values: the bindings' TypeError naming the argument
        with pytest.raises(TypeError, match=r"translation: [\w.]*Real3"):
            sdp.TransformRT(translation=bad)
        with wrong_type("set_gravity", r"gravity: [\w.]*Real3", "list"):
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
    ball = sphere(scene)
    handle = ball.get_handle()
    scene.destroy_actor(ball)
    with pytest.raises(sdp.Error, match=f"actor {handle.value} does not exist"):
        getattr(ball, method)(*ACTOR_CALLS[method])
    scene.step(0.01)


def test_stale_handles_after_destroy_scene_and_shutdown(engine):
    scene = sdp.create_scene("gone")
    ball = sphere(scene)
    arm = two_link_arm(scene)
    sdp.destroy_scene(scene)
    for call in (lambda: scene.step(0.01), lambda: ball.get_mass(), lambda: arm.get_articulated_pose(),
                 lambda: scene.capture_state(), lambda: scene.get_actor(ball.get_handle())):
        with pytest.raises(sdp.Error, match="does not exist"):
            call()
    assert not sdp.is_valid_scene(scene)
    sdp.destroy_scene(scene)  # SuperDex: no effect on a destroyed scene
    live = sdp.create_scene("live")
    live_ball = sphere(live)
    sdp.shutdown()
    with pytest.raises(sdp.Error, match="does not exist"):
        live.step(0.01)
    with pytest.raises(sdp.Error, match="does not exist"):
        live_ball.get_root_transform()
    sdp.initialize(0)
    fresh = sdp.create_scene("fresh")
    fresh.step(0.01)


def test_actor_of_another_scene_is_refused(scene):
    ball = sphere(scene)
    other = sdp.create_scene("other")
    with pytest.raises(sdp.Error, match=f"destroy_actor: actor: actor {ball.get_handle().value} belongs to scene 'test', not 'other'"):
        other.destroy_actor(ball)
    with pytest.raises(sdp.Error, match="enable_actor_contact_symmetric: actor_a: actor .* does not exist in scene 'other'"):
        other.enable_actor_contact_symmetric(ball, ball, False, sdp.IncludeNestedActors.NO)
    assert other.get_actor(ball.get_handle()) is None
    assert scene.get_actor(ball.get_handle()) == ball
