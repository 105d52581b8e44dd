#!/usr/bin/env bash
# The project's entry points. Each command installs what is missing first (tools/bootstrap.sh),
# then builds incrementally into build/ (one build directory shared by Python and C++ tests).
#   tools/dev.sh demo   run the main demo
#   tools/dev.sh test   run every test: C++ (ctest), Python (pytest, float and double builds), and
#                       the fuzz targets for 30 s each (tools/fuzz.sh)
#   tools/dev.sh sanitize   the whole test suite under ASan + UBSan (+ LeakSanitizer for C++), build/asan
#   tools/dev.sh fuzz [target ...]   build the libFuzzer targets (clang, build/fuzz) and fuzz each for
#                       FUZZ_SECONDS (default 30)
set -euo pipefail
cd "$(dirname "$0")/.."

bash tools/bootstrap.sh
export PATH="$HOME/.local/bin:$PATH"
# let ccache reuse objects across checkouts (paths are made relative to the repository)
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true

# Python environment and the editable native modules (scikit-build-core, build/<wheel tag>/).
uv sync --quiet

build_dir() {
  # the directory scikit-build-core configured for this interpreter
  uv run --quiet python - <<'PY'
import sysconfig, pathlib, glob
dirs = sorted(glob.glob("build/cp*"), key=lambda p: pathlib.Path(p).stat().st_mtime)
print(dirs[-1] if dirs else "")
PY
}

case "${1:-}" in
  demo)
    shift
    # the seed example: with a display it opens the debugger page and runs until the page is
    # closed; without one it records the run (3 simulated seconds, one period of its circle,
    # unless SUPERDEX_DEBUGGER_DURATION says otherwise) for `superdex view`
    if [[ -z "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]]; then
      export SUPERDEX_DEBUGGER_RECORD="${SUPERDEX_DEBUGGER_RECORD:-$PWD/build/seed_example.jsonl}"
      export SUPERDEX_DEBUGGER_DURATION="${SUPERDEX_DEBUGGER_DURATION:-3}"
    fi
    exec uv run python superdex_robotics/examples/advanced/example_custom_components.py "$@"
    ;;
  test)
    dir=$(build_dir)
    [[ -n "$dir" ]] || { echo "no build directory under build/" >&2; exit 1; }
    echo "== C++ tests ($dir)"
    cmake --build "$dir" --parallel 2 --target all superdex_physics_tests superdex_robotics_tests
    ctest --test-dir "$dir" --output-on-failure --parallel 2
    echo "== Python tests (float build)"
    SUPERDEX_PRECISION=float uv run pytest -q
    echo "== Python tests (double build)"
    SUPERDEX_PRECISION=double uv run pytest -q
    # every fuzz target, two at a time, for a reproducible campaign of 150,000 inputs from a fixed
    # random seed, so that CI does not pass or fail by chance (clang build in build/fuzz: about 6
    # minutes from scratch on 2 cores, under a minute with ccache warm; fuzzing about 4 minutes).
    # Open-ended fuzzing is tools/dev.sh fuzz (FUZZ_SECONDS per target, new seeds each run).
    # mochi_h5 gets fewer inputs: the reader tries each new file in a child process (HDF5 can
    # crash on a corrupt file), and forking the sanitized fuzzer costs about 15 ms
    echo "== Fuzzing (tools/fuzz.sh)"
    FUZZ_RUNS=150000 FUZZ_SEED=1 bash tools/fuzz.sh mochi_h5:3000 bot_json prefab_json urdf mjcf:30000 obj stl ply recording \
      debugger_message
    ;;
  sanitize)
    shift
    exec bash tools/sanitize.sh "$@"
    ;;
  fuzz)
    shift
    exec bash tools/fuzz.sh "$@"
    ;;
  *)
    echo "usage: tools/dev.sh demo|test|sanitize|fuzz" >&2
    exit 2
    ;;
esac
