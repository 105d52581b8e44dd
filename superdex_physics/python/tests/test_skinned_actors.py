"""Skinned articulations (ArticulatedActorParams.skin) and soft-skinned actors
(Scene.create_soft_skinned_actor), checked against hand-derived references: linear-blend skinning
of the skin's nodes from the link rotations, a ball's weight carried by the skin, the joint torques
that hold a skin-borne load (the weighted Jacobian, derived here), and a soft bar's weight carried
by the link it is tied to."""

import math

import numpy as np
import pytest

import superdex.physics as sdp
from superdex.physics.paths import resolve_asset

G = 9.8  # the engine's default gravity, (0, -9.8, 0)
PIVOT = np.array([0.0, 0.5, 0.0])  # the skin asset's arms: along +x from here, y up
L, W = 0.25, 0.025                 # arm length and width (m)
SKIN_HALF = 0.015                  # the skin tube's half side (m)
SKIN = "samples/articulations_parts/skin.mochi.json"
SOFT = "samples/articulations_parts/soft.mochi.json"


@pytest.fixture
def yscene(engine):
    """A scene with the engine's default gravity, -y."""
    return sdp.create_scene("skins")


def rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def two_arm_params(joint_type=sdp.ArticulatedJointType.REVOLUTE, link_gravity=True, skin=True, world_from_root=None, layer="arms"):
    """Two box arms along +x from the pivot, joints about +z (the skin asset's skeleton)."""
    arm = sdp.load_shape_from_file(file_path=str(resolve_asset("cube/cube_fine_mesh.mochi.json")), bake_scale=[L, W, W])
    centred = sdp.TransformRT(translation=[0, -W / 2, -W / 2])
    p = sdp.ArticulatedActorParams(name="arm")
    if world_from_root is not None:
        p.world_from_root = world_from_root
    p.links = [sdp.ArticulatedLinkParams(name=n, parent_link=parent, parent_joint_from_link=centred, shape=arm, layer=layer,
                                         collider_type=sdp.ColliderType.BOX, density=1000.0, has_gravity=link_gravity)
               for n, parent in (("upper", -1), ("lower", 0))]
    p.joints = [sdp.ArticulatedJointParams(name="shoulder", type=joint_type, axis=[0, 0, 1],
                                           parent_link_from_joint=sdp.TransformRT(translation=list(PIVOT))),
                sdp.ArticulatedJointParams(name="elbow", type=joint_type, axis=[0, 0, 1],
                                           parent_link_from_joint=sdp.TransformRT(translation=[L, W / 2, W / 2]))]
    if skin:
        p.skin = sdp.ArticulatedSkinParams(shape=sdp.load_shape_from_file(file_path=str(resolve_asset(SKIN))), layer="skin")
    return p


def skin_rest():
    """The skin asset's rest nodes (n, 3) and their weights on links 0 and 1 (n, 2)."""
    model = sdp.model.load_from_file(str(resolve_asset(SKIN)))
    x = np.asarray(model.mesh.coordinates, dtype=float).reshape(-1, 3)
    idx = np.asarray(model.mesh.skinning.indices).reshape(-1, 2)
    w = np.asarray(model.mesh.skinning.weights, dtype=float).reshape(-1, 2)
    weights = np.zeros((len(x), 2))
    for k in range(2):
        weights[np.arange(len(x)), idx[:, k]] += w[:, k]
    return x, weights


