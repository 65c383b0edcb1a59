// A quarter of a thick cylinder, bore radius 10 mm, outside 20 mm, 4 mm long, in 10-node
// tetrahedra with curved faces: Lamé's cylinder read from Gmsh.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, 0, 0, 0, 4, 20, Pi/2};
Cylinder(2) = {0, 0, 0, 0, 0, 4, 10, Pi/2};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Physical Volume("cylinder") = {3};
Physical Surface("bore") = Surface In BoundingBox{-0.1, -0.1, -0.1, 10.1, 10.1, 4.1};
Physical Surface("x0") = Surface In BoundingBox{-0.1, -0.1, -0.1, 0.1, 20.1, 4.1};
Physical Surface("y0") = Surface In BoundingBox{-0.1, -0.1, -0.1, 20.1, 0.1, 4.1};
Physical Surface("ends") = Surface In BoundingBox{-0.1, -0.1, -0.1, 20.1, 20.1, 0.1};
Physical Surface("ends") += Surface In BoundingBox{-0.1, -0.1, 3.9, 20.1, 20.1, 4.1};
MeshSize{ PointsOf{ Volume{:}; } } = 2.5;
Mesh.ElementOrder = 2;
Mesh.MshFileVersion = 4.1;
