// Two 10 × 10 mm squares side by side, each drawn with its own points and curves and
// geometry coherence off, so the shared side x = 10 is meshed twice: duplicate nodes, which
// the reader refuses (`Coherence Mesh;` would join them). 8-node quadrilaterals.
Geometry.AutoCoherence = 0;
Point(1) = {0, 0, 0};
Point(2) = {10, 0, 0};
Point(3) = {10, 10, 0};
Point(4) = {0, 10, 0};
Point(5) = {10, 0, 0};
Point(6) = {20, 0, 0};
Point(7) = {20, 10, 0};
Point(8) = {10, 10, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(2) = {2};
Transfinite Curve {1:8} = 3;
Transfinite Surface {1, 2};
Mesh.RecombineAll = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
