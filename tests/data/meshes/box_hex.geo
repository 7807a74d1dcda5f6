// 10 x 2 x 2 box meshed with hexahedra: transfinite curves, surfaces and volume, recombined.
Point(1) = {0, 0, 0};
Point(2) = {10, 0, 0};
Point(3) = {10, 2, 0};
Point(4) = {0, 2, 0};
Point(5) = {0, 0, 2};
Point(6) = {10, 0, 2};
Point(7) = {10, 2, 2};
Point(8) = {0, 2, 2};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 5};
Line(9) = {1, 5};
Line(10) = {2, 6};
Line(11) = {3, 7};
Line(12) = {4, 8};
Curve Loop(1) = {1, 2, 3, 4};     Plane Surface(1) = {1};  // z = 0
Curve Loop(2) = {5, 6, 7, 8};     Plane Surface(2) = {2};  // z = 2
Curve Loop(3) = {1, 10, -5, -9};  Plane Surface(3) = {3};  // y = 0
Curve Loop(4) = {3, 12, -7, -11}; Plane Surface(4) = {4};  // y = 2
Curve Loop(5) = {4, 9, -8, -12};  Plane Surface(5) = {5};  // x = 0
Curve Loop(6) = {2, 11, -6, -10}; Plane Surface(6) = {6};  // x = 10
Surface Loop(1) = {1, 2, 3, 4, 5, 6};
Volume(1) = {1};
Transfinite Curve{1, 3, 5, 7} = 11;
Transfinite Curve{2, 4, 6, 8, 9, 10, 11, 12} = 3;
Transfinite Surface{1:6};
Recombine Surface{1:6};
Transfinite Volume{1};
Physical Volume("bar") = {1};
Physical Surface("clamped") = {5};
Physical Surface("loaded") = {6};
