#!/usr/bin/env bash
# The flagship run on an existing build: a steel sphere at 300 m/s on an alumina plate whose
# cracks are inserted as they grow (examples/sphere_on_alumina/sphere_on_alumina_300_cracks.yaml),
# then its pictures: the crack faces, the fragments, the energy balance and the crack-tip speeds.
# Usage: bash scripts/flagship.sh [OUTDIR] [UNTIL]   (defaults: out/sphere_on_alumina_cracks, the end)
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/sphere_on_alumina_cracks}"
until=()
[ -n "${2:-}" ] && until=(--until "$2")
./build/shard run examples/sphere_on_alumina/sphere_on_alumina_300_cracks.yaml -o "$out" "${until[@]}"
plot=(/usr/bin/python3 tools/shard_plot.py)
"${plot[@]}" field "$out" --field crack_face --no-edges -o "$out/cracks.png"
"${plot[@]}" field "$out" --field fragment --cmap tab20 -o "$out/fragments.png"
"${plot[@]}" energy "$out" -o "$out/energy.png"
# The speeds of the crack tips, against the Rayleigh speed of the alumina (4 912 m/s)
"${plot[@]}" crack-speeds "$out" --limit 4912 -o "$out/crack_speeds.png"
echo "Open $out/frames.pvd in ParaView; pictures: $out/cracks.png, $out/fragments.png, $out/energy.png, $out/crack_speeds.png"
