// As impact_disc_plates.geo, but with square plate corners: the interface y = 3 ends at
// x = +-15, where both plates have a (coincident) convex corner. Reproduces a limitation of
// the contact search at convex corners (see test_contact_impact.cpp).
W = 15; T = 3; R = 4; gap = 0.02;
hd = 0.3;   // disc
ht = 0.25;  // upper plate
hb = 0.35;  // lower plate
Mesh.Algorithm = 6;  // frontal-Delaunay: well-shaped triangles
// Lower plate, 0 <= y <= T.
Point(1) = {-W, 0, 0, hb}; Point(2) = {W, 0, 0, hb}; Point(3) = {W, T, 0, hb}; Point(4) = {-W, T, 0, hb};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
// Upper plate, T <= y <= 2T.
Point(11) = {-W, T, 0, ht}; Point(12) = {W, T, 0, ht}; Point(13) = {W, 2*T, 0, ht}; Point(14) = {-W, 2*T, 0, ht};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};
Curve Loop(11) = {11, 12, 13, 14}; Plane Surface(11) = {11};
// Disc, centre (0, 2T + gap + R).
yc = 2*T + gap + R;
Point(21) = {0, yc, 0, hd}; Point(22) = {R, yc, 0, hd}; Point(23) = {0, yc + R, 0, hd};
Point(24) = {-R, yc, 0, hd}; Point(25) = {0, yc - R, 0, hd};
Circle(21) = {22, 21, 23}; Circle(22) = {23, 21, 24}; Circle(23) = {24, 21, 25}; Circle(24) = {25, 21, 22};
Curve Loop(21) = {21, 22, 23, 24}; Plane Surface(21) = {21};
Physical Surface("lower") = {1};
Physical Surface("upper") = {11};
Physical Surface("disc") = {21};
