// The paper's punch on its base (punch-on-base.geo.inc) with elements of h = 0.087 mm on the
// punch's face: about 200 000 nodes.
h = 0.087;
Include "punch-on-base.geo.inc";
