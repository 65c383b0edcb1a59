//! Table 2 of the paper: the axisymmetric punch pressed down by w = −0.05 mm, the C¹
//! controller with L1 ∈ {50, 40, 30, 20, 0} mm; every row of the iteration of §3.2
//! (k, p_max, Δh_max, TOLH, iterp, iterd) beside the paper's, and the converged values on
//! refined meshes. Writes the plots of Δh(r) and p(r) to `results/paper_table2/`.
//!
//! `cargo run --release --example paper_table2`

use contopt::paper;

fn main() -> Result<(), contopt::Error> {
    let dir = std::path::Path::new("results/paper_table2");
    println!("Table 2: axisymmetric punch, given displacement w = -0.05 mm, TOLH <= 0.5e-6 mm²");
    print!("{}", paper::given_displacement_report(dir)?);
    println!("plots: {}/dh.svg, {}/p.svg", dir.display(), dir.display());
    Ok(())
}
