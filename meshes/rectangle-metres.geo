// The 40 × 20 mm rectangle drawn in metres (0.04 × 0.02), 8-node quadrilaterals: what
// `check_extent` must catch.
h = 0.004;
Point(1) = {0, 0, 0, h};
Point(2) = {0.04, 0, 0, h};
Point(3) = {0.04, 0.02, 0, h};
Point(4) = {0, 0.02, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("body") = {1};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Mesh.RecombineAll = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
