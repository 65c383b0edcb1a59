// A 40 × 20 mm rectangle in two halves sharing the curve x = 20: the left in 8-node
// quadrilaterals (type 16), the right in 6-node triangles (type 9), conforming on x = 20.
// Area: 800 mm². Groups: "body" (both halves), "bottom" (both halves' bottoms, one chain),
// "top", "left", "right".
h = 4;
Point(1) = {0, 0, 0, h};
Point(2) = {20, 0, 0, h};
Point(3) = {40, 0, 0, h};
Point(4) = {40, 20, 0, h};
Point(5) = {20, 20, 0, h};
Point(6) = {0, 20, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Recombine Surface {1};
Physical Surface("body") = {1, 2};
Physical Curve("bottom") = {1, 2};
Physical Curve("top") = {4, 5};
Physical Curve("left") = {6};
Physical Curve("right") = {3};
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
