// A coarse, small version of examples/sphere_on_alumina/sphere_on_alumina.geo for tests: a
// 5 mm sphere 0.03 mm above an alumina plate 4 mm thick and 8 mm in radius, axisymmetric (axis
// x = 0, y up), elements of h = 0.25 mm under the impact growing to hc = 0.8 mm at the rim.
// Physical groups: surfaces "plate" and "sphere"; curves "axis_plate", "axis_sphere", "rim".
R = 8; H = 4;
Rs = 2.5;
gap = 0.03;
h = 0.25;
hc = 0.8;
rf = 3;
Mesh.Algorithm = 6;

Point(1) = {0, -H, 0, h}; Point(2) = {rf, -H, 0, h}; Point(3) = {R, -H, 0, hc};
Point(4) = {R, 0, 0, hc}; Point(5) = {rf, 0, 0, h}; Point(6) = {0, 0, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6}; Plane Surface(1) = {1};

yc = gap + Rs;
Point(11) = {0, yc, 0, h}; Point(12) = {0, yc - Rs, 0, h}; Point(13) = {Rs, yc, 0, 2 * h}; Point(14) = {0, yc + Rs, 0, 2 * h};
Circle(11) = {12, 11, 13}; Circle(12) = {13, 11, 14}; Line(13) = {14, 12};
Curve Loop(11) = {11, 12, 13}; Plane Surface(11) = {11};

Physical Surface("plate") = {1};
Physical Surface("sphere") = {11};
Physical Curve("axis_plate") = {6};
Physical Curve("axis_sphere") = {13};
Physical Curve("rim") = {3};
