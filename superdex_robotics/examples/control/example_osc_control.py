"""Operational-space control written in Python: the arm's tool tracks a circle.

Operational-space control (OSC) commands the motion of a point, here the tool at the end of the
bundled 4-DOF URDF arm, instead of the joints. Every 2 ms step the Python loop reads from the engine

    x      the tool position           actor.get_articulated_link_transforms
    J      the tool's Jacobian         tool_link.get_articulated_jacobian()  (rows 0-2: linear)
    M, c   mass matrix, bias forces    actor.get_articulated_mass_matrix(), get_articulated_bias_forces()

and applies the joint efforts (actor.set_external_forces_on_dofs)

    Lambda = (J M^-1 J^T)^-1                                    the tool's apparent mass (3 x 3)
    F      = Lambda (a_d + Kp (x_d - x) + Kd (v_d - J qdot) - Jdot qdot)
    tau    = J^T F + c + N^T (k_n (q_rest - q) - M d_n qdot),      N = I - M^-1 J^T Lambda J

so the tool moves like a unit mass on a critically damped spring pulled along the desired path
(x_d, v_d, a_d: position, velocity and acceleration of the path at the time of the state the law
reads), gravity and Coriolis forces are cancelled (c), and the arm's fourth DOF, which the 3-D task
leaves free, is pulled towards a rest posture without disturbing the tool (the null-space
projector N). Jdot qdot is estimated by differencing J over a step. The posture spring k_n is the
same for every joint on purpose: a spring scaled by M would settle where the M-weighted distance
to the rest posture is least, which moves the light wrist instead of the heavy shoulder and here
drives the wrist onto its joint limit. Its damping is scaled by M, so that the light wrist is not
over-damped by an explicit damping force (kd dt / I < 2 keeps an explicit damper stable).

The path: first a smooth (minimum-jerk) move from where the tool starts to a point on a horizontal
circle (centre 0.45 m in front of the base, 0.40 m up, radius 0.08 m), then the circle, one lap
every 4 s. The summary prints the tracking error per lap.

Run it with

    uv run python superdex_robotics/examples/control/example_osc_control.py [--laps 3]

Add --debugger to watch it in the scene debugger; without a display, also set
SUPERDEX_DEBUGGER_RECORD=osc.jsonl to record the run to a file (superdex.physics.debugger).
"""

import argparse
import math

import numpy as np

import superdex.physics as physics
import superdex.robotics as robotics

ARM_ASSET = "bots/urdf/tabletop_arm_4dof/tabletop_arm_4dof.urdf"
TOOL_LINK = "tool"
START_POSE = [0.0, 0.45, 1.24, 1.45]  # rad: the tool points down over the circle centre (also the rest posture)
CIRCLE_CENTER = np.array([0.45, 0.0, 0.40])  # m, world
CIRCLE_RADIUS = 0.08  # m
CIRCLE_PERIOD = 4.0  # s, counter-clockwise seen from above, starting at centre + radius * x
APPROACH_SECONDS = 1.0  # s, the minimum-jerk move onto the circle
CONTROL_DT = 0.002  # s
TASK_FREQUENCY = 20.0  # rad/s: Kp = w^2, Kd = 2 w (critically damped, per unit mass)
POSTURE_STIFFNESS = 10.0  # N m/rad, the null-space posture spring (same for every joint)
POSTURE_DAMPING = 10.0  # 1/s, scaled by the mass matrix


def circle_point(t_on_circle: float):
    """Position, velocity and acceleration on the circle, t_on_circle seconds after entering it."""
    w = 2 * math.pi / CIRCLE_PERIOD
    c, s = math.cos(w * t_on_circle), math.sin(w * t_on_circle)
    r = CIRCLE_RADIUS
    return (CIRCLE_CENTER + r * np.array([c, s, 0.0]), r * w * np.array([-s, c, 0.0]), -r * w * w * np.array([c, s, 0.0]))


def desired(t: float, x_start: np.ndarray):
    """The path at time t: a minimum-jerk move from x_start to the circle's start, then the circle."""
    if t >= APPROACH_SECONDS:
        return circle_point(t - APPROACH_SECONDS)
    goal = circle_point(0.0)[0]
    T = APPROACH_SECONDS
    s = t / T
    blend = 10 * s**3 - 15 * s**4 + 6 * s**5
    blend_d = (30 * s**2 - 60 * s**3 + 30 * s**4) / T
    blend_dd = (60 * s - 180 * s**2 + 120 * s**3) / T**2
    d = goal - x_start
    return x_start + blend * d, blend_d * d, blend_dd * d


