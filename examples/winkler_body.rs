//! Write your own body: a Winkler foundation (a bed of independent springs), the body
//! [`Winkler`] of `contopt::greens` (the book's chapter "Write your own body" walks through its
//! file, `crates/greens/src/winkler.rs`), pressed by a rigid sphere, solved by every contact
//! solver of `contopt::contact` and optimised by `contopt::optimise`, each against its closed
//! form.
//!
//! The bed's surface moves by wᵢ = pᵢ/k at each point, k the bed modulus \[MPa/mm\]: the kernel
//! H²(x, x') of eq. (2.5) is δ(x − x')/k, so its block H² of H = H¹ + H² (2.13)₁ is diagonal.
//! Nothing couples the points, so the closed forms are short: a rigid sphere of radius R
//! pressed in by δ gives p(r) = k(δ − r²/2R) for r < a = √(2Rδ) and F = πkRδ²; with a constant
//! controller (v = 1) the optimal gap makes the pressure uniform, p = F/A.
//!
//! `cargo run --release --example winkler_body` prints the table of the book's chapter
//! "Write your own body"; `cargo test --example winkler_body` checks it.

use std::f64::consts::PI;
use std::time::Instant;

use contopt::greens::{AxisymmetricHalfSpace, Winkler};
use contopt::prelude::*;

/// Bed modulus k \[MPa/mm\].
const K: f64 = 50.0;
/// Radius of the rigid sphere R \[mm\].
const R: f64 = 20.0;
/// Force pressing the sphere into the bed F \[N\].
const F: f64 = 1000.0;
/// Outer radius of the interface b \[mm\]: about 1.7 times the contact radius.
const B: f64 = 8.0;
/// Number of rings.
const RINGS: usize = 200;

/// The closed form of a rigid sphere pressed into a Winkler bed by a force.
#[derive(Clone, Copy, Debug)]
struct Sphere {
    /// Approach δ = √(F/(πkR)) \[mm\].
    delta: f64,
    /// Contact radius a = √(2Rδ) \[mm\].
    a: f64,
    /// Pressure at the centre p₀ = kδ \[MPa\].
    p0: f64,
}

impl Sphere {
    fn new(k: f64) -> Self {
        let delta = (F / (PI * k * R)).sqrt();
        Self {
            delta,
            a: (2.0 * R * delta).sqrt(),
            p0: k * delta,
        }
    }
}

/// One line of the table.
#[derive(Debug)]
struct Row {
    method: String,
    p_max: f64,
    /// Contact radius \[mm\].
    a: f64,
    /// Σ wᵢ pᵢ \[N\].
    force: f64,
    /// Largest |pᵢ − p(rᵢ)| over the closed form's p₀ (uniform p for the optimisation).
    error: f64,
    /// How the method ended.
    termination: Termination,
    seconds: f64,
}

// ANCHOR: setup
/// The bed on 200 rings out to r = b, the sphere's initial gap h = r²/2R (2.7) at its points,
/// and the indenter: a rigid body free to translate along the axis of symmetry y, pressed
/// towards the bed by F (it floats: its approach is the multiplier λ of eq. 2.12).
fn setup(k: f64) -> Result<(Winkler, Vec<f64>, RigidBody)> {
    let edges: Vec<f64> = (0..=RINGS).map(|j| B * j as f64 / RINGS as f64).collect();
    let rings = AxisymmetricHalfSpace::rings_interface(&edges)?;
    let bed = Winkler::on("Winkler bed", rings, k)?;
    let gap = bed
        .interface()
        .points()
        .iter()
        .map(|x| x[0] * x[0] / (2.0 * R))
        .collect();
    // The bed's outward normal is +y; the sphere moves away from it along +y.
    let sphere = RigidBody::pressed("sphere", bed.interface(), [0.0, 1.0, 0.0], F)?;
    Ok((bed, gap, sphere))
}
// ANCHOR_END: setup

// ANCHOR: solvers
/// Every solver of `contopt::contact`, each built from its settings, with its label in the
/// table. The penalty parameters are multiples of k: the penalty method's pressure is off by
/// k/c, so c = 10⁶k.
fn solvers(k: f64) -> Result<Vec<(&'static str, Box<dyn ContactSolver>)>> {
    Ok(vec![
        ("QP (clarabel)", Box::new(Qp::new(QpSettings::default())?)),
        (
            "active set",
            Box::new(ActiveSet::new(ActiveSetSettings::default())?),
        ),
        (
            "penalty",
            Box::new(Penalty::new(PenaltySettings {
                c_mpa_per_mm: 1e6 * k,
            })?),
        ),
        (
            "augmented Lagrangian",
            Box::new(AugmentedLagrangian::new(AugmentedLagrangianSettings::new(
                10.0 * k,
            ))?),
        ),
        (
            "Polonsky-Keer",
            Box::new(PolonskyKeer::new(PolonskyKeerSettings::default())?),
        ),
    ])
}
// ANCHOR_END: solvers

