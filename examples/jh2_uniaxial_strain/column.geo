// A ceramic column 10 x 0.5 x 0.5 mm, one row of 40 hexahedra (transfinite + recombine), in mm.
L = 10; H = 0.5; n = 40;
Point(1) = {0, 0, 0}; Point(2) = {L, 0, 0}; Point(3) = {L, H, 0}; Point(4) = {0, H, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Transfinite Curve{1, 3} = n + 1; Transfinite Curve{2, 4} = 2;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Surface{1}; Recombine Surface{1};
out[] = Extrude {0, 0, H} { Surface{1}; Layers{1}; Recombine; };
// out[0] top, out[1] the volume, out[2..5] the sides from lines 1..4
Physical Volume("column") = {out[1]};
Physical Surface("left") = {out[5]};
Physical Surface("right") = {out[3]};
Physical Surface("sides_y") = {out[2], out[4]};
Physical Surface("sides_z") = {1, out[0]};
