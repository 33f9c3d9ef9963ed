// A disc of 100 mm diameter about (100, 100) mm, in millimetres: the Brazilian disc of
// doc/bodies.md, read as mesh(prm/meshes/disc_100mm.msh, 0.001). Regenerate with
//   gmsh -2 disc_100mm.geo -format msh41 -o disc_100mm.msh
SetFactory("OpenCASCADE");
Disk(1) = {100, 100, 0, 50};
Physical Surface(1) = {1};
Mesh.CharacteristicLengthMin = 4;
Mesh.CharacteristicLengthMax = 4;
