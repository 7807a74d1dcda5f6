// A 10 x 2 plate meshed with recombined quadrangles on a clockwise curve loop (-z normal).
Point(1) = {0, 0, 0};
Point(2) = {10, 0, 0};
Point(3) = {10, 2, 0};
Point(4) = {0, 2, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Transfinite Curve{1, 3} = 11;
Transfinite Curve{2, 4} = 3;
Curve Loop(1) = {-4, -3, -2, -1};
Plane Surface(1) = {1};
Transfinite Surface{1};
Recombine Surface{1};
Physical Surface("plate") = {1};
