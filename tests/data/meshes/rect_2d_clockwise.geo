// Same 10 x 2 plate, but the surface is bounded by a clockwise curve loop, so Gmsh gives it a
// -z normal and numbers its cells clockwise: the importer must reorder them.
lc = 1.0;
Point(1) = {0, 0, 0, lc};
Point(2) = {10, 0, 0, lc};
Point(3) = {10, 2, 0, lc};
Point(4) = {0, 2, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {-4, -3, -2, -1};
Plane Surface(1) = {1};
Physical Surface("plate") = {1};
