// The edge-on impact of sic_edge_on_impact.geo meshed with Gmsh's Delaunay algorithm instead of
// the frontal-Delaunay one. Frontal-Delaunay lays its triangles in rows along the beam's faces,
// and the fragmentation damage's leading band runs on the centre line, along such a row: its
// front then moved by up to 1 600 m/s from one element size to the next (7 432, 9 047, 8 682,
// 8 166, 8 240 m/s at h = 0.5, 0.45, 0.42, 0.35, 0.25 mm). On these irregular triangles one
// mesh per size showed no trend with the size; a single mesh still scatters by hundreds of m/s,
// so a size is judged over three (README.md, "The mesh's pattern"). h may be set before this
// file is included, as seeds.py does for other sizes.
Include "sic_edge_on_impact.geo";
Mesh.Algorithm = 5;        // Delaunay: no rows
