// Both bodies of a contact in one file, each meshed on its own (no shared nodes): a base
// block 60 × 20 mm (y from −20 to 0) and above it a punch 20 × 15 mm whose lower edges are
// rounded with a radius of 3 mm, its flat face on y = 0. 8-node quadrilaterals.
// Base: area 1200 mm²; groups "base", "base_bottom", "base_top".
// Punch: area 300 − (4 − π)·9/2 mm²; groups "punch", "punch_top", "punch_face" (the flat
// face and both rounds, one chain).
hb = 4;
hp = 1.5;
Point(1) = {-30, -20, 0, hb};
Point(2) = {30, -20, 0, hb};
Point(3) = {30, 0, 0, hb / 2};
Point(4) = {-30, 0, 0, hb / 2};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

r = 3;
Point(11) = {-7, 0, 0, hp};
Point(12) = {7, 0, 0, hp};
Point(13) = {7, 3, 0, hp};
Point(14) = {10, 3, 0, hp};
Point(15) = {10, 15, 0, 2 * hp};
Point(16) = {-10, 15, 0, 2 * hp};
Point(17) = {-10, 3, 0, hp};
Point(18) = {-7, 3, 0, hp};
Line(11) = {11, 12};
Circle(12) = {12, 13, 14};
Line(13) = {14, 15};
Line(14) = {15, 16};
Line(15) = {16, 17};
Circle(16) = {17, 18, 11};
Curve Loop(11) = {11, 12, 13, 14, 15, 16};
Plane Surface(11) = {11};

Physical Surface("base") = {1};
Physical Curve("base_bottom") = {1};
Physical Curve("base_top") = {3};
Physical Surface("punch") = {11};
Physical Curve("punch_top") = {14};
Physical Curve("punch_face") = {16, 11, 12};
Mesh.RecombineAll = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
