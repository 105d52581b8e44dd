"""Constraints between rigid actors and targets, against analytic references: a spring's sag under
a weight, a physical pendulum's period, the forces a hanging chain carries, a saturated spring's
acceleration, a slider under tilted gravity and its stop, rotation tracking and range stops; and
their API (lookup, parameters, queries, errors, destruction with an actor)."""

import math

import numpy as np
import pytest

import superdex.physics as sdp

G = 9.81


def box(scene, name, center, half=(0.05, 0.05, 0.05), mass=1.0, static=False):
    return scene.create_rigid_actor(name=name, shape=sdp.create_box_shape(half_extents=list(half)), mass=mass, is_static=static,
                                    world_from_local=sdp.TransformRT(translation=list(center)))


def z_of(actor):
    return float(actor.get_root_transform().translation[2])


def test_pivot_sags_by_weight_over_stiffness_and_reports_the_weight(scene):
    b = box(scene, "b", [0, 0, 1], mass=2.0)
    K = 2e4
    c = scene.create_rigid_pivot_position_constraint(actor=b.get_handle(), local_position=[0, 0, 0.05], target_position=[0, 0, 1.05],
                                                     stiffness=K, damping=100)
    c.register_query(sdp.QueryType.CONSTRAINT_FORCE)
    for _ in range(400):
        scene.step(0.01)
    deviation = np.asarray(c.get_deviation())
    np.testing.assert_allclose(deviation, [0, 0, 2.0 * G / K], rtol=1e-3, atol=1e-9)
    force = np.asarray(c.get_force())
    assert force.shape == (6,)
    np.testing.assert_allclose(force, [0, 0, 2.0 * G, 0, 0, 0], rtol=1e-3, atol=1e-6)


def swing_period(ys, dt):
    """The mean period (s) between downward zero crossings of a swing sampled every dt."""
    ys = np.asarray(ys)
    crossings = [(i + 1) * dt + dt * ys[i] / (ys[i] - ys[i + 1]) for i in range(len(ys) - 1) if ys[i] > 0 >= ys[i + 1]]
    assert len(crossings) >= 2
    return float(np.mean(np.diff(crossings)))


def test_a_stiff_pivot_swings_with_the_period_of_the_jointed_pendulum(scene):
    # a 0.02 x 0.02 x 0.2 m rod pinned at its top end, released 0.05 rad from hanging: as a free
    # box on a pivot constraint, and as a one-link articulation on a revolute joint
    length, mass, theta0, dt = 0.2, 0.5, 0.05, 5e-4
    i_com = mass * (0.02**2 + length**2) / 12
    i_pivot = i_com + mass * (length / 2) ** 2
    period = 2 * math.pi * math.sqrt(i_pivot / (mass * G * length / 2))  # small swings
    rod = box(scene, "rod", [0, 0, 1 - length / 2], half=(0.01, 0.01, length / 2), mass=mass)
    scene.create_rigid_pivot_position_constraint(actor=rod.get_handle(), local_position=[0, 0, length / 2], target_position=[0, 0, 1],
                                                 stiffness=1e6, damping=0)
    rod.set_root_transform(sdp.TransformRT(rotation=sdp.Quaternion.from_axis_angle([1, 0, 0], theta0),
                                           translation=[0, length / 2 * math.sin(theta0), 1 - length / 2 * math.cos(theta0)]))
    jointed = scene.create_articulated_actor(
        name="jointed", links=[sdp.ArticulatedLinkParams(name="rod", mass=mass, center_of_mass=[0, 0, -length / 2],
                                                          moment_of_inertia=[i_com, 0, 0, i_com, 0, mass * 0.02**2 / 6])],
        joints=[sdp.ArticulatedJointParams(name="pivot", type=sdp.ArticulatedJointType.REVOLUTE, axis=[1, 0, 0],
                                           parent_link_from_joint=sdp.TransformRT(translation=[5, 0, 1]))])
    jointed.set_articulated_pose_from_joints([theta0])
    ys, ys_jointed = [], []
    for _ in range(int(2.5 * period / dt)):
        scene.step(dt)
        ys.append(float(rod.get_root_transform().translation[1]))
        # the jointed rod's centre, sideways: its angle's sine
        ys_jointed.append(length / 2 * math.sin(float(np.asarray(jointed.get_articulated_pose())[0])))
    measured, reference = swing_period(ys, dt), swing_period(ys_jointed, dt)
    assert measured == pytest.approx(reference, rel=1e-3)
    assert measured == pytest.approx(period, rel=0.01)


