// The punch of filleted-punch.geo.inc with a fillet of 10 mm, elements of 0.25 mm at the fillet (radius series).
rho = 10;
hc = 0.25;
Include "filleted-punch.geo.inc";
