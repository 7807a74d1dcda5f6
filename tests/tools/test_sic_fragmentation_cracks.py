#!/usr/bin/python3
"""Validation (ctest label "validation"): the SiC edge-on impact with fragmentation damage drawing
discrete cracks (examples/sic_edge_on_impact/sic_edge_on_impact_fragmentation_cracks.yaml) against
Riou et al. (1998), as issue 20 states the measured figures. One run to 12 µs at 0.25 mm (about
95 s on 2 threads), measured as seeds.py measures each of its runs (the example's crack_front.py and
tools/shard_plot.py crack-speeds).
Asserted:
- the front of inserted cracks, least squares over 2–8 µs after impact, at 8 200 ± 500 m/s
  (measured 8 406 m/s), and the front of damage ≥ 0.5 too (8 378 m/s);
- the median tip speed recorded at the nodes the tips reached at 4 000 ± 800 m/s (3 483 m/s) and
  none above the Rayleigh speed, about 6 700 m/s (largest 4 300 m/s);
- at least three separate cracks cross the line 20 mm from the impact face 6 µs after impact (8);
- the energy balance within 1 % at every history row (0.023 %).

With SCENARIO, another scenario of the example measured against the same bounds
(sic_edge_on_impact_fragmentation_adaptive.yaml: the same with adaptive remeshing from a coarse
mesh, about 5 minutes: fronts 8 389 and 8 484 m/s, tips' median 3 213 m/s, 10 cracks, 0.11 %).

Usage: test_sic_fragmentation_cracks.py SHARD_EXECUTABLE SOURCE_DIR WORK_DIR [SCENARIO]
"""

import os
import shutil
import sys


def main():
    shard, source, work = sys.argv[1:4]
    scenario = sys.argv[4] if len(sys.argv) > 4 else "sic_edge_on_impact_fragmentation_cracks.yaml"
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    example = os.path.join(source, "examples", "sic_edge_on_impact")
    sys.path.insert(0, example)
    from seeds import measure, outside_bounds, run
    out = os.path.join(work, "sic_fc")
    run([shard, "run", os.path.join(example, scenario), "-o", out, "--quiet"], quiet=False)
    r = measure(out, quiet=False)
    print(f"crack front {r['crack_front_m_per_s']:.0f} m/s, damage front {r['damage_front_m_per_s']:.0f} m/s; tips: "
          f"median {r['tip_median_m_per_s']:.0f} m/s over {r['tip_nodes']} nodes, largest {r['tip_max_m_per_s']:.0f} "
          f"m/s, {r['tips_above_6700']} above 6 700 m/s; {r['cracks_across_20mm_at_6us']} cracks across x = 20 mm at "
          f"6 us; worst balance {100 * r['worst_balance']:.3f} %")
    failures = outside_bounds(r)
    if failures:
        sys.exit("FAIL: " + "; ".join(failures))
    print("PASS")


if __name__ == "__main__":
    main()