def test_a_hanging_chain_carries_the_weight_below_each_joint(scene):
    upper = box(scene, "upper", [0, 0, 0.9], mass=1.0)
    lower = box(scene, "lower", [0, 0, 0.8], mass=0.5)
    scene.enable_actor_contact_symmetric(upper, lower, False, sdp.IncludeNestedActors.NO)
    pivot = scene.create_rigid_pivot_position_constraint(actor=upper.get_handle(), local_position=[0, 0, 0.05], target_position=[0, 0, 0.95],
                                                         stiffness=1e5, damping=50)
    joint = scene.create_rigid_spherical_joint_constraint(actor_a=upper.get_handle(), actor_b=lower.get_handle(), local_pos_a=[0, 0, -0.05],
                                                          local_pos_b=[0, 0, 0.05], stiffness=1e5, damping=50)
    for c in (pivot, joint):
        c.register_query(sdp.QueryType.CONSTRAINT_FORCE)
    for _ in range(300):
        scene.step(0.01)
    np.testing.assert_allclose(np.asarray(pivot.get_force())[:3], [0, 0, 1.5 * G], rtol=1e-3, atol=1e-6)
    joint_force = np.asarray(joint.get_force())
    assert joint_force.shape == (12,)
    # the joint pulls the upper link down and the lower one up by the lower one's weight
    np.testing.assert_allclose(joint_force[:3], [0, 0, -0.5 * G], rtol=1e-3, atol=1e-6)
    np.testing.assert_allclose(joint_force[6:9], [0, 0, 0.5 * G], rtol=1e-3, atol=1e-6)
    # stretched: the lower link's point hangs below the upper one's
    np.testing.assert_allclose(np.asarray(joint.get_deviation()), [0, 0, -0.5 * G / 1e5], rtol=1e-2, atol=1e-9)


def test_a_saturated_spring_lets_the_body_fall_at_the_remaining_acceleration(scene):
    b = box(scene, "b", [0, 0, 1], mass=1.0)
    cap = 4.0  # N, below the weight
    c = scene.create_rigid_pivot_position_constraint(actor=b.get_handle(), target_position=[0, 0, 1], stiffness=1e5, saturation=cap)
    c.register_query(sdp.QueryType.CONSTRAINT_FORCE)
    t = 0.5
    for _ in range(int(t / 0.005)):
        scene.step(0.005)
    assert float(b.get_linear_velocity()[2]) == pytest.approx(-(G - cap) * t, rel=1e-3)
    assert np.asarray(c.get_force())[2] == pytest.approx(cap, rel=1e-6)


def test_without_stiffness_and_damping_the_constraint_exerts_nothing(scene):
    b = box(scene, "b", [0, 0, 1])
    c = scene.create_rigid_pivot_position_constraint(actor=b.get_handle(), target_position=[0, 0, 1], stiffness=0, damping=0)
    c.register_query(sdp.QueryType.CONSTRAINT_FORCE)
    for _ in range(50):
        scene.step(0.01)
    assert float(b.get_linear_velocity()[2]) == pytest.approx(-G * 0.5, rel=1e-6)
    assert np.linalg.norm(np.asarray(c.get_force())) == 0


def test_the_damping_follows_a_moving_target_without_lag(scene):
    # no gravity: a body tracking a target moving at constant speed settles on it (a damper that
    # ignored the target's motion would hold it D u / K behind)
    scene.set_gravity([0, 0, 0])
    b = box(scene, "b", [0, 0, 0])
    K, D, u, dt = 1e3, 200.0, 0.3, 0.01
    c = scene.create_rigid_pivot_position_constraint(actor=b.get_handle(), target_position=[0, 0, 0], stiffness=K, damping=D)
    for k in range(300):
        c.set_target_position(sdp.Real3(u * (k + 1) * dt, 0, 0))
        scene.step(dt)
    assert abs(float(np.asarray(c.get_deviation())[0])) < 1e-3 * D * u / K
    assert float(b.get_linear_velocity()[0]) == pytest.approx(u, rel=1e-4)


