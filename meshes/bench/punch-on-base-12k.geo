// The paper's punch on its base (punch-on-base.geo.inc) with elements of h = 0.38 mm on the
// punch's face: about 12 000 nodes.
h = 0.38;
Include "punch-on-base.geo.inc";
