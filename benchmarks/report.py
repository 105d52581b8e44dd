"""RESULTS.md: the machine, the versions, one table per scene with ratios, a met / not met line per
target with the measured numbers, and the equivalence checks between simulators."""

from __future__ import annotations

import math
import os
import platform
import subprocess
from datetime import datetime, timezone

import numpy as np

RATIO_NOTE = "ratio = ours / peer of the time per step (or per call): below 1 SuperDex is faster"


def machine():
    cpu = "unknown"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    # the CPUs this process may run on (nproc would honour the OMP_NUM_THREADS=1 that run.py sets)
    nproc = str(len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count())
    mem = ""
    try:
        for line in open("/proc/meminfo"):
            if line.startswith("MemTotal"):
                mem = f", {int(line.split()[1]) / 1024 / 1024:.0f} GiB memory"
    except OSError:
        pass
    return f"{cpu}, {nproc} cores (affinity){mem}; {platform.system()} {platform.release()}; Python {platform.python_version()}"


def versions():
    out = {}
    code = ("import importlib.metadata as m, sys\n"
            "for n in ('superdex', 'mujoco', 'pybullet', 'numpy'):\n"
            "    try: print(n, m.version(n))\n"
            "    except Exception: print(n, 'missing')\n"
            "import superdex.physics as sdp; print('precision', 'double' if sdp.uses_double_precision() else 'float')\n")
    import sys

    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    for line in res.stdout.splitlines():
        k, v = line.split(" ", 1)
        out[k] = v
    try:
        here = os.path.dirname(__file__)
        out["commit"] = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, cwd=here).stdout.strip()
        if subprocess.run(["git", "status", "--porcelain"], capture_output=True, text=True, cwd=here).stdout.strip():
            out["commit"] += " with uncommitted changes"
    except OSError:
        pass
    return out


def f(x, digits=3):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "–"
    if isinstance(x, float):
        if x == 0:
            return "0"
        if abs(x) >= 100:
            return f"{x:.0f}"
        return f"{x:.{digits}g}"
    return str(x)


def checks_text(m):
    c = m.get("checks", {})
    return ", ".join(f"{k} {f(v, 4) if isinstance(v, float) else v}" for k, v in c.items())


def table(headers, rows):
    lines = ["| " + " | ".join(headers) + " |", "|" + "|".join("---" for _ in headers) + "|"]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def verdict(ok):
    return "**met**" if ok else "**not met**"


def sim_rows(results, group_key=None):
    """Rows of sim results with the ratio of SuperDex's time per step to each peer's."""
    rows = []
    groups = {}
    for case, m in results:
        groups.setdefault(case.get(group_key) if group_key else "", []).append((case, m))
    for g, items in groups.items():
        ours = next((m for c, m in items if c["sim"] == "superdex"), None)
        for case, m in items:
            ratio = ours["ms_per_step"] / m["ms_per_step"] if ours and case["sim"] != "superdex" else None
            rows.append([case["label"], f(m["ms_per_step"], 3), f(m["steps_per_s"]), f(m.get("rtf")), f(m["peak_rss_mb"]),
                         f(ratio) if ratio else "", checks_text(m)])
    return rows


SIM_HEADERS = ["case", "ms/step", "steps/s", "real-time factor", "peak RSS (MB)", "ours/peer", "equivalence checks"]


def by(results, **kw):
    for case, m in results:
        if all(case.get(k) == v for k, v in kw.items()):
            return m
    return None


# ---------------------------------------------------------------- per scene: (markdown, targets)


def scene1(results, opts):
    rows = [[c["label"], f(m["sim_time"]), f(m["ms_per_step"]), f(m["steps_per_s"]), f(m["rtf"]), f(m["peak_rss_mb"]), checks_text(m)]
            for c, m in results]
    md = table(["variant", "simulated s", "ms/step", "steps/s", "real-time factor", "peak RSS (MB)", "checks"], rows)
    seed, pipe = by(results, variant="seed loop"), by(results, variant="C++ pipeline")
    floor = by(results, variant="physics only")
    targets = [("1: seed loop >= 10x real time", seed["rtf"] >= 10, f"{seed['rtf']:.2f}x"),
               ("1: C++ pipeline >= 30x real time", pipe["rtf"] >= 30, f"{pipe['rtf']:.2f}x")]
    full = by(results, variant="seed loop, full-FEM duck")
    notes = [f"The seed's duck is a reduced soft body (24 vibration modes plus the static correction; "
             f"assets/prefabs/duck_lamp/README.md). The physics alone (no components) runs at {floor['rtf']:.1f}x real time "
             f"({floor['ms_per_step']:.3f} ms/step); with the duck's full finite-element twin the seed loop runs at "
             f"{full['rtf']:.2f}x ({full['ms_per_step']:.1f} ms/step)."]
    return md, targets, notes


def peer_targets(name, results, group_key=None, groups=(None,)):
    targets = []
    for g in groups:
        sel = [(c, m) for c, m in results if group_key is None or c.get(group_key) == g]
        ours = next(m for c, m in sel if c["sim"] == "superdex")
        mj = next(m for c, m in sel if c["sim"] == "mujoco")
        pb = next(m for c, m in sel if c["sim"] == "pybullet")
        label = f"{name} ({g})" if g is not None else name
        targets.append((f"{label}: time per step <= MuJoCo's", ours["ms_per_step"] <= mj["ms_per_step"],
                        f"{ours['ms_per_step']:.4f} vs {mj['ms_per_step']:.4f} ms (ratio {ours['ms_per_step'] / mj['ms_per_step']:.2f})"))
        targets.append((f"{label}: well under PyBullet's (<= 0.5x)", ours["ms_per_step"] <= 0.5 * pb["ms_per_step"],
                        f"{ours['ms_per_step']:.4f} vs {pb['ms_per_step']:.4f} ms (ratio {ours['ms_per_step'] / pb['ms_per_step']:.2f})"))
    return targets


def scene2(results, opts):
    md = table(SIM_HEADERS, sim_rows(results, "variant"))
    # the control variant by parts: the law's calls timed inside the loop, the rest the simulator's
    parts, rows = [], []
    for c, m in results:
        if c["variant"] != "control" or "simulator_wall" not in m:
            continue
        part = {**m, "ms_per_step": 1e3 * m["simulator_wall"] / m["steps"]}
        parts.append((c, part))
        rows.append([c["sim"], f(1e3 * m["ms_per_step"], 3), f(1e6 * m["law_wall"] / m["steps"], 3), f(1e3 * part["ms_per_step"], 3)])
    ours = next(p for c, p in parts if c["sim"] == "superdex")
    for row, (c, p) in zip(rows, parts):
        row.append(f(ours["ms_per_step"] / p["ms_per_step"]) if c["sim"] != "superdex" else "")
    md += ("\n\nThe control variant by parts: the law's calls (controller and servos, the same Python in every "
           "simulator) timed inside the loop, and the rest of the step, the simulator's part (reading the state, "
           "Jacobian and contact force through its Python API, applying the efforts, stepping).\n\n" +
           table(["simulator", "control step (us)", "law in the loop (us)", "simulator's part (us)", "ours/peer (simulator's part)"], rows))
    law, pb = by(results, variant="law alone"), by(results, variant="control", sim="pybullet")
    notes = [f"The control law alone (no simulator) takes {1e3 * law['ms_per_step']:.1f} us per step, "
             f"{law['ms_per_step'] / pb['ms_per_step']:.2f} of PyBullet's control step: the same Python in every "
             "simulator, which no simulator can make faster. The control variant's targets compare the simulator's "
             "part of its step (the table above); the whole control step's ratios are in the first table."]
    targets = peer_targets("2 (control, simulator's part)", parts) + peer_targets("2", results, "variant", ("physics",))
    return md, targets, notes