def test_a_slider_moves_along_its_axis_only_and_stops_at_its_bound(scene):
    # gravity tilted 30 degrees from -z towards +x; the slider's axis is x
    angle = math.radians(30)
    scene.set_gravity([G * math.sin(angle), 0, -G * math.cos(angle)])
    base = box(scene, "base", [0, 0, 0], static=True)
    slider = box(scene, "slider", [0, 0, 0.2], mass=1.0)
    scene.enable_actor_contact_symmetric(base, slider, False, sdp.IncludeNestedActors.NO)
    K = 1e5
    c = scene.create_rigid_prismatic_joint_constraint(actor_a=base.get_handle(), actor_b=slider.get_handle(), free_axis=[1, 0, 0],
                                                      stiffness=K, damping=20)
    t = 0.3
    for _ in range(int(t / 0.005)):
        scene.step(0.005)
    x = float(slider.get_root_transform().translation[0])
    # free along x: x = g sin(angle) t^2 / 2 (the damping acts across the axis only)
    assert x == pytest.approx(0.5 * G * math.sin(angle) * t * t, rel=0.02)
    assert z_of(slider) == pytest.approx(0.2 - G * math.cos(angle) / K, abs=2e-5)
    scene.destroy_constraint(c)
    slider.set_root_transform(sdp.TransformRT(translation=[0, 0, 0.2]))
    slider.set_velocity([0, 0, 0], [0, 0, 0])
    stop = scene.create_rigid_prismatic_joint_constraint(actor_a=base.get_handle(), actor_b=slider.get_handle(), free_axis=[1, 0, 0],
                                                         stiffness=K, damping=200, max=0.05)
    assert list(stop.get_limit_max_values()) == [pytest.approx(0.05)]
    for _ in range(400):
        scene.step(0.005)
    assert float(slider.get_root_transform().translation[0]) == pytest.approx(0.05 + G * math.sin(angle) / K, abs=2e-5)


def test_rotation_tracking_turns_a_body_to_its_target_relative_to_another(scene):
    scene.set_gravity([0, 0, 0])
    base = box(scene, "base", [0, 0, 0], static=True)
    b = box(scene, "b", [0, 0, 0.5])
    c = scene.create_joint_rotation_tracking_constraint(actor_a=base.get_handle(), actor_b=b.get_handle(), stiffness=50, damping=2)
    target = sdp.Quaternion.from_axis_angle([0, 0, 1], math.radians(40))
    c.set_target_rotation(target)
    for _ in range(400):
        scene.step(0.01)
    q = b.get_root_transform().rotation
    angle = 2 * math.degrees(math.atan2(q[2], q[3]))
    assert angle == pytest.approx(40, abs=0.01)
    assert np.linalg.norm(np.asarray(c.get_deviation())) < 1e-4


def test_a_pivot_rotation_holds_a_target_rotation_against_a_torque(scene):
    scene.set_gravity([0, 0, 0])
    b = box(scene, "b", [0, 0, 0])
    K, torque = 200.0, 1.5
    c = scene.create_rigid_pivot_rotation_constraint(actor=b.get_handle(), target_rotation=[0, 0, 0], stiffness=K, damping=5)
    c.register_query(sdp.QueryType.CONSTRAINT_FORCE)
    # a rigid actor's DOFs 3-5: the torque about its centre of mass (N m, world), kept until cleared
    b.set_external_forces_on_dofs([5], [torque])
    for _ in range(600):
        scene.step(0.01)
    tz = float(np.asarray(c.get_force())[2])
    assert tz == pytest.approx(-torque, rel=1e-3)
    assert float(np.asarray(c.get_deviation())[2]) == pytest.approx(-torque / K, rel=1e-2)


def test_a_rotation_range_stops_a_spinning_body_at_its_bound(scene):
    scene.set_gravity([0, 0, 0])
    base = box(scene, "base", [0, 0, 0], static=True)
    b = box(scene, "b", [0, 0, 0.5])
    c = scene.create_joint_rotation_range_constraint(actor_a=base.get_handle(), actor_b=b.get_handle(), angle_range_z=[-0.5, 0.5],
                                                     stiffness=1e4, damping=20)
    assert list(c.get_limit_min_values()) == pytest.approx([-2 * math.pi, -2 * math.pi, -0.5])
    b.set_velocity([0, 0, 0], [0, 0, 2.0])
    for _ in range(300):
        scene.step(0.005)
    q = b.get_root_transform().rotation
    angle = 2 * math.atan2(q[2], q[3])
    assert angle == pytest.approx(0.5, abs=0.01)
    assert abs(float(b.get_angular_velocity()[2])) < 1e-3


