// The rectangle of rectangle.geo.inc in 8-node quadrilaterals (Gmsh type 16).
Include "rectangle.geo.inc";
Mesh.SecondOrderIncomplete = 1;
