// The punch of filleted-punch.geo.inc with a fillet of 2 mm, elements of 0.025 mm where it begins (radius series).
rho = 2;
hc = 0.025;
Include "filleted-punch.geo.inc";
