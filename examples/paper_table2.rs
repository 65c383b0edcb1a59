//! Table 2 of the paper: the axisymmetric punch pressed down by w = −0.05 mm, the C¹
//! controller with L1 ∈ {0, 20, 30, 40, 50} mm. Runs the bundled scene `paper-table2`: every
//! row of the iteration of §3.2 (k, p_max, Δh_max, TOLH, iterp, iterd) beside the paper's, and
//! the linear programme (3.5) on refined meshes. `contopt run paper-table2` draws the plots.
//!
//! `cargo run --release --example paper_table2`

fn main() -> Result<(), contopt::scene::SceneError> {
    println!("Table 2: axisymmetric punch, given displacement w = -0.05 mm, TOLH <= 0.5e-6 mm²");
    print!("{}", contopt_validation::paper::given_displacement_table()?);
    Ok(())
}
