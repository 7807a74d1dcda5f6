#!/usr/bin/env bash
# Builds shard in build-sanitize/ (clang, AddressSanitizer + UndefinedBehaviorSanitizer:
# scripts/configure-sanitized.sh) and runs the unit, verification and lint tests there (not the
# validation label). Any memory error, leak of shard's own or undefined behaviour stops the
# program that has it, and its test fails.
# Usage: bash scripts/run-sanitizers.sh [--ci] [ctest arguments, e.g. -R BadInput]
#   --ci  leaves out the tests that take over 10 s without sanitizers (they run in the release
#         suite; under the sanitizers they would take most of CI's time)
set -euo pipefail
cd "$(dirname "$0")/.."
select=()
if [ "${1:-}" = "--ci" ]; then
  shift
  select=(-E "$(grep -v '^#' scripts/sanitizer-ci-skip.txt | paste -sd '|')")
fi
bash scripts/configure-sanitized.sh
cmake --build build-sanitize -j "$(nproc)" --target shard shard_unit_tests shard_verification_tests
# Gmsh keeps some of what it allocates until the process ends; those are Gmsh's, not shard's.
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir build-sanitize -L "unit|verification|lint" -LE validation "${select[@]}" -j "$(nproc)" \
  --output-on-failure --timeout 3600 "$@"
