"""Elastic rods (superdex.physics.experimental.create_rod_actor) against beam theory:

- a cantilever under its own weight deflects at its tip by w L^4 / (8 EI) (Euler-Bernoulli), within
  3 %, and by four times less when EI is four times larger (no hidden stiffness);
- a cantilever carrying a rigid block through a node-to-rigid and an element-rotation constraint
  deflects by w L^4 / (8 EI) + P L^3 / (3 EI) + M L^2 / (2 EI): the rotation constraint passes the
  block's moment M = P c into the rod;
- a straight rod twisted at one end by a rotation constraint on a turned block stores the torsion
  energy GJ phi^2 / (2 L) and turns its far element by phi (the twist spreads along it);
- a free rod keeps its momentum and falls at g; a bent-back rod straightens (its rest shape is
  straight) without gaining energy;
- generate_tubular_rod_model_data's polyline, axes and tube; bad shapes and materials raise
  superdex.physics.Error naming the field.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import node_positions_world

ex = sdp.experimental
G = 9.81


@pytest.fixture
def scene():
    sdp.initialize(num_worker_threads=0)
    s = sdp.create_scene("rods")
    s.set_gravity([0.0, 0.0, -G])
    yield s
    sdp.destroy_scene(s)
    sdp.shutdown()


def straight_model(length, elements, axis=(0.0, 1.0, 0.0), start=(0.0, 0.0, 0.0)):
    """A straight rod along +X from `start`, `elements` equal elements, frame axes `axis`."""
    t = np.linspace(0.0, 1.0, elements + 1)[:, None]
    nodes = np.asarray(start) + t * np.array([length, 0.0, 0.0])
    axes = np.tile(axis, (elements, 1))
    return ex.generate_tubular_rod_model_data(nodes=nodes, element_frame_axes=axes, radius=0.005, num_cross_section_segments=6,
                                              is_closed_loop=False)


def rod(scene, model, name="rod", **material):
    params = dict(linear_density=0.1, linear_rotational_inertia=1e-6, axial_stiffness=1e5, torsional_stiffness=80.0,
                  flexural_stiffness=[100.0, 100.0])
    params.update(material)
    actor = ex.create_rod_actor(scene, ex.RodActorParams(name=name, shape=sdp.create_model_shape(model),
                                                         material=ex.RodMaterialParams(**params)))
    actor.register_query_and_compute(sdp.QueryType.NODE_POSITIONS)
    actor.register_query_and_compute(sdp.QueryType.ELASTIC_ENERGY)
    return actor


def clamp(rod_actor, nodes=(0, 1)):
    """Pins the given nodes where they are (a clamp: the first element's direction is held).

    The rod's bending lives at its joints, each standing for the rod from one element's midpoint to
    the next one's: held by its first element, the rod is clamped at that element's midpoint, so a
    cantilever beyond node 1 bends over its span plus half an element (free_length)."""
    idx = np.asarray(nodes, dtype=np.int64)
    rod_actor.add_boundary_condition_nodes_world_permanent(idx, node_positions_world(rod_actor)[idx])


def free_length(span, h):
    """The length that bends of a rod clamped by its first element (h long) with `span` beyond it."""
    return span + 0.5 * h


def settle(scene, steps=60, dt=0.05):
    for _ in range(steps):
        scene.step(dt)


# ---- bending ---------------------------------------------------------------------------------


@pytest.mark.parametrize("EI", [100.0, 400.0])
def test_cantilever_under_its_own_weight_matches_euler_bernoulli(scene, EI):
    # clamped over its first element (nodes 0 and 1): the cantilever is the 1 m beyond node 1
    h, span = 0.025, 1.0
    r = rod(scene, straight_model(span + h, 41), flexural_stiffness=[EI, EI], mass_damping_coefficient=20.0)
    clamp(r)
    settle(scene)
    tip = node_positions_world(r)[-1]
    w, L = 0.1 * G, free_length(span, h)
    expected = w * L**4 / (8 * EI)
    assert -tip[2] == pytest.approx(expected, rel=0.03)
    assert abs(tip[1]) < 1e-3 * expected  # no sideways motion


def test_cantilever_bends_about_either_principal_axis_with_its_own_stiffness(scene):
    # frame axis +Y: the first flexural stiffness is about Y (bending in the XZ plane, gravity's)
    h, span = 0.025, 1.0
    soft_about_y = rod(scene, straight_model(span + h, 41, axis=(0, 1, 0)), name="a", flexural_stiffness=[100.0, 1000.0],
                       mass_damping_coefficient=20.0)
    soft_about_z = rod(scene, straight_model(span + h, 41, axis=(0, 0, 1), start=(0, 0.5, 0)), name="b",
                       flexural_stiffness=[100.0, 1000.0], mass_damping_coefficient=20.0)
    clamp(soft_about_y)
    clamp(soft_about_z)
    settle(scene)
    w, L = 0.1 * G, free_length(span, h)
    assert -node_positions_world(soft_about_y)[-1][2] == pytest.approx(w * L**4 / (8 * 100.0), rel=0.03)
    # axis +Z: gravity bends it about Y, its second (stiffer) direction
    assert -node_positions_world(soft_about_z)[-1][2] == pytest.approx(w * L**4 / (8 * 1000.0), rel=0.03)


def test_rotation_constraint_passes_a_blocks_moment_into_the_rod(scene):
    h, span, EI = 0.025, 1.0, 100.0
    r = rod(scene, straight_model(span + h, 41), flexural_stiffness=[EI, EI], mass_damping_coefficient=20.0)
    clamp(r)
    tip = node_positions_world(r)[-1]
    # a 0.2 kg block whose centre is c = 0.05 m beyond the tip, tied to the tip node and to the last
    # element's frame
    c, mass = 0.05, 0.2
    block = scene.create_rigid_actor(name="block", shape=sdp.create_box_shape(half_extents=[c, 0.01, 0.01]), mass=mass,
                                     world_from_local=sdp.TransformRT(translation=list(tip + [c, 0.0, 0.0])))
    scene.create_deformable_node_to_rigid_constraint(deformable_actor=r.get_handle(), rigid_actor=block.get_handle(),
                                                     deformable_node_index=41, fix_to_deformable_pos=True, stiffness=1e7)
    rotation = scene.create_rod_element_rotation_to_rigid_constraint(rigid_actor=block.get_handle(), rod_actor=r.get_handle(),
                                                                     element_index=40, ref_frame_rot_vec=[0.0, 0.0, 0.0], stiffness=1e5)
    assert rotation.get_type() == sdp.ConstraintType.ROD_ELEMENT_ROTATION_TO_RIGID
    rotation.register_query(sdp.QueryType.CONSTRAINT_FORCE)
    settle(scene, steps=100)
    w, P, L = 0.1 * G, mass * G, free_length(span, h)
    M = P * c
    expected = w * L**4 / (8 * EI) + P * L**3 / (3 * EI) + M * L**2 / (2 * EI)
    assert -node_positions_world(r)[-1][2] == pytest.approx(expected, rel=0.03)
    # the torque the constraint puts on the rod's element: the block's moment about the tip, about -Y
    # for a block hanging beyond +X (the element pulls the block's end up)
    torque = np.asarray(rotation.get_force())[3:]
    assert abs(torque[1]) == pytest.approx(M, rel=0.05)


def test_without_the_rotation_constraint_the_block_hangs_from_the_tip(scene):
    # the node-to-rigid tie alone is a ball joint: the block turns, no moment reaches the rod
    h, span, EI = 0.025, 1.0, 100.0
    r = rod(scene, straight_model(span + h, 41), flexural_stiffness=[EI, EI], mass_damping_coefficient=20.0)
    clamp(r)
    tip = node_positions_world(r)[-1]
    mass = 0.2
    block = scene.create_rigid_actor(name="block", shape=sdp.create_box_shape(half_extents=[0.01, 0.01, 0.05]), mass=mass,
                                     world_from_local=sdp.TransformRT(translation=list(tip + [0.0, 0.0, -0.05])))
    scene.create_deformable_node_to_rigid_constraint(deformable_actor=r.get_handle(), rigid_actor=block.get_handle(),
                                                     deformable_node_index=41, fix_to_deformable_pos=True, stiffness=1e7)
    settle(scene, steps=100)
    w, P, L = 0.1 * G, mass * G, free_length(span, h)
    assert -node_positions_world(r)[-1][2] == pytest.approx(w * L**4 / (8 * EI) + P * L**3 / (3 * EI), rel=0.03)


# ---- twisting --------------------------------------------------------------------------------


def test_twisting_one_end_stores_the_torsion_energy(scene):
    scene.set_gravity([0.0, 0.0, 0.0])
    length, elements, GJ = 1.0, 20, 2.0
    r = rod(scene, straight_model(length, elements), torsional_stiffness=GJ, mass_damping_coefficient=20.0)
    x = node_positions_world(r)
    # both ends held by static blocks through their node and their element's frame; the far
    # element's target is its frame turned by phi about the rod's axis (ref_frame_rot_vec)
    phi = 0.3
    near = scene.create_rigid_actor(name="near", shape=sdp.create_box_shape(half_extents=[0.01, 0.01, 0.01]), mass=1.0,
                                    is_static=True, world_from_local=sdp.TransformRT(translation=list(x[0])))
    far = scene.create_rigid_actor(name="far", shape=sdp.create_box_shape(half_extents=[0.01, 0.01, 0.01]), mass=1.0,
                                   is_static=True, world_from_local=sdp.TransformRT(translation=list(x[-1])))
    k_pos, k_rot = 1e6, 1e4
    for node, block in ((0, near), (elements, far)):
        scene.create_deformable_node_to_rigid_constraint(deformable_actor=r.get_handle(), rigid_actor=block.get_handle(),
                                                         deformable_node_index=node, fix_to_deformable_pos=True, stiffness=k_pos)
    scene.create_rod_element_rotation_to_rigid_constraint(rigid_actor=near.get_handle(), rod_actor=r.get_handle(), element_index=0,
                                                          ref_frame_rot_vec=[0.0, 0.0, 0.0], stiffness=k_rot)
    # the far element's target: turned by phi about its tangent (the element frame's third axis)
    twist = scene.create_rod_element_rotation_to_rigid_constraint(rigid_actor=far.get_handle(), rod_actor=r.get_handle(),
                                                                  element_index=elements - 1, ref_frame_rot_vec=[0.0, 0.0, phi],
                                                                  stiffness=k_rot)
    twist.register_query(sdp.QueryType.CONSTRAINT_FORCE)
    settle(scene, steps=80)
    # torsion over the span between the two held elements' midpoints, in series with the two
    # rotation constraints
    h = length / elements
    span = length - h
    k_total = 1.0 / (span / GJ + 2.0 / k_rot)
    torque = np.asarray(twist.get_force())[3:]
    assert np.linalg.norm(torque) == pytest.approx(k_total * phi, rel=0.03)
    assert abs(torque[0]) == pytest.approx(np.linalg.norm(torque), rel=1e-3)  # about the rod's axis


# ---- dynamics --------------------------------------------------------------------------------


def test_a_free_rod_falls_at_g_and_keeps_its_shape(scene):
    r = rod(scene, straight_model(1.0, 10))
    x0 = node_positions_world(r)
    dt, steps = 0.01, 50
    settle(scene, steps=steps, dt=dt)
    x1 = node_positions_world(r)
    t = dt * steps
    # backward Euler: the fall after n steps is g dt^2 n (n + 1) / 2
    fall = G * dt * dt * steps * (steps + 1) / 2
    np.testing.assert_allclose(x1[:, 2] - x0[:, 2], -fall, rtol=1e-4)
    # no sideways drift beyond the round-off of 50 steps (float: about 1e-7 m per step at 1 m)
    np.testing.assert_allclose(x1[:, :2], x0[:, :2], atol=1e-6 if sdp.uses_double_precision() else 1e-5)
    assert t > 0


def test_a_bent_rod_straightens_without_gaining_energy(scene):
    scene.set_gravity([0.0, 0.0, 0.0])
    # a rod whose rest shape is straight, started at rest bent into an arc of 60 degrees
    EI, elements = 1.0, 20
    r = rod(scene, straight_model(1.0, elements), flexural_stiffness=[EI, EI], torsional_stiffness=1.0)
    arc = math.pi / 3
    angle = np.linspace(0.0, arc, elements + 1)
    radius = 1.0 / arc
    bent = np.stack([radius * np.sin(angle), np.zeros_like(angle), radius * (1 - np.cos(angle))], axis=1)
    r.set_node_positions_local(bent.reshape(-1).tolist())
    r.register_query_and_compute(sdp.QueryType.ELASTIC_ENERGY)
    E0 = r.get_elastic_energy()
    # the bending energy EI kappa^2 l / 2 with kappa = pi / 3 per metre, over the length l the
    # joints stand for: from the first element's midpoint to the last one's (1 m less one element)
    assert E0 == pytest.approx(EI * arc**2 * (1.0 - 1.0 / elements) / 2, rel=0.01)
    # kinetic energy of the lumped node masses; backward Euler's x1 = x0 + dt v1 gives v1 exactly
    masses = np.full(elements + 1, 0.1 / elements)
    masses[[0, -1]] /= 2
    dt, x_prev, energies = 0.002, bent, []
    for _ in range(300):
        scene.step(dt)
        x = node_positions_world(r)
        v = (x - x_prev) / dt
        energies.append(r.get_elastic_energy() + 0.5 * float(np.sum(masses[:, None] * v * v)))
        x_prev = x
    chord = np.linalg.norm(x_prev[-1] - x_prev[0])
    assert chord > np.linalg.norm(bent[-1] - bent[0]) + 0.01  # it opened up
    assert max(energies) <= E0 * (1 + 1e-3)


# ---- what the debugger draws -----------------------------------------------------------------


def test_recordings_draw_the_rod_as_a_tube_of_its_own_radius(scene, tmp_path):
    import json

    # a steel-like wire of radius 4 mm: rho A and rho J of a solid circular section
    radius, rho, elements = 0.004, 7800.0, 6
    area, polar = math.pi * radius**2, math.pi * radius**4 / 2
    r = rod(scene, straight_model(0.3, elements), linear_density=rho * area, linear_rotational_inertia=rho * polar)
    path = tmp_path / "rod.jsonl"
    sdp.start_recording(str(path), 0.0)
    scene.step(0.01)
    sdp.stop_recording()
    lines = [json.loads(line) for line in open(path)]
    actor = next(l for l in lines if l["type"] == "actor" and l["handle"] == r.get_handle().value)
    assert actor["kind"] == "soft" and actor["rod"] == {"nodes": elements + 1, "closed": False}
    rings = 8  # vertices per ring
    assert len(actor["nodes"]) == (elements + 1) * rings + 2
    # a closed tube: every edge in two triangles
    assert len(actor["surfaceTriangles"]) == 2 * rings * elements + 2 * rings
    frame = next(l for l in lines if l["type"] == "frame")
    tube = np.asarray(frame["soft"][str(r.get_handle().value)]).reshape(-1, 3)
    centre = node_positions_world(r)
    for i in range(elements + 1):
        ring = tube[i * rings:(i + 1) * rings]
        np.testing.assert_allclose(np.linalg.norm(ring - centre[i], axis=1), radius, rtol=1e-4)
    np.testing.assert_allclose(tube[-2:], centre[[0, -1]], atol=1e-6)


# ---- model data and bad input ----------------------------------------------------------------


def test_tubular_model_data_has_the_polyline_axes_and_a_closed_tube():
    sdp.initialize(num_worker_threads=0)
    try:
        nodes = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0]], dtype=np.float32)
        axes = np.array([[0, 1, 1], [0, 1, 0]], dtype=np.float32)  # the first made unit
        m = ex.generate_tubular_rod_model_data(nodes=nodes, element_frame_axes=axes, radius=0.1, num_cross_section_segments=4,
                                               is_closed_loop=False)
        assert m.mesh.nodes_per_element == 2 and list(m.mesh.connectivity) == [0, 1, 1, 2]
        np.testing.assert_allclose(np.asarray(m.element_frame_axes).reshape(-1, 3), [[0, 2**-0.5, 2**-0.5], [0, 1, 0]], atol=1e-6)
        tube = np.asarray(m.visual_mesh.coordinates).reshape(-1, 3)
        assert len(tube) == 3 * 4 + 2
        # ring vertices at the radius from their node
        assert np.allclose(np.linalg.norm(tube[:4] - nodes[0], axis=1), 0.1, atol=1e-6)
        # closed surface: every edge in exactly two triangles, in opposite directions
        tris = np.asarray(m.visual_mesh.connectivity).reshape(-1, 3)
        edges = {}
        for t in tris:
            for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
                edges[(a, b)] = edges.get((a, b), 0) + 1
        assert all(edges.get((b, a), 0) == 1 for (a, b) in edges) and all(n == 1 for n in edges.values())
        sdp.model.validate(m)
        loop = ex.generate_tubular_rod_model_data(nodes=[[0, 0, 0], [1, 0, 0], [1, 1, 0]], element_frame_axes=[[0, 0, 1]] * 3,
                                                  radius=0.1, num_cross_section_segments=3, is_closed_loop=True)
        assert list(loop.mesh.connectivity) == [0, 1, 1, 2, 2, 0]
    finally:
        sdp.shutdown()


def test_bad_rods_raise_errors_naming_the_field(scene):
    with pytest.raises(sdp.Error, match="radius"):
        ex.generate_tubular_rod_model_data(nodes=[[0, 0, 0], [1, 0, 0]], element_frame_axes=[[0, 1, 0]], radius=0.0,
                                           num_cross_section_segments=6, is_closed_loop=False)
    with pytest.raises(sdp.Error, match="element_frame_axes"):
        ex.generate_tubular_rod_model_data(nodes=[[0, 0, 0], [1, 0, 0]], element_frame_axes=[[1, 0, 0]], radius=0.1,
                                           num_cross_section_segments=6, is_closed_loop=False)
    model = straight_model(1.0, 4)
    with pytest.raises(sdp.Error, match="material.linear_density"):
        rod(scene, model, linear_density=0.0)
    with pytest.raises(sdp.Error, match="torsional_stiffness"):
        rod(scene, model, linear_rotational_inertia=0.0, torsional_stiffness=0.0)
    with pytest.raises(sdp.Error, match="use_contact_skin"):
        ex.create_rod_actor(scene, ex.RodActorParams(name="r", shape=sdp.create_model_shape(model), use_contact_skin=True))
    with pytest.raises(sdp.Error, match="polyline"):
        ex.create_rod_actor(scene, ex.RodActorParams(name="r", shape=sdp.create_box_shape(half_extents=[1, 1, 1])))
    r = rod(scene, model)
    assert r.get_type() == sdp.ActorType.ROD
    assert len(r.get_node_positions_local()) == 3 * 5  # the polyline's nodes only
    box = scene.create_rigid_actor(name="b", shape=sdp.create_box_shape(half_extents=[0.1, 0.1, 0.1]), mass=1.0)
    with pytest.raises(sdp.Error, match="element_index 4 out of range"):
        scene.create_rod_element_rotation_to_rigid_constraint(rigid_actor=box.get_handle(), rod_actor=r.get_handle(), element_index=4)
    with pytest.raises(sdp.Error, match="must be a rod actor"):
        scene.create_rod_element_rotation_to_rigid_constraint(rigid_actor=box.get_handle(), rod_actor=box.get_handle(), element_index=0)
    with pytest.raises(sdp.Error, match="out of range"):
        scene.create_deformable_node_position_constraint(actor=r.get_handle(), node_index=5, position=[0, 0, 0])
