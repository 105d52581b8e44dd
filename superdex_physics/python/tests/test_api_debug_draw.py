"""Debug drawing (Scene.get_debug_draw): features, switches and the data structs.

Scenes: a 0.2 m cube (half extent 0.1 m) resting on a static ground plane z = 0 under
g = 9.81 m/s^2 (contacts), the same cube in free space turned 30 degrees about z (bounds,
frames, centre of mass), the two-link arm of conftest (joint axes) and a one-cell soft cube
(surface edges). Every expected number is worked out by hand from the geometry. Primitives scale
with an actor's size, the diagonal of its bounds in its own frame (a cube's: 2 * half * sqrt(3),
however it turns; 0.1 m for a plane or a link without shapes): contact spheres have radius 2 %
of the smaller actor's size, frame axes are 25 % of it long, centre of mass spheres 4 %, joint
axes 50 % of the child link's.
"""

import copy
import math
import pickle

import numpy as np
import pytest

import superdex.physics as sdp
from conftest import transform, two_link_arm
from contact_helpers import add_box, add_ground, step_for
from test_soft_bodies import box_tet_mesh

HALF = 0.1
DIAGONAL = 2 * HALF * math.sqrt(3)
FEATURES = ["contact_points", "contact_normals", "contact_forces", "actor_aabbs", "actor_frames", "centers_of_mass",
            "joint_axes", "soft_surface_edges"]


def tol():
    """Float builds store positions in float32."""
    return 1e-9 if sdp.uses_double_precision() else 2e-6


def draw_only(scene, *features):
    """The scene's DebugDraw, enabled, with exactly `features` on."""
    draw = scene.get_debug_draw()
    draw.enable(True)
    for i in range(draw.get_num_features()):
        draw.enable_feature(i, draw.get_feature_name(i) in features)
    return draw


def lines(data):
    """Segments as an (n, 2, 3) float64 array."""
    p = np.asarray(data.line_vertices.positions, dtype=np.float64)
    assert len(p) % 2 == 0
    return p.reshape(-1, 2, 3)


def resting_box(scene):
    ground = add_ground(scene)
    box = add_box(scene, "box", [0.3, -0.2, HALF + 1e-3], half=HALF, mass=2.0)
    step_for(scene, 0.01, 0.5)
    return ground, box


def turned_box(scene, angle=math.radians(30)):
    rotation = sdp.Quaternion.rotation_z(angle)
    return add_box(scene, "box", [0.5, 1.0, 2.0], half=HALF, rotation=rotation)


# features and switches


def test_features_have_names_descriptions_and_start_off(scene):
    draw = scene.get_debug_draw()
    assert not draw.is_enabled()
    assert draw.get_num_features() == len(FEATURES)
    assert [draw.get_feature_name(i) for i in range(draw.get_num_features())] == FEATURES
    for i, name in enumerate(FEATURES):
        assert draw.find_feature(name) == i
        assert not draw.is_feature_enabled(i)
        assert len(draw.get_feature_description(i)) > 20
    assert draw.find_feature("no_such_feature") == -1
    assert draw.find_feature("Contact_Points") == -1  # case sensitive
    assert draw.find_feature("") == -1


@pytest.mark.parametrize("index", [-1, len(FEATURES), 1000])
def test_bad_feature_index_raises_error_naming_the_range(scene, index):
    draw = scene.get_debug_draw()
    for call in (lambda: draw.get_feature_name(index), lambda: draw.get_feature_description(index),
                 lambda: draw.is_feature_enabled(index), lambda: draw.enable_feature(index, True)):
        with pytest.raises(sdp.Error, match=rf"index {index} is out of range \[0, {len(FEATURES)}\)"):
            call()


def test_disabled_master_switch_gives_empty_data_and_keeps_feature_settings(scene):
    resting_box(scene)
    draw = scene.get_debug_draw()
    aabbs = draw.find_feature("actor_aabbs")
    draw.enable_feature(aabbs, True)  # while the master switch is off
    assert draw.is_feature_enabled(aabbs)
    data = draw.gather_data()
    assert len(data.line_vertices.positions) == 0 and len(data.spheres.positions) == 0
    assert data == sdp.DebugDrawData()

    draw.enable(True)
    assert draw.is_enabled() and draw.is_feature_enabled(aabbs)
    assert len(draw.gather_data().line_vertices.positions) == 24
    draw.enable(False)
    assert draw.gather_data() == sdp.DebugDrawData()
    assert draw.is_feature_enabled(aabbs)


def test_each_scene_has_its_own_settings(engine):
    a, b = engine.create_scene("a"), engine.create_scene("b")
    a.get_debug_draw().enable(True)
    assert a.get_debug_draw().is_enabled()  # a new handle to the same settings
    assert not b.get_debug_draw().is_enabled()


