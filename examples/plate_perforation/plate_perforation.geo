// A steel rod (in plane strain: a disc of 5 mm diameter per metre of depth) above a thin steel
// plate 40 mm wide and 2 mm thick held at its two ends, drawn in millimetres. The rod is
// gap = 0.2 mm above the plate.
// Physical groups: surfaces "plate" and "projectile"; curves "plate_left", "plate_right".
W = 40; T = 2;     // plate width and thickness
R = 2.5;           // projectile radius
gap = 0.2;
h = 0.2;           // element size (the scenario's mesh.size caps it)
Mesh.Algorithm = 6;

Point(1) = {-W/2, 0, 0, h}; Point(2) = {W/2, 0, 0, h}; Point(3) = {W/2, T, 0, h}; Point(4) = {-W/2, T, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};

yc = T + gap + R;
Point(10) = {0, yc, 0, h}; Point(11) = {R, yc, 0, h}; Point(12) = {0, yc + R, 0, h};
Point(13) = {-R, yc, 0, h}; Point(14) = {0, yc - R, 0, h};
Circle(11) = {11, 10, 12}; Circle(12) = {12, 10, 13}; Circle(13) = {13, 10, 14}; Circle(14) = {14, 10, 11};
Curve Loop(11) = {11, 12, 13, 14}; Plane Surface(11) = {11};

Physical Surface("plate") = {1};
Physical Surface("projectile") = {11};
Physical Curve("plate_left") = {4};
Physical Curve("plate_right") = {2};
