// A shrink fit in plane strain, a quarter of it (x, y ≥ 0), both bodies in one file, each
// meshed on its own (no shared nodes): a solid steel shaft of radius 25.05 mm in an aluminium
// hub of bore 25 mm and outer radius 50 mm, a radial interference of 0.05 mm. Nothing presses
// them but the interference: each is held on its two symmetry lines only.
// Shaft: groups "shaft", "shaft_face" (its arc), "shaft_x0" (on x = 0), "shaft_y0" (on y = 0).
// Hub: groups "hub", "hub_bore" (its bore's arc), "hub_x0", "hub_y0".
// 8-node quadrilaterals; 16 faces on the shaft's arc, 20 on the hub's bore.
bs = 25.05;
bh = 25.0;
c = 50.0;

Point(1) = {0, 0, 0};
Point(2) = {bs, 0, 0};
Point(3) = {0, bs, 0};
Line(1) = {1, 2};
Circle(2) = {2, 1, 3};
Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Transfinite Curve{2} = 17;
Transfinite Curve{1, 3} = 9 Using Progression 0.85;

Point(11) = {bh, 0, 0};
Point(12) = {c, 0, 0};
Point(13) = {0, c, 0};
Point(14) = {0, bh, 0};
Line(11) = {11, 12};
Circle(12) = {12, 1, 13};
Line(13) = {13, 14};
Circle(14) = {14, 1, 11};
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};
Transfinite Curve{12, 14} = 21;
Transfinite Curve{11} = 9 Using Progression 1.15;
Transfinite Curve{13} = 9 Using Progression 1 / 1.15;
Transfinite Surface{11};

Physical Surface("shaft") = {1};
Physical Curve("shaft_face") = {2};
Physical Curve("shaft_x0") = {3};
Physical Curve("shaft_y0") = {1};
Physical Surface("hub") = {11};
Physical Curve("hub_bore") = {14};
Physical Curve("hub_x0") = {13};
Physical Curve("hub_y0") = {11};
Mesh.RecombineAll = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
