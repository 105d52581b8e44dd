"""Timing harness: every measurement runs in a fresh child process (benchmarks/worker.py), so that
its peak resident memory is its own (os.wait4's rusage of that child), and an imported simulator
cannot warm or slow another's run. Repetitions are separate children; results are medians."""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

BENCH = Path(__file__).resolve().parent
REPO = BENCH.parent


class ChildFailed(RuntimeError):
    pass


def run_child(module: str, case: dict, timeout: float = 900.0) -> dict:
    """Runs scenes/<module>.run_case(case) in a new interpreter. Returns its result dict plus
    'peak_rss_mb' (the child's peak resident set size)."""
    cmd = [sys.executable, str(BENCH / "worker.py"), module, json.dumps(case)]
    env = dict(os.environ)
    # numpy's OpenBLAS (and any OpenMP pool) must not spin threads against the simulators' own
    env.setdefault("OMP_NUM_THREADS", "1")
    env.setdefault("OPENBLAS_NUM_THREADS", "1")
    # a scratch working directory: MuJoCo writes MUJOCO_LOG.TXT where it runs when it warns
    with tempfile.TemporaryFile() as err, tempfile.TemporaryDirectory() as scratch:
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=err, cwd=scratch, env=env)
        start = time.monotonic()
        out = proc.stdout.read()  # until the child closes it (exits)
        _, status, usage = os.wait4(proc.pid, 0)
        proc.returncode = os.waitstatus_to_exitcode(status)
        if time.monotonic() - start > timeout:
            raise ChildFailed(f"{module} {case}: took longer than {timeout} s")
        err.seek(0)
        stderr = err.read().decode(errors="replace")
    lines = [line for line in out.decode(errors="replace").splitlines() if line.startswith("RESULT ")]
    if proc.returncode != 0 or not lines:
        raise ChildFailed(f"{module} {case} failed (exit {proc.returncode}):\n{stderr[-3000:]}")
    result = json.loads(lines[-1][len("RESULT "):])
    result["peak_rss_mb"] = usage.ru_maxrss / 1024.0  # KiB on Linux
    return result


def measure_cases(module: str, cases: list, repeats: int, log=print) -> list:
    """Every case `repeats` times, in rounds (each round runs every case once), so that a drift of
    the machine's speed during the run touches every case alike and their ratios stay fair. Each
    case's result is the median over its runs of every numeric field; the first run's other
    fields (checks, notes) are kept as they are; the individual walls are kept in 'walls'."""
    runs = [[] for _ in cases]
    for _ in range(repeats):
        for k, case in enumerate(cases):
            runs[k].append(run_child(module, case))
    results = []
    for case, case_runs in zip(cases, runs):
        merged = dict(case_runs[0])
        for key, value in case_runs[0].items():
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                merged[key] = statistics.median(run[key] for run in case_runs)
        merged["walls"] = [run.get("wall") for run in case_runs]
        merged["repeats"] = repeats
        derive(merged)
        log(f"    {case.get('label', case)}: {summary(merged)}")
        results.append(merged)
    return results


def derive(m: dict) -> None:
    """Steps per second, ms per step and real-time factor from wall, steps and sim_time."""
    if m.get("wall") and m.get("steps"):
        m["steps_per_s"] = m["steps"] / m["wall"]
        m["ms_per_step"] = 1e3 * m["wall"] / m["steps"]
    if m.get("wall") and m.get("sim_time"):
        m["rtf"] = m["sim_time"] / m["wall"]


def summary(m: dict) -> str:
    parts = []
    if "ms_per_step" in m:
        parts.append(f"{m['ms_per_step']:.4f} ms/step")
    if "rtf" in m:
        parts.append(f"{m['rtf']:.1f}x real time")
    parts.append(f"{m['peak_rss_mb']:.0f} MB")
    checks = m.get("checks")
    if checks:
        parts.append(", ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}" for k, v in checks.items()))
    return "; ".join(parts)


class Timer:
    """Wall time of a stepping loop: `with Timer() as t: ...; t.wall`."""

    def __enter__(self):
        self.start = time.perf_counter()
        return self

    def __exit__(self, *exc):
        self.wall = time.perf_counter() - self.start
        return False


def median_of_episodes(case: dict, episode) -> dict:
    """Runs `episode(case)` case["episodes"] times (default 1) in this process; each call builds
    its simulation, times its stepping loop and returns (wall, result). Returns the last
    episode's result with the median wall as "wall" and every wall as "episode_walls" (and, for
    any other field named *_wall, a part of the loop's time, the median over the episodes). For
    scenes whose timed loop lasts a few milliseconds, where one fresh process per measurement
    leaves the result to the machine's noise (a timer interrupt, another process) and to the first
    steps' cold caches."""
    walls, results = [], []
    for _ in range(max(1, case.get("episodes", 1))):
        wall, result = episode(case)
        walls.append(wall)
        results.append(result)
    for key in [k for k in result if k.endswith("_wall")]:
        result[key] = statistics.median(r[key] for r in results)
    result.update(wall=statistics.median(walls), episode_walls=walls)
    return result


def emit(result: dict) -> None:
    """What a child prints: one JSON line the parent reads."""
    sys.stdout.write("RESULT " + json.dumps(result) + "\n")
    sys.stdout.flush()
