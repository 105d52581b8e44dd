"""Contact filtering: by actor pair, by layer pair, and inside articulations.

Rules under test: scene.enable_actor_contact_symmetric(a, b, enable, IncludeNestedActors.NO)
switches contact between two actors; scene.enable_layer_contact_symmetric(la, lb, enable)
between two named layers (at most 64 per scene);
links joined by a joint never collide with each other; other links of one articulation do
(self-collision) unless disabled by actor pair. Every filtered case is paired with the same
scene unfiltered, so a test cannot pass merely because contact does nothing.

Gravity is off except where a ground is involved, so free bodies move uniformly unless a
contact acts: overlapping spheres with contact enabled are pushed apart; with it disabled
they stay where they are, exactly.
"""

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import articulation, joint, link
from contact_helpers import G, add_ground, add_sphere, position, step_for, vec

DT = 0.01
R = 0.1


def overlapping_pair(scene, **kwargs_b):
    scene.set_gravity([0, 0, 0])
    a = add_sphere(scene, "a", [0, 0, 1], radius=R)
    b = add_sphere(scene, "b", [0.1, 0, 1], radius=R, **kwargs_b)
    return a, b


def head_on_pair(scene, layer_a="", layer_b=""):
    """Two balls 1 m apart closing at 2 m/s; without contact they swap places in 1 s."""
    scene.set_gravity([0, 0, 0])
    a = add_sphere(scene, "a", [-0.5, 0, 1], radius=R, layer=layer_a)
    b = add_sphere(scene, "b", [0.5, 0, 1], radius=R, layer=layer_b)
    a.set_velocity([1, 0, 0], [0, 0, 0])
    b.set_velocity([-1, 0, 0], [0, 0, 0])
    return a, b


def test_overlapping_spheres_are_pushed_apart_when_contact_is_on(scene):
    """Control: two balls overlapping by 0.1 m separate (centres > 2 r apart after 1 s)."""
    a, b = overlapping_pair(scene)
    step_for(scene, DT, 1.0)
    assert np.linalg.norm(position(b) - position(a)) > 2 * R


def test_actor_pair_filter_lets_overlapping_spheres_stay(scene):
    """With contact disabled between them, overlapping balls feel nothing: they stay put."""
    a, b = overlapping_pair(scene)
    scene.enable_actor_contact_symmetric(a, b, False, sdp.IncludeNestedActors.NO)
    step_for(scene, DT, 1.0)
    np.testing.assert_allclose(position(a), [0, 0, 1], atol=1e-6)
    np.testing.assert_allclose(position(b), [0.1, 0, 1], atol=1e-6)
    assert scene.get_solver_stats().num_contacts == 0


def test_actor_pair_filter_lets_spheres_pass_through(scene):
    """Head-on balls with their pair disabled (given in either order) pass through each other
    at constant velocity; with contact on (control) they do not pass."""
    a, b = head_on_pair(scene)
    scene.enable_actor_contact_symmetric(b, a, False, sdp.IncludeNestedActors.NO)
    step_for(scene, DT, 1.0)
    np.testing.assert_allclose(position(a), [0.5, 0, 1], atol=1e-5)
    np.testing.assert_allclose(position(b), [-0.5, 0, 1], atol=1e-5)
    np.testing.assert_allclose(vec(a.get_linear_velocity()), [1, 0, 0], atol=1e-6)


def test_head_on_spheres_collide_when_contact_is_on(engine):
    """Control for the pass-through tests, and re-enabling a disabled pair restores contact."""
    for reenable in (False, True):
        scene = sdp.create_scene("s")
        a, b = head_on_pair(scene)
        if reenable:
            scene.enable_actor_contact_symmetric(a, b, False, sdp.IncludeNestedActors.NO)
            scene.enable_actor_contact_symmetric(a, b, True, sdp.IncludeNestedActors.NO)
        step_for(scene, DT, 1.0)
        assert position(a)[0] < position(b)[0] - 2 * R + 1e-3, "the balls passed through each other"


