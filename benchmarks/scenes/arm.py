"""The seed's 2-DOF arm as a simulator-neutral description, the seed's control law, and one thin
adapter per simulator that gives the law what it reads (end-effector position, its Jacobian,
joint velocities, contact force) and applies the joint efforts it returns.

The law is the seed example's (superdex_robotics/examples/advanced/example_custom_components.py):
MyVelocityForceController (task-space velocity control along a circle in the X-Z plane, switching
the Z row to admittance force control when the ball presses with more than 0.5 N) and, per joint,
MyVelocityServoActuator (PI velocity servo with a profiled ramp and effort clamp). Scene 1 runs
the seed's own classes; scene 2 runs this copy of the law in all three simulators, so that the
Python work per step is the same and only the simulator's API and physics differ."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
BOT_FILE = REPO / "assets" / "bots" / "fun" / "example_bot_2dof" / "example_bot_2dof.superdex_bot"
SEED_EXAMPLE = REPO / "superdex_robotics" / "examples" / "advanced" / "example_custom_components.py"
DT = 1.0 / 250.0  # the seed's control rate
BALL_LINK = 3
FRICTION = 0.5


def arm_description(name="arm"):
    """The seed bot file's links and joints (components and render models dropped), its default pose."""
    doc = json.loads(BOT_FILE.read_text())
    links = []
    for link in doc["links"]:
        links.append({k: v for k, v in link.items() if k not in ("sensors", "actuators", "renderModel")})
    for link in links:
        if "shape" in link:
            link.setdefault("contact", {})["coulombFrictionCoefficient"] = FRICTION
    return {"name": name, "links": links, "joints": doc["joints"], "default_pose": doc["defaultPose"],
            "servos": [json.loads(a["params"]) for link in doc["links"] for a in link.get("actuators", [])]}


def box_description():
    """The rigid box that replaces the duck: where the duck lies (x = -0.30 m), its top at 9 cm,
    so that the lowest point of the ball's circle (z = 0.07 - 0.02 radius) presses into it."""
    return {"name": "box", "shape": {"box": {"halfExtents": [0.06, 0.06, 0.045]}}, "mass": 0.5,
            "position": [-0.3, 0.0, 0.045], "rotation": [0, 0, 0, 1], "friction": FRICTION}


def scene_description(with_box=True):
    return {"name": "arm_box", "dt": DT, "gravity": [0, 0, -9.81], "ground": {"friction": FRICTION},
            "bodies": [box_description()] if with_box else [], "articulations": [arm_description()]}


# ---------------------------------------------------------------- the seed's law


def trajectory_target(t):
    center = np.array([-0.3, 0.0, 0.15])
    radius, omega = 0.08, 2 * math.pi / 3.0
    theta = omega * t
    return center + radius * np.array([math.cos(theta), 0.0, math.sin(theta)]), \
        radius * omega * np.array([-math.sin(theta), 0.0, math.cos(theta)])


class Controller:
    """MyVelocityForceController.compute_output, verbatim in its arithmetic."""

    def __init__(self):
        self.k_p, self.k_f, self.f_z_target, self.exit_margin = 5.0, 0.05, 0.5, 0.005
        self.force_mode = False
        self.force_steps = 0

    def compute(self, x, J_pos, f_z, t):
        x_target, x_dot_target = trajectory_target(t)
        v_des = x_dot_target + self.k_p * (x_target - x)
        if not self.force_mode:
            self.force_mode = f_z > self.f_z_target
        elif x_target[2] > x[2] + self.exit_margin or f_z <= 0.0:
            self.force_mode = False
        if self.force_mode:
            v_des[2] = self.k_f * (f_z - self.f_z_target)
            self.force_steps += 1
        return np.linalg.pinv(J_pos[[0, 2], :]) @ v_des[[0, 2]]


class Servo:
    """MyVelocityServoActuator.compute_effort (and the engine's VELOCITY_SERVO law)."""

    def __init__(self, k_p, k_i, effort_limit, profile_accel):
        self.k_p, self.k_i, self.effort_limit, self.profile_accel = k_p, k_i, effort_limit, profile_accel
        self.integral = self.w_traj = 0.0

    def effort(self, w_goal, w_present, dt):
        max_step = self.profile_accel * dt
        self.w_traj = self.w_traj + float(np.clip(w_goal - self.w_traj, -max_step, max_step))
        e = self.w_traj - w_present
        integral_next = self.integral + e * dt
        unsat = self.k_p * e + self.k_i * integral_next
        effort = float(np.clip(unsat, -self.effort_limit, self.effort_limit))
        if effort == unsat or e * unsat < 0:
            self.integral = integral_next
        return effort


# ---------------------------------------------------------------- per-simulator adapters


