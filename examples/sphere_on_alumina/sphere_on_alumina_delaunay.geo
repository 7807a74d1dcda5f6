// The plate and the sphere of sphere_on_alumina.geo meshed with Gmsh's Delaunay algorithm instead
// of the frontal-Delaunay one. Frontal-Delaunay lays the plate's triangles in rows at 0, 60 and
// 120 degrees to the surface, and a smeared crack band wider than its crack-band limit runs along
// such a row: at 50 m/s, where the stress field is nearly Hertz's, the crack from the contact's
// edge ran at about 50 degrees to the surface on the rows and at about 28 degrees on these
// irregular triangles (README.md, "The mesh's rows"). The sizes h, hc and hs may be set before
// this file is included.
Include "sphere_on_alumina.geo";
Mesh.Algorithm = 5;        // Delaunay: no rows
