"""Joint-space control: the built-in BASIC_JSC_PD controller moves an arm through target poses.

The arm is the bundled 4-DOF URDF arm (assets/bots/urdf/tabletop_arm_4dof). A BASIC_JSC_PD
controller is created on the bot; from then on the bot's pipeline runs it inside every scene.step
(in C++) and applies its joint efforts

    tau_i = kp_i (q*_i - q_i) - kd_i v_i + c_i(q, v)

where c(q, v) are the bias forces (gravity, Coriolis, centrifugal) when gravity_compensation is on.
Python only hands it a new target pose every few seconds with context.configure_controller, and
reads the joints.

Choosing the gains. The PD efforts are applied explicitly (computed before each step), and the
joints of this arm move very different inertias: the base yaw about 0.003 kg m^2 with the arm
upright and 0.46 with it stretched out sideways, the shoulder about 0.4, the wrist 0.002. One gain
for all joints would be too soft for some and unstable for others. With gravity compensated, joint i alone behaves like
M_ii qdd_i = kp_i e_i - kd_i v_i, so kp_i = M_ii w^2 and kd_i = 2 zeta M_ii w give every joint the
same natural frequency w and damping ratio zeta. The inertia changes as the arm moves, so before
each move the gains are set for the larger of M_ii at the start and at the target pose (where
the inertia is smaller, the joint moves a little faster and is better damped than planned). The mass matrix at
the target comes from a probe: a second copy of the arm in a scene that is never stepped, posed
with set_articulated_pose_from_joints. zeta = 1.5 leaves room for the coupling between the joints
(the diagonal gains ignore M's off-diagonal terms): no joint overshoots its target.

Run it with

    uv run python superdex_robotics/examples/control/example_jsc_control.py [--seconds-per-pose 2]

Add --debugger to watch it in the scene debugger; without a display, also set
SUPERDEX_DEBUGGER_RECORD=jsc.jsonl to record the run to a file (superdex.physics.debugger).
"""

import argparse

import numpy as np

import superdex.physics as physics
import superdex.robotics as robotics

ARM_ASSET = "bots/urdf/tabletop_arm_4dof/tabletop_arm_4dof.urdf"
START_POSE = [0.0, 0.3, 0.6, 0.3]  # rad: base yaw, shoulder, elbow, wrist
TARGET_POSES = [
    [0.8, 0.6, 0.9, -0.4],
    [-0.6, -0.3, 1.2, 0.8],
    [0.2, 0.9, -0.5, 0.5],
]
NATURAL_FREQUENCY = 20.0  # rad/s
DAMPING_RATIO = 1.5
CONTROL_DT = 0.002  # s: the scene steps at 500 Hz and the controller runs every step


def joint_inertias(probe, pose) -> np.ndarray:
    """The diagonal of the joint-space mass matrix at `pose`, from the probe articulation."""
    probe.set_articulated_pose_from_joints(list(pose))
    n = probe.get_num_dofs()
    return np.diag(np.array(probe.get_articulated_mass_matrix(), dtype=np.float64).reshape(n, n))


def pd_gains(probe, start, target, natural_frequency: float = NATURAL_FREQUENCY, damping_ratio: float = DAMPING_RATIO):
    """kp_i = I_i w^2, kd_i = 2 zeta I_i w with I_i the larger of M_ii at the start and the target."""
    inertia = np.maximum(joint_inertias(probe, start), joint_inertias(probe, target))
    return inertia * natural_frequency**2, 2 * damping_ratio * inertia * natural_frequency


