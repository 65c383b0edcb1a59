// The filleted punch of filleted-punch.geo (fillet 5 mm) with elements of 0.5 mm at the fillet (mesh series).
rho = 5;
hc = 0.5;
Include "filleted-punch.geo.inc";
