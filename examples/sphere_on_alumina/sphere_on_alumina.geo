// A steel sphere on an alumina plate (Field 1988; case 2 of the ceramics paper), axisymmetric:
// the axis is x = 0, the plane r = x >= 0, y up. Drawn in millimetres. The plate is 8.6 mm
// thick and 50 mm in diameter (0 <= r <= 25, -8.6 <= y <= 0); the 5 mm sphere sits `gap` above
// its top face. Elements are `h` near the impact (r < 12 mm, where the cone cracks run) and grow
// to `hc` at the rim. The sphere's are `hs`, not `h`: surface nodes of both bodies at the same
// radii slide onto each other's facet ends near the axis, where the contact penalty jumps, and
// the axis nodes rattle (at 500 m/s the plate's reached 1 470 m/s; docs/theory/contact.md).
// Physical groups: surfaces "plate" and "sphere"; curves "axis_plate", "axis_sphere", "rim",
// "plate_top", "plate_bottom".
R = 25; H = 8.6;           // plate radius and thickness
Rs = 2.5;                  // sphere radius
gap = 0.03;                // lands at 0.1 us at 300 m/s
// The element sizes: a file that sets them first and then Includes this one keeps its own
// (sphere_on_alumina_adaptive.geo).
DefineConstant[ h = 0.1 ];         // element size near the impact
DefineConstant[ hc = 0.5 ];        // element size at the rim
DefineConstant[ hs = 0.0735 ];     // element size in the sphere (0.735 h, as in the Hertz test)
rf = 12;                   // radius of the fine zone
Mesh.Algorithm = 6;

Point(1) = {0, -H, 0, h}; Point(2) = {rf, -H, 0, h}; Point(3) = {R, -H, 0, hc};
Point(4) = {R, 0, 0, hc}; Point(5) = {rf, 0, 0, h}; Point(6) = {0, 0, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6}; Plane Surface(1) = {1};

// Sphere: the half disc r >= 0, centre on the axis, its own points.
yc = gap + Rs;
Point(11) = {0, yc, 0, hs}; Point(12) = {0, yc - Rs, 0, hs}; Point(13) = {Rs, yc, 0, hs}; Point(14) = {0, yc + Rs, 0, hs};
Circle(11) = {12, 11, 13}; Circle(12) = {13, 11, 14}; Line(13) = {14, 12};
Curve Loop(11) = {11, 12, 13}; Plane Surface(11) = {11};

Physical Surface("plate") = {1};
Physical Surface("sphere") = {11};
Physical Curve("axis_plate") = {6};
Physical Curve("axis_sphere") = {13};
Physical Curve("rim") = {3};
Physical Curve("plate_top") = {4, 5};
Physical Curve("plate_bottom") = {1, 2};