def run(seconds_per_pose: float = 2.0, targets=None, debugger: bool = False) -> dict:
    """Moves through `targets` (default TARGET_POSES), holding each for `seconds_per_pose`. Returns
    the start pose, the targets, and after every step the time and the joint positions and
    velocities (float64 arrays)."""
    targets = [list(t) for t in (targets or TARGET_POSES)]
    physics.initialize(num_worker_threads=0)
    try:
        scene = physics.create_scene("Joint-space control")
        scene.set_gravity([0, 0, -9.81])
        prefab = robotics.load_bot_prefab_from_urdf_file(str(physics.paths.resolve_asset(ARM_ASSET)), fixed_base=True)
        prefab.default_pose = START_POSE  # a URDF has no default pose
        context = robotics.create_context()
        bot = robotics.create_bot(scene, prefab, context)
        probe_scene = physics.create_scene("mass-matrix probe")  # never stepped
        probe_bot = robotics.create_bot(probe_scene, prefab, context)
        try:
            arm = bot.get_articulated_actor()
            probe = probe_bot.get_articulated_actor()
            kp, kd = pd_gains(probe, START_POSE, START_POSE)
            # the default target is the pose at creation: the arm holds its start pose
            jsc = bot.create_controller("BASIC_JSC_PD", "joint_pd", {"kp": kp.tolist(), "kd": kd.tolist(),
                                                                      "gravity_compensation": True})
            velocities = np.zeros(arm.get_num_dofs(), dtype=arm.get_articulated_pose().dtype)
            times, poses, speeds = [], [], []
            if debugger:
                physics.debugger.attach()
            for target in targets:
                kp, kd = pd_gains(probe, arm.get_articulated_pose(), target)
                context.configure_controller(jsc, {"target_pose": target, "kp": kp.tolist(), "kd": kd.tolist()})
                for _ in range(int(round(seconds_per_pose / CONTROL_DT))):
                    scene.step(CONTROL_DT)  # the pipeline runs the controller inside the step
                    arm.get_articulated_joint_velocities(velocities)
                    times.append(scene.get_total_simulation_time())
                    poses.append(np.array(arm.get_articulated_pose(), dtype=np.float64))
                    speeds.append(velocities.astype(np.float64))
        finally:
            robotics.destroy_bot(probe_scene, probe_bot)
            robotics.destroy_bot(scene, bot)
        return {"start": np.array(START_POSE), "targets": np.array(targets, dtype=np.float64),
                "steps_per_pose": int(round(seconds_per_pose / CONTROL_DT)),
                "t": np.array(times), "q": np.array(poses), "v": np.array(speeds)}
    finally:
        if debugger:
            physics.debugger.detach()
        physics.shutdown()


def step_response(start, target, q) -> dict:
    """Per joint: final error, overshoot past the target (as a fraction of the move), and the time
    index at which the joint first came within 2 % of the move of its target."""
    move = target - start
    past = (q - target) * np.sign(move)  # > 0 once a joint has gone past its target
    within = np.abs(q - target) <= 0.02 * np.abs(move)[None, :]
    return {
        "final_error": np.abs(q[-1] - target),
        "overshoot": np.maximum(past.max(axis=0), 0.0) / np.maximum(np.abs(move), 1e-12),
        "settle_index": np.array([int(np.argmax(w)) if w.any() else len(q) for w in within.T]),
    }


def print_summary(result: dict) -> None:
    n = result["steps_per_pose"]
    start = result["start"]
    print(f"BASIC_JSC_PD, gains for w = {NATURAL_FREQUENCY} rad/s, zeta = {DAMPING_RATIO}; start pose {start}")
    for k, target in enumerate(result["targets"]):
        q = result["q"][k * n:(k + 1) * n]
        r = step_response(start, target, q)
        print(f"\nmove {k + 1} to {np.array2string(target, precision=2)} rad:")
        print(f"  {'joint':>5} {'move [rad]':>10} {'settled (2 %) [s]':>18} {'overshoot [%]':>14} {'final error [rad]':>18}")
        for j in range(len(target)):
            settle = (r["settle_index"][j] + 1) * (result["t"][1] - result["t"][0])
            print(f"  {j:>5} {target[j] - start[j]:10.3f} {settle:18.3f} {100 * r['overshoot'][j]:14.2f} "
                  f"{r['final_error'][j]:18.2e}")
        start = q[-1]
    print(f"\nlargest joint speed at the end: {np.abs(result['v'][-1]).max():.2e} rad/s")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds-per-pose", type=float, default=2.0, help="simulated time per target pose (s)")
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    print_summary(run(args.seconds_per_pose, debugger=args.debugger))


if __name__ == "__main__":
    main()
