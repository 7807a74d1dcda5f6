// The sphere and the plate of sphere_on_alumina.geo on the ceramics paper's starting mesh for
// adaptive remeshing (table VIII: 0.75 mm everywhere); the remesher refines where the strain
// rate asks (sphere_on_alumina_300_adaptive.yaml).
h = 0.75;
hc = 0.75;
hs = 0.75;
Include "sphere_on_alumina.geo";