/// The contact radius from the pressure: the zero of the line through the last two loaded
/// points in r² (exact on a bed under a sphere, where p is linear in r²); the interface's
/// radius when its last point is loaded.
fn contact_radius(iface: &Interface, pressure: &[f64]) -> f64 {
    let r = |i: usize| iface.points()[i][0];
    match pressure.iter().rposition(|&p| p > 0.0) {
        Some(j) if j + 1 == pressure.len() => B,
        Some(j) if j > 0 => {
            let slope = (pressure[j - 1] - pressure[j]) / (r(j).powi(2) - r(j - 1).powi(2));
            (r(j).powi(2) + pressure[j] / slope).sqrt()
        }
        _ => 0.0,
    }
}

/// The sphere on the bed by `solver`, against the closed form of modulus `k` (the bed's own,
/// unless a test asks what a wrong k would look like).
fn contact_row(bed_k: f64, k: f64, (label, solver): (&str, &dyn ContactSolver)) -> Result<Row> {
    let (bed, gap, sphere) = setup(bed_k)?;
    let exact = Sphere::new(k);
    let clock = Instant::now();
    // ANCHOR: solve
    let problem = InterfaceProblem::new(&bed, &sphere, &gap)?;
    let state = solver.solve(&problem)?;
    // A method that stops short says why: `state.termination`, its last iterate kept.
    // ANCHOR_END: solve
    let seconds = clock.elapsed().as_secs_f64();
    let error = state
        .pressure
        .iter()
        .zip(&gap)
        .map(|(p, h)| (p - k * (exact.delta - h).max(0.0)).abs() / exact.p0)
        .fold(0.0, f64::max);
    Ok(Row {
        method: label.into(),
        p_max: state.p_max(),
        a: contact_radius(bed.interface(), &state.pressure),
        force: bed.interface().resultant(&state.pressure),
        error,
        termination: state.termination,
        seconds,
    })
}