# features: geometry from the scene's state


def test_contact_points_lie_on_the_ground_under_the_box(scene):
    ground, box = resting_box(scene)
    data = draw_only(scene, "contact_points").gather_data()
    p = np.asarray(data.spheres.positions, dtype=np.float64)
    assert len(p) >= 4
    assert len(data.spheres.radii) == len(p) and len(data.spheres.colors) == len(p)
    assert len(data.line_vertices.positions) == 0
    # on the plane (within the resting penetration), inside the box's footprint
    assert np.all(np.abs(p[:, 2]) < 2e-3)
    assert np.all(np.abs(p[:, 0] - 0.3) <= HALF + 1e-3)
    assert np.all(np.abs(p[:, 1] + 0.2) <= HALF + 1e-3)
    # the support polygon spans the footprint: points near opposite corners
    assert np.ptp(p[:, 0]) > 1.5 * HALF and np.ptp(p[:, 1]) > 1.5 * HALF
    np.testing.assert_allclose(np.asarray(data.spheres.radii), 0.02 * DIAGONAL, rtol=1e-5)
    assert len({tuple(c) for c in data.spheres.colors}) == 1


def test_contact_normals_and_forces_point_up_from_the_contacts(scene):
    resting_box(scene)
    draw = draw_only(scene, "contact_points", "contact_normals", "contact_forces")
    data = draw.gather_data()
    points = np.asarray(data.spheres.positions, dtype=np.float64)
    segments = lines(data)
    n = len(points)
    assert len(segments) == 2 * n  # per contact: its normal, then its force
    normals, forces = segments[0::2], segments[1::2]
    np.testing.assert_allclose(normals[:, 0], points, atol=tol())
    np.testing.assert_allclose(forces[:, 0], points, atol=tol())
    d = normals[:, 1] - normals[:, 0]
    np.testing.assert_allclose(np.linalg.norm(d, axis=1), 0.25 * DIAGONAL, rtol=1e-4)
    assert np.all(np.abs(d[:, 2]) > 0.999 * np.linalg.norm(d, axis=1))  # vertical
    f = forces[:, 1] - forces[:, 0]
    lengths = np.linalg.norm(f, axis=1)
    # the largest force is drawn 25 % of the diagonal long, the others shorter; all vertical
    assert lengths.max() == pytest.approx(0.25 * DIAGONAL, rel=1e-4)
    assert np.all(np.abs(f[:, 2]) > 0.99 * lengths)


def test_aabb_feature_draws_the_twelve_edges_of_the_analytic_bounds(scene):
    angle = math.radians(30)
    turned_box(scene, angle)
    add_ground(scene)  # unbounded: not drawn
    data = draw_only(scene, "actor_aabbs").gather_data()
    segments = lines(data)
    assert segments.shape == (12, 2, 3)
    e = HALF * (math.cos(angle) + math.sin(angle))
    lo, hi = np.array([0.5 - e, 1.0 - e, 2.0 - HALF]), np.array([0.5 + e, 1.0 + e, 2.0 + HALF])
    p = segments.reshape(-1, 3)
    np.testing.assert_allclose(p.min(axis=0), lo, atol=1e-5)
    np.testing.assert_allclose(p.max(axis=0), hi, atol=1e-5)
    # every vertex is a corner, every edge is parallel to one axis and spans the box along it
    assert np.all(np.isclose(p, lo, atol=1e-5) | np.isclose(p, hi, atol=1e-5))
    d = np.abs(segments[:, 1] - segments[:, 0])
    assert sorted(np.argmax(d, axis=1).tolist()) == [0] * 4 + [1] * 4 + [2] * 4
    for k in range(3):
        np.testing.assert_allclose(d[np.argmax(d, axis=1) == k, k], (hi - lo)[k], atol=1e-5)


def test_actor_frames_draw_the_rotated_axes(scene):
    angle = math.radians(30)
    turned_box(scene, angle)
    data = draw_only(scene, "actor_frames").gather_data()
    segments = lines(data)
    assert segments.shape == (3, 2, 3)
    np.testing.assert_allclose(segments[:, 0], [[0.5, 1.0, 2.0]] * 3, atol=tol())
    c, s = math.cos(angle), math.sin(angle)
    axes = np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]]) * 0.25 * DIAGONAL
    np.testing.assert_allclose(segments[:, 1] - segments[:, 0], axes, atol=1e-5)
    colors = [tuple(col) for col in data.line_vertices.colors]
    assert colors[0] == colors[1] and colors[2] == colors[3] and colors[4] == colors[5]
    assert len({colors[0], colors[2], colors[4]}) == 3


