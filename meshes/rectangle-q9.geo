// The rectangle of rectangle.geo.inc in 9-node quadrilaterals (Gmsh type 10).
Include "rectangle.geo.inc";
Mesh.SecondOrderIncomplete = 0;
