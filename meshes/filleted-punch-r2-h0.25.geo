// The punch of filleted-punch.geo.inc with a fillet of 2 mm, elements of 0.25 mm at the fillet (radius series).
rho = 2;
hc = 0.25;
Include "filleted-punch.geo.inc";
