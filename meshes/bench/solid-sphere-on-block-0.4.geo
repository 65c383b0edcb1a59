// The sphere on the block, 0.4 mm elements at the contact (convergence table).
fine = 0.4;
Include "../solid-sphere-on-block.geo.inc";