def scene3(results, opts):
    for c, _ in results:
        c["group"] = "table" if c["table"] else "free"
    md = table(SIM_HEADERS, sim_rows(results, "group"))
    return md, peer_targets("3", results, "group", ("free", "table")), []


def scene4(results, opts):
    md = table(SIM_HEADERS, sim_rows(results))
    ours, mj = by(results, sim="superdex"), by(results, sim="mujoco")
    ratio = ours["ms_per_step"] / mj["ms_per_step"]
    jitter = ours["checks"]["max_speed_mm_s"]
    targets = [("4: time per step / MuJoCo's <= 1.5", ratio <= 1.5, f"ratio {ratio:.2f}"),
               ("4: no jitter (every box < 1 mm/s after settling)", jitter < 1.0,
                f"largest box speed in the untimed {results[0][0]['window']:g} s after the run: {jitter:.3g} mm/s "
                f"(MuJoCo {mj['checks']['max_speed_mm_s']:.3g}, PyBullet {by(results, sim='pybullet')['checks']['max_speed_mm_s']:.3g})")]
    return md, targets, []


def fit_exponent(points):
    """Least-squares slope of log(ms/step) against log(tets)."""
    x = np.log([p[0] for p in points])
    y = np.log([p[1] for p in points])
    return float(np.polyfit(x, y, 1)[0]) if len(points) >= 2 else float("nan")


def scene5(results, opts):
    rows = []
    fits = {}
    for sim in ("superdex", "mujoco"):
        pts = [(m["tets"], m["ms_per_step"]) for c, m in results if c["sim"] == sim]
        fits[sim] = fit_exponent(pts)
    for c, m in results:
        ours = by(results, sim="superdex", size=c["size"])
        ratio = ours["ms_per_step"] / m["ms_per_step"] if c["sim"] != "superdex" else None
        rows.append([c["label"], m["tets"], m["nodes"], f(m["ms_per_step"]), f(m["rtf"]), f(m["peak_rss_mb"]),
                     f(ratio) if ratio else "", checks_text(m)])
    md = table(["case", "tetrahedra", "nodes", "ms/step", "real-time factor", "peak RSS (MB)", "ours/peer", "checks"], rows)
    md += (f"\n\nFitted growth of the time per step, t ~ n^k: SuperDex k = {fits['superdex']:.2f}, "
           f"MuJoCo flex k = {fits['mujoco']:.2f}.")
    targets = [("5: cost per step grows no faster than n^1.2", fits["superdex"] <= 1.2, f"fitted exponent {fits['superdex']:.2f}")]
    return md, targets, []


def scene6(results, opts):
    from benchmarks.scenes.s6_python_overhead import CALLS

    ours, mj, pb = by(results, sim="superdex"), by(results, sim="mujoco"), by(results, sim="pybullet")
    rows, targets = [], []
    for call in CALLS:
        k = f"ns_{call}"
        r = ours[k] / mj[k]
        rows.append([call, f(ours[k] / 1e3), f(mj[k] / 1e3), f(r), f(pb[k] / 1e3) if pb else "–",
                     f(ours[k] / pb[k]) if pb else "–"])
        targets.append((f"6: {call} no slower than MuJoCo's", r <= 1.0, f"{ours[k] / 1e3:.3f} vs {mj[k] / 1e3:.3f} us (ratio {r:.2f})"))
    md = table(["call", "SuperDex (us)", "MuJoCo (us)", "ours/MuJoCo", "PyBullet (us)", "ours/PyBullet"], rows)
    return md, targets, []


def scene7(results, opts):
    rows = []
    targets = []
    for variant in ("worker threads", "Python threads"):
        one, two = by(results, variant=variant, threads=1), by(results, variant=variant, threads=2)
        for threads, m in ((1, one), (2, two)):
            rows.append([variant, threads, m["n"] if "n" in m else "", f(m["scene_steps_per_s"]), f(m["wall"]), f(m["peak_rss_mb"]),
                         f(m["scene_steps_per_s"] / one["scene_steps_per_s"]), checks_text(m)])
        speedup = two["scene_steps_per_s"] / one["scene_steps_per_s"]
        targets.append((f"7 ({variant}): 2 threads >= 1.8x the throughput of 1", speedup >= 1.8, f"{speedup:.2f}x"))
    md = table(["variant", "threads", "", "scene-steps/s", "wall (s)", "peak RSS (MB)", "throughput / 1 thread", "checks"], rows)
    return md, targets, []


def scene8(results, opts):
    rows = []
    targets = []
    for task in sorted({c["task"] for c, _ in results}, key=lambda t: [c["task"] for c, _ in results].index(t)):
        one, two = by(results, task=task, threads=1), by(results, task=task, threads=2)
        scenes = next(c["n"] for c, _ in results if c["task"] == task)
        for threads, m in ((1, one), (2, two)):
            rows.append([task, threads, scenes, f(m["scene_steps_per_s"]), f(m["wall"]), f(m["cpu_over_wall"]),
                         f(m["peak_rss_mb"]), f(m["scene_steps_per_s"] / one["scene_steps_per_s"]), checks_text(m)])
        speedup = two["scene_steps_per_s"] / one["scene_steps_per_s"]
        same = one["checks"]["obs digest"] == two["checks"]["obs digest"]
        targets.append((f"8 ({task}): 64 scenes on 2 threads >= 1.8x the throughput of 1", speedup >= 1.8 and same,
                        f"{speedup:.2f}x; observations {'identical' if same else 'DIFFER'} on 1 and 2 threads"))
    md = table(["task", "threads", "scenes", "scene-steps/s", "wall (s)", "CPU / wall", "peak RSS (MB)", "throughput / 1 thread",
                "checks"], rows)
    return md, targets, []


def scene9(results, opts):
    md = table(SIM_HEADERS, sim_rows(results, "model"))
    targets = []
    for model in dict.fromkeys(c["model"] for c, _ in results):
        ours, mj = by(results, model=model, sim="superdex"), by(results, model=model, sim="mujoco")
        ratio = ours["ms_per_step"] / mj["ms_per_step"]
        targets.append((f"9 ({model}): time per step <= MuJoCo's on the same file", ratio <= 1.0,
                        f"{ours['ms_per_step']:.4f} vs {mj['ms_per_step']:.4f} ms (ratio {ratio:.2f})"))
    return md, targets, []


def scene10(results, opts):
    rows, targets, notes = [], [], []
    for case, m in results:
        if "ms_per_solve" in m:
            rows.append([case["label"], "", f(m["ms_per_solve"], 3) + " per solve", "", f(m["wall"]), f(m["peak_rss_mb"]), checks_text(m)])
            notes.append(f"{case['label']}: {m['solves']} solves, {m['checks']['reached']} reached, {m['ms_per_solve']:.2f} ms per "
                         f"solve (building the scene and the solver included).")
            continue
        rows.append([case["label"], f(m["sim_time"]), f(m["ms_per_step"]), f(m["rtf"]), f(m["wall"]), f(m["peak_rss_mb"]), checks_text(m)])
        targets.append((f"10 ({case['label']}): the example runs at least at real time", m["rtf"] >= 1.0, f"{m['rtf']:.1f}x"))
    md = table(["example", "simulated s", "ms per step (IK: per solve)", "real-time factor", "wall (s)", "peak RSS (MB)", "checks"], rows)
    return md, targets, notes


