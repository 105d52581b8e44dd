"""Soft bodies in contact with moving rigid bodies, in one implicit solve (soft nodes against the
rigid shape's distance field; the rigid body's and the nodes' velocities are unknowns of the same
Newton problem).

- A rigid 1 kg sphere resting on a soft block pinned at its base: at rest the block's contact force
  from the sphere and the sphere's contact force both equal the sphere's weight within 1 %
  (momentum balance of the sphere), and the node contact forces add up to it.
- The duck-lamp prefab pressed by a sphere on a vertical slider carrying a known downward force: the
  reaction equals the applied force plus the sphere's weight within 2 % at rest, the sphere sinks
  into the surface by Hertz's indentation within 50 % (finite body, 7 mm elements), the nodes under
  it sink, and the far ends of the duck hardly move.
- A rigid box dropped on a soft block bounces no higher than it fell (energy does not rise).
"""

from pathlib import Path

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import articulation, joint, link, node_contact_forces_world, node_positions_world, soft_actor, soft_material
from test_soft_bodies import box_tet_mesh

DUCK = Path(__file__).resolve().parents[3] / "assets" / "prefabs" / "duck_lamp" / "duck_lamp_recumbent_full.mochi_prefab"


def soft_block(scene, size=0.1, cells=5, E=1e5):
    nodes, tets = box_tet_mesh([size, size, size], [cells, cells, cells])
    nodes[:, :2] -= size / 2
    base = np.flatnonzero(nodes[:, 2] < 1e-9)
    block = soft_actor(scene, "block", sdp.create_tet_mesh_shape(nodes, tets),
                       material=soft_material(youngs_modulus=E, poisson_ratio=0.3, density=500, stiffness_damping=0.01),
                       fixed_nodes=base)
    return block, nodes


def test_rigid_sphere_rests_on_a_soft_block(scene):
    block, nodes = soft_block(scene)
    sphere = scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.03), is_static=False, mass=1.0,
                                      world_from_local=sdp.TransformRT(translation=[0, 0, 0.1 + 0.03 + 0.002]))
    for a in (block, sphere):
        a.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    block.register_query(sdp.QueryType.NODE_CONTACT_FORCES)
    for _ in range(450):  # it settles into the dent it makes within about 4 s
        scene.step(0.01)
    weight = 9.81
    f_sphere = sphere.get_contact_force_world()
    f_block = block.get_contact_force_from_actor_world(sphere)
    assert f_sphere[2] == pytest.approx(weight, rel=0.01)
    np.testing.assert_allclose(f_block, -f_sphere, rtol=1e-5, atol=1e-5)
    np.testing.assert_allclose(node_contact_forces_world(block, len(nodes)).sum(axis=0), block.get_contact_force_world(),
                               rtol=1e-5, atol=1e-5)
    # the block is pressed in under the sphere: its top centre sank
    x = node_positions_world(block)
    top = np.flatnonzero(nodes[:, 2] > 0.1 - 1e-9)
    centre = top[np.argmin(np.linalg.norm(nodes[top, :2], axis=1))]
    assert x[centre, 2] < 0.1 - 2e-4
    assert np.linalg.norm(sphere.get_linear_velocity()) < 1e-3


def test_duck_reacts_to_a_pressing_sphere_and_dents(scene):
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    duck = sdp.prefab.add_to_scene(str(DUCK), "/duck", scene).actors[0]
    duck.register_query(sdp.QueryType.NODE_POSITIONS)
    for _ in range(100):  # it settles under its own weight first
        scene.step(0.004)
    rest = node_positions_world(duck)
    # the highest surface point near the seed's press point (x = -0.30, y = 0)
    near = np.linalg.norm(rest[:, :2] - [-0.30, 0.0], axis=1) < 0.01
    top = rest[near, 2].max()
    radius, mass, push = 0.015, 0.01, 1.0
    # a ball on a vertical slider above the press point (the seed's arm holds its ball likewise)
    links = [link("base", mass=1.0, moment_of_inertia=[1e-3, 0, 0, 1e-3, 0, 1e-3]),
             link("ball", parent=0, mass=mass, moment_of_inertia=[1e-6, 0, 0, 1e-6, 0, 1e-6],
                  shape=sdp.create_sphere_shape([0, 0, 0], radius))]
    joints = [joint("weld", "hard", at=[-0.30, 0, top + radius + 0.001]),
              joint("slide", "prismatic", axis=[0, 0, 1])]
    slider = articulation(scene, "slider", links, joints)
    ball = scene.get_actor(slider.get_nested_link_actors()[1])
    slider.set_external_forces_on_dofs([0], [-push])
    for a in (duck, ball):
        a.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
    for _ in range(150):
        scene.step(0.004)
        assert np.isfinite(ball.get_root_transform().translation).all()
    applied = push + mass * 9.81
    reaction = ball.get_contact_force_world()
    assert reaction[2] == pytest.approx(applied, rel=0.02)
    np.testing.assert_allclose(duck.get_contact_force_from_actor_world(ball), -reaction, rtol=1e-5, atol=1e-5)
    # a dent under the ball, not a sunk duck: the ball's bottom sits below the settled surface by
    # Hertz's indentation of a rigid sphere into an elastic half-space, (9 F^2 / (16 E*^2 R))^(1/3),
    # E* = E / (1 - nu^2), within +-50 % (a finite body, 7 mm elements)
    x = node_positions_world(duck)
    sink = rest[:, 2] - x[:, 2]
    xf = sdp.DynamicArrayTransformRT(2)
    slider.get_articulated_link_transforms(xf)
    indentation = top - (float(xf[1].translation[2]) - radius)
    E_star = 1e5 / (1 - 0.45**2)
    hertz = (9 * applied**2 / (16 * E_star**2 * radius)) ** (1 / 3)
    assert 0.5 * hertz < indentation < 1.5 * hertz, f"indentation {indentation * 1000:.2f} mm, Hertz {hertz * 1000:.2f} mm"
    under = np.linalg.norm(rest[:, :2] - np.array([-0.30, 0.0]), axis=1) < 0.008
    under &= rest[:, 2] > top - 0.004
    assert under.any() and sink[under].max() > 0.2 * hertz, "the surface nodes under the ball sink"
    far = np.abs(rest[:, 0] + 0.30) > 0.05
    assert np.abs(sink[far]).max() < 0.3 * indentation, "away from the ball the duck keeps its shape"


def test_box_dropped_on_soft_block_does_not_gain_energy(scene):
    block, _ = soft_block(scene, cells=4)
    box = scene.create_rigid_actor(name="box", shape=sdp.create_box_shape([0.02, 0.02, 0.02]), is_static=False, mass=0.2,
                                   world_from_local=sdp.TransformRT(translation=[0, 0, 0.15]))
    heights = []
    for _ in range(150):
        scene.step(0.005)
        heights.append(box.get_root_transform().translation[2])
    heights = np.array(heights)
    assert np.isfinite(heights).all()
    assert heights.max() <= 0.15 + 1e-6
    assert heights[-1] == pytest.approx(0.1 + 0.02, abs=0.005), "it comes to rest on the block's top"
