// The bundled scene filleted-punch: the paper's punch with a fillet of 5 mm at its rim on its base, elements of 0.25 mm where the fillet begins (filleted-punch.geo.inc): enough for the design, whose pressure falls to zero there; the peak before the design needs 0.025 mm (filleted-punch-r5-h0.025.geo).
rho = 5;
hc = 0.25;
Include "filleted-punch.geo.inc";
