//! The penalty parameter on the paper's punch (the bundled scene `paper-table1`, zero initial
//! gap, no optimisation): c = E·10ᵏ for k = 0 … 12, the augmented Lagrangian with plain Uzawa
//! steps and the penalty, each against the QP's pressure (largest difference over p_max), with
//! the penalty's penetration. The table of the book's contact chapter; the test
//! `penalty_parameter_sweep` asserts what it shows.
//!
//! `cargo run --release --example penalty_sweep`

use contopt::contact::{AugmentedLagrangian, ContactSolver, InterfaceProblem, Penalty, Qp};
use contopt::scene::geometry::PunchOnBase;
use contopt::{ContactState, ElasticBody};

/// The bodies' Young's modulus [MPa], the scale of c.
const E: f64 = 2.0e5;
/// Uzawa steps allowed (plain steps converge slowly at small c).
const MAX_STEPS: usize = 5000;
/// The largest exponent k of c = E·10ᵏ.
const LARGEST_K: i32 = 12;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (base, punch) = PunchOnBase::bundled("paper-table1")?.bodies()?;
    let problem = InterfaceProblem::new(&base, &punch, &vec![0.0; base.interface().len()])?;
    let reference = Qp::default().solve(&problem)?;
    let error = |st: &ContactState| {
        st.pressure
            .iter()
            .zip(&reference.pressure)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / reference.p_max()
    };
    println!("| k | AL error | Uzawa steps | penalty error | penetration mm |");
    println!("| --- | --- | --- | --- | --- |");
    for k in 0..=LARGEST_K {
        let c = E * 10f64.powi(k);
        let al = AugmentedLagrangian {
            max_steps: MAX_STEPS,
            accelerate: false,
            ..AugmentedLagrangian::new(c)
        }
        .solve(&problem)?;
        let penalty = Penalty { c }.solve(&problem)?;
        println!(
            "| {k} | {:.1e} | {} | {:.1e} | {:.1e} |",
            error(&al),
            al.iterations,
            error(&penalty),
            penalty.residuals.penetration
        );
    }
    Ok(())
}
