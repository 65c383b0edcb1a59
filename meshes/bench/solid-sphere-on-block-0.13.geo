// The sphere on the block, 0.13 mm elements at the contact (convergence table).
fine = 0.13;
Include "../solid-sphere-on-block.geo.inc";
