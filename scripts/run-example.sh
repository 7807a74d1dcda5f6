#!/usr/bin/env bash
# Sets up shard and runs the flagship example end to end: examples/bar_impact (2D, plane strain),
# writing out/bar_impact_2d/ (ParaView frames, history.csv, summary.json) and two pictures.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
out=out/bar_impact_2d
./build/shard run examples/bar_impact/bar_2d.yaml -o "$out"
/usr/bin/python3 tools/shard_plot.py field "$out" --field stress --component xx --frame 12 -o "$out/stress_xx_12us.png"
/usr/bin/python3 tools/shard_plot.py energy "$out" -o "$out/energy.png"
echo "Open $out/frames.pvd in ParaView; pictures: $out/stress_xx_12us.png, $out/energy.png"
