"""The soft-body solve runs on the thread that steps the scene.

The sparse factorization behind soft bodies (CHOLMOD) was built with OpenMP regions of a fixed
team size; left alone, the first factorization starts a team of threads that every later one
wakes and joins, which cost more than the factorization itself. The engine keeps every OpenMP
region on its opening thread: stepping a soft prop starts no OpenMP team."""

import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[3]
DUCK = REPO / "assets" / "prefabs" / "duck_lamp" / "duck_lamp_recumbent_full.mochi_prefab"

CHILD = r"""
import ctypes, os, sys
import superdex.physics as sdp

def threads():
    return len(os.listdir("/proc/self/task"))

sdp.initialize(num_worker_threads=0)
scene = sdp.create_scene("threads")
scene.set_gravity([0, 0, -9.81])
scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape([0, 0, 1], 0), is_static=True)
sdp.prefab.add_to_scene(sys.argv[1], "/duck", scene)
before = threads()
for _ in range(3):
    scene.step(0.004)
assert scene.get_solver_stats().total_non_linear_iters > 0
# the process's OpenMP runtime, as CHOLMOD loaded it (the same instance, already in the process)
gomp = ctypes.CDLL("libgomp.so.1", mode=os.RTLD_NOLOAD)
print("THREADS", before, threads(), gomp.omp_get_max_active_levels())
"""


def test_stepping_a_soft_prop_starts_no_openmp_team():
    # a fresh process: threads that an earlier test started would hide the ones this one looks for
    run = subprocess.run([sys.executable, "-c", CHILD, str(DUCK)], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-3000:]
    line = [x for x in run.stdout.splitlines() if x.startswith("THREADS ")][-1]
    before, after, max_active_levels = (int(x) for x in line.split()[1:])
    # no OpenMP region may start a team
    assert max_active_levels == 0
    # the serial BLAS keeps one idle server thread, started at its first use; CHOLMOD's team of
    # four would add three
    assert after - before <= 1, f"stepping the soft prop started {after - before} threads"
