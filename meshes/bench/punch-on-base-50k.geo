// The paper's punch on its base (punch-on-base.geo.inc) with elements of h = 0.18 mm on the
// punch's face: about 50 000 nodes.
h = 0.18;
Include "punch-on-base.geo.inc";
