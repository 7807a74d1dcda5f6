#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, AddressSanitizer and UndefinedBehaviorSanitizer) in
# build-sanitize/, replays every input kept in fuzz/regressions/ (each must pass), then fuzzes each
# target for SECONDS (default 60; as many targets at once as there are cores) from a seed corpus of the examples, tests/bad_input and the test
# meshes. A failure stops with status 1 and copies the input to fuzz/regressions/<target>/: commit
# it with the fix. Usage: bash scripts/run-fuzzers.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
# A fixed seed: the same inputs in the same order on every run, so that CI does not fail on a
# new find that depends on the day (set FUZZ_SEED=0 for a fresh one each run).
seed="${FUZZ_SEED:-1}"
bash scripts/configure-sanitized.sh
cmake --build build-sanitize -j "$(nproc)" --target fuzz_scenario fuzz_units fuzz_mesh

corpus=build-sanitize/corpus
rm -rf "$corpus"
mkdir -p "$corpus"/fuzz_scenario "$corpus"/fuzz_units "$corpus"/fuzz_mesh
i=0
while IFS= read -r f; do cp "$f" "$corpus/fuzz_scenario/seed_$((i++))"; done \
  < <(find examples tests/bad_input -name '*.yaml' | sort)
for f in tests/data/meshes/*.msh; do cp "$f" "$corpus/fuzz_mesh/"; done
for u in "370 MPa" "7830 kg/m^3" "0.5 mm" "203 m/s" "1e6 1/s" "20 us" "0.75 N/mm" "100 rad/s" "-5.4e-3 GPa" "1 J/m^2"; do
  printf '%s' "$u" > "$corpus/fuzz_units/$(echo "$u" | tr -c 'a-zA-Z0-9' '_')"
done

export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Replay first: every input that ever failed must pass before new ones are looked for.
targets=(fuzz_scenario fuzz_mesh fuzz_units)
for target in "${targets[@]}"; do
  kept="fuzz/regressions/$target"
  mkdir -p "$kept"
  if compgen -G "$kept/*" > /dev/null; then
    echo "== $target: replaying $(ls "$kept" | wc -l) kept inputs"
    build-sanitize/fuzz/$target -runs=0 "$kept"/* > "build-sanitize/$target.replay.log" 2>&1 \
      || { tail -40 "build-sanitize/$target.replay.log"; exit 1; }
  fi
done

# Each target fuzzes on one core; as many side by side as there are cores.
fuzz() {
  local target=$1 kept="fuzz/regressions/$1" found="build-sanitize/artifacts/$1"
  rm -rf "$found"
  mkdir -p "$found"
  if ! build-sanitize/fuzz/$target -max_total_time="$seconds" -seed="$seed" -timeout=20 -rss_limit_mb=2048 -max_len=65536 \
      -artifact_prefix="$found/" -print_final_stats=1 "$corpus/$target" > "build-sanitize/$target.log" 2>&1; then
    tail -60 "build-sanitize/$target.log"
    # Only the input the fuzzer itself names is kept: the mesh reader's child processes (which
    # inherit the fuzzer's handlers) may leave files of inputs the parent handled.
    local input
    input=$(grep -o "Test unit written to .*" "build-sanitize/$target.log" | tail -1 | sed 's/Test unit written to //')
    if [ -n "$input" ] && [ -f "$input" ]; then cp "$input" "$kept/"; fi
    echo "$target found a failure: the input is in $kept/$(basename "${input:-none}")"
    return 1
  fi
  echo "== $target: $seconds s, $(grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "build-sanitize/$target.log" | tr '\n' ' ')"
}
status=0
running=0
for target in "${targets[@]}"; do
  fuzz "$target" &
  running=$((running + 1))
  if [ "$running" -ge "$(nproc)" ]; then
    wait -n || status=1
    running=$((running - 1))
  fi
done
while [ "$running" -gt 0 ]; do
  wait -n || status=1
  running=$((running - 1))
done
exit "$status"
