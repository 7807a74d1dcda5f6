// The plate and the sphere of sphere_on_alumina.geo meshed with Gmsh's Delaunay algorithm instead
// of the frontal-Delaunay one. Frontal-Delaunay lays the plate's triangles in rows at 0, 60 and
// 120 degrees to the surface, and where elements are wider than the crack-band limit a smeared
// crack runs along such a row: at 50 m/s the crack from the contact's edge ran at 57 degrees to
// the surface on the rows and at 31 degrees on these irregular triangles (README.md, "The mesh's
// rows"). The sizes h, hc and hs may be set before this file is included.
Include "sphere_on_alumina.geo";
Mesh.Algorithm = 5;        // Delaunay: no rows
