// A 5 mm steel ball 0.05 mm above a 1 mm steel plate, 16 x 16 mm, in millimetres (OpenCASCADE).
// The plate is hexahedra: a 64 x 64 square of 0.25 mm quadrangles extruded in 4 layers; the
// ball is tetrahedra of about 0.4 mm.
SetFactory("OpenCASCADE");
Rectangle(1) = {-8, -8, -1, 16, 16};
Transfinite Curve{1:4} = 65;
Transfinite Surface{1};
Recombine Surface{1};
plate[] = Extrude{0, 0, 1}{Surface{1}; Layers{4}; Recombine;};
Sphere(10) = {0, 0, 2.55, 2.5};
MeshSize{PointsOf{Volume{10};}} = 0.4;
Physical Volume("plate") = {plate[1]};
Physical Volume("ball") = {10};
Physical Surface("rim") = {plate[2], plate[3], plate[4], plate[5]};
