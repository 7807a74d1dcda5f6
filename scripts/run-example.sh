#!/usr/bin/env bash
# Sets up shard and runs the flagship example end to end: a steel sphere at 300 m/s on an alumina
# plate that cracks (examples/sphere_on_alumina, axisymmetric, discrete cracks), writing
# out/sphere_on_alumina_cracks/ (ParaView frames, history.csv, fragments.csv, summary.json) and
# pictures of the cracks, the fragments and the energy balance (scripts/flagship.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
bash scripts/flagship.sh out/sphere_on_alumina_cracks
