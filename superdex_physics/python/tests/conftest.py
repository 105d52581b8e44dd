"""Shared fixtures: an initialized engine per test, and small articulations built from dicts."""

import numpy as np
import pytest

import superdex.physics as sdp


@pytest.fixture
def engine():
    """Initializes the engine for one test and shuts it down afterwards."""
    sdp.initialize(num_worker_threads=0)
    yield sdp
    sdp.shutdown()


@pytest.fixture
def scene(engine):
    s = sdp.create_scene("test")
    s.set_gravity([0, 0, -9.81])
    return s


def real_dtype():
    return np.float64 if sdp.uses_double_precision() else np.float32


def two_link_arm(scene, name="arm", **joint_extra):
    """A welded base and two revolute links about Y, each 0.5 m long with 1 kg at its tip."""
    links = [
        {"name": "base", "mass": 1.0, "momentOfInertia": [0.01, 0, 0, 0.01, 0, 0.01]},
        {"name": "l1", "parentLink": 0, "mass": 1.0, "centerOfMass": [0.5, 0, 0],
         "momentOfInertia": [0.001, 0, 0, 0.001, 0, 0.001]},
        {"name": "l2", "parentLink": 1, "mass": 1.0, "centerOfMass": [0.5, 0, 0],
         "momentOfInertia": [0.001, 0, 0, 0.001, 0, 0.001]},
    ]
    joints = [
        {"name": "weld", "type": "Hard", "parentLinkFromJoint": {"translation": [0, 0, 1]}},
        {"name": "j1", "type": "Revolute", "axis": [0, 1, 0], **joint_extra},
        {"name": "j2", "type": "Revolute", "axis": [0, 1, 0], "parentLinkFromJoint": {"translation": [0.5, 0, 0]},
         **joint_extra},
    ]
    return scene.create_articulated_actor(name, links, joints)