REPORTERS = {1: scene1, 2: scene2, 3: scene3, 4: scene4, 5: scene5, 6: scene6, 7: scene7, 8: scene8, 9: scene9, 10: scene10}


FINDINGS = """## Why targets are not met: profiles, what was fixed, what remains

Taken with `perf record` on the float build (not re-measured by each run); the numbers above are
this run's.

- Scene 1 (seed scene): the soft duck's own step is the floor; the seed loop and the C++ pipeline
  differ by little, so control is not where the time goes. The duck has 3839 tetrahedra and 3090
  free DOFs. Found: CHOLMOD's supernodal factorization opens OpenMP regions with a team of four
  threads fixed when it was built (OMP_NUM_THREADS does not override it), and the calls meant to
  make the BLAS and OpenMP serial looked their functions up where a Python extension's libraries
  are not visible, so every factorization woke and joined that team: 30 % of a duck step was
  spent in futex waits and wake-ups. Fixed: the functions are looked up in the loaded libraries,
  and OpenMP regions run on the thread that opens them: 120 to 46 ms per seed step, 41 to 17 ms
  per physics-only step (the benchmark runs before and after), at the same Newton iterations. Earlier fixes: the Hessian at the start
  of the step, computed for the stiffness damping, also serves the first Newton iteration; the
  element Hessians are assembled by 3 x 3 blocks; the element loops keep their buffers and skip
  the energies the line search does not need. Found next (perf, the pressed duck of
  benchmarks/soft_duck_press.py at 37 ms per step and 3.4 Newton iterations): every iteration
  after the first recomputed the projected Hessian of all 3839 tetrahedra, although only those
  near the ball deform, and factored the whole matrix again, although it changed only near the
  contacts; each iteration evaluated again the elastic gradient that the line search had just
  evaluated at the same point; and every factorization began with CHOLMOD's permuted transpose of
  the matrix (cholmod_transpose_sym, 6 %). Fixed: an iteration recomputes only the elements whose
  deformation gradient moved by more than SolverParams.soft_hessian_reuse_strain (1e-3) since the
  start of the step, about 4 % of them; its Newton system is solved by conjugate gradients
  preconditioned by the factorization of the solve's first iteration (a new factorization only
  when 12 iterations do not converge; SolverStats.soft_factorizations), and a matrix equal bit
  for bit to the factored one keeps its factor; the line search's gradient carries over; the
  matrix is kept in CHOLMOD's order and factored as stored. The gradients, the problem and its
  tolerance are unchanged. Pressed duck 37 to 18 ms per step, settling 26 to 13.4; in this suite
  46 to 22.5 ms per seed step, 17 to 12 ms per physics-only step. What remains per step (perf,
  float): the element Hessians at the start of the step, which the stiffness damping (K at the
  step's start) and the first iteration need, about 17 % (the 3 x 3 SVDs alone 6 %); the one
  factorization and the conjugate gradients' triangular solves, about 25 %; the gradients, about
  10 %; and some 5 % in the kernel: CHOLMOD opens an OpenMP region for each supernode even when
  no team may start, and libgomp ends each region with a futex wake-up. 10x and 30x real time
  mean 0.4 ms and 0.13 ms per step, 55 to 170 times less than this step and still about 10 times
  less than one factorization of this mesh: that needs a reduced model of the prop (modal or
  coarser mesh), not a constant factor.
- Scene 1, the reduced duck. The seed's duck prefab is now a reduced soft body: linear
  elasticity in 24 vibration modes plus the static correction (its static response to gravity
  and contact is the full linear FEM one; tests check it against an independent numpy FEM and
  against the full twin, which it matches within 7 % under the seed's press). The seed loop went
  from 0.17x to about 3x real time. Found next (perf, C++ pipeline, 1.3 ms per step): the dense
  Newton built J^T G J from all of about 320 contact rows, most of them the face points of the
  duck's surface within the 1 cm margin of the ball that never act; the collider's samples were
  matched against a closest-triangle hierarchy of the whole surface rebuilt every step. Fixed:
  only active rows join J^T G J (1.3 to 0.58 ms per step); soft contacts that cannot close
  within the step at the current speeds are deferred, joining a second solve only if the first
  one's velocities would close half their gap (0.58 to 0.5); the hierarchy holds only the faces
  near the collider (collision 0.3 to 0.06 ms). Found next (per-step timings of the C++
  pipeline, 0.37 s for 3 s): one step of 184 ms at the first touch, where the second solve took
  every deferred candidate and so some 150 duck nodes needed their residual compliance at once,
  each a solve of the rest stiffness (0.8 ms a node with Eigen's simplicial LDL^T); the
  closest-triangle hierarchy still rebuilt every step for a ball of six samples. Fixed: deferred
  contacts join the re-solve one by one as the solution closes them (the spike went, 0.37 to
  0.19 s); the rest stiffness is factored by CHOLMOD and a step's new nodes are solved together
  (0.8 to 0.33-0.48 ms a node); face bounds are computed once per body and step, and colliders of
  at most 32 samples are matched against the near faces directly (collision 0.087 to 0.060 ms
  per pressing step). The seed's controller law now has a built-in C++ counterpart,
  HYBRID_FORCE_VELOCITY (tested step by step against the seed's own Python components: paths
  agree to 1e-7 m), so the C++ pipeline variant runs all three components in C++; with the law
  in Python it is listed apart. Measured then (perf, C++ pipeline, 0.11 s for 3 s): the 275
  pressing steps take 0.34 ms each, the 475 others 0.043 ms. Of a pressing step: the residual
  compliance of nodes touched for the first time, about 30 % (some 90 nodes in the run, 0.3 ms
  each, cached after; it is one sparse triangular solve pair per node, bound by the factor's
  size); the dense Newton over the arm, the 24 modes and the contact nodes (n about 60, 30
  contacts, two friction passes a step while the ball slides), about 28 %; the contact search,
  15 %. The build for x86-64-v3 and the small-problem changes of scenes 2, 3 and 6 (below) took
  the run to about 0.099 s, just past 30x: the target is met with little margin. Tried and not
  kept: CHOLMOD's simplicial factor for the residual solves (the rest stiffness is factored once,
  so only the solve matters): 0.44 to 0.42 ms for one node, 2.3 to 3.2 ms for eight. Found next
  (perf and a timer around the soft contact search, C++ pipeline at 0.14 ms per step): the search
  was a fifth of the step, 27.6 us; each of the duck's 954 surface nodes met the ground plane
  through the general signed-distance call (a shape visit, a transform and a normalization per
  node). Fixed: a half-space's distance is affine in the world point, so it is found once per
  step as a normal and an offset, and a body whose bounds are out of the plane's reach skips it
  (a new test puts a soft cube on a tilted, moved plane): search 27.6 to 22.1 us, step 0.140 to
  0.123 ms. What remains of the search: each bounded collider near the duck (the arm's links)
  still tests every surface node and face against its box.
- Scene 5 (soft block): the same per-iteration costs, and the same OpenMP fix. The fitted
  exponent varies between runs and machines (1.2 to 1.27 on the Xeon, 1.05 to 1.22 on the EPYC):
  it is set by the sparse factorization, whose cost grows faster than n for 3-D meshes, and by
  the per-step costs that do not grow with n. CHOLMOD now keeps the sparser of AMD's and METIS's
  orderings (its default tries METIS only for very dense factors): 5k block 105 to 76 ms per step.
  The reuses of scene 1 then made every size faster: 1k 14.4 to 8.7 ms per step, 5k 85 to 40,
  20k 495 to 235 (now half of MuJoCo flex's 452). The reuse of element Hessians alone made the
  element work, linear in n, cheaper and raised the exponent to 1.22 (the run before this one);
  the conjugate gradients then removed most factorizations, whose cost grows faster than n, and
  it fell to 1.11.
- Scene 4 (pile). Found: every Newton iteration re-ran CHOLMOD's symbolic analysis and built
  J^T G J by sparse products; Newton started from the free motion, so a settled pile took about
  12 iterations per step; each friction pass started over. Fixed: a solve starts from the current
  velocities when bodies touch (about 3 iterations per step); the Newton matrix's pattern is built
  once per island and kept across steps while the island keeps its contacts (A's structure is
  its bodies' blocks, whatever their values); each block's J_b^T G_b J_b is scattered into known
  slots; rigid islands use a simplicial Cholesky in double (no BLAS or OpenMP threads). Measured next (solver statistics per
  step, float): the settled pile costs about 1.1 to 1.7 ms per step at 3 Newton iterations, but
  the landing (steps 30 to 100 of the 1000 timed) takes 50 to 100 iterations per step, the
  friction passes included, at about 0.35 ms each: 15 to 50 ms per step, about half of the timed
  run. In float, resting contacts creep at their friction bound, which ran the friction passes
  every step of the settled pile; the passes now run only for contacts that slip faster than
  SolverParams.friction_pass_min_slip (0.1 mm/s; the cone model's separation is mu times the slip
  speed): 1.67 to 1.15 ms per settled step. What remains is the landing: fewer iterations per
  pass, or passes that stop earlier, and a cheaper factorization. Measured with the friction
  passes off (max_friction_passes = 0, the pile settles to the same heights): the landing takes
  19 Newton iterations per step instead of 63 and the whole timed run 1.34 s instead of 2.47 s,
  so the passes are half of the run; without them the ratio to MuJoCo would still be about 3,
  from the landing's 19 iterations and a settled step of 0.9 ms (3 iterations at 0.3 ms).
  Found next (perf): the scalar simplicial factorization, with Eigen's permuted copy of the
  matrix before each one, was about a quarter of the run, and the dense product J_b^T G_b J_b of
  each contact block a tenth. Fixed: a block-sparse Cholesky on the bodies' dense blocks
  (block_cholesky.h: AMD on the graph of bodies once per pattern, dense 6 x 6 kernels, double
  precision), into whose stored blocks each contact writes its J_b^T G_b J_b entry by entry:
  the timed run 2.23 to 1.68 s, 9.1 to 6.5 ms per landing step, 1.0 to 0.83 ms per settled step
  (solver statistics per step, float). What remains: the landing's Newton iterations, about 40
  per step, two thirds of them in the friction passes (SolverStats.friction_passes: 4 re-solves
  in most landing steps, each a solve from the last solution whose slow first phase crosses the
  kinks of many contacts); and in float, the settled pile's largest island takes 2 to 3
  iterations per step where double takes 1: float round-off keeps the pile from a steady state
  and the residual ends near float's floor. A stopping test at an estimated round-off floor was
  tried and not kept (the estimates were off by two orders of magnitude one way or the other).
  MuJoCo, whose softer contacts make a smoother problem, takes 3 iterations per landing step and
  1 per settled step. Measured next (perf over landing steps 30 to 90, and each Newton
  iteration's step length and line-search trials): the one big island (300 DOFs, about 440
  contacts) takes 15 to 18 iterations in the first solve and 16, 17, 10 and 3 in the four friction
  passes; most iterations are damped (step lengths 0.1 to 0.4) and their exact line searches take
  5 to 25 trials, each a pass over every contact block: block_response alone is 18 % of a landing
  step, the block Cholesky 33 %. The iteration counts are the same in double, so this is the
  problem's, not round-off. A looser line search (stopping at 5 % of the initial slope, as the
  soft bodies' does) made Newton fail to converge in 50 iterations; at 1e-3 it saved 8 % of the
  run, not kept. What would change the ratio is fewer damped iterations (a better start for the
  friction passes, or a smoother contact model during impacts), not a cheaper iteration.
  Measured next (per-step timings and solver statistics): of the 1.64 s timed run, the 100
  landing steps took 0.94 s and the 900 settled steps 0.7 s (0.6 to 0.75 ms each, about one Newton
  iteration per island); MuJoCo takes 0.63 ms per landing step at 4 iterations and 0.41 ms per
  settled step at 1. Fixed, each measured on this scene: the block Cholesky's 6 x 6 kernels as
  plain loops unrolled at compile time instead of Eigen's dynamic-size triangular solves and
  products (1.64 to 1.45 s); the line search evaluates, after its first trial, only the blocks
  with an impulse at either end of the segment (a block zero at both ends is zero along it: its
  zero set is the minimizer set of its convex cost), and in float stops at 1e-6 of the slope
  instead of 1e-10, below float's round-off of the slope (8.8 to 5.4 trials per search; 1.45 to
  1.33 s); later Newton iterations of a problem add to H only the blocks whose Hessian block
  changed (1.33 to 1.27 s); on the sparse path a contact's rows enter J whole, so that J's pattern
  depends on the contact's bodies only and the Newton pattern refills its values in place from
  step to step instead of gathering and sorting them again (settled step 0.63 to 0.54 ms; 1.27 to
  1.14 s); friction passes before the last are solved to 100 times the tolerance, the last to
  the full one (1.14 to 1.08 s). Tried and not kept: keeping the cone model for contacts strictly
  inside their cone during the passes (no change); starting each solve from the solution with
  5 to 25 times softer friction (more iterations in all); a softer friction regularization
  (friction_sigma 0.025 instead of 1e-3) halves the landing's cost but lets a sticking box creep
  at up to 0.3 mm/s, so the default stays. What remains: the landing's 55 to 65 Newton iterations
  per step (four friction passes of 5 to 13 damped iterations each), of which the block
  factorization is now a quarter and the line search a sixth; and a settled step of 0.54 ms
  against MuJoCo's 0.41, spread over contact assembly, the box-box narrow phase and one Newton
  iteration. Tried next and not kept: contacts that persist from the last step (matched by their
  pair of links and nearest point) started with their last friction bound instead of the cone
  model, and the passes stopped once Coulomb's law held for every contact: the first solve then
  took 27 iterations instead of the cone's 19 and each pass still 9 to 14, the same run time;
  the factor's diagonal blocks updated in their lower triangle only (the full unrolled 6 x 6
  update vectorizes better: 136 against 140 us for 50 blocks, each coupled to 3 random others). The
  settled pile's islands (about 8 boxes each) now take the block-sparse path (scene 7 below);
  this scene's time is the same either way (1.08 to 1.13 s, measured alternately). Found next
  (a trace of each Newton iteration in landing step 60: step length, contacts changing between
  sticking, sliding and apart): the first solve took 23 iterations and the four passes 10, 7, 3
  and 2, each pass starting with about 30 contacts changing state, because a sliding contact
  whose normal impulse the cone model had kept while it drifted apart loses it in the fixed-bound
  problem. Reusing the last factorization for each pass's first direction saved 2 % of the
  iterations, and passes that corrected the cone model's normal targets instead of fixing the
  bounds still took 12 iterations each; not kept. Fixed: the drift correction moved into the
  Newton iterations themselves (SolverParams.drift_correction_iterations): from the second
  iteration on, each contact's normal target is lowered by mu times its slip beyond the friction
  regularization at the current iterate, until the residual is within 100 times the tolerance;
  the passes are gone. A sliding contact then keeps its own normal law with friction mu gamma_n
  within the one solve (a pushed box and two boxes sliding on each other keep contact exactly, in
  the tests). The timed run 1.09-1.12 s to 0.74-0.80 s (the landing's 100 steps 0.61-0.65 to
  0.31-0.35 s), with the same pile heights. What remains: the landing's first solve (about 20
  damped Newton iterations, a quarter of it the block factorization and a sixth the contacts'
  responses; the friction regularization, 1e-3 of w, makes any change of a contact's slip above
  about 2e-5 m/s cross a kink) and the settled step (about 0.47 ms against MuJoCo's 0.41), of
  which the contacts' Jacobian rows, their Delassus diagonals and J's assembly are a third.
  Measured next (Newton iterations per step, one thread): the costly part of the landing is not
  the impacts but steps 20 to 90, when the pile is one island of about 425 contacts that still
  slides and tips, at 20 to 36 iterations per step (2712 iterations in the first 100 steps, 200
  per 100 settled steps). Without the drift correction those 100 steps take 1696 iterations (a
  traced step: 23 iterations against 30, the residual falling by about a fifth per damped
  iteration either way), so the problem itself, not the correction, needs most of them. Tried
  and not kept: the correction applied from the first iteration at the start velocities (2382
  landing iterations, but settled steps 200 to 356: contacts at the edge of their cones then
  start off their fixed point); a slip below which no correction is made (1e-5 to 1e-3 m/s:
  more iterations in both phases, the threshold being a discontinuity); a start extrapolated
  from the last two steps' velocities (2699 landing iterations, no gain); the free body's 6 x 6
  triangular solves in the Delassus diagonals at compile-time size (no change in the timed run).
  Found next (a trace of step 39: 35 iterations): after the first two, most iterations change
  5 to 20 contacts between sticking and sliding at step lengths of 0.02 to 0.6, and the line
  search takes about 6.5 trials over some 300 live contacts per iteration (a looser line-search
  tolerance, up to 0.1, left the trials at 5 and the iterations unchanged). Fixed: the drift
  correction's first step is made at the solve's start, with the impulses there, so that a
  contact that slid in the last step starts near its corrected target (the landing's 100 steps:
  2347 iterations instead of 2712, counted with the Delassus change below in place too; over 4
  pile seeds, the start correction alone took 9905 instead of 11384). Fewer correction
  iterations with it (6 instead of 20) cut the landing by a further sixth, but from a cold start their fixed point is then reached only to
  about 1e-4 of the normal impulse (a solver test asks for 1e-7), so the default stays 20. Then
  (callgrind, settled steps) each contact side's Delassus diagonal solved its body's triangular
  factor, and sparse islands zeroed a dense n x n momentum matrix that they did not use: about 14 %
  of a settled step's instructions. Fixed: the diagonal from the link's 6 x 6 compliance
  J A^-1 J^T, computed once per link and solve, and no dense matrix on the sparse path (about 3 %
  now). What remains in a settled step: J's assembly from triplets (a tenth), writing every
  contact's J^T G J into the block factor (a tenth) and its factorization.
  Found next (perf on an unstripped build, 12000 settled steps and 10 landings): in a settled
  step, J's assembly (compressed rows, then refilled into the Newton system's own per-block copy
  through an index map) was about 14 %, scattering each contact's J_b^T G_b J_b entry by entry
  through a table of slots 8 %, the sparse products with J 6 %; in the landing, analysing the
  block pattern anew (AMD ordering, slots) whenever a contact came or went was 13 % and the
  block factorization 17 %. Fixed: large islands keep J by bodies (BodyJacobian: each block's
  rows on each body it moves as one dense piece, written by the island solver directly), J x
  and J^T y run on the pieces, each block's J_a^T dG J_b goes into its bodies' dense blocks of
  H whole (6 x 6 at fixed size for free bodies), the block Cholesky analysis is kept while the
  island has the same bodies and couples no new pair (and three quarters of those analysed), and
  the factor's 6 x 6 Schur updates use Eigen's fixed-size product (BM_BlockCholeskyFactor/50
  88 to 74 us). Summed over 4 pile seeds (1000 steps each, one thread): 2.015 to 1.633 s (the
  landing 0.789 to 0.614 s, the settled steps 1.226 to 1.019 s), the landing's Newton
  iterations unchanged (9928 against 9974); the settled steps' count moves by some 10 % either
  way with the float round-off of the new products. What remains in a settled step (perf): the
  box-box narrow phase (about a sixth), the contacts' rows and Delassus diagonals (a sixth),
  J_b^T G_b J_b into H and its factorization (a fifth). The pile is chaotic: any change in the
  float round-off (scene 2's changes: reciprocal diagonals, a free body's mass matrix in closed
  form, the small products' order) settles it differently, and the settled steps' Newton
  iterations of one pile move by up to a factor 2.5. The suite's pile took 1.27-1.31 of
  MuJoCo's time before those changes and 1.36-1.37 after, at more settled iterations; over 16
  piles the settled iterations are the same (55431 before, 55630 after) and over 12 piles the
  time is 1.5-2.5 % lower (4.55-4.59 to 4.47-4.49 s, alternate runs).
- Scenes 2, 3 and 6 (step). Found: the mass matrix was built with 6 x 6 products for every
  (link, ancestor) pair, a third of a free Panda step, and a pressing contact took 6 Newton
  iterations per step. Fixed: composite inertias about link origins (additive, moved up the tree
  without 6 x 6 products) and the mass matrix column by column; joint motion per column in
  inverse dynamics; the warm start above (the Panda on the table converges in 0 or 1 iteration).
  Then the allocations per step (malloc and free were about a tenth of a small step): the step's
  lists, the island solves' matrices and the contact lists now live in a workspace kept in the
  scene across steps (86 to 1.2 allocations per seed-box scene-step). Found next (perf, free
  Panda): the Panda's 14 joint-limit rows entered every solve, with a Newton solve and the
  diagonal of A^-1 for their compliance, although no joint was near its limit. Fixed: limit rows
  that the free motion keeps far from acting are left out and checked on the result (a solve
  that would violate one is repeated with them; SolverParams.defer_inactive_joint_limits): 5.4 to
  4.2 us per free step. Joint velocities in the kinematics by a fixed-size column loop instead of
  a dynamic product (7-link chain 561 to 380 ns). What remains in a free Panda step: the mass
  matrix (about 15 %), kinematics (about 10 %), the timers of the solver statistics (about 4 %)
  and the broad phase (about 4 %). The dynamics kernels run at about 90 ns per link, where
  spatial-algebra libraries reach 20 to 30: the 6-vectors are written as two 3-vector halves and
  then read as packets that straddle them, which stalls store forwarding; building with
  -march=native did not change that (mass matrix 647 to 562 ns, kinematics and inverse dynamics
  unchanged), so the next step is spatial vectors kept as 3-vector pairs. Found next (perf and
  callgrind, the Panda on the table after it settles, 6.4 us per step): the solver statistics'
  timers read steady_clock 12 times per step (4 %); the bot pipeline and BASIC_JSC_PD allocated
  six vectors per step; a contact's compliance estimate solved with A for the whole 3 x 3
  Delassus block, of which only the diagonal is read. Fixed: the timers read the time-stamp
  counter (seconds from the step's own steady_clock interval); the vectors are kept; the
  diagonal comes from L^-1 alone: 6.4 to 5.9 us per settled step. Found next (perf, the Panda
  resting on its joint limits in scene 6 with two active limit rows and 1 or 2 Newton iterations
  a step; the Panda on the table; the arm on the ground in scene 2): Eigen's blocked kernels for
  matrices of 2 to 9 rows (the packing of a matrix product for H's J^T G J, 6 % of a step; the
  triangular solves against the identity for A^-1's diagonal and against a contact side's three
  rows for its Delassus diagonal, 4 to 5 %); a contact side's rows built by two dynamic-size
  matrix products; and the dynamics visiting the four links welded to the Panda's base and hand.
  Fixed: below 24 variables each active block's J_b^T G_b J_b is added into H's lower triangle
  directly; forward substitution for articulations of up to 32 DOFs; a side's rows column by
  column as 3-vectors; welded links' inertias added to their parents' at model build (the
  dynamics visit 7 of the Panda's 11 links). Scene 6's step 5.65 to 4.8 us, scene 2's physics
  step 7.1 to 6.65 us. The build now targets x86-64-v3 (AVX2, FMA) when the build machine runs it
  (CMake SUPERDEX_ARCH; MuJoCo's own wheels use AVX): with these changes, scene 6's step 4.8 to
  4.5 us, the Panda on the table 6.45 to 6.2 us. Compiler-contracted FMA stays off
  (-ffp-contract=off): with it a built-in component no longer matched the same law in Python bit
  for bit. Found next (callgrind, scene 2's physics step: 68k instructions, two islands and
  five contacts): Eigen's blocked matrix-vector kernel ran every product of the dense Newton
  loop (A v, J v, J^T y) and each column of the small Cholesky factorizations, and cost more to
  set up than to compute at 2 to 12 variables (about 8 %); J was assembled as compressed rows
  block by block and then copied into the dense matrix the dense algebra works on (about 8 %).
  Fixed: below 24 variables the products are coefficient-based; dense islands write J as a dense
  matrix in place; Cholesky factorizations up to 16 rows run in plain loops (SmallLLT, Eigen's
  LLT with its own factorization). 68k to 59k instructions, 5.9 to 4.4 us per step. What remains
  is spread thin: the Newton loop a quarter (its own vector arithmetic on dynamic-size vectors,
  one factorization per island), the contact rows and compliances a sixth, the articulations'
  mass matrices, bias forces and factorizations a sixth, collision an eighth. The control
  variant cannot reach half of PyBullet's time in any simulator: the shared Python law alone
  takes about 0.6 of PyBullet's control step (the note under scene 2's table). Found next
  (callgrind, 57.6k instructions per physics step; and the clock reads): each of a capsule's 17
  balls queried the box's distance where none was near, and the ball list was built against the
  ground plane too (collision an eighth of the step); the step read steady_clock twice (21 ns a
  read here) and the time-stamp counter 17 times (9 ns) to time its parts, some 0.2 us in all.
  Fixed: against an exact distance field (every shape but a mesh) the balls that a queried
  neighbour's distance proves out of contact are skipped, and planes need no ball list (the
  contacts are the same ones); the counter's rate is calibrated once per process and the
  articulations are timed by group; the small solves multiply by the factor's reciprocal
  diagonal: 57.6k to 53.2k instructions, 4.2 to 4.0 us per step, 0.55 to 0.53 of PyBullet's
  step. Then: the small Cholesky factorizations and solves (the momentum matrices, the Newton
  matrices and the link compliances' L^-1 J^T) on raw storage, unrolled at 1, 2, 3 and 6 rows
  (about 1k instructions a 6 x 6 factorization before); a free body's mass matrix in closed
  form; the dense islands' products with A, J and J^T in plain loops (few instructions fewer,
  but 3.80 to 3.70 us: shorter dependency chains than Eigen's dynamic-size lazy products).
  49.7k instructions, 3.7 us per step, 0.49 of PyBullet's in this run and the two before it. What
  remains is spread as before: the Newton loop's dynamic-size vector arithmetic, the contact
  rows, the articulations' terms and collision, none above a tenth. Tried and not kept:
  carrying the line search's last trial (its constraint velocities and impulses) into the next
  Newton iteration (0.7k instructions fewer, no measurable time, and a sum that drifts from J v
  over many iterations). The control variant: its targets now compare the simulator's part of
  the step, the law's calls being timed apart inside the loop (second table of scene 2); before,
  the whole step was compared, and the Python law alone, the same in every simulator, was 0.62
  of PyBullet's whole control step, so no simulator could reach half of it. Measured by calls in
  the loop (median of 7 runs of 6 s): SuperDex's part 10.4 us (reading the state, Jacobian and
  contact force 2.8 + 1.1, applying 0.4, the step 6.2), PyBullet's 18.8, MuJoCo's 15.2; the step
  costs more than the physics variant's 3.7 us because of the 331 steps in which the ball presses
  and slides on the box (13 us each, 3.9 the others). Found: reading TransformRT.translation took
  0.85 us, because the binding returned the array with rv_policy::move, which made nanobind copy
  it a second time through numpy; and the adapter converted a fresh Jacobian array where
  MuJoCo's adapter passes mj_jacBody its own array. Fixed: the binding hands over its array
  (0.31 us), the adapter passes get_articulated_jacobian an out array: SuperDex's part 9.0-9.5 us,
  0.47-0.50 of PyBullet's. What remains: the pressing steps take 8.5 Newton iterations, nearly
  all in the drift correction's fixed point (with k corrections allowed they take about k, and
  converge at once after): its corrections approach the fixed point by a factor of about 0.3 per
  iteration while the contact alternates between touching and not from step to step. Tried and
  not kept: Aitken's extrapolation of the corrections (one ratio for all contacts): 8.5 to 6.1
  iterations per pressing step here (the step 6.0 to 5.6 us), but no fewer on random problems
  with one or four sliding contacts (311 against 298 and 282 against 289 iterations in all).
  Fixed: the corrections are solved by Newton's method together with the step. After each
  Newton direction, the sliding contacts' corrections are linearized with the step (one solve
  with the factored Newton matrix per sliding contact that touches, up to 8 sliding contacts)
  and the small system for their changes gives the targets the step is then taken towards; six
  predictions in a row that do not halve the next plain correction hand over to the plain fixed
  point. (A first version solved for speculative contacts apart too, and made scene 7's settled
  piles 10 % slower for the same iterations; they get no solve now.) Pressing steps take at
  most 4 Newton iterations (up to 11 before), the step in the control loop 6.1 to 5.0 us,
  SuperDex's part 8.1 us, 0.44 of PyBullet's. On random problems (12 variables, 1 to 8 sliding
  contacts, friction 0.3 to 1, 40 of each) the iterations fall by a half to two thirds (one
  contact: 177-274 to 87-93 in all), and within the default 20 corrections problems of up to 4
  contacts now all reach Coulomb's law to 1e-7, where 40 of their contacts did not.
- Scene 6 (calls). Found: every call imported numpy and converted its arguments with
  numpy.ascontiguousarray; an out array was checked through Python attribute lookups. Fixed: lists
  and contiguous arrays are read directly and writable out arrays of the right dtype are used as
  they are; the general path remains for everything else. get_articulated_jacobian allocated a
  matrix and a new array per call (0.97 against MuJoCo's 0.55 us); it now fills an `out` array
  when given one, as mj_jacBody fills the caller's, and this scene passes one.
- Scenes 7 and 8 (threads). Found, earlier: CHOLMOD's OpenMP team, spinning after each
  factorization, took the second core from a concurrent step of another scene (two Python
  threads: 1.05x). Rigid islands are now factored without OpenMP and the soft bodies' CHOLMOD
  threads sleep when idle. Found later (per-phase timers in the step, and which thread solved
  which island): with worker threads the range partitioner gave one thread most of the big
  islands while the other waited, and collision detection and the commit ran serially. Fixed:
  threads take the next item when free (greedy), islands go largest first, the narrow phase runs
  in chunks of 16 pairs on the threads (joined in pair order: the contacts, and so the results,
  are bitwise the same on 1 and 2 threads), and the soft-body steps, dynamics terms and narrow
  phase share one parallel region. Found next (malloc counts per step, perf): a seed-box
  scene-step made 86 heap allocations, and two threads of one process slowed each other down in
  the allocator. Fixed: a per-scene step workspace kept across steps (1.2 allocations per
  scene-step; the Panda with its table still makes about 24 per scene-step, in box-box clipping
  and dense solver matrices whose size changes with the contact count, some 1 % of its time).
  Found next (alternating 1- and 2-thread runs in one process): in a batch the scenes went to
  whichever thread was free, so a scene moved between the cores from step to step with its data;
  the batch step alone gave about 1.45x on 2 threads. Fixed: each thread keeps a contiguous share
  of the scenes step after step and helps with the other's from its end (home threads): about
  1.85x for the batch step alone. What remains in scene 8: the task's reward and observation in
  numpy, about 31 us per vector step for the seed task (64 rows), run on one thread while the
  other waits (Amdahl: with some 270 us of physics on 2 threads this alone caps the speed-up near
  1.8x); and the machine itself: two copies of a compute loop scale by 2.0x side by side, but the
  engine's memory-bound steps give two processes side by side 1.6-1.9x, and the 2-thread times
  vary by up to 30 % between neighbouring runs (the 1-thread ones by 10-20 %), so each case is
  measured in rounds and the ratios compare neighbouring runs. On this machine the ratios moved
  between runs of the same build by more than the targets' margin: scene 7 with worker threads
  1.62x and 1.82x; the seed task in scene 8 1.50x to 1.68x in four runs of one build, and 1.50x
  and 2.24x in two consecutive runs of another. Found next (perf, scene 7 on one thread): a
  third of the step was the dense path's matrix products (Eigen's packed GEMM for J^T G J and
  the dense Cholesky) on islands of 3 to 16 boxes, all under the 96 DOFs from which islands took
  the sparse path. Since the block Cholesky's 6 x 6 kernels and J's structural pattern, the
  sparse path costs less per iteration from three free bodies on: SolverParams.
  dense_island_max_dofs is now 12, and 250 steps of scene 7 on one thread went from 0.91 to
  0.69 s (alternate runs). With the parallel part cheaper, the serial part of a step (broad
  phase, islands, commit, contact records) weighs more in the 2-thread ratio. Found next (a
  timer around each part of scene 7's step, 260 steps on one thread, 0.68 s in all): broad
  phase 6.3 ms, islands 3.8 ms, the commit 5.5 ms (most of it the link poses and velocities of
  the 144 boxes' next states), the contact results 8.0 ms (a sort of the step's 1008 contact
  records), all on one thread whatever the number of threads. Fixed: the broad phase orders the
  pairs by the links of their contacts (the plane pairs, appended after the sweep's, had put the
  list out of order), so the results are written in the contact list's order without a sort
  (8.0 to 2.1 ms); each island's solve computes its bodies' next kinematics on the worker threads
  (the commit 5.5 to 2.5 ms); world bounds and sweep bounds in closed form instead of loops over
  the eight corners. 250 steps, alternate runs: one thread 0.651-0.662 s, two threads
  0.344-0.346 s (1.89-1.91x). What remains serial: the broad phase and the islands, some 10 ms of
  the 0.35 s on two threads. And the machine: in some spells a 2-thread run takes 0.42 s instead
  of 0.35 s, with no other process running, so the ratio of one run can still land under 1.8.
  Later, with the large islands solved by bodies (scene 4), 250 steps of scene 7 on one thread
  took 0.267 s instead of 0.359 s, on two 0.147 s instead of 0.192 s: the ratio went from 1.87x
  to 1.82x, the serial part (about 11 ms: broad phase, islands, the commit, contact results and
  the step's Python call) being the same. Found then: OpenBLAS threads spin for a while after
  they start and after each call, and take a core from a 2-thread run (in a process of its own,
  a run right after the import took 0.187 s instead of 0.145 s, its CPU time 0.37 s instead of
  0.29 s). The harness kept them to one thread in each measurement's process but not in the
  suite's own, which imports numpy too: its threads slowed the children's 2-thread runs, scene 7
  with worker threads measuring 1.44x in three runs in a row and 1.83x to 1.87x once the suite's
  process had them on one thread as well (it now does). The runs before that were affected
  when the spinning overlapped a measurement, which explains part of the spread reported above.
  Also fixed: the articulations' dynamics terms (about 1 us each) go to the threads by groups of
  8 instead of one work item each (the region with the narrow phase scaled 1.74x, now 1.88x).
  Scene 8's seed task, measured by parts (64 scenes): the batch step 276-279 us on one thread
  and 143-160 us on two (1.74x to 1.94x between runs of one build), the Python part 26 us (the
  task's target, reward and observation 15.7 us of it, nearly all fixed cost per call: 19 us
  with 8 scenes); with the physics now cheaper, that serial part weighs more: 1.81x and 1.82x
  in three runs of the scene with the suite's threads fixed, just over the target. With scene
  2's speed-ups (the same arm and box), measured by parts: the batch step 252 us on one thread
  and 129 us on two (1.96x), the Python part 25 us, so 1.82x by parts and 1.79x in the suite's
  runs. The target and reward written with fewer numpy calls (one cosine for the circle's three
  coordinates, the contact test as any()) were no cheaper (the target 5.5 to 6.3 us): at 64 rows
  each numpy call costs its fixed half microsecond or more whatever it computes. Fixed: the
  built-in environments' tasks (the seed's circle target, observation and reward; the Panda's
  goal columns and reward) are computed in C++ by each scene's worker thread after its step
  (SceneBatchSpec.task, a BatchTask), so that the Python part of a vector step is 8 us instead of
  25 (the action's clipping and scaling, the call, the copies of the observations and rewards):
  measured by parts, 253.5 us per vector step on one thread and 132.3 on two (1.92x), 1.89x and
  1.90x in two runs of scene 8.
- Scene 9 (robots people bring). Found (perf and the step's own timers, float): the Shadow hand's
  step spent half its solve on contacts that never act: 21 contacts per step against MuJoCo's 4,
  most of them speculative (the margin's 1 cm around the block and the fingers), each with its
  rows, its link's compliance J A^-1 J^T (a dense triangular solve of the hand's 24 DOFs) and
  its part of the Newton matrix. Fixed: contacts that both the current velocities and the free
  motion keep more than half their gap apart (friction's reach included) leave the first solve
  and join a second only if its result would close them (the same result; the Newton's cradle of
  deferred_contacts_test must still move its third ball in the impact's step); an articulation's
  momentum matrix is factored along its tree (L^T D L, no fill-in), so a link's compliance
  touches only its ancestors' DOFs. The hand's solve went from 0.078 to 0.033 ms per step and
  its dynamics terms from 0.032 to 0.020 ms. The G1 falling onto its floor (hulls of 130 to 2200
  corners): half its step is the narrow phase, 19 hull pairs and 9 hull-plane pairs per step.
  Found: a quarter of it thinned contact points by sorting them (a hull lying on the ground has
  hundreds of corners within the margin), and GJK ran 7 to 13 iterations on finely meshed curved
  hulls to its relative tolerance. Fixed: the thinning keeps the deepest point per cell in one
  pass, the reduction allocates nothing, and GJK also stops within 1e-6 of the shapes' size of
  its lower bound. What remains on the G1: the support searches on such hulls (hill climbing
  over some 6 corners per search, 300 searches per step), the plane walks over the corners within
  the margin, and Newton's iterations: 8.4 per step in double (all converged) against MuJoCo's
  2.4; without the friction drift correction 5.4, with a softer near-rigid regularisation (beta
  2 instead of 1) 6.9. MuJoCo's friction is far softer (its regularisation equal on normal and
  friction rows, where this engine's friction rows are 25 times stiffer than its normal ones), a
  better-conditioned problem that creeps more.
  Found next (traces of the heap the G1 falls into, float): in float the residual of its stiff
  contacts has a round-off floor near the tolerance, and solves ground at it until the
  50-iteration limit (9 of the 500 steps of the first second at 50 or more, the largest 92 over
  two solves); deferred contacts that the first solve's result left inactive still joined a
  second solve, which repeated the first from the same start. Fixed: in float, three iterations
  within 100 times the tolerance that do not halve the residual end the solve (Stopped; no step
  of that second above 29 iterations, 7.2 per step on average instead of 9.7); a deferred contact
  joins only when the result would make it act (the exact test: its target is at most minus its
  allowed closing speed), and a solve again starts from the last one's result
  (SolverStats.num_island_solves counts them). The step's time did not move with them: the heap
  the fall ends in changed (60 contacts per step over 2 s instead of 56, 8.8 Newton iterations
  instead of 10.5) and its narrow phase took longer (0.38 against 0.30 ms per step); the fall is
  chaotic, and the G1's time is the heap's. What remains there: the friction drift
  corrections of a heap with more than 8 sliding contacts fall back to the plain fixed point
  (linear convergence, up to its 20 iterations), and each Newton iteration of the G1's 35 DOFs
  costs some 25 microseconds.
  Found next: the face clipping of every hull pair scanned all faces of both hulls for the one
  most aligned with the normal, three scans per pair (a G1 hull has up to 4000 faces); and the
  Newton matrix's dense diagonal blocks (the hand's 24 DOFs, the G1's 35) were factored by
  scalar loops. Fixed: hulls of 64 faces or more group their faces by the direction of their
  normals (a cube map of 216 cells, each with the cone that holds its normals), and the search
  scans the cells whose cone could hold a better face than the best found (the same face:
  checked against a scan of every face); blocks of 20 DOFs or more are factored and solved by
  Eigen's kernels. Measured alone: a pair of 3000-corner hulls within a few millimetres of
  touching, 30-39 to 19-20 microseconds per pair (the same contacts); the factorization of a
  24 + 6 DOF system 2.9 to 2.0 microseconds, of 35 DOFs 4.1-6.5 to 3.6-5.5.
  Found next (perf, the G1 lying on its floor after the fall): a hull against a plane walked every
  corner within the margin (212 on average per pair, some 2500 per step: a thigh or the torso
  lying on the floor has a wide 1 cm band) and then reduced them to four. Fixed: the deepest
  corner and, along 8 directions in the plane, the support corner of the plane's normal tilted
  towards each (the tilt scaled, as on a quadratic surface, until that corner lies within the
  margin), a few short climbs from the deepest corner; the contacts still span the patch (checked
  against a scan of every corner). The G1's collision time at rest went from 0.22 to 0.13-0.16 ms
  per step; over the benchmark's first second, mostly the fall, its step from 0.217 to 0.203 ms.
  What remains on the G1: GJK between hulls (a fifth of its step; each search starts cold, as a
  warm start kept between steps would have to join the captured state to keep restores bitwise),
  and Newton's iterations (8 to 10 per step while falling, MuJoCo 2.5).
"""


