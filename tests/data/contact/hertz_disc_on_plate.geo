// Disc of radius R = 10 (units set by the scenario), centre (0, R), resting on a plate
// -W <= x <= W, -T <= y <= 0: it touches the plate's top at the origin. Disc and plate have
// their own points and lines (no point at the origin on the plate), so they are two meshes that
// do not share nodes. Elements of size hmin within rfine of the contact point, growing linearly
// to hmax at distance rcoarse (Gmsh MathEval size field), in both bodies.
R = 10; W = 20; T = 10; hmin = 0.04; rfine = 1.2; hmax = 1.0; rcoarse = 7;
Point(1) = {0, R, 0}; Point(2) = {R, R, 0}; Point(3) = {0, 2 * R, 0};
Point(4) = {-R, R, 0}; Point(5) = {0, 0, 0};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("disc") = {1};
Point(11) = {-W, -T, 0}; Point(12) = {W, -T, 0}; Point(13) = {W, 0, 0}; Point(14) = {-W, 0, 0};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};
Physical Surface("plate") = {11};
Field[1] = MathEval;
Field[1].F = Sprintf("min(%g, %g + (%g - %g) * max(0, sqrt(x^2 + y^2) - %g) / (%g - %g))", hmax, hmin, hmax, hmin, rfine, rcoarse, rfine);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
