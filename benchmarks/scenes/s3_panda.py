"""Scene 3: the 7-DOF Franka Panda (example-robot-data URDF, scenes/panda.py) under joint PD
control from the "ready" pose to a target that lowers the hand by 21 cm (joints 2, 4, 6 by +0.3, -0.3, +0.3 rad), at 1 kHz, with
and without a table under the hand (with the table, the target lies below its top, so the two
fingertip spheres press on it and stay in contact).

The PD law tau = kp (q* - q) - kd v, clamped to the URDF's effort limits, runs inside each
simulator's step, as each one offers it: SuperDex's BASIC_JSC_PD controller (C++ bot pipeline),
MuJoCo position-servo actuators (gain kp, bias -kp q - kd v, force range), PyBullet's PD_CONTROL
motors. No Python runs per step: the loop only steps.
"""

from __future__ import annotations

import json
import os
import tempfile

import numpy as np

from benchmarks.harness import Timer, median_of_episodes
from benchmarks.models import build_pybullet, build_superdex, mujoco_set_default_pose, to_mjcf
from benchmarks.scenes import panda

NUMBER = 3
TITLE = "7-DOF Panda under joint PD control (1 kHz)"
SIMS = ("superdex", "mujoco", "pybullet")
DT = 0.001
TARGET = list(np.add(panda.READY, [0.0, 0.3, 0.0, -0.3, 0.0, 0.3, 0.0]))
PRESS = 0.02  # m: the table top lies this far above the fingertips' target height


def scene_description(table):
    arm, efforts = panda.description()
    bodies = []
    if table:
        tips = panda.forward_kinematics(arm, TARGET)[-2:]
        top = min(t[2] for t in tips) - panda.TIP_RADIUS + PRESS
        center = np.mean(tips, axis=0)
        bodies.append({"name": "table", "static": True, "shape": {"box": {"halfExtents": [0.15, 0.15, 0.02]}},
                       "position": [float(center[0]), float(center[1]), top - 0.02], "friction": 0.5})
    return {"name": "panda", "dt": DT, "gravity": [0, 0, -9.81], "ground": None, "bodies": bodies,
            "articulations": [arm]}, efforts


def cases(opts):
    seconds = 0.02 if opts.quick else 2.0
    # a loop of some 10 ms: the median of several episodes in the process
    episodes = 1 if opts.quick else 9
    return [{"label": f"{'table' if table else 'free'} / {sim}", "sim": sim, "table": table, "seconds": seconds,
             "episodes": episodes} for table in (False, True) for sim in SIMS]


class SuperDex:
    def __init__(self, desc, efforts):
        import superdex.physics as sdp
        import superdex.robotics as sdr

        self.sdp = sdp
        sdp.initialize(num_worker_threads=0)
        arm = desc["articulations"][0]
        scene, actors = build_superdex({**desc, "articulations": []}, sdp)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "panda.superdex_bot")
            with open(path, "w") as f:
                json.dump({"name": arm["name"], "links": arm["links"], "joints": arm["joints"], "defaultPose": arm["default_pose"]}, f)
            prefab = sdr.load_bot_prefab_from_file(path)
        ctx = sdr.create_context()
        self.bot = sdr.create_bot(scene, prefab, ctx)
        self.bot.create_controller("BASIC_JSC_PD", "pd", {"kp": panda.KP, "kd": panda.KD, "saturation": efforts, "target_pose": TARGET})
        self.scene, self.arm = scene, self.bot.get_articulated_actor()
        self.tips = [scene.get_actor(h) for h in list(self.arm.get_nested_link_actors())[-2:]]
        for tip in self.tips:
            tip.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)

    def step(self):
        self.scene.step(DT)

    def q(self):
        return np.array(self.arm.get_articulated_pose(), dtype=np.float64)

    def tip_force_z(self):
        return sum(float(t.get_contact_force_world()[2]) for t in self.tips)

    def close(self):
        self.sdp.shutdown()


