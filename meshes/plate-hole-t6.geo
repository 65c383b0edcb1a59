// A quarter of a 50 × 50 mm plate with a hole of radius 10 mm at the origin, in 6-node
// triangles (Gmsh type 9). The curve loop runs clockwise, so the surface's normal is −z and
// Gmsh meshes it clockwise: the reader must renumber it, not refuse it.
// Area: 2500 − 25π mm². Groups: "plate", "hole" (the arc), "bottom" (y = 0), "left"
// (x = 0), "top", "right", "corner" (the point (50, 50)).
r = 10;
a = 50;
h = 5;
Point(1) = {0, 0, 0, h};
Point(2) = {r, 0, 0, h / 2};
Point(3) = {a, 0, 0, h};
Point(4) = {a, a, 0, h};
Point(5) = {0, a, 0, h};
Point(6) = {0, r, 0, h / 2};
Line(1) = {2, 3};
Line(2) = {3, 4};
Line(3) = {4, 5};
Line(4) = {5, 6};
Circle(5) = {6, 1, 2};
Curve Loop(1) = {-5, -4, -3, -2, -1};
Plane Surface(1) = {1};
Physical Surface("plate") = {1};
Physical Curve("hole") = {5};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Point("corner") = {4};
Mesh.ElementOrder = 2;
