// The sharp punch (no fillet) of filleted-punch.geo.inc with elements of 0.5 mm at its rim: its rim pressure grows as the mesh is refined (singular).
rho = 0;
hc = 0.5;
Include "filleted-punch.geo.inc";
