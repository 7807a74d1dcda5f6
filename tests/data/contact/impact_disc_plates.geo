// A disc (radius 4) above two stacked plates 30 x 3 (units set by the scenario), plane strain.
// Each plate has its own points and lines, so the plates are two meshes that touch along
// y = 3 without sharing nodes; the upper plate is meshed finer than the lower one, so the
// interface nodes do not coincide. The corners where the interface meets the plates' sides are
// rounded (radius 1): see test_contact_impact.cpp for why.
W = 15; T = 3; R = 4; gap = 0.02; rc = 1;
hd = 0.3;   // disc
ht = 0.25;  // upper plate
hb = 0.35;  // lower plate
Mesh.Algorithm = 6;  // frontal-Delaunay: well-shaped triangles
// Lower plate, 0 <= y <= T, top corners rounded.
Point(1) = {-W, 0, 0, hb}; Point(2) = {W, 0, 0, hb}; Point(3) = {W, T - rc, 0, hb};
Point(4) = {W - rc, T - rc, 0, hb}; Point(5) = {W - rc, T, 0, hb}; Point(6) = {-W + rc, T, 0, hb};
Point(7) = {-W + rc, T - rc, 0, hb}; Point(8) = {-W, T - rc, 0, hb};
Line(1) = {1, 2}; Line(2) = {2, 3}; Circle(3) = {3, 4, 5}; Line(4) = {5, 6}; Circle(5) = {6, 7, 8};
Line(6) = {8, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6}; Plane Surface(1) = {1};
// Upper plate, T <= y <= 2T, bottom corners rounded.
Point(11) = {-W + rc, T, 0, ht}; Point(12) = {W - rc, T, 0, ht}; Point(13) = {W - rc, T + rc, 0, ht};
Point(14) = {W, T + rc, 0, ht}; Point(15) = {W, 2 * T, 0, ht}; Point(16) = {-W, 2 * T, 0, ht};
Point(17) = {-W, T + rc, 0, ht}; Point(18) = {-W + rc, T + rc, 0, ht};
Line(11) = {11, 12}; Circle(12) = {12, 13, 14}; Line(13) = {14, 15}; Line(14) = {15, 16};
Line(15) = {16, 17}; Circle(16) = {17, 18, 11};
Curve Loop(11) = {11, 12, 13, 14, 15, 16}; Plane Surface(11) = {11};
// Disc, centre (0, 2T + gap + R).
yc = 2 * T + gap + R;
Point(21) = {0, yc, 0, hd}; Point(22) = {R, yc, 0, hd}; Point(23) = {0, yc + R, 0, hd};
Point(24) = {-R, yc, 0, hd}; Point(25) = {0, yc - R, 0, hd};
Circle(21) = {22, 21, 23}; Circle(22) = {23, 21, 24}; Circle(23) = {24, 21, 25}; Circle(24) = {25, 21, 22};
Curve Loop(21) = {21, 22, 23, 24}; Plane Surface(21) = {21};
Physical Surface("lower") = {1};
Physical Surface("upper") = {11};
Physical Surface("disc") = {21};