def test_constraint_api_lookup_queries_errors_and_destruction(scene):
    a = box(scene, "a", [0, 0, 1])
    b = box(scene, "b", [0, 0, 2])
    c = scene.create_rigid_spherical_joint_constraint(actor_a=a.get_handle(), actor_b=b.get_handle(), stiffness=10, damping=1)
    assert c.get_type() == sdp.ConstraintType.RIGID_SPHERICAL_JOINT
    assert scene.get_constraint(c.get_handle()) == c
    assert [a.get_handle(), b.get_handle()] == [c.get_actor(actor_index=i).get_handle() for i in range(c.get_num_actors())]
    assert list(c.get_dof_indices_for_actor(actor_index=1)) == [0, 1, 2, 3, 4, 5]
    with pytest.raises(sdp.Error, match="CONSTRAINT_FORCE"):
        c.get_force()
    with pytest.raises(sdp.Error, match="saturation"):
        c.set_saturation(0)
    with pytest.raises(sdp.Error, match="stiffness"):
        c.set_stiffness(-1)
    with pytest.raises(sdp.Error, match="RIGID_SPHERICAL_JOINT"):
        c.set_target_position(sdp.Real3(0, 0, 0))
    with pytest.raises(sdp.Error, match="actor_b"):
        scene.create_rigid_spherical_joint_constraint(actor_a=a.get_handle(), actor_b=a.get_handle())
    with pytest.raises(sdp.Error, match="free_axis"):
        scene.create_rigid_prismatic_joint_constraint(actor_a=a.get_handle(), actor_b=b.get_handle(), free_axis=[0, 0, 0])
    soft = scene.create_soft_actor(shape=sdp.create_tet_mesh_shape([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], [[0, 1, 2, 3]]))
    with pytest.raises(sdp.Error, match="rigid actor"):
        scene.create_rigid_pivot_position_constraint(actor=soft.get_handle())
    pivot = scene.create_rigid_pivot_position_constraint(actor=b.get_handle(), target_position=[0, 0, 2])
    seen = []
    scene.for_each_constraint(lambda k: seen.append(k.get_type()))
    assert seen == [sdp.ConstraintType.RIGID_SPHERICAL_JOINT, sdp.ConstraintType.RIGID_PIVOT_POSITION]
    # a constraint goes with either of its actors
    scene.destroy_actor(b)
    assert scene.get_constraint(c.get_handle()) is None and scene.get_constraint(pivot.get_handle()) is None
    with pytest.raises(sdp.Error, match="does not exist"):
        c.get_stiffness()


def soft_block(scene, name, center, size=0.1, density=500.0):
    from conftest import soft_actor, soft_material
    from test_soft_bodies import box_tet_mesh

    nodes, tets = box_tet_mesh([size] * 3, [2, 2, 2])
    nodes = np.asarray(nodes, dtype=float) - size / 2
    return soft_actor(scene, name, sdp.create_tet_mesh_shape(nodes, tets),
                      material=soft_material(youngs_modulus=1e5, poisson_ratio=0.3, density=density, stiffness_damping=0.01),
                      world_from_local=sdp.TransformRT(translation=list(center)))


def test_a_soft_block_hanging_by_a_node_carries_its_weight_on_it(scene):
    from conftest import node_positions_world

    block = soft_block(scene, "block", [0, 0, 1])
    top = int(np.argmax(node_positions_world(block)[:, 2] * 10 - np.abs(node_positions_world(block)[:, :2]).sum(axis=1)))
    x_top = node_positions_world(block)[top]
    K = 1e5
    c = scene.create_deformable_node_position_constraint(actor=block.get_handle(), node_index=top, position=list(x_top), stiffness=K,
                                                         damping=20)
    assert list(c.get_dof_indices_for_actor(actor_index=0)) == [3 * top, 3 * top + 1, 3 * top + 2]
    c.register_query(sdp.QueryType.CONSTRAINT_FORCE)
    for _ in range(300):
        scene.step(0.01)
    weight = block.get_mass() * G
    # (sideways: the tetrahedra's split of the cells leans the stretched block a little)
    np.testing.assert_allclose(np.asarray(c.get_force()), [0, 0, weight], rtol=1e-3, atol=1e-4 * weight)
    np.testing.assert_allclose(np.asarray(c.get_deviation()), [0, 0, weight / K], rtol=1e-2, atol=1e-8)


