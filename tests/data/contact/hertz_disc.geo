// Disc of radius R = 10 (units set by the scenario), centre (0, R): it touches the wall y = 0
// at the origin. Elements of size hmin within rfine of the contact point, growing linearly to
// hmax at distance rcoarse (Gmsh MathEval size field).
R = 10; hmin = 0.03; rfine = 1.0; hmax = 1.0; rcoarse = 6;
Point(1) = {0, R, 0}; Point(2) = {R, R, 0}; Point(3) = {0, 2 * R, 0};
Point(4) = {-R, R, 0}; Point(5) = {0, 0, 0};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("disc") = {1};
Field[1] = MathEval;
Field[1].F = Sprintf("min(%g, %g + (%g - %g) * max(0, sqrt(x^2 + y^2) - %g) / (%g - %g))", hmax, hmin, hmax, hmin, rfine, rcoarse, rfine);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
