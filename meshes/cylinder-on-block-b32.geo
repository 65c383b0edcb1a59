// The cylinder on a block of cylinder-on-block.geo.inc with elements of b/32 at the contact
// (b = 0.3 mm, the bundled load's Hertz half-width).
hc = 0.3 / 32;
Include "cylinder-on-block.geo.inc";
