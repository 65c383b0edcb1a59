// The filleted punch of filleted-punch.geo (fillet 5 mm) with elements of 0.125 mm at the fillet: the finest of the mesh series.
rho = 5;
hc = 0.125;
Include "filleted-punch.geo.inc";
