// The sharp punch (no fillet) of filleted-punch.geo.inc with elements of 1 mm at its rim: its rim pressure grows as the mesh is refined (singular).
rho = 0;
hc = 1;
Include "filleted-punch.geo.inc";
