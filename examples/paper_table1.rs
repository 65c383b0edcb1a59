//! Table 1 of the paper: the axisymmetric punch on its base under 100 MPa, the C¹ controller with
//! L1 ∈ {0, 20, 30, 40, 50} mm; p_max from equilibrium and the optimal gap change Δh, beside
//! the paper's figures, with a mesh-refinement study. Writes the plots of Δh(r) and p(r) to
//! `results/paper_table1/`.
//!
//! `cargo run --release --example paper_table1`

use contopt::fem::Analysis;
use contopt::paper;

fn main() -> Result<(), contopt::Error> {
    let dir = std::path::Path::new("results/paper_table1");
    println!("Table 1: axisymmetric punch on its base, given load 100 MPa");
    print!(
        "{}",
        paper::given_load_report(Analysis::Axisymmetric, &paper::TABLE1, dir)?
    );
    println!("plots: {}/dh.svg, {}/p.svg", dir.display(), dir.display());
    Ok(())
}
