// Taylor bar of the DynELA/Abaqus code-to-code benchmark: 42CrMo4 rod 32.4 mm long, 3.2 mm
// radius (x = r, y = z, mm), 5 x 50 cells split into triangles, on the anvil at y = 0.
R = 3.2;
L = 32.4;
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
Transfinite Curve{1, 3} = 6;
Transfinite Curve{2, 4} = 51;
Transfinite Surface{1} Alternate;
Physical Surface("bar") = {1};
Physical Curve("axis") = {4};
