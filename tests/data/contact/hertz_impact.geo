// A 5 mm sphere just above a thick block, axisymmetric: the axis is x = 0, the plane r = x >= 0,
// y up, drawn in millimetres. The block is B wide (radius) and D deep (0 <= r <= B, -D <= y <= 0);
// the sphere (radius Rs) sits `gap` above its top face, touching it at the origin when it lands.
// The two bodies have their own points, so their meshes share no node. Elements are hblock0 in
// the block and hsphere0 in the sphere within rfine of the contact point, and grow linearly with
// the distance d from it, by `rate` per unit of d, to hblock and hsphere (Gmsh MathEval fields
// restricted to each surface). The two sizes at the contact differ, in a ratio far from any
// ratio of small integers, so that the surface nodes of the two bodies do not start on top of
// each other: matching meshes make the contact rattle in axisymmetry
// (tests/verification/test_hertz_impact.cpp says why). Physical groups: surfaces "block" and "sphere"; curves "axis_block", "axis_sphere",
// "block_top", "block_bottom", "block_side".
B = 50; D = 50;            // block radius and depth
Rs = 2.5;                  // sphere radius
gap = 0.0005;              // lands at 0.05 us at 10 m/s
hblock0 = 0.02;            // block's elements at the contact (a = 0.30 mm at 10 m/s: a/h = 15)
hsphere0 = 0.0147;         // sphere's elements at the contact (a/h = 20)
rfine = 0.45;              // radius of the fine zone about the contact point (1.5 a)
rate = 0.25;               // growth of the element size with the distance beyond rfine
hsphere = 0.2;             // largest element in the sphere
hblock = 5;                // largest element in the block
Mesh.Algorithm = 6;

Point(1) = {0, -D, 0}; Point(2) = {B, -D, 0}; Point(3) = {B, 0, 0}; Point(4) = {0, 0, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};

yc = gap + Rs;
Point(11) = {0, yc, 0}; Point(12) = {0, gap, 0}; Point(13) = {Rs, yc, 0}; Point(14) = {0, yc + Rs, 0};
Circle(11) = {12, 11, 13}; Circle(12) = {13, 11, 14}; Line(13) = {14, 12};
Curve Loop(11) = {11, 12, 13}; Plane Surface(11) = {11};

Physical Surface("block") = {1};
Physical Surface("sphere") = {11};
Physical Curve("axis_block") = {4};
Physical Curve("axis_sphere") = {13};
Physical Curve("block_top") = {3};
Physical Curve("block_bottom") = {1};
Physical Curve("block_side") = {2};

size = "%g + %g * max(0, sqrt(x^2 + y^2) - %g)";
Field[1] = MathEval;
Field[1].F = Sprintf(StrCat("min(%g, ", size, ")"), hblock, hblock0, rate, rfine);
Field[2] = Restrict; Field[2].InField = 1; Field[2].SurfacesList = {1}; Field[2].CurvesList = {1, 2, 3, 4};
Field[3] = MathEval;
Field[3].F = Sprintf(StrCat("min(%g, ", size, ")"), hsphere, hsphere0, rate, rfine);
Field[4] = Restrict; Field[4].InField = 3; Field[4].SurfacesList = {11}; Field[4].CurvesList = {11, 12, 13};
Field[5] = Min; Field[5].FieldsList = {2, 4};
Background Field = 5;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
