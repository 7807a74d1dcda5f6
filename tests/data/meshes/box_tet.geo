// 10 x 2 x 2 box meshed with tetrahedra (OpenCASCADE kernel).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 10, 2, 2};
Mesh.MeshSizeMax = 1.0;
Physical Volume("bar") = {1};
Physical Surface("clamped") = {1};  // x = 0 face of an OpenCASCADE box
