#!/usr/bin/env bash
# Builds shard with AddressSanitizer and UndefinedBehaviorSanitizer in build-asan/ and runs the
# unit and verification tests there (not the long validation label). Any memory error, leak of
# shard's own or undefined behaviour stops the program that has it, and its test fails.
# Usage: bash scripts/run-sanitizers.sh [ctest arguments, e.g. -R BadInput]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHARD_SANITIZE=ON -DSHARD_NATIVE=OFF \
  -DSHARD_BUILD_BENCH=OFF -DSHARD_BUILD_PYTHON=OFF > build-asan.log 2>&1 || { cat build-asan.log; exit 1; }
cmake --build build-asan -j "$(nproc)"
# Gmsh keeps some of what it allocates until the process ends; those are Gmsh's, not shard's.
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir build-asan -L "unit|verification|lint" -LE validation -j "$(nproc)" --output-on-failure --timeout 3600 "$@"
