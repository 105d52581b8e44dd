"""Shared fixtures: an initialized engine per test, and small builders of actor params structs."""

import numpy as np
import pytest

import superdex.physics as sdp


@pytest.fixture
def engine():
    """Initializes the engine for one test and shuts it down afterwards."""
    sdp.initialize(num_worker_threads=0)
    yield sdp
    if sdp.is_initialized():
        sdp.shutdown()


@pytest.fixture
def scene(engine):
    """A Z-up scene (the engine's default gravity is SuperDex's (0, -9.8, 0))."""
    s = sdp.create_scene("test")
    s.set_gravity([0, 0, -9.81])
    return s


def real_dtype():
    return np.float64 if sdp.uses_double_precision() else np.float32


def transform(translation=(0, 0, 0), rotation=None):
    """A TransformRT from a translation (m) and an optional Quaternion (x, y, z, w)."""
    return sdp.TransformRT(rotation=rotation if rotation is not None else sdp.Quaternion(0, 0, 0, 1),
                           translation=[float(x) for x in translation])


def contact(mu=0.5, **fields):
    """ContactParams with Coulomb friction `mu` and any other fields by their names."""
    return sdp.ContactParams(coulomb_friction_coefficient=mu, **fields)


def link(name, parent=-1, **fields):
    """An ArticulatedLinkParams: `parent` is the parent link's index (-1 for the root); the other
    fields by their names (mass, center_of_mass, moment_of_inertia, shape, contact, ...)."""
    return sdp.ArticulatedLinkParams(name=name, parent_link=parent, **fields)


def joint(name, type, at=None, **fields):
    """An ArticulatedJointParams of `type` (an ArticulatedJointType or its name, any case) whose
    frame is `at` (a translation, m) in its parent link's frame; other fields by their names."""
    if isinstance(type, str):
        type = getattr(sdp.ArticulatedJointType, type.upper())
    if at is not None:
        fields["parent_link_from_joint"] = transform(at)
    return sdp.ArticulatedJointParams(name=name, type=type, **fields)


def articulation(scene, name, links, joints, **fields):
    """An articulated actor from lists of link and joint params (fields: world_from_root,
    joint_velocities, cycles)."""
    return scene.create_articulated_actor(sdp.ArticulatedActorParams(name=name, links=links, joints=joints, **fields))


def two_link_arm(scene, name="arm", **joint_extra):
    """A welded base and two revolute links about Y, each 0.5 m long with 1 kg at its tip;
    joint_extra: fields of both revolute joints (min_limit, max_limit, friction, ...)."""
    links = [
        link("base", mass=1.0, moment_of_inertia=[0.01, 0, 0, 0.01, 0, 0.01]),
        link("l1", parent=0, mass=1.0, center_of_mass=[0.5, 0, 0], moment_of_inertia=[0.001, 0, 0, 0.001, 0, 0.001]),
        link("l2", parent=1, mass=1.0, center_of_mass=[0.5, 0, 0], moment_of_inertia=[0.001, 0, 0, 0.001, 0, 0.001]),
    ]
    joints = [
        joint("weld", "hard", at=[0, 0, 1]),
        joint("j1", "revolute", axis=[0, 1, 0], **joint_extra),
        joint("j2", "revolute", at=[0.5, 0, 0], axis=[0, 1, 0], **joint_extra),
    ]
    return articulation(scene, name, links, joints)
