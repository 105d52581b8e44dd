"""The benchmark suite: SuperDex against MuJoCo and PyBullet on the same scenes, in one run.

    uv run python benchmarks/run.py [--quick] [--only 2,4] [--repeats N] [--out FILE] [--no-cpp]

Scenes (benchmarks/scenes/s<N>_*.py; each builds its models from one description, models.py):
  1 the seed scene (2-DOF arm, ground, soft duck; seed loop and C++ pipeline)
  2 the 2-DOF arm on a rigid box          (SuperDex, MuJoCo, PyBullet)
  3 the Panda under joint PD, free / table (SuperDex, MuJoCo, PyBullet)
  4 50 boxes falling into a pile           (SuperDex, MuJoCo, PyBullet)
  5 soft block, 1k / 5k / 20k tetrahedra   (SuperDex, MuJoCo flex)
  6 Python overhead per call               (SuperDex, MuJoCo, PyBullet)
  7 threads: N independent scenes, 1 and 2 threads (SuperDex)
  8 the lab's batched vector env, 64 scenes, 1 and 2 worker threads (SuperDex)
  9 robots from MuJoCo model files: Shadow hand with block, humanoid (SuperDex, MuJoCo)
 10 the feature examples (constraints, pose control, IK) as users run them (SuperDex)
then the Google Benchmark micro-benchmarks of the hot kernels (benchmarks/cpp, target
superdex_microbench, built in the project's build directory).

Every measurement runs in a fresh process (harness.py); results are medians of --repeats runs,
taken in rounds (every case of a scene once per round).
Writes benchmarks/RESULTS.md (or --out) and prints every measurement with its equivalence checks.
--quick: tiny sizes, one repetition, a few steps: a smoke run whose numbers mean nothing.
"""

from __future__ import annotations

import argparse
import glob
import importlib
import json
import os
import subprocess
import sys
import time
from pathlib import Path

# This process imports numpy too (the scenes' case lists, the report): its OpenBLAS threads,
# which spin for a while after they start and after each call, took a core from the measurements
# of two threads (scene 7 with worker threads measured 1.44x instead of 1.83x), so they are one
# thread here as in every measurement's own process (harness.py). Set before numpy loads.
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks import report  # noqa: E402
from benchmarks.harness import BENCH, REPO, measure_cases  # noqa: E402

SCENES = {1: "s1_seed", 2: "s2_arm_box", 3: "s3_panda", 4: "s4_pile", 5: "s5_soft_block", 6: "s6_python_overhead",
          7: "s7_threads", 8: "s8_batched", 9: "s9_mjcf_robots", 10: "s10_feature_examples"}


def build_dir():
    """The directory scikit-build-core configured for this interpreter (as tools/dev.sh finds it)."""
    dirs = sorted(glob.glob(str(REPO / "build" / "cp*")), key=lambda p: Path(p).stat().st_mtime)
    return dirs[-1] if dirs else None


def micro_benchmarks(opts):
    """Builds and runs superdex_microbench; a markdown table of its results (or why there is none)."""
    if opts.no_cpp:
        return "Skipped (--no-cpp)."
    bdir = build_dir()
    if not bdir:
        return "Skipped: no build directory under build/ (run `uv sync` first)."
    print(f"== micro-benchmarks: building superdex_microbench in {bdir}", flush=True)
    build = subprocess.run(["cmake", "--build", bdir, "--parallel", "2", "--target", "superdex_microbench"],
                           capture_output=True, text=True)
    if build.returncode != 0:
        tail = (build.stdout + build.stderr)[-1500:]
        return f"Not built (is libbenchmark-dev installed? `find_package(benchmark)` guards the target):\n\n```\n{tail}\n```"
    exe = Path(bdir) / "benchmarks" / "cpp" / "superdex_microbench"
    min_time = "0.01" if opts.quick else "0.2"
    run = subprocess.run([str(exe), "--benchmark_format=json", f"--benchmark_min_time={min_time}"], capture_output=True, text=True)
    if run.returncode != 0:
        return f"superdex_microbench failed:\n\n```\n{run.stderr[-1500:]}\n```"
    data = json.loads(run.stdout)
    rows = []
    for b in data["benchmarks"]:
        unit = b.get("time_unit", "ns")
        extra = ", ".join(f"{k} {report.f(float(v))}" for k, v in b.items()
                          if k not in ("name", "run_name", "run_type", "repetitions", "repetition_index", "threads", "iterations",
                                       "real_time", "cpu_time", "time_unit", "family_index", "per_family_instance_index",
                                       "aggregate_name", "aggregate_unit", "label") and isinstance(v, (int, float)))
        rows.append([f"`{b['name']}`", f"{report.f(b['real_time'])} {unit}", f"{report.f(b['cpu_time'])} {unit}", b["iterations"],
                     b.get("label", "") or extra])
    ctx = data.get("context", {})
    head = (f"{ctx.get('num_cpus', '?')} CPUs at {ctx.get('mhz_per_cpu', '?')} MHz; the engine in Release, the Google "
            f"Benchmark library itself reports a {ctx.get('library_build_type', '?')} build (Debian's package); "
            f"min time {min_time} s per benchmark.\n\n")
    return head + report.table(["benchmark", "wall", "CPU", "iterations", "counters"], rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="tiny sizes, 1 repetition, a few steps (smoke run)")
    parser.add_argument("--only", default="", help="comma-separated scene numbers, e.g. 2,4")
    parser.add_argument("--repeats", type=int, default=None, help="repetitions per measurement (default 3, --quick 1)")
    parser.add_argument("--out", default=str(BENCH / "RESULTS.md"), help="results file (default benchmarks/RESULTS.md)")
    parser.add_argument("--no-cpp", action="store_true", help="skip building and running the C++ micro-benchmarks")
    opts = parser.parse_args()
    if opts.repeats is None:
        opts.repeats = 1 if opts.quick else 3
    numbers = [int(n) for n in opts.only.split(",") if n.strip()] or list(SCENES)
    start = time.monotonic()
    sections = []
    for number in numbers:
        module = importlib.import_module(f"benchmarks.scenes.{SCENES[number]}")
        print(f"== scene {number}: {module.TITLE}", flush=True)
        cases = module.cases(opts)
        results = list(zip(cases, measure_cases(SCENES[number], cases, opts.repeats, log=lambda s: print(s, flush=True))))
        md, targets, notes = report.REPORTERS[number](results, opts)
        for name, ok, text in targets:
            print(f"  target {name}: {'met' if ok else 'NOT MET'} ({text})", flush=True)
        sections.append((number, module.TITLE, module.__doc__ or "", md, targets, notes))
    micro = micro_benchmarks(opts)
    targets = report.write(opts.out, sections, micro, opts, time.monotonic() - start)
    met = sum(1 for _, ok, _ in targets if ok)
    print(f"== wrote {opts.out}: {met} of {len(targets)} targets met, {(time.monotonic() - start) / 60:.1f} min", flush=True)


if __name__ == "__main__":
    main()
