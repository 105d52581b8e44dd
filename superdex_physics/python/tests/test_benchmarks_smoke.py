"""The benchmark suite runs: benchmarks/run.py --quick (tiny sizes, one repetition, a few steps)
completes and writes a results file with every scene's table and target lines.

Benchmarks are never tests: nothing here looks at a time. The C++ micro-benchmarks are skipped
(--no-cpp): building them is the full run's business."""

import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[3]
# tools/sanitize.sh runs the suite with the sanitized engine, many times slower
SLOW = 5 if os.environ.get("SUPERDEX_SANITIZED") == "1" else 1


def test_benchmark_suite_quick_run_writes_every_table(tmp_path):
    out = tmp_path / "RESULTS.md"
    run = subprocess.run([sys.executable, str(REPO / "benchmarks" / "run.py"), "--quick", "--no-cpp", "--out", str(out)],
                         capture_output=True, text=True, timeout=300 * SLOW, cwd=REPO)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    text = out.read_text()
    for number in range(1, 11):
        section = text.split(f"\n## {number}. ", 1)
        assert len(section) == 2, f"no section for scene {number}"
        body = section[1].split("\n## ", 1)[0]
        assert "\n|---" in body, f"scene {number} has no table"
        assert "met**" in body, f"scene {number} states no target"
    assert "## Targets" in text and "Machine:" in text and "mujoco" in text and "pybullet" in text