def test_layer_filter(scene):
    """Layers "one" and "two" have contact disabled between them: head-on balls on those layers
    pass through each other. Balls on layers "three" and "four" (no filter) collide."""
    scene.enable_layer_contact_symmetric("one", "two", False)
    assert not scene.is_layer_contact_enabled("one", "two") and not scene.is_layer_contact_enabled("two", "one")
    assert scene.is_layer_contact_enabled("three", "four")
    a, b = head_on_pair(scene, layer_a="one", layer_b="two")
    c = add_sphere(scene, "c", [-0.5, 2, 1], radius=R, layer="three")
    d = add_sphere(scene, "d", [0.5, 2, 1], radius=R, layer="four")
    c.set_velocity([1, 0, 0], [0, 0, 0])
    d.set_velocity([-1, 0, 0], [0, 0, 0])
    step_for(scene, DT, 1.0)
    np.testing.assert_allclose(position(a), [0.5, 0, 1], atol=1e-5)
    np.testing.assert_allclose(position(b), [-0.5, 0, 1], atol=1e-5)
    assert position(c)[0] < position(d)[0] - 2 * R + 1e-3


def test_layer_filter_against_the_ground(scene):
    """The ground is on layer "ground". Disabling layers ("ghost", "ground") lets a ball on layer
    "ghost" fall through the ground (free fall: z = 0.3 - g t^2 / 2 after t = 0.6 s), while a
    ball on layer "solid" lands and rests on it."""
    scene.enable_layer_contact_symmetric("ghost", "ground", False)
    add_ground(scene, layer="ground")
    ghost = add_sphere(scene, "ghost", [0, 0, 0.3], radius=R, layer="ghost")
    solid = add_sphere(scene, "solid", [1, 0, 0.3], radius=R, layer="solid")
    step_for(scene, DT, 0.6)
    assert position(ghost)[2] == pytest.approx(0.3 - 0.5 * G * 0.6**2, abs=0.03)
    assert position(solid)[2] == pytest.approx(R, abs=1e-3)


def test_bad_layers_raise(scene):
    """Layers are names, registered on first use, at most 64 per scene (the actors' default
    layer "" among them): an empty name cannot be filtered, and a 65th layer raises, each error
    naming the argument or field."""
    with pytest.raises(sdp.Error, match="layer_a"):
        scene.enable_layer_contact_symmetric("", "x", False)
    with pytest.raises(sdp.Error, match="layer_b"):
        scene.enable_layer_contact_symmetric("x", "", False)
    for k in range(63):
        scene.enable_layer_contact_symmetric(f"layer{k}", "layer0", True)
    assert scene.get_num_contact_layers() == 63
    with pytest.raises(sdp.Error, match="at most 64"):
        scene.enable_layer_contact_symmetric("layer63", "layer0", False)
    with pytest.raises(sdp.Error, match="params.layer"):
        add_sphere(scene, "bad", [0, 0, 1], layer="layer63")


# --------------------------------------------------------------------------------------
# articulations

INERTIA = [0.002, 0, 0, 0.02, 0, 0.02]


def double_pendulum(scene, name, y, with_shapes):
    """Base welded at (0, y, 1); two 0.5 m links about Y. With shapes, every joined pair
    overlaps: a ball on the base at the shoulder; a 1.2 m bar on link 1 centred on the
    shoulder, reaching through the elbow; a ball on link 2 centred on the elbow. The only
    non-joined pair, base and link 2, stays 0.5 m apart (the elbow circles the shoulder)."""
    links = [
        link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
        link("upper", parent=0, mass=1.0, center_of_mass=[0.25, 0, 0], moment_of_inertia=INERTIA),
        link("lower", parent=1, mass=1.0, center_of_mass=[0.25, 0, 0], moment_of_inertia=INERTIA),
    ]
    if with_shapes:
        shapes = [sdp.create_sphere_shape([0, 0, 0], 0.12), sdp.create_box_shape([0.6, 0.05, 0.05]),
                  sdp.create_sphere_shape([0, 0, 0], R)]
        for params, shape in zip(links, shapes):
            params.shape = shape
    joints = [
        joint("weld", "hard", at=[0, y, 1]),
        joint("shoulder", "revolute", axis=[0, 1, 0]),
        joint("elbow", "revolute", at=[0.5, 0, 0], axis=[0, 1, 0]),
    ]
    arm = articulation(scene, name, links, joints)
    arm.set_articulated_pose_from_joints([0.0, 0.5])
    return arm


