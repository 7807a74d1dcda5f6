// Quarter of a sphere of radius R = 10 (units set by the scenario), centre (0, R, 0), x >= 0 and
// z >= 0: it touches the wall y = 0 at the origin. Symmetry faces "sym_x" (x = 0) and "sym_z"
// (z = 0). Element size hmin within rfine of the contact point, growing linearly to hmax at
// distance rcoarse (Gmsh MathEval size field).
//
// "anchor": one fixed cube well away from the sphere, small enough (edge 0.21 hmin) that its
// stable time step is the smallest of the model (about 0.7 of the sphere's) and never changes,
// so that the automatic contact penalty, which follows the element stable step, stays constant
// (see tests/verification/test_hertz.cpp).
SetFactory("OpenCASCADE");
R = 10; hmin = 0.12; rfine = 1.3; hmax = 2.5; rcoarse = 8;
La = 0.2083 * hmin;
Sphere(1) = {0, R, 0, R};
Box(2) = {0, -1, 0, R + 1, 2 * R + 2, R + 1};
v() = BooleanIntersection{ Volume{1}; Delete; }{ Volume{2}; Delete; };
Box(3) = {12, 1, 1, La, La, La};
e = 1e-6;
Transfinite Curve{ Curve In BoundingBox{12 - e, 1 - e, 1 - e, 12 + La + e, 1 + La + e, 1 + La + e} } = 2;
Transfinite Surface{ Surface In BoundingBox{12 - e, 1 - e, 1 - e, 12 + La + e, 1 + La + e, 1 + La + e} };
Recombine Surface{ Surface In BoundingBox{12 - e, 1 - e, 1 - e, 12 + La + e, 1 + La + e, 1 + La + e} };
Transfinite Volume{3};
Physical Volume("sphere") = v();
Physical Volume("anchor") = {3};
Physical Surface("sym_x") = Surface In BoundingBox{-e, -e, -e, e, 2 * R + e, R + e};
Physical Surface("sym_z") = Surface In BoundingBox{-e, -e, -e, R + e, 2 * R + e, e};
Field[1] = MathEval;
Field[1].F = Sprintf("min(%g, %g + (%g - %g) * max(0, sqrt(x^2 + y^2 + z^2) - %g) / (%g - %g))", hmax, hmin, hmax, hmin, rfine, rcoarse, rfine);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
