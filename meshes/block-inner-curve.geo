// A 20 × 10 mm block of two surfaces that share the curve x = 10, one body: the curve
// "inner" lies inside it, not on its boundary, and cannot be a contact face.
// Groups: "block" (both halves), "top", "bottom", "inner".
h = 2.5;
Point(1) = {0, 0, 0, h};
Point(2) = {10, 0, 0, h};
Point(3) = {20, 0, 0, h};
Point(4) = {20, 10, 0, h};
Point(5) = {10, 10, 0, h};
Point(6) = {0, 10, 0, h};
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
Physical Surface("block") = {1, 2};
Physical Curve("top") = {4, 5};
Physical Curve("bottom") = {1, 2};
Physical Curve("inner") = {7};
Mesh.RecombineAll = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
