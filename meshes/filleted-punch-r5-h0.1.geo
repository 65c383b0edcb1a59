// The filleted punch of filleted-punch.geo (fillet 5 mm) with elements of 0.1 mm where the fillet begins: the coarsest of the mesh series, too coarse for the contact's reach onto the fillet.
rho = 5;
hc = 0.1;
Include "filleted-punch.geo.inc";
