"""A box resting on the ground: its weight is carried by the contact, reported per actor, per pair and per point.

Scene: a 2 kg cube of half extent 0.1 m, released 1 mm above a static ground plane (z = 0,
normal +z) under g = 9.81 m/s^2, stepped at dt = 10 ms. Once at rest, Newton's laws fix every
reported quantity: the contact force on the box is +m g z (it cancels gravity), the force on
the ground is -m g z (action and reaction), and the contact forces have no moment about the
box's centre of mass (the weight acts there), so their centre of pressure lies under it.
"""

import numpy as np
import pytest

import superdex.physics as sdp
from contact_helpers import G, add_box, add_ground, position, quaternion, rotation_angle, step_for, vec

M = 2.0
HALF = 0.1
DT = 0.01
WEIGHT = M * G


def resting_box(scene, settle_seconds=1.0, positions=None):
    """Ground + box; registers both queries on the box; steps `settle_seconds`."""
    ground = add_ground(scene)
    box = add_box(scene, "box", [0, 0, HALF + 1e-3], half=HALF, mass=M)
    box.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    box.register_query(sdp.QueryType.CONTACT_POINTS)
    each = None if positions is None else (lambda k: positions.append(position(box)))
    step_for(scene, DT, settle_seconds, each)
    return ground, box


def test_resting_box_carries_its_weight(scene):
    """At rest, sum of forces = 0: the contact force on the box is (0, 0, m g) to 0.5 %, with
    no horizontal part; the box sits on the surface (centre 0.1 m up, no tilt) and does not move
    (< 0.1 mm over the last 0.5 s of a 1 s run)."""
    positions = []
    ground, box = resting_box(scene, 1.0, positions)
    f = vec(box.get_contact_force_world())
    assert f.shape == (3,)
    assert f[2] == pytest.approx(WEIGHT, rel=5e-3)
    assert abs(f[0]) < 1e-3 * WEIGHT and abs(f[1]) < 1e-3 * WEIGHT

    half_way = len(positions) // 2
    drift = max(np.linalg.norm(p - positions[half_way]) for p in positions[half_way:])
    assert drift < 1e-4, f"the resting box moved {drift * 1e3:.3f} mm in the last 0.5 s"
    assert position(box)[2] == pytest.approx(HALF, abs=1e-3)
    assert rotation_angle(quaternion(box), np.array([0, 0, 0, 1.0])) < 1e-3
    assert np.linalg.norm(vec(box.get_linear_velocity())) < 1e-3


def test_resting_box_contact_torque_vanishes(scene):
    """Moment balance about the centre of mass (the box origin): gravity has no moment there,
    so at rest the contact forces' moment about the origin is zero (here < 0.5 % of m g times
    the half size, the moment one corner's share of the weight would have)."""
    ground, box = resting_box(scene)
    tau = vec(box.get_contact_torque_world())
    assert tau.shape == (3,)
    assert np.linalg.norm(tau) < 5e-3 * WEIGHT * HALF


def test_contact_force_from_ground_is_the_total(scene):
    """The ground is the only thing touching the box, so the force from the ground alone equals
    the total contact force."""
    ground, box = resting_box(scene)
    total = vec(box.get_contact_force_world())
    from_ground = vec(box.get_contact_force_from_actor_world(ground))
    np.testing.assert_allclose(from_ground, total, rtol=1e-5, atol=1e-5 * WEIGHT)


def test_static_ground_feels_the_reaction(scene):
    """Newton's third law: the static ground, with its own registered query, is pushed down by
    the box's weight, (0, 0, -m g), equal and opposite to the force on the box; and the force
    on the ground from the box is that same force."""
    ground = add_ground(scene)
    box = add_box(scene, "box", [0, 0, HALF + 1e-3], half=HALF, mass=M)
    box.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    ground.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    step_for(scene, DT, 1.0)
    on_ground = vec(ground.get_contact_force_world())
    assert on_ground[2] == pytest.approx(-WEIGHT, rel=5e-3)
    assert abs(on_ground[0]) < 1e-3 * WEIGHT and abs(on_ground[1]) < 1e-3 * WEIGHT
    np.testing.assert_allclose(on_ground, -vec(box.get_contact_force_world()), rtol=1e-5, atol=1e-5 * WEIGHT)
    np.testing.assert_allclose(vec(ground.get_contact_force_from_actor_world(box)), on_ground,
                               rtol=1e-5, atol=1e-5 * WEIGHT)


