#!/usr/bin/env bash
# Sets up shard and runs the default test suite (unit + verification; not the long
# "validation" label, see docs/testing.md).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
ctest --test-dir build -LE validation -j "$(nproc)" --output-on-failure --timeout 600
