"""A pneumatic (McKibben) muscle lifting a forearm.

A forearm (a 0.3 m box, 0.5 kg) hangs on an elbow, a revolute joint about the horizontal y axis.
A McKibben muscle pulls on a linear transmission with a 2 cm moment arm: raising the forearm by q
shortens the muscle by 2 cm per radian. The muscle's tension follows Chou and Hannaford's static
model, (P - P_min) b^2 / (4 pi n^2) (3 L^2 / b^2 - 1) plus its deflated spring, so a higher
pressure holds the forearm higher. The script raises the pressure in steps, through the
actuator's state variable, and prints where the forearm settles at each one.

Run: uv run python superdex_physics/examples/mc_kibben_muscle.py [--hold 1.5] [--dt 0.002]

Add --debugger to watch it in the scene debugger; without a display, also set
SUPERDEX_DEBUGGER_RECORD=muscle.jsonl to record the run to a file.
"""

import argparse

import numpy as np

import superdex.physics as sdp

ex = sdp.experimental
G = 9.81
FOREARM_LENGTH, FOREARM_MASS = 0.3, 0.5  # m, kg
MOMENT_ARM = 0.02                        # m of muscle length per radian of elbow
ELBOW_DAMPING = 0.2                      # N m s/rad: the elbow's viscous friction settles it
MUSCLE = dict(minimum_pressure=2e4, thread_length=0.15, number_of_wraps=3.0, deflated_stiffness=500.0,
              deflated_equilibrium_length=0.1)
PRESSURES = (1e5, 2e5, 3e5, 4e5)        # Pa, each held in turn


def build(scene: sdp.Scene):
    """The forearm on its elbow and the muscle's transmission; returns (arm, transmission)."""
    half = FOREARM_LENGTH / 2
    params = sdp.ArticulatedActorParams(name="forearm")
    # about -y: a positive elbow angle raises the forearm's far end (+x towards +z)
    params.joints = [sdp.ArticulatedJointParams(name="elbow", type=sdp.ArticulatedJointType.REVOLUTE, axis=[0, -1, 0],
                                                parent_link_from_joint=sdp.TransformRT(translation=[0, 0, 1]),
                                                friction=sdp.ArticulatedJointFrictionParams(viscous=ELBOW_DAMPING))]
    params.links = [sdp.ArticulatedLinkParams(name="forearm", parent_link=-1, parent_joint_from_link=sdp.TransformRT(translation=[half, 0, 0]),
                                              shape=sdp.create_box_shape(half_extents=[half, 0.02, 0.02]), mass=FOREARM_MASS)]
    arm = scene.create_articulated_actor(params)
    # the muscle's length change: -MOMENT_ARM per radian (raising the forearm shortens it)
    k = ex.add_linear_transmission(arm, ex.LinearTransmissionParams(joint_indices=[0], joint_coefficients=[-MOMENT_ARM]))
    ex.attach_mc_kibben_actuator(arm, k, ex.McKibbenActuatorParams(pressure=PRESSURES[0], **MUSCLE))
    return arm, k


def run(hold: float = 1.5, dt: float = 0.002, debugger: bool = False) -> dict:
    """Holds each pressure for `hold` seconds; returns the settled elbow angle at each (rad)."""
    sdp.initialize(num_worker_threads=0)
    scene = sdp.create_scene("McKibben muscle")
    scene.set_gravity([0, 0, -G])
    arm, k = build(scene)
    if debugger:
        sdp.debugger.attach()
    settled = []
    for pressure in PRESSURES:
        ex.set_transmission_actuator_state_variables(arm, k, np.array([pressure]))
        for _ in range(int(round(hold / dt))):
            scene.step(dt)
        q = float(arm.get_articulated_pose()[0])
        settled.append(q)
        length = MUSCLE["deflated_equilibrium_length"] + ex.get_transmission_displacement(arm, k)
        print(f"pressure {pressure / 1e5:.1f} bar: the forearm settles at {np.degrees(q):6.1f} deg, the muscle {100 * length:.2f} cm long")
    if debugger:
        sdp.debugger.detach()
    sdp.shutdown()
    return {"pressures": PRESSURES, "angles": np.array(settled)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--hold", type=float, default=1.5, help="seconds at each pressure")
    parser.add_argument("--dt", type=float, default=0.002)
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    result = run(args.hold, args.dt, debugger=args.debugger)
    print(f"from {np.degrees(result['angles'][0]):.1f} to {np.degrees(result['angles'][-1]):.1f} deg as the pressure rises")


if __name__ == "__main__":
    main()
