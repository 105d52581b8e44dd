"""Actor.query_nodes_in_volume_local: the nodes of an actor inside an Aabb, Obb or Sphere given in
its local frame. Expected node sets are worked out by hand for a unit cube's corners."""

import math

import numpy as np
import pytest

import superdex.physics as sdp

# the unit cube [0, 1]^3 split into five tetrahedra; corner i has x = bit 0, y = bit 1, z = bit 2
NODES = np.array([[(i >> 0) & 1, (i >> 1) & 1, (i >> 2) & 1] for i in range(8)], dtype=float)
TETS = np.array([[0, 1, 2, 4], [1, 3, 2, 7], [1, 5, 7, 4], [2, 7, 6, 4], [2, 1, 7, 4]])


@pytest.fixture
def scene():
    sdp.initialize()
    yield sdp.create_scene("volumes")
    sdp.shutdown()


def found(actor, volume, boundary_only):
    out = []
    actor.query_nodes_in_volume_local(volume, boundary_only, lambda i, p: out.append((i, list(p))))
    return sorted(out)


def test_soft_nodes_in_each_kind_of_volume(scene):
    # placed away from the origin: positions are reported in the actor frame all the same
    soft = scene.create_soft_actor(name="cube", shape=sdp.create_tet_mesh_shape(NODES, TETS),
                                   world_from_local=sdp.TransformRT(translation=[3, 0, 1]))
    handle = soft.register_query_and_compute(sdp.QueryType.NODE_POSITIONS)
    # x > 0.5: the corners with bit 0 set
    hits = found(soft, sdp.Aabb([0.5, -1, -1], [2, 2, 2]), False)
    assert [i for i, _ in hits] == [1, 3, 5, 7]
    np.testing.assert_allclose([p for _, p in hits], NODES[[1, 3, 5, 7]], atol=1e-6)
    # a ball of radius 1.1 about the origin corner reaches the corners at distance 0 and 1 only
    assert [i for i, _ in found(soft, sdp.Sphere(center=[0, 0, 0], radius=1.1), False)] == [0, 1, 2, 4]
    # a thin box through the cube's centre turned 45 degrees about z holds the corners with x != y
    obb = sdp.Obb(transform=sdp.TransformRT(rotation=sdp.Quaternion.rotation_z(math.pi / 4), translation=[0.5, 0.5, 0.5]),
                  half_extents=[0.1, 0.8, 1.0])
    assert [i for i, _ in found(soft, obb, False)] == [1, 2, 5, 6]
    assert found(soft, sdp.Aabb([5, 5, 5], [6, 6, 6]), False) == []
    soft.cancel_query(handle)
    # the nodes' positions must have been asked for
    with pytest.raises(sdp.Error, match="NODE_POSITIONS"):
        found(soft, sdp.Aabb([-1, -1, -1], [2, 2, 2]), False)
    soft.register_query_and_compute(sdp.QueryType.SURFACE_NODE_POSITIONS)
    # every corner is on the surface, reported by its mesh index
    assert [i for i, _ in found(soft, sdp.Aabb([-1, -1, -1], [2, 2, 2]), True)] == list(range(8))


def test_rigid_mesh_surface_nodes_and_errors(scene):
    rigid = scene.create_rigid_actor(name="block", shape=sdp.create_tet_mesh_shape(NODES, TETS))
    # the top face z = 1: corners 4..7, indexed as get_mesh() (the compact surface keeps node order)
    hits = found(rigid, sdp.Aabb([-1, -1, 0.9], [2, 2, 2]), True)
    assert [i for i, _ in hits] == [4, 5, 6, 7]
    mesh_xyz = np.asarray(rigid.get_mesh().coordinates).reshape(-1, 3)
    np.testing.assert_allclose([p for _, p in hits], mesh_xyz[[4, 5, 6, 7]])
    with pytest.raises(sdp.Error, match="boundary_only=False needs a soft actor"):
        found(rigid, sdp.Aabb([-1, -1, -1], [2, 2, 2]), False)
    ball = scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 1.0))
    with pytest.raises(sdp.Error, match="has no mesh surface"):
        found(ball, sdp.Aabb([-1, -1, -1], [2, 2, 2]), True)
    with pytest.raises(sdp.Error, match="volume: expected an Aabb, Obb or Sphere"):
        found(rigid, [0, 0, 0], True)
