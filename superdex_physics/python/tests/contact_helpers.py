"""Small builders and measurements shared by the contact acceptance tests (test_contact_*.py, test_state.py).

Nothing here reads a number the engine computes as a reference: the helpers only build
scenes through the public API and read poses, velocities and forces back as float64 arrays.
"""

import numpy as np

import superdex.physics as sdp

G = 9.81


def material(mu=0.5, **extra):
    """ContactParams for create_rigid_actor(contact=...) or a link's `contact`: Coulomb friction mu
    (combined with the other side's by their geometric mean) and other fields by their names."""
    return sdp.ContactParams(coulomb_friction_coefficient=mu, **extra)


def add_ground(scene, mu=0.5, name="ground", **kwargs):
    """A static half-space below z = 0 (normal +z); kwargs: other RigidActorParams fields."""
    return scene.create_rigid_actor(name=name, shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True,
                                    contact=material(mu), **kwargs)


def add_box(scene, name, center, half=0.1, mass=1.0, mu=0.5, rotation=None, **kwargs):
    """A dynamic cube of half extent `half` (its origin is its centre of mass)."""
    xf = sdp.TransformRT(rotation=rotation or sdp.Quaternion(0, 0, 0, 1), translation=list(center))
    return scene.create_rigid_actor(name=name, shape=sdp.create_box_shape([half, half, half]), world_from_local=xf,
                                    mass=mass, contact=material(mu), **kwargs)


def add_sphere(scene, name, center, radius=0.1, mass=1.0, mu=0.5, **kwargs):
    """A dynamic solid ball centred on its origin."""
    xf = sdp.TransformRT(rotation=sdp.Quaternion(0, 0, 0, 1), translation=list(center))
    return scene.create_rigid_actor(name=name, shape=sdp.create_sphere_shape([0, 0, 0], radius), world_from_local=xf,
                                    mass=mass, contact=material(mu), **kwargs)


def position(actor):
    return np.asarray(actor.get_root_transform().translation, dtype=np.float64)


def quaternion(actor):
    """[x, y, z, w]"""
    return np.asarray(np.array(actor.get_root_transform().rotation), dtype=np.float64)


def rotation_angle(q_a, q_b):
    """Angle (rad) of the rotation between two unit quaternions [x, y, z, w]."""
    d = abs(float(np.dot(q_a / np.linalg.norm(q_a), q_b / np.linalg.norm(q_b))))
    return 2.0 * np.arccos(min(1.0, d))


def rotation_matrix(q):
    """3x3 rotation matrix of a unit quaternion [x, y, z, w]."""
    x, y, z, w = np.asarray(q, dtype=np.float64) / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def vec(a):
    return np.asarray(a, dtype=np.float64)


def skew(p):
    """[p]x, so that skew(p) @ w == np.cross(p, w)."""
    return np.array([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]], dtype=np.float64)


def step_for(scene, dt, seconds, each=None):
    """Steps `seconds / dt` times, calling each(k) after step k (1-based) when given."""
    n = int(round(seconds / dt))
    for k in range(1, n + 1):
        scene.step(dt)
        if each is not None:
            each(k)
    return n