class MuJoCo:
    def __init__(self, desc, efforts):
        import mujoco

        self.mj = mujoco
        acts = "\n".join(
            f'    <general joint="panda/panda_joint{k + 1}" gainprm="{kp!r}" biastype="affine" biasprm="0 {-kp!r} {-kd!r}" '
            f'forcelimited="true" forcerange="{-e!r} {e!r}"/>'
            for k, (kp, kd, e) in enumerate(zip(panda.KP, panda.KD, efforts)))
        self.model = mujoco.MjModel.from_xml_string(to_mjcf(desc, actuators=f"  <actuator>\n{acts}\n  </actuator>"))
        self.data = mujoco.MjData(self.model)
        mujoco_set_default_pose(self.model, self.data, desc, mujoco)
        self.data.ctrl[:] = TARGET
        self.qadr = [self.model.joint(f"panda/panda_joint{k + 1}").qposadr[0] for k in range(7)]
        self.tip_geoms = {self.model.geom("panda/tip_left").id, self.model.geom("panda/tip_right").id}
        self.f6 = np.zeros(6)

    def step(self):
        self.mj.mj_step(self.model, self.data)

    def q(self):
        return self.data.qpos[self.qadr].copy()

    def tip_force_z(self):
        total = 0.0
        for i in range(self.data.ncon):
            c = self.data.contact[i]
            if c.geom1 in self.tip_geoms or c.geom2 in self.tip_geoms:
                self.mj.mj_contactForce(self.model, self.data, i, self.f6)
                f = c.frame.reshape(3, 3).T @ self.f6[:3]
                total += f[2] if c.geom2 in self.tip_geoms else -f[2]
        return total


    def close(self):
        pass


class PyBullet:
    def __init__(self, desc, efforts):
        import pybullet as p

        self.p = p
        self.c = p.connect(p.DIRECT)
        ids = build_pybullet(desc, p, self.c)
        self.arm = ids["panda"]
        index = ids["panda/joints"]
        self.joints = [index[f"panda_joint{k + 1}"] for k in range(7)]
        self.tips = [index["tip_left_weld"], index["tip_right_weld"]]
        # explicit PD computed by PyBullet in every stepSimulation (its PD_CONTROL motors)
        p.setJointMotorControlArray(self.arm, self.joints, p.PD_CONTROL, targetPositions=TARGET, targetVelocities=[0.0] * 7,
                                    positionGains=panda.KP, velocityGains=panda.KD, forces=efforts, physicsClientId=self.c)

    def step(self):
        self.p.stepSimulation(physicsClientId=self.c)

    def q(self):
        return np.array([s[0] for s in self.p.getJointStates(self.arm, self.joints, physicsClientId=self.c)])

    def tip_force_z(self):
        total = 0.0
        for tip in self.tips:
            for cp in self.p.getContactPoints(bodyA=self.arm, linkIndexA=tip, physicsClientId=self.c):
                total += cp[9] * cp[7][2]
        return total

    def close(self):
        self.p.disconnect(self.c)


SIM_CLASSES = {"superdex": SuperDex, "mujoco": MuJoCo, "pybullet": PyBullet}


def run_case(case):
    return median_of_episodes(case, run_episode)


def run_episode(case):
    """One episode on a freshly built simulation: (wall of its stepping loop, result)."""
    desc, efforts = scene_description(case["table"])
    sim = SIM_CLASSES[case["sim"]](desc, efforts)
    steps = int(round(case["seconds"] / DT))
    with Timer() as timer:
        for _ in range(steps):
            sim.step()
    q = sim.q()
    checks = {"max_joint_error_rad": float(np.max(np.abs(q - TARGET))), "tip_force_z_N": float(sim.tip_force_z()),
              "q2": float(q[1]), "q4": float(q[3])}
    sim.close()
    return timer.wall, {"steps": steps, "sim_time": steps * DT, "checks": checks}