def test_a_soft_block_tied_under_a_rigid_box_hangs_from_it(scene):
    from conftest import node_positions_world

    box_actor = box(scene, "box", [0, 0, 1.0], mass=1.0)
    block = soft_block(scene, "block", [0, 0, 0.9])
    scene.enable_actor_contact_symmetric(box_actor, block, False, sdp.IncludeNestedActors.NO)
    pivot = scene.create_rigid_pivot_position_constraint(actor=box_actor.get_handle(), target_position=[0, 0, 1.0], stiffness=1e5, damping=50)
    # the block's top-centre surface node, found by find_closest from the box's bottom centre
    tie = scene.create_deformable_node_to_rigid_constraint(rigid_actor=box_actor.get_handle(), deformable_actor=block.get_handle(),
                                                           rigid_local_pos=[0, 0, -0.05], find_closest=True, stiffness=1e5, damping=20)
    node = int(tie.get_dof_indices_for_actor(actor_index=1)[0]) // 3
    np.testing.assert_allclose(node_positions_world(block)[node], [0, 0, 0.95], atol=1e-9)
    for c in (pivot, tie):
        c.register_query(sdp.QueryType.CONSTRAINT_FORCE)
    for _ in range(300):
        scene.step(0.01)
    soft_weight = block.get_mass() * G
    np.testing.assert_allclose(np.asarray(pivot.get_force())[:3], [0, 0, G * 1.0 + soft_weight], rtol=1e-3, atol=1e-4 * soft_weight)
    force = np.asarray(tie.get_force())
    assert force.shape == (9,)
    # down on the box, up on the node, each the block's weight
    np.testing.assert_allclose(force[:3], [0, 0, -soft_weight], rtol=1e-3, atol=1e-4 * soft_weight)
    np.testing.assert_allclose(force[6:], [0, 0, soft_weight], rtol=1e-3, atol=1e-4 * soft_weight)


def test_a_soft_block_tied_under_another_hangs_from_it_by_one_node(scene):
    """Two soft blocks: the upper hung from the world by a node, the lower tied to it node to node
    (find_closest: the two surface nodes nearest the midpoint of their origins, the facing
    centres). At rest the tie carries the lower block's weight, up on its node and down on the
    upper block's, the hanger both weights; the two nodes stay together within weight / K."""
    from conftest import node_positions_world

    upper = soft_block(scene, "upper", [0, 0, 1.0])
    lower = soft_block(scene, "lower", [0, 0, 0.89])
    scene.enable_actor_contact_symmetric(upper, lower, False, sdp.IncludeNestedActors.NO)
    x_upper = node_positions_world(upper)
    top = int(np.argmin(np.linalg.norm(x_upper - [0, 0, 1.05], axis=1)))
    hanger = scene.create_deformable_node_position_constraint(actor=upper.get_handle(), node_index=top, position=list(x_upper[top]),
                                                              stiffness=1e5, damping=20)
    K = 1e5
    tie = scene.create_deformable_node_to_deformable_node_constraint(actor_a=upper.get_handle(), actor_b=lower.get_handle(),
                                                                     find_closest=True, stiffness=K, damping=20)
    assert tie.get_type() == sdp.ConstraintType.DEFORMABLE_NODE_TO_DEFORMABLE_NODE
    node_a = int(tie.get_dof_indices_for_actor(actor_index=0)[0]) // 3
    node_b = int(tie.get_dof_indices_for_actor(actor_index=1)[0]) // 3
    np.testing.assert_allclose(node_positions_world(upper)[node_a], [0, 0, 0.95], atol=1e-9)
    np.testing.assert_allclose(node_positions_world(lower)[node_b], [0, 0, 0.94], atol=1e-9)
    for c in (hanger, tie):
        c.register_query(sdp.QueryType.CONSTRAINT_FORCE)
    for _ in range(300):
        scene.step(0.01)
    w_upper, w_lower = upper.get_mass() * G, lower.get_mass() * G
    np.testing.assert_allclose(np.asarray(hanger.get_force()), [0, 0, w_upper + w_lower], rtol=1e-3, atol=1e-4 * w_lower)
    force = np.asarray(tie.get_force())
    assert force.shape == (6,)
    np.testing.assert_allclose(force[:3], [0, 0, -w_lower], rtol=1e-3, atol=1e-4 * w_lower)
    np.testing.assert_allclose(force[3:], [0, 0, w_lower], rtol=1e-3, atol=1e-4 * w_lower)
    gap = node_positions_world(upper)[node_a] - node_positions_world(lower)[node_b]
    np.testing.assert_allclose(np.asarray(tie.get_deviation()), gap, atol=1e-9 if sdp.uses_double_precision() else 2e-7)
    np.testing.assert_allclose(gap, [0, 0, w_lower / K], rtol=1e-2, atol=1e-8)


