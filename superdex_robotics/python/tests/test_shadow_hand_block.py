"""gymnasium-robotics' Shadow hand with its block (hand/manipulate_block.xml), imported and stepped
with no controller, against MuJoCo on the same file: the position servos hold MuJoCo's ctrl = 0,
the distal tendons couple the fingers and the joint limits rest at their margins, so after 1 s
the block lies in the palm where MuJoCo's does and the hand holds MuJoCo's pose.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

try:
    import mujoco
except ImportError as exc:  # a declared dev dependency: missing means a broken environment
    raise ImportError("mujoco (a dev dependency in pyproject.toml) is required by this test; run `uv sync`") from exc

import superdex.physics as sdp
import superdex.robotics as sdr


def test_the_hand_keeps_its_block_where_mujoco_does():
    import gymnasium_robotics

    path = Path(gymnasium_robotics.__file__).parent / "envs/assets/hand/manipulate_block.xml"
    m = mujoco.MjModel.from_xml_path(str(path))
    d = mujoco.MjData(m)
    sdp.initialize(num_worker_threads=0)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # sensors and explicit contact pairs are left out
            model = sdr.load_mjcf_file(path)
        scene = sdp.create_scene("shadow")
        scene.set_gravity(model.gravity)
        ctx = sdr.create_context()
        bots = [sdr.create_bot(scene, p, ctx) for p in model.bots]
        hand = bots[0].get_articulated_actor()
        block = next(b for b, p in zip(bots, model.bots) if p.links[0].name == "object").get_articulated_actor()
        start = np.asarray(block.get_articulated_link_transforms()[0].translation, dtype=float)
        for _ in range(int(round(1.0 / model.timestep))):
            scene.step(model.timestep)
            mujoco.mj_step(m, d)
        q = np.asarray(hand.get_articulated_pose(), dtype=float)
        p = np.asarray(block.get_articulated_link_transforms()[0].translation, dtype=float)
    finally:
        sdp.shutdown()
    p_ref = d.xpos[m.body("object").id]
    # the block dropped 3 cm into the palm and stays there, as in MuJoCo (not onto the floor)
    assert start[2] - p_ref[2] > 0.02
    assert np.abs(p - p_ref).max() < 3e-3
    # the hand's 24 joints (its qpos comes first): the wrist's 0.096 rad sag and the fingers
    # 0.01 rad off their limits, to MuJoCo's soft-constraint give (3e-3 at the distal joints)
    assert abs(q[1] - d.qpos[1]) < 1e-3 and abs(d.qpos[1] + 0.096) < 2e-3
    assert np.abs(q - d.qpos[:24]).max() < 5e-3