class PythonOsc:
    """The control law of the docstring, reading the engine through the Python API."""

    def __init__(self, arm, tool_index: int, rest_pose):
        self.arm = arm
        self.tool = arm.get_scene().get_actor(arm.get_nested_link_actors()[tool_index])
        self.tool_index = tool_index
        self.n = arm.get_num_dofs()
        self.rest = np.asarray(rest_pose, dtype=np.float64)
        self.kp, self.kd = TASK_FREQUENCY**2, 2 * TASK_FREQUENCY
        self.k_n, self.d_n = POSTURE_STIFFNESS, POSTURE_DAMPING
        self.xforms = physics.DynamicArrayTransformRT(len(arm.get_nested_link_actors()))
        self.velocities = np.zeros(self.n, dtype=arm.get_articulated_pose().dtype)
        self.previous_J = None

    def tool_position(self) -> np.ndarray:
        self.arm.get_articulated_link_transforms(self.xforms)
        return np.array(self.xforms[self.tool_index].translation, dtype=np.float64)

    def efforts(self, x_d, v_d, a_d, dt: float) -> np.ndarray:
        n = self.n
        q = np.array(self.arm.get_articulated_pose(), dtype=np.float64)
        self.arm.get_articulated_joint_velocities(self.velocities)
        qdot = self.velocities.astype(np.float64)
        x = self.tool_position()
        J = np.array(self.tool.get_articulated_jacobian(), dtype=np.float64).reshape(6, n)[:3]
        M = np.array(self.arm.get_articulated_mass_matrix(), dtype=np.float64).reshape(n, n)
        c = np.array(self.arm.get_articulated_bias_forces(), dtype=np.float64)
        Jdot_qdot = np.zeros(3) if self.previous_J is None else (J - self.previous_J) @ qdot / dt
        self.previous_J = J

        Minv_Jt = np.linalg.solve(M, J.T)
        Lambda = np.linalg.inv(J @ Minv_Jt)
        F = Lambda @ (a_d + self.kp * (x_d - x) + self.kd * (v_d - J @ qdot) - Jdot_qdot)
        Jbar = Minv_Jt @ Lambda  # dynamically consistent inverse of J
        tau_posture = self.k_n * (self.rest - q) - M @ (self.d_n * qdot)
        tau_null = tau_posture - J.T @ (Jbar.T @ tau_posture)  # N^T tau_posture
        return J.T @ F + c + tau_null


def run(laps: float = 3.0, debugger: bool = False) -> dict:
    """Approaches the circle, then tracks it for `laps` laps. Returns the time, the desired and the
    actual tool position after every step, the joint positions, and the efforts applied."""
    physics.initialize(num_worker_threads=0)
    try:
        scene = physics.create_scene("Operational-space control")
        scene.set_gravity([0, 0, -9.81])
        prefab = robotics.load_bot_prefab_from_urdf_file(str(physics.paths.resolve_asset(ARM_ASSET)), fixed_base=True)
        prefab.default_pose = START_POSE
        bot = robotics.create_bot(scene, prefab, robotics.create_context())
        try:
            arm = bot.get_articulated_actor()
            tool_index = list(arm.get_articulated_shape_info().link_names).index(TOOL_LINK)
            osc = PythonOsc(arm, tool_index, START_POSE)
            dofs = list(range(arm.get_num_dofs()))
            x_start = osc.tool_position()
            times, wanted, actual, poses, efforts = [], [], [], [], []
            steps = int(round((APPROACH_SECONDS + laps * CIRCLE_PERIOD) / CONTROL_DT))
            if debugger:
                physics.debugger.attach()
            for k in range(steps):
                t = k * CONTROL_DT
                tau = osc.efforts(*desired(t, x_start), CONTROL_DT)  # the path at the time of the state
                arm.set_external_forces_on_dofs(dof_indices=dofs, force_values=tau)
                scene.step(CONTROL_DT)
                times.append(scene.get_total_simulation_time())
                wanted.append(desired(t + CONTROL_DT, x_start)[0])
                actual.append(osc.tool_position())
                poses.append(np.array(arm.get_articulated_pose(), dtype=np.float64))
                efforts.append(tau)
        finally:
            robotics.destroy_bot(scene, bot)
        return {"t": np.array(times), "x_desired": np.array(wanted), "x": np.array(actual), "q": np.array(poses),
                "tau": np.array(efforts), "x_start": x_start}
    finally:
        if debugger:
            physics.debugger.detach()
        physics.shutdown()


def print_summary(result: dict) -> None:
    error = np.linalg.norm(result["x"] - result["x_desired"], axis=1)
    print(f"tool starts at {np.array2string(result['x_start'], precision=3)} m; circle centre "
          f"{np.array2string(CIRCLE_CENTER, precision=3)} m, radius {CIRCLE_RADIUS} m, period {CIRCLE_PERIOD} s")
    approach = int(round(APPROACH_SECONDS / CONTROL_DT))
    per_lap = int(round(CIRCLE_PERIOD / CONTROL_DT))
    print(f"approach (0-{APPROACH_SECONDS:g} s): largest error {1e3 * error[:approach].max():.3f} mm")
    for lap, first in enumerate(range(approach, len(error), per_lap)):
        inside = error[first:first + per_lap]
        start = APPROACH_SECONDS + lap * CIRCLE_PERIOD
        rms = math.sqrt(float(np.mean(inside**2)))
        print(f"lap {lap + 1} ({start:g}-{start + len(inside) * CONTROL_DT:g} s): RMS error {1e3 * rms:.3f} mm, "
              f"largest {1e3 * inside.max():.3f} mm")
    print(f"largest joint effort {np.abs(result['tau']).max(axis=0).round(2)} N m")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--laps", type=float, default=3.0, help="laps of the circle after the approach")
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    print_summary(run(args.laps, args.debugger))


if __name__ == "__main__":
    main()
