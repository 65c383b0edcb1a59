// The sphere on the block, 0.18 mm elements at the contact (convergence table).
fine = 0.18;
Include "../solid-sphere-on-block.geo.inc";
