"""Contact filtering: by actor pair, by layer pair, and inside articulations.

Rules under test: scene.enable_actor_contact_symmetric(a, b, enable) switches contact between
two actors; scene.enable_layer_contact_symmetric(la, lb, enable) between two layers (0..63);
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
from contact_helpers import G, add_ground, add_sphere, position, step_for, vec

DT = 0.01
R = 0.1


def overlapping_pair(scene, **kwargs_b):
    scene.set_gravity([0, 0, 0])
    a = add_sphere(scene, "a", [0, 0, 1], radius=R)
    b = add_sphere(scene, "b", [0.1, 0, 1], radius=R, **kwargs_b)
    return a, b


def head_on_pair(scene, layer_a=0, layer_b=0):
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
    scene.enable_actor_contact_symmetric(a, b, False)
    step_for(scene, DT, 1.0)
    np.testing.assert_allclose(position(a), [0, 0, 1], atol=1e-6)
    np.testing.assert_allclose(position(b), [0.1, 0, 1], atol=1e-6)
    assert scene.get_solver_stats().num_contacts == 0


def test_actor_pair_filter_lets_spheres_pass_through(scene):
    """Head-on balls with their pair disabled (given in either order) pass through each other
    at constant velocity; with contact on (control) they do not pass."""
    a, b = head_on_pair(scene)
    scene.enable_actor_contact_symmetric(b, a, False)
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
            scene.enable_actor_contact_symmetric(a, b, False)
            scene.enable_actor_contact_symmetric(a, b, True)
        step_for(scene, DT, 1.0)
        assert position(a)[0] < position(b)[0] - 2 * R + 1e-3, "the balls passed through each other"


def test_layer_filter(scene):
    """Layers 1 and 2 have contact disabled between them: head-on balls on those layers pass
    through each other. Balls on layers 3 and 4 (no filter) collide."""
    scene.enable_layer_contact_symmetric(1, 2, False)
    a, b = head_on_pair(scene, layer_a=1, layer_b=2)
    c = add_sphere(scene, "c", [-0.5, 2, 1], radius=R, layer=3)
    d = add_sphere(scene, "d", [0.5, 2, 1], radius=R, layer=4)
    c.set_velocity([1, 0, 0], [0, 0, 0])
    d.set_velocity([-1, 0, 0], [0, 0, 0])
    step_for(scene, DT, 1.0)
    np.testing.assert_allclose(position(a), [0.5, 0, 1], atol=1e-5)
    np.testing.assert_allclose(position(b), [-0.5, 0, 1], atol=1e-5)
    assert position(c)[0] < position(d)[0] - 2 * R + 1e-3


def test_layer_filter_against_the_ground(scene):
    """The ground is on layer 0. Disabling layers (0, 5) lets a ball on layer 5 fall through the
    ground (free fall: z = 0.3 - g t^2 / 2 after t = 0.6 s), while a ball on layer 6 lands and
    rests on it."""
    scene.enable_layer_contact_symmetric(5, 0, False)
    add_ground(scene)
    ghost = add_sphere(scene, "ghost", [0, 0, 0.3], radius=R, layer=5)
    solid = add_sphere(scene, "solid", [1, 0, 0.3], radius=R, layer=6)
    step_for(scene, DT, 0.6)
    assert position(ghost)[2] == pytest.approx(0.3 - 0.5 * G * 0.6**2, abs=0.03)
    assert position(solid)[2] == pytest.approx(R, abs=1e-3)


def test_layers_out_of_range_raise(scene):
    with pytest.raises(sdp.Error):
        scene.enable_layer_contact_symmetric(64, 0, False)
    with pytest.raises(sdp.Error):
        scene.enable_layer_contact_symmetric(0, -1, False)
    with pytest.raises(sdp.Error):
        add_sphere(scene, "bad", [0, 0, 1], layer=64)


# --------------------------------------------------------------------------------------
# articulations

INERTIA = [0.002, 0, 0, 0.02, 0, 0.02]


def double_pendulum(scene, name, y, with_shapes):
    """Base welded at (0, y, 1); two 0.5 m links about Y. With shapes, every joined pair
    overlaps: a ball on the base at the shoulder; a 1.2 m bar on link 1 centred on the
    shoulder, reaching through the elbow; a ball on link 2 centred on the elbow. The only
    non-joined pair, base and link 2, stays 0.5 m apart (the elbow circles the shoulder)."""
    shapes = [{"sphere": {"radius": 0.12, "center": [0, 0, 0]}},
              {"box": {"halfExtents": [0.6, 0.05, 0.05]}},
              {"sphere": {"radius": R, "center": [0, 0, 0]}}]
    links = [
        {"name": "base", "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01]},
        {"name": "upper", "parentLink": 0, "mass": 1.0, "centerOfMass": [0.25, 0, 0], "momentOfInertia": INERTIA},
        {"name": "lower", "parentLink": 1, "mass": 1.0, "centerOfMass": [0.25, 0, 0], "momentOfInertia": INERTIA},
    ]
    if with_shapes:
        for link, shape in zip(links, shapes):
            link["shape"] = shape
    joints = [
        {"name": "weld", "type": "Hard", "parentLinkFromJoint": {"translation": [0, y, 1]}},
        {"name": "shoulder", "type": "Revolute", "axis": [0, 1, 0]},
        {"name": "elbow", "type": "Revolute", "axis": [0, 1, 0], "parentLinkFromJoint": {"translation": [0.5, 0, 0]}},
    ]
    arm = scene.create_articulated_actor(name, links, joints)
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


def folding_chain(scene):
    """Three links, gravity off: 'a' welded at height 1 with a ball at x = 0.5; 'b' welded to 'a';
    'c' hinged (about Y) to 'b' at x = 0.25, with a ball 0.25 further out. At q = 0 the balls
    coincide; they touch (centres 2 r apart) at |q| = 2 asin(2 r / 0.5) = 0.823 rad. 'c' starts
    at q = -1.2 swinging towards q = 0 at 2 rad/s. 'a' and 'c' are not joined to each other."""
    scene.set_gravity([0, 0, 0])
    links = [
        {"name": "a", "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01],
         "shape": {"sphere": {"radius": R, "center": [0.5, 0, 0]}}},
        {"name": "b", "parentLink": 0, "mass": 0.1, "momentOfInertia": [1e-3, 0, 0, 1e-3, 0, 1e-3]},
        {"name": "c", "parentLink": 1, "mass": 1.0, "centerOfMass": [0.25, 0, 0], "momentOfInertia": INERTIA,
         "shape": {"sphere": {"radius": R, "center": [0.25, 0, 0]}}},
    ]
    joints = [
        {"name": "weld", "type": "Hard", "parentLinkFromJoint": {"translation": [0, 0, 1]}},
        {"name": "ab", "type": "Hard"},
        {"name": "bc", "type": "Revolute", "axis": [0, 1, 0], "parentLinkFromJoint": {"translation": [0.25, 0, 0]}},
    ]
    chain = scene.create_articulated_actor("chain", links, joints)
    chain.set_articulated_pose_from_joints([-1.2])
    chain.set_articulated_joint_velocities([2.0])
    handles = chain.get_nested_link_actors()
    return chain, scene.get_actor(handles[0]), scene.get_actor(handles[2])


def test_non_adjacent_links_collide(scene):
    """Self-collision: the swinging ball of 'c' hits the ball of 'a' and cannot pass q = -0.80
    (touching at -0.823; -0.80 would be 5 mm of penetration)."""
    chain, a, c = folding_chain(scene)
    q_max = []
    step_for(scene, DT, 1.0, lambda _: q_max.append(float(chain.get_articulated_pose()[0])))
    assert max(q_max) < -0.80, f"link c swung through link a (q reached {max(q_max):.3f})"


def test_self_collision_can_be_disabled_by_actor_pair(scene):
    """The same chain with contact disabled between links 'a' and 'c' swings freely:
    q = -1.2 + 2 t, so q = 0.8 after 1 s."""
    chain, a, c = folding_chain(scene)
    scene.enable_actor_contact_symmetric(a, c, False)
    step_for(scene, DT, 1.0)
    assert float(chain.get_articulated_pose()[0]) == pytest.approx(0.8, abs=1e-3)
