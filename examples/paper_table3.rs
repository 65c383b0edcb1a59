//! Table 3 of the paper: the plane-stress punch (b = 10 mm) on its base under 100 MPa, the C¹ controller with
//! L1 ∈ {0, 20, 30, 40, 50} mm; p_max from equilibrium and the optimal gap change Δh, beside
//! the paper's figures, with a mesh-refinement study. Writes the plots of Δh(r) and p(r) to
//! `results/paper_table3/`.
//!
//! `cargo run --release --example paper_table3`

use contopt::fem::Analysis;
use contopt::paper;

fn main() -> Result<(), contopt::Error> {
    let dir = std::path::Path::new("results/paper_table3");
    println!("Table 3: plane-stress punch (b = 10 mm) on its base, given load 100 MPa");
    println!("(the printed p_max 283.3 for L1 = 0 is a misprint: equilibrium gives 200, and the printed Δh_max 88.35 µm belongs to 200)");
    print!(
        "{}",
        paper::given_load_report(
            Analysis::PlaneStress { thickness: 10.0 },
            &paper::TABLE3,
            dir
        )?
    );
    println!("plots: {}/dh.svg, {}/p.svg", dir.display(), dir.display());
    Ok(())
}
