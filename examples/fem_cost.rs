//! What a finite-element body costs to build: the paper's base block (r ≤ 100 mm, height
//! 50 mm, clamped bottom), axisymmetric Q8, condensed onto a 201-point interface (67 contact
//! faces under the punch), at about 10k, 50k and 200k unknowns: the size of the factor, the
//! time of each phase of one build and its peak heap. The table of the book's chapter on
//! finite-element bodies; `cargo bench --bench fem` times the phases with criterion.
//!
//! `cargo run --release --example fem_cost`

use std::time::Duration;

use contopt::prelude::*;
use contopt_validation::fixtures::{base_block, PeakAlloc};

#[global_allocator]
static ALLOC: PeakAlloc = PeakAlloc;

/// The contact points of the base block.
const POINTS: usize = 201;

/// The meshes: elements outside the punch radius and layers through the height.
const SIZES: [(usize, usize); 3] = [(13, 20), (83, 55), (233, 110)];

fn main() -> Result<()> {
    println!(
        "{:>9} {:>7} {:>8}  {:>11} {:>14} {:>14} {:>13} {:>9}",
        "unknowns",
        "face",
        "nnz(L)",
        "assembly",
        "factorisation",
        "condensation",
        "load solve",
        "peak MiB"
    );
    for (outer, layers) in SIZES {
        let start = PeakAlloc::start();
        let body = base_block(outer, layers)?;
        let peak = PeakAlloc::peak_since(start);
        assert_eq!(body.interface().len(), POINTS);
        let s = *body.stats();
        let ms = |d: Duration| format!("{:.1} ms", d.as_secs_f64() * 1e3);
        println!(
            "{:>9} {:>7} {:>7.1}M  {:>11} {:>14} {:>14} {:>13} {peak:>9.0}",
            s.unknowns,
            s.face_unknowns,
            s.factor_nnz as f64 * 1e-6,
            ms(s.assembly),
            ms(s.factorisation),
            ms(s.condensation),
            ms(s.load_solve)
        );
    }
    Ok(())
}
