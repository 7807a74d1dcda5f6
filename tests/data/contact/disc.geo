// Disc of radius 5 (units set by the scenario), centre (0, 6): 1 above the wall y = 0.
R = 5; h = 0.5;
Point(1) = {0, 6, 0, h}; Point(2) = {R, 6, 0, h}; Point(3) = {0, 6 + R, 0, h};
Point(4) = {-R, 6, 0, h}; Point(5) = {0, 6 - R, 0, h};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("disc") = {1};
