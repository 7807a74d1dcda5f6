// The beam and projectile of sic_edge_on_impact.geo on a coarse start mesh (2 mm in the beam,
// 1 mm at the projectile's back) for adaptive remeshing: the remesher refines where the strain
// rate asks, and ahead of it (sic_edge_on_impact_adaptive.yaml).
h = 2;
hp = 1;
Include "sic_edge_on_impact.geo";
