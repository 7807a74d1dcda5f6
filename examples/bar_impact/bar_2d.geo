// Steel bar 100 mm x 10 mm (plane strain), drawn in millimetres.
// Physical groups: the surface "bar" and its four sides.
L = 100; H = 10; h = 1;
Point(1) = {0, 0, 0, h}; Point(2) = {L, 0, 0, h}; Point(3) = {L, H, 0, h}; Point(4) = {0, H, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("bar") = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
