// The block of solid-block.geo.inc in 10-node tetrahedra (Gmsh type 11).
Include "solid-block.geo.inc";
MeshSize{ PointsOf{ Volume{:}; } } = 2.5;
Mesh.ElementOrder = 2;
