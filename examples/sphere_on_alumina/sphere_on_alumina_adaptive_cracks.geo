// The sphere and the plate of sphere_on_alumina.geo on a start mesh for adaptive remeshing with
// discrete cracks (sphere_on_alumina_300_adaptive_cracks.yaml): the ceramics paper's 0.75 mm
// (table VIII), but 0.1 mm within 3 mm of the impact point, graded to 0.75 mm at 6 mm, in both
// bodies. The plate cracks under the sphere in its first steps of contact, before the strain rate
// has asked for a finer mesh, and a crack's lips keep the size they were made at: on the paper's
// uniform 0.75 mm start those first lips stay 0.75 mm long (README.md, "Adaptive remeshing with
// discrete cracks").
h = 0.75;
hc = 0.75;
hs = 0.75;
Include "sphere_on_alumina.geo";
Field[1] = Distance;
Field[1].PointsList = {6, 12};  // the plate's top on the axis, the sphere's lowest point
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.1;
Field[2].SizeMax = 0.75;
Field[2].DistMin = 3;
Field[2].DistMax = 6;
Background Field = 2;
