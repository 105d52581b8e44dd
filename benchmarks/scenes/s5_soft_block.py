"""Scene 5: a soft block (10 cm cube, Neo-Hookean E = 100 kPa, nu = 0.45, 500 kg/m^3, stiffness
damping 0.01 s) dropped from 1 mm onto the ground, at 100 Hz, meshed with about 1k, 5k and 20k
tetrahedra (a grid of cells, 6 tetrahedra each): time per step against tetrahedron count, and the
exponent of its growth (least-squares fit of log time against log count).

MuJoCo models the same block with a 3-D flexcomp grid: the same nodes and the same 6-tetrahedra
cells, its linear FEM elasticity (Young's modulus, Poisson's ratio, damping) and the same mass.
MuJoCo 4 rejects flex elasticity under its implicit integrators, so it runs with
integrator="discrete"; its warnings (MjData.warning counters: ill-conditioned solves) are reported.
"""

from __future__ import annotations

import numpy as np

from benchmarks.harness import Timer
from benchmarks.models import node_positions_world

NUMBER = 5
TITLE = "Soft block on the ground: time per step against tetrahedron count (100 Hz)"
DT = 0.01
SIZE = 0.1
E, NU, RHO, DAMPING = 1e5, 0.45, 500.0, 0.01
DROP = 0.001  # m: contact from the second step on
GRIDS = {"1k": (5, 5, 7), "5k": (9, 9, 10), "20k": (15, 15, 15)}
STEPS = 8  # the same simulated interval (landing and the first contact response) at every size


def cases(opts):
    out = []
    grids = {"1k": (2, 2, 2), "5k": (3, 3, 3), "20k": (4, 4, 4)} if opts.quick else GRIDS
    for sim in ("superdex", "mujoco"):
        for size, cells in grids.items():
            out.append({"label": f"{size} / {sim}", "sim": sim, "size": size, "cells": list(cells),
                        "steps": 2 if opts.quick else STEPS})
    return out


def box_tet_mesh(size, cells):
    """A box [0, size] split into cells, each into 6 positively oriented tetrahedra (Kuhn)."""
    nx, ny, nz = cells
    xs = [np.linspace(0, size[k], cells[k] + 1) for k in range(3)]
    index = lambda i, j, k: (k * (ny + 1) + j) * (nx + 1) + i  # noqa: E731
    nodes = np.array([[xs[0][i], xs[1][j], xs[2][k]] for k in range(nz + 1) for j in range(ny + 1) for i in range(nx + 1)])
    tets = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                c = [index(i + a, j + b, k + d) for d in (0, 1) for b in (0, 1) for a in (0, 1)]
                for path in ((1, 3), (1, 5), (2, 3), (2, 6), (4, 5), (4, 6)):
                    tet = [c[0], c[path[0]], c[path[1]], c[7]]
                    p = nodes[tet]
                    if np.linalg.det(np.array([p[1] - p[0], p[2] - p[0], p[3] - p[0]])) < 0:
                        tet[1], tet[2] = tet[2], tet[1]
                    tets.append(tet)
    return nodes, np.array(tets, dtype=np.int64)


def run_superdex(cells, steps):
    import superdex.physics as sdp

    sdp.initialize(num_worker_threads=0)
    scene = sdp.create_scene("soft block")
    scene.set_gravity([0, 0, -9.81])
    scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
    nodes, tets = box_tet_mesh([SIZE] * 3, cells)
    # Neo-Hookean; DAMPING is the stiffness-proportional (Kelvin-Voigt) coefficient, s
    material = sdp.SoftMaterialParams(type=sdp.SoftMaterialType.NEO_HOOKEAN,
                                      neo_hookean=sdp.NeoHookeanMaterialParams(youngs_modulus=E, poisson_ratio=NU),
                                      density=RHO, stiffness_damping_coefficient=DAMPING)
    block = scene.create_soft_actor(name="block", shape=sdp.create_tet_mesh_shape(nodes, tets), material=material,
                                    world_from_local=sdp.TransformRT(translation=[-SIZE / 2, -SIZE / 2, DROP]))
    block.register_query(sdp.QueryType.NODE_POSITIONS)
    iterations = 0
    with Timer() as timer:
        for _ in range(steps):
            scene.step(DT)
            iterations += scene.get_solver_stats().total_non_linear_iters
    x = node_positions_world(block)
    out = {"wall": timer.wall, "tets": len(tets), "nodes": len(nodes),
           "checks": {"min_z_mm": 1e3 * float(x[:, 2].min()), "top_z_mm": 1e3 * float(x[:, 2].max()),
                      "newton_per_step": iterations / steps}}
    sdp.shutdown()
    return out


def run_mujoco(cells, steps):
    import mujoco

    nx, ny, nz = cells
    spacing = [SIZE / nx, SIZE / ny, SIZE / nz]
    xml = f"""<mujoco model="soft block">
  <option timestep="{DT}" integrator="discrete" gravity="0 0 -9.81"/>
  <worldbody>
    <geom name="ground" type="plane" size="0 0 1"/>
    <flexcomp name="block" type="grid" dim="3" count="{nx + 1} {ny + 1} {nz + 1}" spacing="{spacing[0]} {spacing[1]} {spacing[2]}"
              pos="0 0 {DROP + SIZE / 2}" radius="0.0005" mass="{RHO * SIZE ** 3}">
      <edge equality="false"/>
      <elasticity young="{E}" poisson="{NU}" damping="{DAMPING}"/>
      <contact selfcollide="none"/>
    </flexcomp>
  </worldbody>
</mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    with Timer() as timer:
        for _ in range(steps):
            mujoco.mj_step(model, data)
    warnings = int(sum(data.warning[i].number for i in range(len(data.warning))))
    x = data.flexvert_xpos
    return {"wall": timer.wall, "tets": int(model.flex_elemnum[0]), "nodes": int(model.flex_vertnum[0]),
            "checks": {"min_z_mm": 1e3 * float(x[:, 2].min()), "top_z_mm": 1e3 * float(x[:, 2].max()), "warnings": warnings}}


def run_case(case):
    out = (run_superdex if case["sim"] == "superdex" else run_mujoco)(case["cells"], case["steps"])
    out.update({"steps": case["steps"], "sim_time": case["steps"] * DT})
    return out
