// The filleted punch of filleted-punch.geo (fillet 5 mm) with elements of 0.0125 mm where the fillet begins: the finest of the mesh series.
rho = 5;
hc = 0.0125;
Include "filleted-punch.geo.inc";
