// The beam and projectile of sic_edge_on_impact.geo on a coarse start mesh for adaptive
// remeshing (sic_edge_on_impact_adaptive.yaml): 0.5 mm at the impact edge, where the beam cracks
// before the first assessment, graded to 2.5 mm at the distal face; 1 mm at the projectile's
// back. The remesher refines where the strain rate asks, and ahead of it.
h = 0.5;
hp = 1;
Include "sic_edge_on_impact.geo";
MeshSize {2, 3} = 2.5;  // the beam's distal corners
