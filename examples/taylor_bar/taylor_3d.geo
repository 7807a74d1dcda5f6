// Taylor bar, 3D quarter (x, y: cross-section, z: axis, in mm): OFHC copper rod 25.4 mm long,
// 7.62 mm diameter, standing on the rigid anvil at z = 0, symmetric about x = 0 and y = 0.
// Hexahedra on an O-grid: a square core and two curved blocks, extruded along the axis.
R = 3.81;
L = 25.4;
n_core = 6;    // cells along each core edge and along each quarter arc (two arcs of 45°)
n_ring = 5;    // cells from the core to the surface
n_axis = 60;   // cells along the axis
c = 0.5 * R;   // core square: (0,0)-(c,0)-(k,k)-(0,c)
k = 0.42 * R;
Point(1) = {0, 0, 0};
Point(2) = {c, 0, 0};
Point(3) = {k, k, 0};
Point(4) = {0, c, 0};
Point(5) = {R, 0, 0};
Point(6) = {R / Sqrt(2), R / Sqrt(2), 0};
Point(7) = {0, R, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {2, 5};
Line(6) = {3, 6};
Line(7) = {4, 7};
Circle(8) = {5, 1, 6};
Circle(9) = {6, 1, 7};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 8, -6, -2};
Plane Surface(2) = {2};
Curve Loop(3) = {6, 9, -7, -3};
Plane Surface(3) = {3};
Transfinite Curve{1, 2, 3, 4, 8, 9} = n_core + 1;
Transfinite Curve{5, 6, 7} = n_ring + 1;
Transfinite Surface{1, 2, 3};
Recombine Surface{1, 2, 3};
Extrude {0, 0, L} { Surface{1, 2, 3}; Layers{n_axis}; Recombine; }
Physical Volume("bar") = Volume{:};
e = 1e-6;
Physical Surface("symmetry_x") = Surface In BoundingBox{-e, -e, -e, e, R + e, L + e};
Physical Surface("symmetry_y") = Surface In BoundingBox{-e, -e, -e, R + e, e, L + e};
Physical Surface("impact_face") = Surface In BoundingBox{-e, -e, -e, R + e, R + e, e};
