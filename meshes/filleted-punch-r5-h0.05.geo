// The filleted punch of filleted-punch.geo (fillet 5 mm) with elements of 0.05 mm where the fillet begins (mesh series).
rho = 5;
hc = 0.05;
Include "filleted-punch.geo.inc";
