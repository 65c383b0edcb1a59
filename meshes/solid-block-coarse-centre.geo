// A steel block 4 x 4 x 2 mm (x, y in [-2, 2], z in [-2, 0]) in 10-node tetrahedra whose top
// face is meshed coarse at its centre (0.5 mm across |x|, |y| < 0.5) and fine around it (0.1
// mm out to |x|, |y| < 1): a face with many nodes under a grid of 24 x 24 cells of 0.07 mm
// (815 face nodes against 576 cells) and few where a sphere presses it (58 within |x|, |y| <=
// 0.5 mm, under 196 of the cells). The case of crates/scene/tests/solids.rs where a count of the face's
// nodes under the whole grid passes while the pressure at the centre is not determined.
SetFactory("OpenCASCADE");
Box(1) = {-2, -2, -2, 4, 4, 2};
Physical Volume("block") = {1};
Physical Surface("top") = Surface In BoundingBox{-2.1, -2.1, -0.1, 2.1, 2.1, 0.1};
Physical Surface("bottom") = Surface In BoundingBox{-2.1, -2.1, -2.1, 2.1, 2.1, -1.9};
// Fine within the ring 0.5 < |x|, |y| < 1 near the top, 0.5 mm elsewhere.
Field[1] = Box;
Field[1].VIn = 0.1;
Field[1].VOut = 0.5;
Field[1].XMin = -1; Field[1].XMax = 1;
Field[1].YMin = -1; Field[1].YMax = 1;
Field[1].ZMin = -0.2; Field[1].ZMax = 0.1;
Field[2] = Box;
Field[2].VIn = 0.5;
Field[2].VOut = 0;
Field[2].XMin = -0.5; Field[2].XMax = 0.5;
Field[2].YMin = -0.5; Field[2].YMax = 0.5;
Field[2].ZMin = -2.1; Field[2].ZMax = 0.1;
Field[3] = Max;
Field[3].FieldsList = {1, 2};
Background Field = 3;
// Delaunay follows the field on the plane faces (Frontal-Delaunay, the default, meshed them at 0.5 mm).
Mesh.Algorithm = 5;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.ElementOrder = 2;
Mesh.MshFileVersion = 4.1;
