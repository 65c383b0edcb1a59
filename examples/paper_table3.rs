//! Table 3 of the paper: the plane-stress punch (b = 10 mm) on its base under 100 MPa, the C¹
//! controller with L1 ∈ {0, 20, 30, 40, 50} mm. Runs the bundled scene `paper-table3` on 18, 36
//! and 72 elements across the contact radius and prints p_max (from equilibrium) and Δh_max
//! beside the paper's figures. `contopt run paper-table3` draws the plots.
//!
//! `cargo run --release --example paper_table3`

use contopt_validation::paper;

fn main() -> Result<(), contopt::scene::SceneError> {
    println!("Table 3: plane-stress punch (b = 10 mm) on its base, given load 100 MPa");
    println!(
        "(the printed p_max 283.3 for L1 = 0 is a misprint: equilibrium gives 200, and the \
         printed Δh_max 88.35 µm belongs to 200)"
    );
    print!(
        "{}",
        paper::given_load_table("paper-table3", &paper::TABLE3, false)?
    );
    Ok(())
}