def test_centers_of_mass_of_dynamic_actors_only(scene):
    box = turned_box(scene)
    add_ground(scene)
    box.set_inertia_properties(2.0, [0.02, -0.01, 0.03], [0.01, 0, 0, 0.01, 0, 0.01])
    data = draw_only(scene, "centers_of_mass").gather_data()
    p = np.asarray(data.spheres.positions, dtype=np.float64)
    assert p.shape == (1, 3)  # not the static ground
    expected = box.get_root_transform() * sdp.Real3(0.02, -0.01, 0.03)
    np.testing.assert_allclose(p[0], np.asarray(expected), atol=1e-5)
    assert data.spheres.radii[0] == pytest.approx(0.04 * DIAGONAL, rel=1e-5)


def test_joint_axes_follow_the_pose(scene):
    arm = two_link_arm(scene)
    draw = draw_only(scene, "joint_axes")
    segments = lines(draw.gather_data())
    assert segments.shape == (2, 2, 3)  # the two revolute joints, not the weld
    mid = segments.mean(axis=1)
    np.testing.assert_allclose(mid, [[0, 0, 1], [0.5, 0, 1]], atol=1e-5)
    d = segments[:, 1] - segments[:, 0]
    np.testing.assert_allclose(np.abs(d), [[0, 0.05, 0], [0, 0.05, 0]], atol=1e-5)  # about y; links without shapes: 0.1 m
    # the first joint turned by 90 degrees about y carries the second one to (0, 0, 1 - 0.5)
    arm.set_articulated_pose_from_joints([math.pi / 2, 0])
    mid = lines(draw.gather_data()).mean(axis=1)
    np.testing.assert_allclose(mid, [[0, 0, 1], [0, 0, 0.5]], atol=1e-5)


def test_soft_surface_edges_are_the_cube_surface_edges(scene):
    size = 0.1
    nodes, tets = box_tet_mesh([size] * 3, [1, 1, 1])
    offset = np.array([1.0, 2.0, 3.0])
    scene.create_soft_actor(name="cube", shape=sdp.create_tet_mesh_shape(nodes, tets), world_from_local=transform(offset))
    segments = lines(draw_only(scene, "soft_surface_edges").gather_data())
    # 12 triangles on the 6 faces: the 12 cube edges and one diagonal per face, each once
    assert segments.shape == (18, 2, 3)
    lengths = sorted(np.linalg.norm(segments[:, 1] - segments[:, 0], axis=1))
    np.testing.assert_allclose(lengths, [size] * 12 + [size * math.sqrt(2)] * 6, rtol=1e-5)
    corners = {tuple(np.round(v, 5)) for v in segments.reshape(-1, 3)}
    assert corners == {tuple(np.round(v, 5)) for v in nodes + offset}


# actors


def test_disabled_actor_draws_nothing_and_hides_its_contacts(scene):
    ground, box = resting_box(scene)
    other = add_box(scene, "other", [3, 0, 2], half=HALF)
    draw = draw_only(scene, "actor_aabbs", "contact_points")
    data = draw.gather_data()
    assert len(data.line_vertices.positions) == 48 and len(data.spheres.positions) >= 4
    assert draw.is_actor_enabled(box)
    draw.enable_actor(box, False)
    assert not draw.is_actor_enabled(box)
    data = draw.gather_data()
    # the other box's bounds only; the box's contacts go with it
    p = np.asarray(data.line_vertices.positions, dtype=np.float64)
    assert len(p) == 24 and np.all(p[:, 0] > 2)
    assert len(data.spheres.positions) == 0
    draw.enable_actor(box.get_handle(), True)  # a handle works as well
    assert len(draw.gather_data().line_vertices.positions) == 48


def test_disabling_an_articulation_disables_its_links(scene):
    arm = two_link_arm(scene)
    draw = draw_only(scene, "joint_axes", "actor_frames")
    links = arm.get_nested_link_actors()
    assert len(lines(draw.gather_data())) == 2 + 3 * len(links)
    draw.enable_actor(arm, False)
    assert all(not draw.is_actor_enabled(link) for link in links)
    assert draw.gather_data() == sdp.DebugDrawData()
    draw.enable_actor(arm, True)
    draw.enable_actor(links[2], False)  # the second moving link: its frame and its joint's axis
    assert len(lines(draw.gather_data())) == 1 + 3 * (len(links) - 1)


