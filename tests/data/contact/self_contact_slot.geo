// A C-shaped block (units set by the scenario): 20 wide, 10 high, with a slot 0.2 wide and 8 deep
// cut down from the top in the middle, so the two arms face each other across the slot.
h = 0.4;
Point(1) = {0, 0, 0, h}; Point(2) = {20, 0, 0, h}; Point(3) = {20, 10, 0, h}; Point(4) = {10.1, 10, 0, h};
Point(5) = {10.1, 2, 0, h}; Point(6) = {9.9, 2, 0, h}; Point(7) = {9.9, 10, 0, h}; Point(8) = {0, 10, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8};
Plane Surface(1) = {1};
Physical Surface("body") = {1};
Physical Curve("left") = {8};
Physical Curve("right") = {2};
