// The sphere on the block, 0.09 mm elements at the contact (convergence table).
fine = 0.09;
Include "../solid-sphere-on-block.geo.inc";
