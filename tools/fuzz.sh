#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with clang into build/fuzz and fuzzes each one for a bounded
# time, starting from its seed corpus in fuzz/corpus/<target>/. Fails (exit 1) when any target
# crashes, hangs or runs out of memory; the input that did it is kept in build/fuzz/crashes/.
# Once fixed, such an input goes to fuzz/regressions/<target>/ (read by every later run) and into
# the malformed corpus with its exact error (tools/make_malformed_corpus.py).
#   tools/fuzz.sh [target ...]         all targets when none is named
#   FUZZ_SECONDS=300 tools/fuzz.sh     seconds per target (default 30)
#   FUZZ_JOBS=1 tools/fuzz.sh          targets fuzzed at the same time (default 2)
#   FUZZ_RUNS=50000 tools/fuzz.sh      a reproducible campaign instead: this many inputs per target
#                                      from random seed FUZZ_SEED (default 1), starting from the
#                                      committed corpora only, so every machine runs the same inputs
#   FUZZ_RUNS=50000 tools/fuzz.sh urdf mochi_h5:3000
#                                      a target's own count of inputs after a colon
# Inputs the fuzzer finds that reach new code go to build/fuzz/corpus/<target>/, not to the repo.
set -euo pipefail
cd "$(dirname "$0")/.."
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true

seconds=${FUZZ_SECONDS:-30}
dir=build/fuzz
all=(bot_json prefab_json urdf mjcf mochi_h5 model_json model_h5 obj stl ply off recording debugger_message)
specs=("${@:-${all[@]}}")
# target names without their run counts, and the counts by name
targets=()
declare -A runs_of=()
for spec in "${specs[@]}"; do
  t=${spec%%:*}
  targets+=("$t")
  [[ "$spec" == *:* ]] && runs_of[$t]=${spec#*:}
done

# -O1 -g: fast enough to fuzz, quick to build, line numbers in reports; asserts stay on
cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_C_FLAGS_RELEASE="-O1 -g" -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g" \
  -DSUPERDEX_FUZZ=ON -DSUPERDEX_BUILD_TESTS=OFF -DSUPERDEX_BUILD_PYTHON=OFF >/dev/null
cmake --build "$dir" --parallel 2 --target "${targets[@]/%/_fuzzer}"

mkdir -p "$dir/crashes" "$dir/logs"
# leaks inside third-party libraries (each suppression says why)
export LSAN_OPTIONS="suppressions=$PWD/tools/sanitizers/lsan.supp:print_suppressions=0"

# Fuzzes one target; writes "ok" or "failed" to its result file.
fuzz_one() {
  local t=$1 log="$dir/logs/$1.log"
  mkdir -p "$dir/corpus/$t"
  # the first corpus folder receives the new inputs; the committed seeds and the inputs that
  # once crashed (fuzz/regressions/<target>/) are only read
  local corpora=("$dir/corpus/$t" "fuzz/corpus/$t") budget=(-max_total_time="$seconds")
  # a reproducible campaign neither reads nor keeps the inputs of earlier runs
  if [[ -n "${FUZZ_RUNS:-}" ]]; then
    corpora[0]="$dir/corpus-runs/$t"
    rm -rf "${corpora[0]}" && mkdir -p "${corpora[0]}"
    budget=(-runs="${runs_of[$t]:-$FUZZ_RUNS}" -seed="${FUZZ_SEED:-1}")
  fi
  [[ -d "fuzz/regressions/$t" ]] && corpora+=("fuzz/regressions/$t")
  if "$dir/fuzz/${t}_fuzzer" "${budget[@]}" -timeout=20 -rss_limit_mb=2048 \
       -artifact_prefix="$dir/crashes/$t-" "${corpora[@]}" >"$log" 2>&1; then
    echo "fuzz $t: ok ($(grep -o 'Done [0-9]* runs in [0-9]* second' "$log" | tail -1))"
    echo ok >"$dir/logs/$t.result"
  else
    echo "fuzz $t: FAILED (log $log)"
    grep -A30 -m1 '^==[0-9]*==ERROR\|ERROR: libFuzzer\|runtime error' "$log" | head -40 || tail -40 "$log"
    echo failed >"$dir/logs/$t.result"
  fi
}

# FUZZ_JOBS targets at a time (default 2: one per core of the CI machine)
jobs_max=${FUZZ_JOBS:-2}
for t in "${targets[@]}"; do
  rm -f "$dir/logs/$t.result"
  while (($(jobs -rp | wc -l) >= jobs_max)); do wait -n || true; done
  fuzz_one "$t" &
done
wait
failed=()
for t in "${targets[@]}"; do
  [[ "$(cat "$dir/logs/$t.result" 2>/dev/null)" == ok ]] || failed+=("$t")
done
if ((${#failed[@]})); then
  echo "fuzzing found crashes in: ${failed[*]} (inputs in $dir/crashes/)" >&2
  exit 1
fi