class SuperDexArm:
    def __init__(self, desc, control=True):
        import superdex.physics as sdp

        self.sdp = sdp
        sdp.initialize(num_worker_threads=0)
        self.scene, actors = __import__("benchmarks.models", fromlist=["x"]).build_superdex(desc, sdp)
        self.arm = actors["arm"]
        self.box = actors.get("box")
        self.ball = self.scene.get_actor(self.arm.get_nested_link_actors()[BALL_LINK])
        self.ball.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
        self.real = np.float64 if sdp.uses_double_precision() else np.float32
        self.xforms = sdp.DynamicArrayTransformRT(len(self.arm.get_nested_link_actors()))
        self.qd = np.zeros(self.arm.get_num_dofs(), dtype=self.real)
        # the ball's Jacobian filled in place (6 x n, row-major), as MuJoCo's adapter passes mj_jacBody its array
        self.jac = np.zeros(6 * self.arm.get_num_dofs(), dtype=self.real)
        self.jac_rows = self.jac.reshape(6, -1)
        self.dt = desc["dt"]

    def observe(self):
        self.arm.get_articulated_link_transforms(self.xforms)
        x = np.asarray(self.xforms[BALL_LINK].translation, dtype=np.float64)
        self.ball.get_articulated_jacobian(self.jac)
        self.arm.get_articulated_joint_velocities(self.qd)
        return x, self.jac_rows[0:3].astype(np.float64), self.qd.astype(np.float64)

    def apply(self, efforts):
        self.arm.set_external_forces_on_dofs([0, 1], efforts)

    def step(self):
        self.scene.step(self.dt)

    def contact_force(self):
        return np.asarray(self.ball.get_contact_force_world(), dtype=np.float64)

    def time(self):
        return self.scene.get_total_simulation_time()

    def box_position(self):
        return np.array(self.box.get_root_transform().translation, dtype=np.float64) if self.box else None

    def close(self):
        self.sdp.shutdown()


class MuJoCoArm:
    def __init__(self, desc, control=True):
        import mujoco

        from benchmarks.models import mujoco_set_default_pose, to_mjcf

        self.mj = mujoco
        self.model = mujoco.MjModel.from_xml_string(to_mjcf(desc))
        self.data = mujoco.MjData(self.model)
        mujoco_set_default_pose(self.model, self.data, desc, mujoco)
        self.ball_body = self.model.body("arm/ball").id
        self.ball_geom = self.model.geom("arm/ball").id
        self.box_body = self.model.body("box").id if desc["bodies"] else None
        self.dofs = [self.model.joint("arm/shoulder").dofadr[0], self.model.joint("arm/elbow").dofadr[0]]
        self.jacp = np.zeros((3, self.model.nv))
        self.f6 = np.zeros(6)
        self.t = 0.0

    def observe(self):
        d = self.data
        x = d.xpos[self.ball_body].copy()
        self.mj.mj_jacBody(self.model, d, self.jacp, None, self.ball_body)
        return x, self.jacp[:, self.dofs].copy(), d.qvel[self.dofs].copy()

    def apply(self, efforts):
        self.data.qfrc_applied[self.dofs] = efforts

    def step(self):
        self.mj.mj_step(self.model, self.data)

    def contact_force(self):
        total = np.zeros(3)
        d = self.data
        for i in range(d.ncon):
            c = d.contact[i]
            if c.geom1 != self.ball_geom and c.geom2 != self.ball_geom:
                continue
            self.mj.mj_contactForce(self.model, d, i, self.f6)
            f_world = c.frame.reshape(3, 3).T @ self.f6[:3]  # force of geom1 on geom2
            total += f_world if c.geom2 == self.ball_geom else -f_world
        return total

    def time(self):
        return self.data.time

    def box_position(self):
        return self.data.xpos[self.box_body].copy() if self.box_body is not None else None

    def close(self):
        pass


class PyBulletArm:
    def __init__(self, desc, control=True):
        import pybullet as p

        from benchmarks.models import build_pybullet

        self.p = p
        self.c = p.connect(p.DIRECT)
        self.ids = build_pybullet(desc, p, self.c)
        self.arm = self.ids["arm"]
        index = self.ids["arm/joints"]
        # PyBullet link index = index of the joint that attaches the link
        self.ball = index["ball_weld"]
        self.joints = [index["shoulder"], index["elbow"]]
        self.box = self.ids.get("box")
        self.dt = desc["dt"]
        self.t = 0.0
        self.efforts = [0.0, 0.0]

    def observe(self):
        p, c = self.p, self.c
        states = p.getJointStates(self.arm, self.joints, physicsClientId=c)
        q = [s[0] for s in states]
        qd = [s[1] for s in states]
        x = np.array(p.getLinkState(self.arm, self.ball, computeForwardKinematics=1, physicsClientId=c)[4])
        lin, _ = p.calculateJacobian(self.arm, self.ball, [0, 0, 0], q, qd, [0.0, 0.0], physicsClientId=c)
        return x, np.array(lin), np.array(qd)

    def apply(self, efforts):
        self.efforts = list(efforts)

    def step(self):
        # torques given with TORQUE_CONTROL act for one stepSimulation: given every step
        self.p.setJointMotorControlArray(self.arm, self.joints, self.p.TORQUE_CONTROL, forces=self.efforts, physicsClientId=self.c)
        self.p.stepSimulation(physicsClientId=self.c)
        self.t += self.dt

    def contact_force(self):
        total = np.zeros(3)
        for cp in self.p.getContactPoints(bodyA=self.arm, linkIndexA=self.ball, physicsClientId=self.c):
            total += cp[9] * np.array(cp[7]) + cp[10] * np.array(cp[11]) + cp[12] * np.array(cp[13])
        return total

    def time(self):
        return self.t

    def box_position(self):
        return np.array(self.p.getBasePositionAndOrientation(self.box, physicsClientId=self.c)[0]) if self.box is not None else None

    def close(self):
        self.p.disconnect(self.c)


ADAPTERS = {"superdex": SuperDexArm, "mujoco": MuJoCoArm, "pybullet": PyBulletArm}
