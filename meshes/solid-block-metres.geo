// The block of solid-block.geo.inc drawn in metres: 1000 times too small for contopt's mm.
Include "solid-block.geo.inc";
MeshSize{ PointsOf{ Volume{:}; } } = 4;
Mesh.ElementOrder = 2;
Mesh.ScalingFactor = 0.001;
