// Edge-on impact (Riou et al. 1998; case 1 of the ceramics paper): a steel cylinder, 11 mm in
// diameter and 20 mm long, strikes the 15 mm edge of a silicon carbide beam 100 mm long, in plane
// strain (the beam is 10 mm wide out of plane). Drawn in millimetres: the beam spans
// 0 <= x <= 100, -7.5 <= y <= 7.5; the projectile travels along +x and its face is `gap` short
// of the beam's impact edge, so at 203 m/s it lands at t = gap / v.
// Physical groups: surfaces "beam" and "projectile"; curves "impact_edge", "distal_edge".
L = 100; T = 15;           // beam length and thickness (the plane of the model)
Lp = 20; Dp = 11; rf = 0.5; // projectile length, diameter, edge radius (a machined edge)
gap = 0.0203;              // lands at 0.1 us at 203 m/s
DefineConstant[ h = 0.25 ];  // element size in the beam (mesh.size in the scenario caps it)
DefineConstant[ hp = 0.5 ];  // element size in the projectile
Mesh.Algorithm = 6;        // frontal-Delaunay: well-shaped triangles

Point(1) = {0, -T/2, 0, h}; Point(2) = {L, -T/2, 0, h}; Point(3) = {L, T/2, 0, h}; Point(4) = {0, T/2, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};

// Projectile: its own points (no shared nodes), the impact face at x = -gap, edges rounded.
x0 = -gap;
Point(11) = {x0, -Dp/2 + rf, 0, h}; Point(12) = {x0, Dp/2 - rf, 0, h};
Point(13) = {x0 - rf, Dp/2 - rf, 0, h}; Point(14) = {x0 - rf, Dp/2, 0, h};
Point(15) = {x0 - Lp, Dp/2, 0, hp}; Point(16) = {x0 - Lp, -Dp/2, 0, hp};
Point(17) = {x0 - rf, -Dp/2, 0, h}; Point(18) = {x0 - rf, -Dp/2 + rf, 0, h};
Line(11) = {11, 12}; Circle(12) = {12, 13, 14}; Line(13) = {14, 15}; Line(14) = {15, 16};
Line(15) = {16, 17}; Circle(16) = {17, 18, 11};
Curve Loop(11) = {11, 12, 13, 14, 15, 16}; Plane Surface(11) = {11};

Physical Surface("beam") = {1};
Physical Surface("projectile") = {11};
Physical Curve("impact_edge") = {4};
Physical Curve("distal_edge") = {2};
