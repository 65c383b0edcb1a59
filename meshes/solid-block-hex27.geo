// The block of solid-block.geo.inc in 2 x 2 x 3 27-node hexahedra (Gmsh type 12).
Include "solid-block.geo.inc";
Transfinite Curve{:} = 3;
Transfinite Curve{9, 10, 11, 12} = 4;
Transfinite Surface{:};
Transfinite Volume{1};
Recombine Surface{:};
Mesh.Recombine3DAll = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 0;
