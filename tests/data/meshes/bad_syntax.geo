// A syntax error on line 3 (missing closing brace): Gmsh's own message must reach the user.
Point(1) = {0, 0, 0, 1};
Point(2) = {1, 0, 0, 1;
