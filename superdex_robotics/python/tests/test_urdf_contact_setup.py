"""How a URDF robot is set up to collide: mesh colliders are convex hulls by default, link pairs
that overlap at the zero configuration are switched off (and named), links on one rigid body or
on two bodies joined by a joint never touch, and joints whose limits exclude zero start at the
nearest limit.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from robotics_helpers import scene  # noqa: F401

INERTIAL = '<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>'


def box(size, xyz=(0, 0, 0)):
    return (f'<collision><origin xyz="{xyz[0]} {xyz[1]} {xyz[2]}"/>'
            f'<geometry><box size="{size} {size} {size}"/></geometry></collision>')


def link(name, body=""):
    return f'<link name="{name}">{INERTIAL}{body}</link>'


def joint(name, kind, parent, child, axis="0 0 1", limit=""):
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<axis xyz="{axis}"/>{limit}</joint>')


def load(path, text, **options):
    path.write_text(f'<?xml version="1.0"?>\n<robot name="bot">{text}</robot>\n')
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        prefab = sdr.load_bot_prefab_from_urdf_file(str(path), fixed_base=True, **options)
    return prefab, [str(w.message) for w in caught]


# A base box (0.2 m, welded to the world); 'arm' hinged to it about z with a box 0.3 m away;
# 'cover' welded to 'arm' and overlapping both 'arm' and the base; 'tip' hinged to 'arm' about y,
# its box overlapping the base's corner (x 0.07..0.1, z 0..0.1): pushed out along +x below the
# hinge, it would turn about y. Only (base, tip) is neither one body nor joined.
OVERLAPPING = (
    link("base", box(0.2)) + link("arm", box(0.1, (-0.3, 0, 0))) + link("cover", box(0.15)) +
    link("tip", box(0.1, (0.12, 0, 0.05))) +
    joint("j_arm", "continuous", "base", "arm") + joint("j_cover", "fixed", "arm", "cover") +
    joint("j_tip", "continuous", "arm", "tip", axis="0 1 0")
)


def run(scene, prefab, seconds=0.2, dt=0.005):
    scene.set_gravity([0, 0, 0])
    bot = sdr.create_bot(scene, prefab, sdr.create_context())
    art = bot.get_articulated_actor()
    for _ in range(round(seconds / dt)):
        scene.step(dt)
    return np.asarray(art.get_articulated_pose())


def test_links_overlapping_at_zero_are_switched_off_and_named(scene, tmp_path):
    prefab, messages = load(tmp_path / "bot.urdf", OVERLAPPING)
    overlaps = [m for m in messages if "overlap at the zero configuration" in m]
    assert len(overlaps) == 1, messages
    assert "1 pair(s) of links" in overlaps[0] and "('base', 'tip')" in overlaps[0]
    # nothing pushes: gravity is off and the one overlapping pair does not collide
    np.testing.assert_allclose(run(scene, prefab), 0, atol=1e-9)


def test_overlapping_links_collide_when_asked(scene, tmp_path):
    prefab, messages = load(tmp_path / "bot.urdf", OVERLAPPING, exclude_overlapping_links=False)
    assert not any("overlap" in m for m in messages), messages
    q = run(scene, prefab)
    # the base pushes the tip out: it turns about y; 'arm' (joined to the base) and 'cover' (on
    # arm's body) feel nothing from the base
    assert abs(q[1]) > 0.01, q
    assert abs(q[0]) < 1e-6, q


def test_joints_start_inside_their_limits(scene, tmp_path):
    text = (link("base") + link("a", box(0.05, (0.3, 0, 0))) + link("b", box(0.05, (0.6, 0, 0))) +
            joint("ja", "revolute", "base", "a", limit='<limit lower="0.5" upper="1.0" effort="1" velocity="1"/>') +
            joint("jb", "prismatic", "a", "b", axis="1 0 0", limit='<limit lower="-0.3" upper="-0.1" effort="1" velocity="1"/>'))
    prefab, messages = load(tmp_path / "bot.urdf", text)
    starts = [m for m in messages if "zero lies outside" in m]
    assert len(starts) == 2, messages
    assert "<joint name='ja'>" in starts[0] and "[0.5, 1]" in starts[0] and "joint at 0.5" in starts[0]
    assert "<joint name='jb'>" in starts[1] and "joint at -0.1" in starts[1]
    np.testing.assert_allclose(run(scene, prefab, seconds=0.05), [0.5, -0.1], atol=1e-6)


def open_box_obj(path, half=0.2, height=0.2):
    """A box [-half, half]^2 x [0, height] without its top face: an open mesh."""
    v = [(x, y, z) for z in (0, height) for y in (-half, half) for x in (-half, half)]
    faces = [(1, 3, 4, 2), (1, 2, 6, 5), (2, 4, 8, 6), (4, 3, 7, 8), (3, 1, 5, 7)]  # bottom and sides
    lines = [f"v {x} {y} {z}" for x, y, z in v]
    for a, b, c, d in faces:
        lines += [f"f {a} {b} {c}", f"f {a} {c} {d}"]
    path.write_text("\n".join(lines) + "\n")
    return path.name


def test_an_open_mesh_collides_as_its_convex_hull(scene, tmp_path):
    mesh = open_box_obj(tmp_path / "tray.obj")
    text = link("tray", f'<collision><geometry><mesh filename="{mesh}"/></geometry></collision>')
    prefab, messages = load(tmp_path / "bot.urdf", text)
    scene.set_gravity([0, 0, -9.81])
    sdr.create_bot(scene, prefab, sdr.create_context())
    r = 0.05
    ball = scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], r), density=1000.0,
                                    world_from_local=sdp.TransformRT(translation=[0.05, -0.03, 0.4]))
    for _ in range(400):
        scene.step(0.005)
    # the hull closes the tray's open top at z = 0.2: the ball rests on it, not inside
    np.testing.assert_allclose(np.asarray(ball.get_root_transform().translation), [0.05, -0.03, 0.2 + r], atol=2e-3)


def test_an_open_mesh_kept_as_a_mesh_cannot_be_touched(scene, tmp_path):
    mesh = open_box_obj(tmp_path / "tray.obj")
    text = link("tray", f'<collision><geometry><mesh filename="{mesh}"/></geometry></collision>')
    prefab, _ = load(tmp_path / "bot.urdf", text, mesh_collision="mesh")
    scene.set_gravity([0, 0, -9.81])
    sdr.create_bot(scene, prefab, sdr.create_context())
    scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.05), density=1000.0,
                             world_from_local=sdp.TransformRT(translation=[0, 0, 0.3]))
    with pytest.raises(sdp.Error, match="tray.obj: the mesh is open and has no signed-distance field"):
        for _ in range(400):
            scene.step(0.005)


def test_mesh_collision_option_is_checked(tmp_path):
    with pytest.raises(sdp.Error, match="mesh_collision must be 'convex_hull' or 'mesh', got 'hull'"):
        load(tmp_path / "bot.urdf", link("a"), mesh_collision="hull")
