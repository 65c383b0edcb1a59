//! Table 1 of the paper: the axisymmetric punch on its base under 100 MPa, the C¹ controller
//! with L1 ∈ {0, 20, 30, 40, 50} mm. Runs the bundled scene `paper-table1` on 18, 36 and 72
//! elements across the contact radius and prints p_max (from equilibrium) and Δh_max beside the
//! paper's figures. `contopt run paper-table1` draws the plots.
//!
//! `cargo run --release --example paper_table1`

use contopt_validation::paper;

fn main() -> Result<(), contopt::scene::SceneError> {
    println!("Table 1: axisymmetric punch on its base, given load 100 MPa");
    print!(
        "{}",
        paper::given_load_table("paper-table1", &paper::TABLE1, true)?
    );
    Ok(())
}