def test_skin_nodes_follow_the_links_by_their_blend_weights(yscene):
    """With the joints at (q0, q1), each node sits at w0 R(q0)(p - o0) + o0 + w1 (R(q0 + q1)(p - o1)
    + o1'), o1' the elbow moved by the shoulder (derived here): read back in the root joint's parent
    frame through SURFACE_NODE_POSITIONS, within 1e-5 m; bounds and normals agree."""
    offset = np.array([0.3, 0.0, -0.2])
    arm = yscene.create_articulated_actor(two_arm_params(world_from_root=sdp.TransformRT(translation=list(offset))))
    q = np.array([0.4, -0.7])
    arm.set_articulated_pose_from_joints(q)
    assert arm.is_query_supported(sdp.QueryType.SURFACE_NODE_POSITIONS)
    assert not arm.is_query_supported(sdp.QueryType.NODE_POSITIONS)
    with pytest.raises(sdp.Error):
        arm.get_surface_mesh_node_positions_local()  # the query is not registered
    arm.register_query_and_compute(sdp.QueryType.SURFACE_NODE_POSITIONS)
    arm.register_query_and_compute(sdp.QueryType.SURFACE_NODE_NORMALS)
    p, w = skin_rest()
    o0, o1 = PIVOT, PIVOT + [L, 0, 0]
    o1_moved = o0 + rot_z(q[0]) @ (o1 - o0)
    expected = (w[:, :1] * ((p - o0) @ rot_z(q[0]).T + o0) + w[:, 1:] * ((p - o1) @ rot_z(q.sum()).T + o1_moved))
    got = np.asarray(arm.get_surface_mesh_node_positions_local()).reshape(-1, 3)
    np.testing.assert_allclose(got, expected, atol=1e-5)
    assert arm.get_surface_mesh().get_num_nodes() == len(p)
    aabb = arm.get_aabb_world()
    assert np.all(np.asarray(aabb.min) <= expected.min(axis=0) + offset + 1e-6)
    assert np.all(np.asarray(aabb.max) >= expected.max(axis=0) + offset - 1e-6)
    n = np.asarray(arm.get_surface_mesh_node_normals_local()).reshape(-1, 3)
    np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1, atol=1e-5)
    # the middle node of the tube's top side, in the upper arm's part: the arm's rotated +y
    top = int(np.argmin(np.linalg.norm(p - [0.1, 0.5 + SKIN_HALF, 0], axis=1)))
    np.testing.assert_allclose(n[top], rot_z(q[0])[:, 1], atol=1e-5)
    # the surface nodes in a volume, in the same frame: those past the rotated elbow
    hits = []
    arm.query_nodes_in_volume_local(sdp.Sphere(center=list(o1_moved), radius=0.02), True, lambda i, _x: hits.append(i))
    assert sorted(hits) == sorted(np.flatnonzero(np.linalg.norm(expected - o1_moved, axis=1) < 0.02).tolist())


def ball(scene, x, y, radius=0.05, density=500.0):
    shape = sdp.create_sphere_shape(center=[0, 0, 0], radius=radius)
    return scene.create_rigid_actor(name="ball", layer="ball", shape=shape, density=density,
                                    world_from_local=sdp.TransformRT(translation=[x, y, 0]))


def test_a_ball_rests_on_a_welded_skin_and_presses_with_its_weight(yscene):
    """A ball dropped on the skin of a welded arm comes to rest on the skin's top nodes (its centre
    at their height plus the radius, within 1 mm) and the skin carries its weight, m g, within 1 %;
    the arms' own colliders are filtered out, so the skin alone holds it."""
    arm = yscene.create_articulated_actor(two_arm_params(joint_type=sdp.ArticulatedJointType.HARD))
    yscene.enable_layer_contact_symmetric("arms", "ball", False)
    r = 0.05
    b = ball(yscene, 0.1, 0.5 + SKIN_HALF + r + 0.01, r)
    arm.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    b.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    for _ in range(300):
        yscene.step(0.005)
    y = b.get_root_transform().translation[1]
    assert abs(y - (0.5 + SKIN_HALF + r)) < 1e-3
    weight = b.get_mass() * G
    np.testing.assert_allclose(np.asarray(b.get_contact_force_from_actor_world(arm)), [0, weight, 0], rtol=1e-2, atol=1e-2 * weight)
    np.testing.assert_allclose(np.asarray(b.get_contact_force_world()), [0, weight, 0], rtol=1e-2, atol=1e-2 * weight)
    # and the skin, the articulation's surface, takes it the other way
    np.testing.assert_allclose(np.asarray(arm.get_contact_force_world()), [0, -weight, 0], rtol=1e-2, atol=1e-2 * weight)


