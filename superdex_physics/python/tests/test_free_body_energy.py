"""A tumbling asymmetric body in zero gravity never gains kinetic energy.

Torque-free rotation conserves 1/2 w^T I w exactly; an explicit gyroscopic term w x (I w)
makes it grow. The engine integrates that term implicitly (backward Euler on Euler's
equations), so the energy may decay but never rise, at any step. The body spins near its
unstable intermediate axis, where explicit integration blows up fastest. For small steps the
angular momentum direction and size stay close to their initial values.
"""

import numpy as np
import pytest

import superdex.physics as sdp
from contact_helpers import quaternion, rotation_matrix, vec

HALF = np.array([0.3, 0.1, 0.05])
MASS = 1.0
# box inertia about its centre, body frame
INERTIA = np.diag([HALF[1] ** 2 + HALF[2] ** 2, HALF[0] ** 2 + HALF[2] ** 2, HALF[0] ** 2 + HALF[1] ** 2]) * MASS / 3


@pytest.mark.parametrize("dt", [0.001, 0.01, 0.025])
def test_tumbling_box_never_gains_energy(scene, dt):
    scene.set_gravity([0, 0, 0])
    box = scene.create_rigid_actor(name="box", shape=sdp.create_box_shape(HALF.tolist()), mass=MASS)
    box.set_velocity([0, 0, 0], [0.1, 8.0, 0.2])  # the body starts unrotated: body and world axes agree

    def kinetic():
        # the angular velocity (world) in the body frame, whose axes are the box's
        w_body = rotation_matrix(quaternion(box)).T @ vec(box.get_angular_velocity())
        return 0.5 * w_body @ INERTIA @ w_body

    e = [kinetic()]
    for _ in range(int(3.0 / dt)):
        scene.step(dt)
        e.append(kinetic())
    e = np.array(e)
    tol = 1e-5 * e[0] if not sdp.uses_double_precision() else 1e-12 * e[0]
    assert np.diff(e).max() <= tol, f"kinetic energy rose by {np.diff(e).max():.3e} J"
    if dt == 0.001:
        # small steps: little numerical dissipation over 3 s
        assert e[-1] > 0.95 * e[0]
