// A steel rod on a ceramic tile, axisymmetric (x = r, y = z), mm. Two bodies meshed apart, in
// contact; the rod's corner elements erode first, leaving nodes that no element holds.
DefineConstant[ h = 0.4 ];
Rr = 3; Lr = 10; gap = 0.05;   // rod radius, length, stand-off
Rt = 12; Tt = 6;               // tile radius, thickness
Point(1) = {0, 0, 0, h}; Point(2) = {Rt, 0, 0, 2*h}; Point(3) = {Rt, Tt, 0, 2*h}; Point(4) = {0, Tt, 0, h};
Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,1};
Curve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};
y0 = Tt + gap;
Point(11) = {0, y0, 0, h}; Point(12) = {Rr, y0, 0, h}; Point(13) = {Rr, y0+Lr, 0, h}; Point(14) = {0, y0+Lr, 0, h};
Line(11) = {11,12}; Line(12) = {12,13}; Line(13) = {13,14}; Line(14) = {14,11};
Curve Loop(11) = {11,12,13,14}; Plane Surface(11) = {11};
Physical Surface("tile") = {1};
Physical Surface("rod") = {11};
Physical Curve("axis_tile") = {4};
Physical Curve("axis_rod") = {14};
