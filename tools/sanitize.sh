#!/usr/bin/env bash
# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer (gcc), in its own build
# directory (build/asan): the GoogleTest suites with LeakSanitizer on (a leak fails the test),
# then pytest in the float and double builds with the sanitized native modules.
#   tools/dev.sh sanitize [pytest args...]   (tools/dev.sh has installed and synced first)
#   SANITIZE_PRECISIONS=double tools/dev.sh sanitize   pytest in one build only (default: float double)
# Any sanitizer report ends the process with an error, so a finding fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.local/bin:$PATH"
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true

dir=build/asan
flags="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
# -O2 keeps the physics tests fast enough; -g1 gives line numbers in the reports
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_C_FLAGS_RELEASE="-O2 -g1 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELEASE="-O2 -g1 -DNDEBUG" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DSUPERDEX_BUILD_PYTHON=ON -DSUPERDEX_BUILD_TESTS=ON -DPython_EXECUTABLE="$PWD/.venv/bin/python" >/dev/null
precisions=(${SANITIZE_PRECISIONS:-float double})
cmake --build "$dir" --parallel 2 --target superdex_physics_tests superdex_robotics_tests "${precisions[@]/#/_superdex_}"

# third-party reports that are not ours (each line of the file says why)
supp="$PWD/tools/sanitizers"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$supp/ubsan.supp"
# HDF5 sizes some allocations from file headers and checks what malloc returns: a corrupt file
# (malformed corpus) asks for petabytes, which malloc refuses in a normal process; ASan would
# abort instead. operator new is not affected (it still throws).
asan_common="allocator_may_return_null=1:abort_on_error=1"

echo "== C++ tests under ASan + UBSan + LeakSanitizer ($dir)"
ASAN_OPTIONS="detect_leaks=1:$asan_common" LSAN_OPTIONS="suppressions=$supp/lsan.supp" \
  ctest --test-dir "$dir" --output-on-failure --parallel 2

# The Python package loads the sanitized modules from SUPERDEX_NATIVE_DIR (python/superdex/_native.py);
# the sanitizer runtimes must be loaded before the interpreter's own libraries (LD_PRELOAD).
# CPython keeps its objects alive at exit by design, so leak detection is off for Python.
# SUPERDEX_SANITIZED=1 tells the tests that the engine runs many times slower and that ASan holds
# freed memory in its quarantine: they wait longer, run the seed example for one press instead of
# four, start node and chromium without the sanitizer runtimes, and do not compare resident sizes.
normal_build=$(ls -td build/cp* 2>/dev/null | head -1)
for precision in "${precisions[@]}"; do
  echo "== Python tests under ASan + UBSan ($precision build)"
  # --capture=sys: pytest captures Python's output only, so a sanitizer report written to the
  # process's stderr is shown even when it ends the process
  SUPERDEX_SANITIZED=1 SUPERDEX_PRECISION=$precision SUPERDEX_NATIVE_DIR="$PWD/$dir/python" \
  SKBUILD_EDITABLE_SKIP="${normal_build:+$PWD/$normal_build}" \
  ASAN_OPTIONS="detect_leaks=0:$asan_common" \
  LD_PRELOAD="$(gcc -print-file-name=libasan.so):$(gcc -print-file-name=libubsan.so)" \
    .venv/bin/python -m pytest -q --capture=sys "$@"
done
