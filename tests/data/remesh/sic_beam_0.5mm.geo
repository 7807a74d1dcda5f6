// The beam and projectile of the SiC edge-on impact on a uniform 0.5 mm mesh: the smallest size
// the adaptive example asks for (tests/verification/test_remesh_scenarios.cpp).
h = 0.5;
hp = 0.5;
Include "../../../examples/sic_edge_on_impact/sic_edge_on_impact.geo";
