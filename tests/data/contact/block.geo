// Square block 10 x 10 (units set by the scenario) resting on y = 0.
h = 1;
Point(1) = {0, 0, 0, h}; Point(2) = {10, 0, 0, h}; Point(3) = {10, 10, 0, h}; Point(4) = {0, 10, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("block") = {1};