def test_links_joined_by_a_joint_do_not_collide(engine):
    """A double pendulum whose joined links overlap at every joint swings exactly like the same
    pendulum without shapes (1.5 s from horizontal, poses within 1e-5 rad at every step, 1e-3 in
    float32), and
    its scene reports no contact."""
    trajectories = []
    for with_shapes in (True, False):
        scene = sdp.create_scene("s")
        scene.set_gravity([0, 0, -G])
        arm = double_pendulum(scene, "arm", 0.0, with_shapes)
        poses = []

        def record(_):
            poses.append(vec(arm.get_articulated_pose()))
            if with_shapes:
                assert scene.get_solver_stats().num_contacts == 0

        step_for(scene, 0.005, 1.5, record)
        trajectories.append(np.array(poses))
    assert np.abs(trajectories[1] - trajectories[1][0]).max() > 0.5, "the pendulum should swing"
    # identical inputs give identical results; float32 leaves room for differently ordered sums
    atol = 1e-5 if sdp.uses_double_precision() else 1e-3
    np.testing.assert_allclose(trajectories[0], trajectories[1], atol=atol)


def folding_chain(scene, ab="revolute"):
    """Three links, gravity off: 'a' welded at height 1 with a ball at x = 0.5; 'b' hinged to 'a'
    about X (nothing turns it: 'c' swings in the XZ plane, so its reaction has no moment about X);
    'c' hinged (about Y) to 'b' at x = 0.25, with a ball 0.25 further out. At q = 0 the balls
    coincide; they touch (centres 2 r apart) at |q| = 2 asin(2 r / 0.5) = 0.823 rad. 'c' starts
    at q = -1.2 swinging towards q = 0 at 2 rad/s. 'a' and 'c' are not joined to each other,
    unless ab="hard" welds 'b' to 'a': then 'c' hangs on the rigid body of 'a' and 'b'."""
    scene.set_gravity([0, 0, 0])
    links = [
        link("a", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01], shape=sdp.create_sphere_shape([0.5, 0, 0], R)),
        link("b", parent=0, mass=0.1, moment_of_inertia=[1e-3, 0, 0, 1e-3, 0, 1e-3]),
        link("c", parent=1, mass=1.0, center_of_mass=[0.25, 0, 0], moment_of_inertia=INERTIA,
             shape=sdp.create_sphere_shape([0.25, 0, 0], R)),
    ]
    joints = [
        joint("weld", "hard", at=[0, 0, 1]),
        joint("ab", ab, axis=[1, 0, 0]),
        joint("bc", "revolute", at=[0.25, 0, 0], axis=[0, 1, 0]),
    ]
    chain = articulation(scene, "chain", links, joints)
    chain.set_articulated_pose_from_joints([0.0, -1.2] if ab == "revolute" else [-1.2])
    chain.set_articulated_joint_velocities([0.0, 2.0] if ab == "revolute" else [2.0])
    handles = chain.get_nested_link_actors()
    return chain, scene.get_actor(handles[0]), scene.get_actor(handles[2])


def test_non_adjacent_links_collide(scene):
    """Self-collision: the swinging ball of 'c' hits the ball of 'a' and cannot pass q = -0.80
    (touching at -0.823; -0.80 would be 5 mm of penetration)."""
    chain, a, c = folding_chain(scene)
    q_max = []
    step_for(scene, DT, 1.0, lambda _: q_max.append(float(chain.get_articulated_pose()[-1])))
    assert max(q_max) < -0.80, f"link c swung through link a (q reached {max(q_max):.3f})"


def test_a_link_hanging_on_a_welded_group_is_joined_to_all_of_it(scene):
    """With 'b' welded to 'a', 'a' and 'b' are one rigid body and 'c' hangs on it by its hinge: as
    a child of 'b' it is joined to 'a' too (MuJoCo's weld rule), so it swings through 'a' freely:
    q = -1.2 + 2 t = 0.8 after 1 s."""
    chain, a, c = folding_chain(scene, ab="hard")
    step_for(scene, DT, 1.0)
    assert float(chain.get_articulated_pose()[-1]) == pytest.approx(0.8, abs=1e-3)


def test_self_collision_can_be_disabled_by_actor_pair(scene):
    """The same chain with contact disabled between links 'a' and 'c' swings freely:
    q = -1.2 + 2 t, so q = 0.8 after 1 s."""
    chain, a, c = folding_chain(scene)
    scene.enable_actor_contact_symmetric(a, c, False, sdp.IncludeNestedActors.NO)
    step_for(scene, DT, 1.0)
    assert float(chain.get_articulated_pose()[-1]) == pytest.approx(0.8, abs=1e-3)
