// The sphere on the block of solid-sphere-on-block.geo.inc, 0.25 mm elements at the contact
// (the bundled resolution of the Hertz check; contact radius 1 mm).
fine = 0.25;
Include "solid-sphere-on-block.geo.inc";
