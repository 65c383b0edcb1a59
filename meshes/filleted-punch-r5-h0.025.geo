// The filleted punch of filleted-punch.geo (fillet 5 mm) with elements of 0.025 mm where the fillet begins, a fifth of the contact's reach onto it before the design (mesh series).
rho = 5;
hc = 0.025;
Include "filleted-punch.geo.inc";