def test_enable_actor_refuses_unknown_actors(engine):
    a, b = engine.create_scene("a"), engine.create_scene("b")
    box = add_box(b, "box", [0, 0, 0])
    draw = a.get_debug_draw()
    with pytest.raises(sdp.Error, match="enable_actor"):
        draw.enable_actor(box, False)
    with pytest.raises(sdp.Error, match="enable_actor"):
        draw.enable_actor(123456789, True)
    with pytest.raises(sdp.Error, match="enable_actor: actor"):
        draw.enable_actor("box", True)


# lifetime of the data


def test_data_survives_a_later_gather_and_the_scene(engine):
    scene = engine.create_scene("s")
    box = turned_box(scene)
    draw = draw_only(scene, "actor_aabbs")
    first = draw.gather_data()
    before = np.asarray(first.line_vertices.positions).copy()
    positions = first.line_vertices.positions  # a span alone keeps the buffer too
    box.set_root_transform(transform([5, 5, 5]))
    second = draw.gather_data()
    assert first != second
    np.testing.assert_array_equal(np.asarray(first.line_vertices.positions), before)
    engine.destroy_scene(scene)
    del first, second
    np.testing.assert_array_equal(np.asarray(positions), before)
    assert len(positions.tolist()) == 24
    with pytest.raises(sdp.Error):
        draw.gather_data()
    with pytest.raises(sdp.Error):
        draw.is_enabled()


# the data structs


def test_structs_default_to_empty_and_compare_by_value(engine):
    data = sdp.DebugDrawData()
    assert len(data.line_vertices.positions) == 0 and len(data.line_vertices.colors) == 0
    assert len(data.spheres.positions) == 0 and len(data.spheres.radii) == 0 and len(data.spheres.colors) == 0
    assert data == sdp.DebugDrawData()
    spheres = sdp.DebugDrawSpheres(positions=[[0, 0, 1], [1, 2, 3]], radii=[0.5, 0.25], colors=[sdp.Color(255, 0, 0), sdp.Color()])
    assert np.asarray(spheres.positions).tolist() == [[0, 0, 1], [1, 2, 3]]
    assert spheres.radii.tolist() == [0.5, 0.25]
    assert spheres.colors[0] == sdp.Color(255, 0, 0, 255) and spheres.colors[1] == sdp.Color(255, 255, 255, 255)
    same = sdp.DebugDrawSpheres(positions=sdp.DynamicArrayReal3([[0, 0, 1], [1, 2, 3]]), radii=np.array([0.5, 0.25]),
                                colors=spheres.colors)
    assert same == spheres
    same.radii = [0.5, 0.3]
    assert same != spheres
    line = sdp.DebugDrawLineVertices(positions=[[0, 0, 0], [1, 0, 0]], colors=[sdp.Color(1, 2, 3, 4)] * 2)
    data = sdp.DebugDrawData(line_vertices=line, spheres=spheres)
    assert data.spheres == spheres and data.line_vertices == line
    assert data != sdp.DebugDrawData()
    np.testing.assert_array_equal(np.asarray(line.colors), [[1, 2, 3, 4]] * 2)
    assert np.asarray(line.colors).dtype == np.uint8
    with pytest.raises(TypeError, match="unexpected keyword argument 'points'"):
        sdp.DebugDrawSpheres(points=[])


@pytest.mark.parametrize("make", [sdp.DebugDrawData, sdp.DebugDrawSpheres, sdp.DebugDrawLineVertices])
def test_structs_of_views_cannot_be_copied(engine, make):
    value = make()
    with pytest.raises(TypeError):
        copy.copy(value)
    with pytest.raises(TypeError):
        copy.deepcopy(value)
    with pytest.raises(TypeError):
        pickle.dumps(value)


def test_gathered_data_cannot_be_copied(scene):
    resting_box(scene)
    data = draw_only(scene, *FEATURES).gather_data()
    with pytest.raises(TypeError):
        copy.deepcopy(data)
    # the spans themselves copy into owning arrays
    assert copy.copy(data.spheres.radii).tolist() == data.spheres.radii.tolist()


def test_color_channels(engine):
    c = sdp.Color(10, 20, 30)
    assert (c.r, c.g, c.b, c.a) == (10, 20, 30, 255)
    assert list(c) == [10, 20, 30, 255] and c[-1] == 255 and len(c) == 4
    assert repr(c) == "Color(10, 20, 30, 255)"
    assert copy.deepcopy(c) == c and pickle.loads(pickle.dumps(c)) == c
    c.a = 0
    assert c != sdp.Color(10, 20, 30)
    assert np.asarray(c).dtype == np.uint8
    with pytest.raises(sdp.Error, match=r"Color: g must be in \[0, 255\], got 256"):
        sdp.Color(0, 256, 0)
    with pytest.raises(sdp.Error, match="Color: r"):
        c.r = -1