def test_two_free_soft_blocks_pulled_together_keep_their_momentum(scene):
    """Without gravity, a tie between two free blocks 5 cm apart draws their nodes together with
    equal and opposite forces: the total momentum stays zero, the tied nodes meet."""
    from conftest import node_positions_world

    scene.set_gravity([0, 0, 0])
    a = soft_block(scene, "a", [0, 0, 0])
    b = soft_block(scene, "b", [0.15, 0, 0])
    x_a, x_b = node_positions_world(a), node_positions_world(b)
    node_a = int(np.argmin(np.linalg.norm(x_a - [0.05, 0, 0], axis=1)))
    node_b = int(np.argmin(np.linalg.norm(x_b - [0.1, 0, 0], axis=1)))
    tie = scene.create_deformable_node_to_deformable_node_constraint(actor_a=a.get_handle(), node_index_a=node_a, actor_b=b.get_handle(),
                                                                     node_index_b=node_b, stiffness=1e3, damping=5)
    np.testing.assert_allclose(np.asarray(tie.get_deviation()), [-0.05, 0, 0], atol=1e-9 if sdp.uses_double_precision() else 1e-7)
    mass = a.get_mass()

    def centre(actor):
        return node_positions_world(actor).mean(axis=0)  # uniform grid of equal cells: the nodes' mean is the centre of mass

    start = (centre(a) + centre(b)) / 2
    for _ in range(200):
        scene.step(0.01)
    # the blocks' centre of mass has not moved (equal masses: the mean of their centres)
    np.testing.assert_allclose((centre(a) + centre(b)) / 2, start, atol=1e-8 if sdp.uses_double_precision() else 1e-5)
    assert np.linalg.norm(np.asarray(tie.get_deviation())) < 1e-3
    assert centre(a)[0] > 0.02 and centre(b)[0] < 0.13  # both moved towards each other
    assert mass == pytest.approx(b.get_mass())


def test_node_to_node_constraint_errors(scene):
    a = soft_block(scene, "a", [0, 0, 0])
    b = soft_block(scene, "b", [0.2, 0, 0])
    rigid = box(scene, "box", [0, 0.3, 0])
    create = scene.create_deformable_node_to_deformable_node_constraint
    with pytest.raises(sdp.Error, match="actor_b .* must be a soft actor"):
        create(actor_a=a.get_handle(), actor_b=rigid.get_handle(), node_index_a=0, node_index_b=0)
    with pytest.raises(sdp.Error, match="node_index_b 1000 out of range"):
        create(actor_a=a.get_handle(), actor_b=b.get_handle(), node_index_a=0, node_index_b=1000)
    with pytest.raises(sdp.Error, match="the same node"):
        create(actor_a=a.get_handle(), actor_b=a.get_handle(), node_index_a=3, node_index_b=3)
    # two nodes of one body: a spring inside it
    c = create(actor_a=a.get_handle(), actor_b=a.get_handle(), node_index_a=0, node_index_b=1, stiffness=10.0)
    assert c.get_num_actors() == 2 and c.get_actor(0) == c.get_actor(1)
    scene.destroy_actor(b)
    assert scene.get_constraint(c.get_handle()) is not None
    # a constraint goes with either of its actors
    tie = create(actor_a=a.get_handle(), actor_b=soft_block(scene, "c", [0, 0.5, 0]).get_handle(), node_index_a=0, node_index_b=0)
    scene.destroy_actor(a)
    assert scene.get_constraint(tie.get_handle()) is None and scene.get_constraint(c.get_handle()) is None


