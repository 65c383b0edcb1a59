// The block of solid-block.geo.inc in linear tetrahedra: refused (contopt's elements are
// quadratic).
Include "solid-block.geo.inc";
MeshSize{ PointsOf{ Volume{:}; } } = 4;
Mesh.ElementOrder = 1;
