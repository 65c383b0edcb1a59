// The base of the paper's punch (Páczelt 1994, the scenes paper-table1…3): 100 mm in radius
// (plane: half-width) and 50 mm high, its top the plane y = 0, meshed on its own in 8-node
// quadrilaterals, about 2.8 mm at the top and growing with depth and towards the rim; its
// nodes do not match the punch's (paper-punch.geo).
// Groups: "base", "base_face" (y = 0 under the punch, x ≤ 50: the contact face, as the
// paper's zone), "base_top" (y = 0 beyond the punch), "base_bottom" (y = −50), "base_axis"
// (x = 0), "base_rim" (x = 100).
Point(1) = {0, 0, 0};
Point(2) = {50, 0, 0};
Point(3) = {100, 0, 0};
Point(4) = {100, -50, 0};
Point(5) = {0, -50, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Physical Surface("base") = {1};
Physical Curve("base_face") = {1};
Physical Curve("base_top") = {2};
Physical Curve("base_rim") = {3};
Physical Curve("base_bottom") = {4};
Physical Curve("base_axis") = {5};
// 2.8 mm under the punch (x ≤ 50), growing by a fifth of the distance from it.
Field[1] = MathEval;
Field[1].F = "Min(8, 2.8 + 0.2 * (Max(x - 50, 0) - y))";
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 8;
Mesh.RecombineAll = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
