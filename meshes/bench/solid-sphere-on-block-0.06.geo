// The sphere on the block, 0.06 mm elements at the contact (convergence table).
fine = 0.06;
Include "../solid-sphere-on-block.geo.inc";
