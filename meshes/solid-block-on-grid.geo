// A steel block 10 x 10 x 5 mm (x, y in [-5, 5], z in [-5, 0]) in 20-node hexahedra, graded
// towards the centre of its top face z = 0, where a sphere presses it: the solid of the
// bundled scene scenes/sphere-on-solid-block.toml, which stands it on the scene's grid zone
// and reads its top face at the grid's cells.
SetFactory("OpenCASCADE");
Box(1) = {-5, -5, -5, 10, 10, 5};
Physical Volume("block") = {1};
Physical Surface("top") = Surface In BoundingBox{-5.1, -5.1, -0.1, 5.1, 5.1, 0.1};
Physical Surface("bottom") = Surface In BoundingBox{-5.1, -5.1, -5.1, 5.1, 5.1, -4.9};
// Across x and y (the edges of the top and bottom faces): finest at the centre.
across() = Curve In BoundingBox{-5.1, -5.1, -0.1, 5.1, 5.1, 0.1};
across() += Curve In BoundingBox{-5.1, -5.1, -5.1, 5.1, 5.1, -4.9};
Transfinite Curve{across()} = 15 Using Bump 40;
// Along z: finest at the top (each vertical edge runs from z = -5 up to z = 0).
down() = Curve{:};
down() -= across();
Transfinite Curve{down()} = 8 Using Progression 0.7;
Transfinite Surface{:};
Transfinite Volume{1};
Recombine Surface{:};
Mesh.Recombine3DAll = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
Mesh.MshFileVersion = 4.1;