def write(path, sections, micro, opts, elapsed):
    v = versions()
    lines = ["# Benchmark results", "",
             f"Produced by `uv run python benchmarks/run.py{' --quick' if opts.quick else ''}"
             f"{' --only ' + opts.only if opts.only else ''} --repeats {opts.repeats}` on "
             f"{datetime.now(timezone.utc).strftime('%Y-%m-%d %H:%M UTC')} in {elapsed / 60:.1f} min"
             f"{' (QUICK: tiny sizes, numbers mean nothing)' if opts.quick else ''}.", "",
             f"- Machine: {machine()}",
             f"- Versions: superdex {v.get('superdex')} ({v.get('precision')} build, commit {v.get('commit', '?')}), "
             f"mujoco {v.get('mujoco')}, pybullet {v.get('pybullet')}, numpy {v.get('numpy')}",
             f"- Method: every (scene, simulator) measurement runs in a fresh process; wall time of the stepping loop "
             f"only (model building excluded) by perf_counter; median of {opts.repeats} repetitions; peak RSS of that process. "
             f"Single-threaded unless the scene says otherwise. {RATIO_NOTE}.", ""]
    all_targets = []
    for number, title, doc, md, targets, notes in sections:
        all_targets += targets
    lines += ["## Targets", "", table(["target", "result", "measured"], [[t, verdict(ok), txt] for t, ok, txt in all_targets]), ""]
    met = sum(1 for _, ok, _ in all_targets if ok)
    lines += [f"{met} of {len(all_targets)} targets met.", ""]
    for number, title, doc, md, targets, notes in sections:
        lines += [f"## {number}. {title}", "", doc.strip(), "", md, ""]
        for t, ok, txt in targets:
            lines.append(f"- {t}: {verdict(ok)} ({txt})")
        for n in notes:
            lines.append(f"- Note: {n}")
        lines.append("")
    lines += [FINDINGS, ""]
    lines += ["## Micro-benchmarks (Google Benchmark, double build)", ""]
    lines += [micro, ""]
    with open(path, "w") as fh:
        fh.write("\n".join(lines))
    return all_targets
