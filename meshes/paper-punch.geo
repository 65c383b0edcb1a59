// The paper's punch (Páczelt 1994, the scenes paper-table1…3): 50 mm in radius (plane:
// half-width) and 50 mm high, its face the plane y = 0, meshed on its own in 8-node
// quadrilaterals, about 2 mm at the face and growing towards the top; its nodes do not match
// the base's (paper-base.geo).
// Groups: "punch", "punch_face" (y = 0, the contact face), "punch_top" (y = 50),
// "punch_axis" (x = 0), "punch_side" (x = 50).
Point(1) = {0, 0, 0};
Point(2) = {50, 0, 0};
Point(3) = {50, 50, 0};
Point(4) = {0, 50, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("punch") = {1};
Physical Curve("punch_face") = {1};
Physical Curve("punch_side") = {2};
Physical Curve("punch_top") = {3};
Physical Curve("punch_axis") = {4};
// 2 mm at the face, growing by a fifth of the height.
Field[1] = MathEval;
Field[1].F = "Min(6, 2 + 0.2 * y)";
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 8;
Mesh.RecombineAll = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