/// An optimisation: its label, the method with its settings, and its contact solver's.
type Design = (&'static str, OptimisationMethod, SolverSettings);

// ANCHOR: methods
/// The optimisations: the iteration of §3.2 under the given load, the LP (3.5) and the load
/// split, each with its contact solver; the settings not written take the library's defaults.
fn optimisations() -> [Design; 3] {
    let active_set = SolverSettings::ActiveSet(ActiveSetSettings::default());
    [
        (
            "iteration §3.2 (active set)",
            OptimisationMethod::GivenLoad(IterationSettings {
                tolh_mm2: 1e-12,
                max_iterations: 10,
            }),
            active_set.clone(),
        ),
        (
            "LP (3.5) (active set)",
            OptimisationMethod::LinearProgramme(LinearProgrammeSettings::default()),
            active_set,
        ),
        (
            "load split (Polonsky-Keer)",
            OptimisationMethod::LoadSplit(LoadSplitSettings {
                tolerance: 1e-10,
                max_iterations: 50,
            }),
            SolverSettings::PolonskyKeer(PolonskyKeerSettings::default()),
        ),
    ]
}
// ANCHOR_END: methods

/// The gap that makes the sphere's pressure uniform (v = 1 on every point), one design value
/// per point. The gap may only open (Δh ≥ 0, eq. 3.5), so one point keeps its gap: by default
/// the one whose change comes out least, here the rim, where the sphere's gap is largest:
/// Δh(r) = (r_N² − r²)/2R, and p = F/A everywhere.
fn optimise_row((label, method, solver): &Design) -> Result<(Row, Optimum)> {
    let (bed, gap, sphere) = setup(K)?;
    let clock = Instant::now();
    let problem = InterfaceProblem::new(&bed, &sphere, &gap)?;
    // ANCHOR: optimise
    let shape = GapShape::pointwise(bed.interface());
    let optimisation = Optimisation::new(&problem, &shape, &Constant::new(1.0)?)?;
    let optimum = method.run(&optimisation, solver.build()?.as_ref())?;
    // ANCHOR_END: optimise
    let seconds = clock.elapsed().as_secs_f64();
    let uniform = F / bed.interface().area();
    let error = optimum
        .pressure
        .iter()
        .map(|p| (p - uniform).abs() / uniform)
        .fold(0.0, f64::max);
    let row = Row {
        method: label.to_string(),
        p_max: optimum.p_max,
        a: contact_radius(bed.interface(), &optimum.pressure),
        force: bed.interface().resultant(&optimum.pressure),
        error,
        termination: optimum.termination.clone(),
        seconds,
    };
    Ok((row, optimum))
}

/// A row of the table; a method that stopped short says how after its label.
fn print(r: &Row) {
    let ended = match &r.termination {
        Termination::Converged => String::new(),
        other => format!(" ({other})"),
    };
    println!(
        "| {}{ended} | {:.6} | {:.6} | {:.4} | {:.1e} | {:.1} ms |",
        r.method,
        r.p_max,
        r.a,
        r.force,
        r.error,
        1e3 * r.seconds
    )
}

fn main() -> Result<()> {
    let exact = Sphere::new(K);
    println!("Rigid sphere R = {R} mm pressed by F = {F} N into a Winkler bed k = {K} MPa/mm,");
    println!(
        "{RINGS} rings to r = {B} mm. Closed form: δ = {:.6} mm.\n",
        exact.delta
    );
    println!("| method | p_max [MPa] | contact radius [mm] | force [N] | error | time |");
    println!("| --- | --- | --- | --- | --- | --- |");
    println!(
        "| closed form | {:.6} | {:.6} | {F:.4} | | |",
        exact.p0, exact.a
    );
    for (label, solver) in solvers(K)? {
        print(&contact_row(K, K, (label, solver.as_ref()))?);
    }
    println!(
        "| optimum, closed form | {:.6} | {B:.6} | {F:.4} | | |",
        F / (PI * B * B)
    );
    for design in optimisations() {
        print(&optimise_row(&design)?.0);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Agreement with the continuum closed form (quadrature: the rings miss it by 10⁻⁵), while
    /// k off by 1 % moves p₀ ∝ √k by 0.5 % and a ∝ k^(−1/4) by 0.25 %.
    const CLOSED_FORM: f64 = 1e-4;
    /// Agreement of the optimum with uniform pressure: solver round-off (the ring areas are
    /// exact, so the closed form is too).
    const UNIFORM: f64 = 1e-8;

    #[test]
    fn every_solver_agrees_with_the_closed_form() {
        let exact = Sphere::new(K);
        for (name, solver) in solvers(K).unwrap() {
            let row = contact_row(K, K, (name, solver.as_ref())).unwrap();
            assert!(row.termination.is_converged(), "{name}: {row:?}");
            assert!(
                row.error < CLOSED_FORM,
                "{name}: pointwise error {:e}",
                row.error
            );
            assert!(
                (row.p_max / exact.p0 - 1.0).abs() < CLOSED_FORM,
                "{name}: {row:?}"
            );
            assert!(
                (row.a / exact.a - 1.0).abs() < CLOSED_FORM,
                "{name}: {row:?}"
            );
            assert!((row.force / F - 1.0).abs() < 1e-9, "{name}: {row:?}");
        }
    }

    /// The tolerance is tight enough to see a bed modulus off by 1 %, either way.
    #[test]
    fn a_one_percent_error_in_k_fails_the_tolerance() {
        let active_set = ActiveSet::new(ActiveSetSettings::default()).unwrap();
        for wrong in [0.99 * K, 1.01 * K] {
            let row = contact_row(wrong, K, ("active set", &active_set)).unwrap();
            assert!(
                row.error > CLOSED_FORM,
                "k = {wrong}: error {:e}",
                row.error
            );
            let exact = Sphere::new(K);
            assert!(
                (row.p_max / exact.p0 - 1.0).abs() > CLOSED_FORM,
                "k = {wrong}"
            );
        }
    }

    #[test]
    fn every_optimisation_makes_the_pressure_uniform() {
        let (bed, gap, _) = setup(K).unwrap();
        let rim = gap[RINGS - 1];
        for design in optimisations() {
            let method = design.0;
            let (row, optimum) = optimise_row(&design).unwrap();
            assert!(optimum.is_converged(), "{method}: {row:?}");
            assert!(row.error < UNIFORM, "{method}: {row:?}");
            assert!(
                (row.p_max * bed.interface().area() / F - 1.0).abs() < UNIFORM,
                "{method}"
            );
            for (i, (dh, h)) in optimum.gap_change.iter().zip(&gap).enumerate() {
                assert!(
                    (dh - (rim - h)).abs() < UNIFORM * rim,
                    "{method}: Δh at point {i}"
                );
            }
        }
    }

    /// The bed's influence is diagonal, 1/(k wᵢ), its preconditioner the exact inverse, and
    /// bad input an error that names the field.
    #[test]
    fn the_bed_is_diagonal_and_rejects_bad_input() {
        let rings = AxisymmetricHalfSpace::rings_interface(&[0.0, 1.0, 2.0]).unwrap();
        let bed = Winkler::on("bed", rings.clone(), 2.0).unwrap();
        let a = bed.influence_matrix();
        let w = bed.interface().weights();
        // A unit pressure on every ring sinks the bed by 1/k everywhere.
        let mut u = vec![0.0; 2];
        bed.apply_influence(w, &mut u);
        assert_eq!(u, vec![0.5, 0.5]);
        assert_eq!(
            (a[(0, 0)] * w[0], a[(1, 1)] * w[1], a[(0, 1)]),
            (0.5, 0.5, 0.0)
        );
        let mut f = vec![0.0; 2];
        assert!(bed.precondition(&u, &mut f));
        assert!((f[0] - w[0]).abs() < 1e-15 && (f[1] - w[1]).abs() < 1e-15);
        let e = Winkler::on("bed", rings.clone(), -1.0)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("modulus_mpa_per_mm = -1"), "{e}");
        assert!(Winkler::on("bed", rings, f64::NAN).is_err());
        let e = AxisymmetricHalfSpace::rings_interface(&[0.0, 2.0, 1.0])
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("edges"), "{e}");
        assert!(AxisymmetricHalfSpace::rings_interface(&[0.0]).is_err());
    }
}
