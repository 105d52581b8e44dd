"""One measurement in its own process: `worker.py MODULE CASE_JSON` imports benchmarks/scenes/MODULE.py,
calls run_case(case) and prints its result as one 'RESULT {json}' line (see harness.py)."""

import importlib
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.harness import emit  # noqa: E402

if __name__ == "__main__":
    module = importlib.import_module(f"benchmarks.scenes.{sys.argv[1]}")
    emit(module.run_case(json.loads(sys.argv[2])))
