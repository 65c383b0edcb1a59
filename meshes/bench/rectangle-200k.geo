// The reader's measurement (book: design notes, "Gmsh reader"): a 400 × 200 mm rectangle in
// about 67 000 unstructured 8-node quadrilaterals, about 200 000 nodes. Not committed as a
// mesh: `python3 meshes/generate.py --bench target/gmsh-bench` writes it.
h = 1.18;
Point(1) = {0, 0, 0, h};
Point(2) = {400, 0, 0, h};
Point(3) = {400, 200, 0, h};
Point(4) = {0, 200, 0, h};
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
