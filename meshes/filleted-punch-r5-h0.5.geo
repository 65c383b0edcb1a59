// The filleted punch of filleted-punch.geo (fillet 5 mm) with elements of 0.5 mm where the fillet begins (the design's mesh series).
rho = 5;
hc = 0.5;
Include "filleted-punch.geo.inc";