def test_contact_points_of_a_resting_box(scene):
    """Each contact point is a record of the pair (a = the box, b = the ground) with a unit normal
    pointing from the ground into the box (+z), a position on the box's bottom face (z ~ 0,
    inside the 0.2 m x 0.2 m footprint), a gap of at most a millimetre, and a force that pushes
    (normal part >= 0) and stays in the friction cone (mu = 0.5). The point forces add up to
    the total contact force, and their centre of pressure is under the centre of mass (moment
    balance), within 1 mm."""
    ground, box = resting_box(scene)
    points = box.get_contact_points_world()
    assert len(points) >= 1
    total = vec(box.get_contact_force_world())
    summed = np.zeros(3)
    moment_z = np.zeros(2)
    for p in points:
        assert p.actor_a == box.get_handle()
        assert p.actor_b == ground.get_handle()
        n, x, f = vec(p.normal), vec(p.pos_a), vec(p.force)
        assert n.shape == x.shape == f.shape == (3,)
        np.testing.assert_allclose(n, [0, 0, 1], atol=1e-4)
        assert abs(x[2]) < 1e-3
        assert abs(x[0]) <= HALF + 1e-3 and abs(x[1]) <= HALF + 1e-3
        assert abs(p.distance) < 1e-3
        fn = float(f @ n)
        assert fn >= -1e-6 * WEIGHT
        assert np.linalg.norm(f - fn * n) <= 0.5 * fn + 1e-6 * WEIGHT
        summed += f
        moment_z += fn * x[:2]
    np.testing.assert_allclose(summed, total, rtol=1e-5, atol=1e-5 * WEIGHT)
    center_of_pressure = moment_z / summed[2]
    np.testing.assert_allclose(center_of_pressure, position(box)[:2], atol=1e-3)


def test_solver_stats_report_the_contact(scene):
    """A resting box is one island with contact; the solve converges, and, warm-started from the
    resting velocities of the last step, within a couple of Newton iterations."""
    resting_box(scene, settle_seconds=0.5)
    stats = scene.get_solver_stats()
    assert stats.convergence_status == sdp.ConvergenceStatus.CONVERGED
    assert stats.num_contacts >= 1
    assert stats.num_islands == 1
    assert stats.max_non_linear_iters <= 2
    assert stats.residual_norm >= 0


def test_unregistered_queries_raise(scene):
    """Results exist only for registered queries: asking without registering raises sdp.Error
    naming the query type to register; registering one type does not provide the other."""
    ground = add_ground(scene)
    box = add_box(scene, "box", [0, 0, HALF], half=HALF, mass=M)
    step_for(scene, DT, 0.1)
    for ask in (box.get_contact_force_world, box.get_contact_torque_world,
                lambda: box.get_contact_force_from_actor_world(ground)):
        with pytest.raises(sdp.Error, match="TOTAL_CONTACT_FORCE"):
            ask()
    with pytest.raises(sdp.Error, match="CONTACT_POINTS"):
        box.get_contact_points_world()

    handle = box.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    assert isinstance(handle, sdp.QueryHandle) and handle.is_valid()
    scene.step(DT)
    box.get_contact_force_world()
    with pytest.raises(sdp.Error, match="CONTACT_POINTS"):
        box.get_contact_points_world()
    with pytest.raises(sdp.Error, match="TOTAL_CONTACT_FORCE"):
        ground.get_contact_force_world()


def test_queries_can_be_cancelled_and_registered_again(scene):
    """A query handle can be cancelled; registering again gives results after the next step."""
    ground = add_ground(scene)
    box = add_box(scene, "box", [0, 0, HALF], half=HALF, mass=M)
    h1 = box.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    h2 = box.register_query(sdp.QueryType.CONTACT_POINTS)
    assert isinstance(h2, sdp.QueryHandle) and h2.is_valid() and h2 != h1
    step_for(scene, DT, 0.5)
    box.cancel_query(h1)
    box.cancel_query(h2)
    scene.step(DT)
    box.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    step_for(scene, DT, 0.5)
    assert vec(box.get_contact_force_world())[2] == pytest.approx(WEIGHT, rel=5e-3)