def test_a_load_on_the_blend_region_pushes_the_links_by_the_weights(yscene):
    """A ball rests on the skin where node weights are (0.25, 0.75) on (upper, lower) arm. Its
    weight m g at x on the skin maps to joint torques (derived here from the skinned point's
    velocity, sum_k w_k z x (p - o_k)): -m g x on the shoulder and -m g w1 (x - L) on the elbow.
    Those torques, applied the other way, hold the weightless arms still (within 2 mrad over 0.5 s);
    the torques of a point fixed on the lower arm (w1 = 1) do not (the elbow turns > 20 mrad)."""
    def run(w1_assumed):
        scene = sdp.create_scene(f"blend {w1_assumed}")
        arm = scene.create_articulated_actor(two_arm_params(link_gravity=False))
        scene.enable_layer_contact_symmetric("arms", "ball", False)
        x = 0.2625  # a ring of nodes: weights 0.25 and 0.75 (the ramp runs over 0.225-0.275)
        p, w = skin_rest()
        assert np.isclose(w[np.isclose(p[:, 0], x)][0, 1], 0.75)
        b = ball(scene, x, 0.5 + SKIN_HALF + 0.05)  # touching the ring's top node
        m = b.get_mass()
        arm.set_external_forces_on_dofs(dof_indices=[0, 1], force_values=[m * G * x, m * G * w1_assumed * (x - L)])
        for _ in range(250):
            scene.step(0.002)
        q = np.asarray(arm.get_articulated_pose(), dtype=float)
        sdp.destroy_scene(scene)
        return q

    held = run(0.75)
    assert np.all(np.abs(held) < 2e-3), held
    rigid = run(1.0)
    assert rigid[1] > 0.02, rigid


def test_the_skin_strikes_a_ball_when_the_arms_swing(yscene):
    """Released horizontal, the skinned arms swing down through a ball on the ground: the ball,
    touched by the skin only (the arms' colliders filtered out), is knocked away (> 5 cm)."""
    yscene.create_articulated_actor(two_arm_params())
    yscene.enable_layer_contact_symmetric("arms", "ball", False)
    yscene.enable_layer_contact_symmetric("arms", "ground", False)
    yscene.enable_layer_contact_symmetric("skin", "ground", False)
    b = ball(yscene, 0.05, 0.05)
    yscene.create_rigid_actor(name="ground", layer="ground", shape=sdp.create_plane_shape(normal=[0, 1, 0], distance=0), is_static=True)
    for _ in range(200):
        yscene.step(0.005)
    assert np.linalg.norm(np.asarray(b.get_root_transform().translation) - [0.05, 0.05, 0]) > 0.05


def test_a_skin_needs_skinning_weights_over_the_links(yscene):
    """A plain triangle mesh is refused as a skin, naming the field; so are weights on a link the
    articulation does not have; nothing is created."""
    p = two_arm_params(skin=False)
    p.skin = sdp.ArticulatedSkinParams(shape=sdp.create_tri_mesh_shape(coordinates=[0, 0, 0, 1, 0, 0, 0, 1, 0], connectivity=[0, 1, 2]))
    with pytest.raises(sdp.Error, match=r"skin\.shape.*skinning"):
        yscene.create_articulated_actor(p)
    mesh = sdp.MeshData(nodes_per_element=3, coordinates=[0, 0, 0, 1, 0, 0, 0, 1, 0], connectivity=[0, 1, 2],
                        skinning=sdp.SkinningData(weights_per_node=1, indices=[0, 1, 2], weights=[1, 1, 1]))
    p.skin = sdp.ArticulatedSkinParams(shape=sdp.create_model_shape(sdp.ModelData(mesh=mesh)))
    with pytest.raises(sdp.Error, match=r"link 2 out of range"):
        yscene.create_articulated_actor(p)
    assert yscene.get_num_actors() == 0


# ------------------------------------------------------------------------------ soft-skinned


def soft_skinned_params(attach=("lower",), joint_type=sdp.ArticulatedJointType.REVOLUTE, **kwargs):
    """The two-arm skeleton (the lower arm 0.125 m) and the soft bar beyond it (x 0.375-0.475)."""
    p = two_arm_params(joint_type=joint_type, skin=False)
    p.links[1].shape = sdp.load_shape_from_file(file_path=str(resolve_asset("cube/cube_fine_mesh.mochi.json")), bake_scale=[L / 2, W, W])
    soft = sdp.SoftActorParams(name="bar", shape=sdp.load_shape_from_file(file_path=str(resolve_asset(SOFT))), layer="soft")
    soft.material.neo_hookean.youngs_modulus = 1e6
    return sdp.SoftSkinnedActorParams(skeleton_params=p, soft_params=[soft], soft_attach_links=list(attach), **kwargs)


