#!/usr/bin/env bash
# Configures build-sanitize/: clang with AddressSanitizer, UndefinedBehaviorSanitizer and
# libFuzzer's coverage on all of shard, so that one build serves both the tests under the
# sanitizers (scripts/run-sanitizers.sh) and the fuzz targets (scripts/run-fuzzers.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
CXX=clang++ cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHARD_SANITIZE=ON -DSHARD_FUZZ=ON \
  -DSHARD_NATIVE=OFF -DSHARD_BUILD_BENCH=OFF -DSHARD_BUILD_PYTHON=OFF > build-sanitize.log 2>&1 \
  || { cat build-sanitize.log; exit 1; }
