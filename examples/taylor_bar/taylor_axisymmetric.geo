// Taylor bar, axisymmetric half section (x = r, y = z, in mm): OFHC copper rod 25.4 mm long,
// 7.62 mm diameter, standing on the rigid anvil at y = 0. Structured triangles (transfinite,
// alternating diagonals) of about `h` mm.
R = 3.81;
L = 25.4;
h = 0.254;
nr = Ceil(R / h);
nz = Ceil(L / h);
Point(1) = {0, 0, 0};
Point(2) = {R, 0, 0};
Point(3) = {R, L, 0};
Point(4) = {0, L, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nr + 1;
Transfinite Curve{2, 4} = nz + 1;
Transfinite Surface{1} Alternate;
Physical Surface("bar") = {1};
Physical Curve("axis") = {4};
Physical Curve("impact_face") = {1};
