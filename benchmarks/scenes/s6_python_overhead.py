"""Scene 6: the cost of one Python call, on the Panda (scene 3's model, no table), against each
peer's closest Python equivalent. Each call is repeated in a tight loop (batches, median batch);
every call fills caller-owned arrays where the API allows, as a control loop would.

| SuperDex | MuJoCo | PyBullet |
|---|---|---|
| arm.get_articulated_joint_velocities(out) | out[:] = data.qvel | getJointStates(arm, joints) |
| arm.get_articulated_link_transforms(out) | copy data.xpos and data.xquat | getLinkStates(arm, links) |
| hand.get_articulated_jacobian(out) | mj_jacBody(model, data, jacp, jacr, hand) | calculateJacobian(arm, hand, ...) |
| arm.set_external_forces_on_dofs(dofs, f) | data.qfrc_applied[:] = f | setJointMotorControlArray(TORQUE_CONTROL) |
| scene.step(dt) | mj_step(model, data) | stepSimulation() |
"""

from __future__ import annotations

import statistics
import time

import numpy as np

from benchmarks.scenes import panda

NUMBER = 6
TITLE = "Python overhead: cost per call (Panda, 7 DOF)"
SIMS = ("superdex", "mujoco", "pybullet")
CALLS = ("get_articulated_joint_velocities", "get_articulated_link_transforms", "get_articulated_jacobian",
         "set_external_forces_on_dofs", "step")
DT = 0.001


def cases(opts):
    return [{"label": sim, "sim": sim, "calls": 200 if opts.quick else 20000, "batches": 2 if opts.quick else 7} for sim in SIMS]


def per_call_ns(fn, calls, batches):
    times = []
    for _ in range(batches):
        start = time.perf_counter_ns()
        for _ in range(calls):
            fn()
        times.append((time.perf_counter_ns() - start) / calls)
    return statistics.median(times)


def functions(sim):
    desc = {"name": "panda", "dt": DT, "gravity": [0, 0, -9.81], "ground": None, "bodies": [],
            "articulations": [panda.description()[0]]}
    tau = np.linspace(-1.0, 1.0, 7)
    if sim == "superdex":
        import superdex.physics as sdp

        from benchmarks.models import build_superdex

        sdp.initialize(num_worker_threads=0)
        scene, actors = build_superdex(desc, sdp)
        arm = actors["panda"]
        hand = scene.get_actor(arm.get_nested_link_actors()[8])
        real = np.float64 if sdp.uses_double_precision() else np.float32
        v = np.zeros(arm.get_num_dofs(), dtype=real)
        xf = sdp.DynamicArrayTransformRT(len(arm.get_nested_link_actors()))
        J = np.zeros(6 * arm.get_num_dofs(), dtype=real)
        dofs = list(range(7))
        return {"get_articulated_joint_velocities": lambda: arm.get_articulated_joint_velocities(v),
                "get_articulated_link_transforms": lambda: arm.get_articulated_link_transforms(xf),
                "get_articulated_jacobian": lambda: hand.get_articulated_jacobian(J),
                "set_external_forces_on_dofs": lambda: arm.set_external_forces_on_dofs(dofs, tau),
                "step": lambda: scene.step(DT)}, sdp.shutdown
    if sim == "mujoco":
        import mujoco

        from benchmarks.models import mujoco_set_default_pose, to_mjcf

        model = mujoco.MjModel.from_xml_string(to_mjcf(desc))
        data = mujoco.MjData(model)
        mujoco_set_default_pose(model, data, desc, mujoco)
        hand = model.body("panda/panda_hand").id
        v = np.zeros(model.nv)
        pos, quat = np.zeros_like(data.xpos), np.zeros_like(data.xquat)
        jacp, jacr = np.zeros((3, model.nv)), np.zeros((3, model.nv))

        def transforms():
            np.copyto(pos, data.xpos)
            np.copyto(quat, data.xquat)

        def forces():
            data.qfrc_applied[:] = tau

        def velocities():
            v[:] = data.qvel

        return {"get_articulated_joint_velocities": velocities,
                "get_articulated_link_transforms": transforms,
                "get_articulated_jacobian": lambda: mujoco.mj_jacBody(model, data, jacp, jacr, hand),
                "set_external_forces_on_dofs": forces,
                "step": lambda: mujoco.mj_step(model, data)}, lambda: None
    import pybullet as p

    from benchmarks.models import build_pybullet

    c = p.connect(p.DIRECT)
    ids = build_pybullet(desc, p, c)
    arm = ids["panda"]
    index = ids["panda/joints"]
    joints = [index[f"panda_joint{k + 1}"] for k in range(7)]
    links = list(range(p.getNumJoints(arm, physicsClientId=c)))
    hand = index["hand_weld"]
    zeros = [0.0] * 7
    taus = tau.tolist()

    def jacobian():
        q = [s[0] for s in p.getJointStates(arm, joints, physicsClientId=c)]
        return p.calculateJacobian(arm, hand, [0, 0, 0], q, zeros, zeros, physicsClientId=c)

    return {"get_articulated_joint_velocities": lambda: p.getJointStates(arm, joints, physicsClientId=c),
            "get_articulated_link_transforms": lambda: p.getLinkStates(arm, links, physicsClientId=c),
            "get_articulated_jacobian": jacobian,
            "set_external_forces_on_dofs": lambda: p.setJointMotorControlArray(arm, joints, p.TORQUE_CONTROL, forces=taus,
                                                                              physicsClientId=c),
            "step": lambda: p.stepSimulation(physicsClientId=c)}, lambda: p.disconnect(c)


def run_case(case):
    fns, close = functions(case["sim"])
    out = {}
    for name in CALLS:
        calls = case["calls"] if name != "step" else max(2, case["calls"] // 10)
        out[f"ns_{name}"] = per_call_ns(fns[name], calls, case["batches"])
    close()
    return out
