#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, AddressSanitizer and UndefinedBehaviorSanitizer) in
# build-fuzz/, replays every input kept in fuzz/regressions/ (each must pass), then fuzzes each
# target for SECONDS (default 60) from a seed corpus of the examples, tests/bad_input and the test
# meshes. A crash stops with status 1 and leaves the input in fuzz/regressions/<target>/: commit it
# with the fix. Usage: bash scripts/run-fuzzers.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHARD_FUZZ=ON -DSHARD_NATIVE=OFF \
  -DSHARD_BUILD_TESTS=OFF -DSHARD_BUILD_BENCH=OFF -DSHARD_BUILD_PYTHON=OFF > build-fuzz.log 2>&1 || { cat build-fuzz.log; exit 1; }
cmake --build build-fuzz -j "$(nproc)" --target fuzz_scenario fuzz_units fuzz_mesh

corpus=build-fuzz/corpus
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
for target in fuzz_scenario fuzz_units fuzz_mesh; do
  kept="fuzz/regressions/$target"
  mkdir -p "$kept"
  if compgen -G "$kept/*" > /dev/null; then
    echo "== $target: replaying $(ls "$kept" | wc -l) kept inputs"
    build-fuzz/fuzz/$target -runs=0 "$kept"/* > "build-fuzz/$target.replay.log" 2>&1 \
      || { tail -40 "build-fuzz/$target.replay.log"; exit 1; }
  fi
  echo "== $target: fuzzing for $seconds s"
  build-fuzz/fuzz/$target -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 -max_len=65536 \
    -artifact_prefix="$kept/" -print_final_stats=1 "$corpus/$target" > "build-fuzz/$target.log" 2>&1 \
    || { tail -60 "build-fuzz/$target.log"; echo "$target found a crash: the input is in $kept/"; exit 1; }
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "build-fuzz/$target.log" | tr '\n' ' '; echo
done
