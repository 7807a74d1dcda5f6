// A flat-ended steel cylinder (10 mm diameter, 20 mm long; in plane strain a bar of that
// section) above an alumina plate 50 mm wide and 10 mm thick, drawn in millimetres.
// The plate rests on y = 0 (the rigid base wall of the scenario); the cylinder's end face is
// gap = 0.15 mm above the plate, so at 150 m/s it lands at t = 1 us. The cylinder's two impact
// edges are rounded (radius 0.5 mm), as on a machined projectile: a square corner pressed onto
// a flat face is also a weak spot of node-to-facet contact.
// Physical groups: surfaces "plate" and "cylinder"; curves "plate_top", "plate_bottom", "impact_face".
W = 50; H = 10;            // plate width and thickness
D = 10; L = 20; rf = 0.5;  // cylinder diameter, length, edge radius
gap = 0.15;
h = 0.25;                  // element size (the scenario's mesh.size caps it)
Mesh.Algorithm = 6;        // frontal-Delaunay: well-shaped triangles

// Plate.
Point(1) = {-W/2, 0, 0, h}; Point(2) = {W/2, 0, 0, h}; Point(3) = {W/2, H, 0, h}; Point(4) = {-W/2, H, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};

// Cylinder: its own points, so the two bodies share no nodes.
y0 = H + gap;
Point(11) = {-D/2 + rf, y0, 0, h}; Point(12) = {D/2 - rf, y0, 0, h};
Point(13) = {D/2 - rf, y0 + rf, 0, h}; Point(14) = {D/2, y0 + rf, 0, h};
Point(15) = {D/2, y0 + L, 0, h}; Point(16) = {-D/2, y0 + L, 0, h};
Point(17) = {-D/2, y0 + rf, 0, h}; Point(18) = {-D/2 + rf, y0 + rf, 0, h};
Line(11) = {11, 12}; Circle(12) = {12, 13, 14}; Line(13) = {14, 15}; Line(14) = {15, 16};
Line(15) = {16, 17}; Circle(16) = {17, 18, 11};
Curve Loop(11) = {11, 12, 13, 14, 15, 16}; Plane Surface(11) = {11};

Physical Surface("plate") = {1};
Physical Surface("cylinder") = {11};
Physical Curve("plate_bottom") = {1};
Physical Curve("plate_top") = {3};
Physical Curve("impact_face") = {11};