def test_a_restored_state_brings_back_the_constraints_targets_and_springs(scene):
    # capture, then move the pivot's target and soften it; restoring the capture and stepping
    # again repeats the first run exactly
    b = box(scene, "b", [0, 0, 1])
    c = scene.create_rigid_pivot_position_constraint(actor=b.get_handle(), target_position=[0, 0, 1], stiffness=500, damping=5)
    for _ in range(10):
        scene.step(0.01)
    state = scene.capture_state()
    run = []
    for k in range(20):
        c.set_target_position(sdp.Real3(0.01 * k, 0, 1))
        scene.step(0.01)
        run.append(np.asarray(b.get_root_transform().translation, dtype=float))
    c.set_stiffness(1.0)
    c.set_target_position(sdp.Real3(3, 3, 3))
    scene.restore_state(state, release_immediately=False)
    assert c.get_stiffness() == pytest.approx(500)
    np.testing.assert_allclose(np.asarray(c.get_deviation()), -np.asarray(b.get_root_transform().translation, dtype=float) + [0, 0, 1],
                               atol=1e-6)
    for k in range(20):
        c.set_target_position(sdp.Real3(0.01 * k, 0, 1))
        scene.step(0.01)
        np.testing.assert_array_equal(np.asarray(b.get_root_transform().translation, dtype=float), run[k])
    # a state of a scene with other constraints does not restore
    scene.destroy_constraint(c)
    with pytest.raises(sdp.Error, match="constraints"):
        scene.restore_state(state, release_immediately=False)


def test_joint_limits_are_constraints_of_their_articulation(scene):
    """A hinge limited to [-0.5, 0]: one ARTICULATED_SINGLE_DOF_RANGE constraint with those limits
    and the joint's limit stiffness. A horizontal rod (1 kg at 0.5 m) falls onto its upper limit,
    which gives like a spring of that stiffness, K q = m g L cos q; stiffened or softened through
    the constraint, it gives accordingly; at stiffness 0 (near rigid) it stops at the limit."""
    from conftest import articulation, joint, link

    m, L = 1.0, 0.5
    links = [link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
             link("rod", parent=0, mass=m, center_of_mass=[L, 0, 0], moment_of_inertia=[1e-3, 0, 0, 1e-3, 0, 1e-3])]
    rod = articulation(scene, "rod", links, [joint("weld", "hard"),
                                             joint("hinge", "revolute", axis=[0, 1, 0], min_limit=[0, -0.5, 0], max_limit=[0, 0, 0])])
    before = scene.get_num_constraints()
    (limit,) = rod.get_articulated_joint_limit_constraints()
    assert limit.get_type() == sdp.ConstraintType.ARTICULATED_SINGLE_DOF_RANGE
    assert list(limit.get_limit_min_values()) == [pytest.approx(-0.5)] and list(limit.get_limit_max_values()) == [pytest.approx(0.0)]
    assert list(limit.get_dof_indices_for_actor(0)) == [0]
    rod.set_articulated_pose_from_joints(np.array([0.2]))
    assert float(limit.get_deviation()[0]) == pytest.approx(-0.2)
    rod.set_articulated_pose_from_joints(np.array([-0.2]))
    assert float(limit.get_deviation()[0]) == 0

    def settle():
        for _ in range(1500):
            scene.step(0.005)
        return float(rod.get_articulated_pose()[0])

    for K in (limit.get_stiffness(), 50.0):
        assert K > 0
        limit.set_stiffness(K)
        limit.set_damping(2.0)
        q = settle()
        assert K * q == pytest.approx(m * G * L * math.cos(q), rel=1e-2)
        assert float(limit.get_deviation()[0]) == pytest.approx(-q, rel=1e-6)
    limit.set_stiffness(0.0)
    limit.set_damping(0.0)
    assert settle() == pytest.approx(0.0, abs=2e-3)
    with pytest.raises(sdp.Error, match="joint limits"):
        scene.destroy_constraint(limit)
    with pytest.raises(sdp.Error, match="not reported"):
        limit.register_query(sdp.QueryType.CONSTRAINT_FORCE)
    with pytest.raises(sdp.Error, match="force cap"):
        limit.set_saturation(10.0)
    scene.destroy_actor(rod)
    assert scene.get_num_constraints() == before - 1
