"""Compound collision from URDF: every <collision> element of a link collides, at its own
origin, as part of one rigid body.

A floating table (a 0.2 m box top, four 0.1 m ball feet 0.5 m below it, 0.3 m out along the
axes) dropped on a plane must come to rest on its feet: the link origin 0.6 m above the ground
(foot radius plus the feet's depth), its world box reaching down to the ground. If only the
first <collision> were imported it would lie on its top at 0.1 m.
"""

from __future__ import annotations

import numpy as np
import pytest

import superdex.physics as sdp
import superdex.robotics as sdr
from robotics_helpers import ground_scene, scene  # noqa: F401

FOOT_RADIUS = 0.1
FOOT_DEPTH = 0.5
FEET = [(0.3, 0.0), (-0.3, 0.0), (0.0, 0.3), (0.0, -0.3)]


def table_urdf(path):
    feet = "".join(
        f'<collision><origin xyz="{x} {y} {-FOOT_DEPTH}"/><geometry><sphere radius="{FOOT_RADIUS}"/></geometry></collision>'
        for x, y in FEET
    )
    path.write_text(
        '<?xml version="1.0"?>\n<robot name="table"><link name="top">'
        '<inertial><mass value="2"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>'
        '<collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>'
        f"{feet}</link></robot>\n"
    )
    return str(path)


def test_every_collision_element_holds_the_body_up(ground_scene, tmp_path):
    prefab = sdr.load_bot_prefab_from_urdf_file(table_urdf(tmp_path / "table.urdf"))
    prefab.world_from_root = sdp.TransformRT(translation=[0, 0, 1.0])
    bot = sdr.create_bot(ground_scene, prefab, sdr.create_context())
    art = bot.get_articulated_actor()
    (top,) = [ground_scene.get_actor(h) for h in art.get_nested_link_actors()]
    # the link's box spans all five shapes
    box = top.get_aabb_local()
    np.testing.assert_allclose(box.min, [-0.3 - FOOT_RADIUS, -0.3 - FOOT_RADIUS, -FOOT_DEPTH - FOOT_RADIUS], atol=1e-6)
    np.testing.assert_allclose(box.max, [0.3 + FOOT_RADIUS, 0.3 + FOOT_RADIUS, 0.1], atol=1e-6)
    for _ in range(750):
        ground_scene.step(0.002)
    z = np.asarray(art.get_root_transform().translation)[2]
    assert z == pytest.approx(FOOT_DEPTH + FOOT_RADIUS, abs=2e-3)
    assert np.asarray(top.get_aabb_world().min)[2] == pytest.approx(0.0, abs=2e-3)
    # at rest on its feet
    assert np.linalg.norm(np.asarray(art.get_articulated_joint_velocities())) < 1e-2