def test_a_soft_skinned_actor_nests_its_soft_bodies_and_goes_with_them(yscene):
    actor = yscene.create_soft_skinned_actor(soft_skinned_params(enable_colliding_links=True))
    assert actor.get_type() == sdp.ActorType.ARTICULATED
    links = [yscene.get_actor(h) for h in actor.get_nested_link_actors()]
    softs = [yscene.get_actor(h) for h in actor.get_nested_soft_actors()]
    assert [l.get_name() for l in links] == ["arm/upper", "arm/lower"]
    assert len(softs) == 1 and softs[0].get_type() == sdp.ActorType.SOFT
    assert softs[0].is_nested_soft_actor() and not softs[0].is_nested_link_actor()
    assert all(l.is_nested_link_actor() and not l.is_nested_soft_actor() for l in links)
    # the bar's four constrained nodes are tied to the lower arm where they are
    ties = []
    yscene.for_each_constraint(lambda c: ties.append(c))
    assert [c.get_type() for c in ties] == [sdp.ConstraintType.DEFORMABLE_NODE_TO_RIGID] * 4
    with pytest.raises(sdp.Error, match="soft-skinned"):
        yscene.destroy_actor(softs[0])
    with pytest.raises(sdp.Error, match="tie"):
        yscene.destroy_constraint(ties[0])
    yscene.step(0.01)
    yscene.destroy_actor(actor)
    assert yscene.get_actor(softs[0].get_handle()) is None
    remaining = []
    yscene.for_each_constraint(lambda c: remaining.append(c))
    assert remaining == []
    plain = yscene.create_articulated_actor(two_arm_params(skin=False))
    assert list(plain.get_nested_soft_actors()) == []


def test_soft_skinned_errors_name_the_field(yscene):
    with pytest.raises(sdp.Error, match=r"soft_attach_links\[0\].*'nowhere'"):
        yscene.create_soft_skinned_actor(soft_skinned_params(attach=("nowhere",)))
    with pytest.raises(sdp.Error, match="soft_attach_links"):
        p = soft_skinned_params(attach=("upper", "lower"))
        yscene.create_soft_skinned_actor(p)
    p = soft_skinned_params()
    p.soft_params[0].shape = sdp.load_shape_from_file(file_path=str(resolve_asset("cube/cube_fine_mesh.mochi.json")))
    with pytest.raises(sdp.Error, match=r"soft_params\[0\]\.shape.*constrained nodes"):
        yscene.create_soft_skinned_actor(p)
    p = soft_skinned_params(attach=())
    with pytest.raises(sdp.Error, match="skinning"):  # no link named, and no weights to choose one
        yscene.create_soft_skinned_actor(p)
    left = []
    yscene.for_each_constraint(lambda c: left.append(c))
    assert left == []


def test_the_link_carries_the_soft_bar_hung_on_it(yscene):
    """A welded skeleton holds the bar (tied by its four end nodes): at rest the ties pull the lower
    arm down by the bar's weight m g, within 1 %, and push the bar's nodes up by as much; with the
    skeleton on a vertical slider, the force that holds it still is the arms' and the bar's weight
    together (it holds within 1 mm over 0.5 s), while the arms' weight alone lets it fall."""
    actor = yscene.create_soft_skinned_actor(soft_skinned_params(joint_type=sdp.ArticulatedJointType.HARD))
    bar = yscene.get_actor(actor.get_nested_soft_actors()[0])
    ties = []
    yscene.for_each_constraint(lambda c: ties.append(c))
    for c in ties:
        c.register_query(sdp.QueryType.CONSTRAINT_FORCE)
    for _ in range(400):
        yscene.step(0.005)
    weight = bar.get_mass() * G
    on_link = sum(np.asarray(c.get_force())[:3] for c in ties)
    np.testing.assert_allclose(on_link, [0, -weight, 0], rtol=1e-2, atol=1e-2 * weight)

    def slide(total_mass_held):
        scene = sdp.create_scene("slider")
        p = soft_skinned_params()
        p.skeleton_params.joints[0].type = sdp.ArticulatedJointType.PRISMATIC
        p.skeleton_params.joints[0].axis = [0, 1, 0]
        p.skeleton_params.joints[1].type = sdp.ArticulatedJointType.HARD
        a = scene.create_soft_skinned_actor(p)
        soft = scene.get_actor(a.get_nested_soft_actors()[0])
        arms = sum(scene.get_actor(h).get_mass() for h in a.get_nested_link_actors())
        masses = {"all": arms + soft.get_mass(), "arms": arms}
        a.set_external_forces_on_dofs(dof_indices=[0], force_values=[masses[total_mass_held] * G])
        for _ in range(100):
            scene.step(0.005)
        y = float(np.asarray(a.get_articulated_pose())[0])
        sdp.destroy_scene(scene)
        return y

    assert abs(slide("all")) < 1e-3
    assert slide("arms") < -0.01
