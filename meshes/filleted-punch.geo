// The bundled scene filleted-punch: the paper's punch with a fillet of 5 mm at its rim on its base, elements of 0.25 mm at the fillet (filleted-punch.geo.inc).
rho = 5;
hc = 0.25;
Include "filleted-punch.geo.inc";
