//! Write your own body: a Winkler foundation (a bed of independent springs) as an
//! [`ElasticBody`], pressed by a rigid sphere, solved by every contact solver of
//! `contopt::contact` and optimised by `contopt::optimise`, each against its closed form.
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

use contopt::contact::{
    ActiveSet, AugmentedLagrangian, ContactSolver, InterfaceProblem, Penalty, PolonskyKeer, Qp,
};
use contopt::optimise::{Constant, Mode, Optimisation, Optimum};
use contopt::{ElasticBody, Error, GapShape, Geometry, Interface, Result, RigidBody, RigidMode};

// ANCHOR: body
/// A Winkler foundation on rings ρⱼ ≤ r ≤ ρⱼ₊₁ of an axisymmetric surface: each ring sinks by
/// its own pressure over k and feels no other ring.
pub struct Winkler {
    name: String,
    interface: Interface,
    /// Bed modulus k \[MPa/mm\]: the pressure that sinks the surface by 1 mm.
    k: f64,
}

impl Winkler {
    /// A bed of modulus `k` \[MPa/mm\] whose contact points are the mid-radii of the rings
    /// between the radii `edges` \[mm\] (increasing, from 0 or more). The surface is z = 0
    /// with outward normal +z; a ring's weight is its area π(ρⱼ₊₁² − ρⱼ²), so Σ wᵢ pᵢ is the
    /// force of a pressure uniform over each ring.
    pub fn rings(name: &str, k: f64, edges: &[f64]) -> Result<Self> {
        if !(k.is_finite() && k > 0.0) {
            return Err(Error::invalid(
                "winkler.k",
                k,
                "must be positive and finite [MPa/mm]",
            ));
        }
        let increasing = edges.windows(2).all(|e| e[1] > e[0]) && edges.len() >= 2;
        if !(increasing && edges[0] >= 0.0 && edges.iter().all(|e| e.is_finite())) {
            return Err(Error::invalid(
                "winkler.edges",
                format!("{edges:?}"),
                "at least two finite radii, increasing from 0 or more [mm]",
            ));
        }
        let rings = edges.windows(2);
        let interface = Interface::new(
            Geometry::Axisymmetric,
            rings
                .clone()
                .map(|e| [0.5 * (e[0] + e[1]), 0.0, 0.0])
                .collect(),
            rings.map(|e| PI * (e[1] * e[1] - e[0] * e[0])).collect(),
            vec![[0.0, 1.0, 0.0]; edges.len() - 1],
        )?;
        Ok(Self {
            name: name.into(),
            interface,
            k,
        })
    }
}
// ANCHOR_END: body

// ANCHOR: trait
impl ElasticBody for Winkler {
    /// The name the solvers' messages use.
    fn name(&self) -> &str {
        &self.name
    }

    /// The proposed contact zone Ω: points, weights wᵢ (∫ p dS ≈ Σ wᵢ pᵢ) and outward normals.
    /// The partner's interface must hold the same points with opposite normals.
    fn interface(&self) -> &Interface {
        &self.interface
    }

    /// The influence operator of eq. (2.5): the displacement into the body at each point under
    /// compressive forces Fⱼ = wⱼpⱼ at the points. A spring bed moves each point by its own
    /// pressure, uᵢ = pᵢ/k = Fᵢ/(k wᵢ). The contact problem sums it with the partner's (A¹ + A²,
    /// the H¹ + H² of eq. 2.13₁) and the matrix-free solver (Polonsky–Keer) needs nothing else.
    fn apply_influence(&self, force: &[f64], displacement: &mut [f64]) {
        for ((u, f), w) in displacement
            .iter_mut()
            .zip(force)
            .zip(&self.interface.weights)
        {
            *u = f / (self.k * w);
        }
    }

    /// Optional: an approximate inverse of the influence operator, which preconditions the
    /// matrix-free solver. The bed's is exact: Fᵢ = k wᵢ uᵢ.
    fn precondition(&self, displacement: &[f64], force: &mut [f64]) -> bool {
        for ((f, u), w) in force
            .iter_mut()
            .zip(displacement)
            .zip(&self.interface.weights)
        {
            *f = self.k * w * u;
        }
        true
    }

    /// f² of eqs. (2.5) and (2.7): the displacement under the body's own given loads, before
    /// any contact pressure. The bed carries none.
    fn load_displacement(&self) -> Result<Vec<f64>> {
        Ok(vec![0.0; self.interface.len()])
    }

    /// The rigid motions the supports leave free, the columns of G_R in the equilibrium
    /// (2.10)–(2.11). The ground holds the bed: none. (A floating body lists each mode's
    /// displacement per unit amplitude and the load q it must balance.)
    fn rigid_modes(&self) -> &[RigidMode] {
        &[]
    }

    // Not written, so the defaults hold: the dense matrix A of the dense solvers (QP, active
    // set, penalty, augmented Lagrangian, the LP of eq. 3.5; H = W A W of 2.12–2.14) is built
    // column by column from `apply_influence` (`influence_matrix`); no stresses below the
    // surface (`subsurface`: a spring bed has no interior); no cheaper part of the body
    // (`restrict`); no kernel shared with a partner (`influence_shape`); no pressure field
    // finer than the points (`pressure_basis`).
}
// ANCHOR_END: trait

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
    seconds: f64,
}

// ANCHOR: setup
/// The bed, the sphere's initial gap h = r²/2R (2.7) at its points, and the indenter pressed
/// by F along +z (a floating rigid body: its approach is the multiplier λ of eq. 2.12).
fn setup(k: f64) -> Result<(Winkler, Vec<f64>, RigidBody)> {
    let edges: Vec<f64> = (0..=RINGS).map(|j| B * j as f64 / RINGS as f64).collect();
    let bed = Winkler::rings("Winkler bed", k, &edges)?;
    let gap = bed
        .interface()
        .points
        .iter()
        .map(|x| x[0] * x[0] / (2.0 * R))
        .collect();
    let sphere = RigidBody::pressed("sphere", bed.interface(), [0.0, 1.0, 0.0], F)?;
    Ok((bed, gap, sphere))
}
// ANCHOR_END: setup

// ANCHOR: solvers
/// Every solver of `contopt::contact`. The penalty parameters are multiples of k: the penalty
/// method's pressure is off by k/c, so c = 10⁶k.
fn solvers(k: f64) -> Vec<Box<dyn ContactSolver>> {
    vec![
        Box::new(Qp::default()),
        Box::new(ActiveSet),
        Box::new(Penalty { c: 1e6 * k }),
        Box::new(AugmentedLagrangian::new(10.0 * k)),
        Box::new(PolonskyKeer::default()),
    ]
}
// ANCHOR_END: solvers

/// The contact radius from the pressure: the zero of the line through the last two loaded
/// points in r² (exact on a bed under a sphere, where p is linear in r²); the interface's
/// radius when its last point is loaded.
fn contact_radius(iface: &Interface, pressure: &[f64]) -> f64 {
    let r = |i: usize| iface.points[i][0];
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
fn contact_row(bed_k: f64, k: f64, solver: &dyn ContactSolver) -> Result<Row> {
    let (bed, gap, sphere) = setup(bed_k)?;
    let exact = Sphere::new(k);
    let clock = Instant::now();
    // ANCHOR: solve
    let problem = InterfaceProblem::new(&bed, &sphere, &gap)?;
    let state = solver.solve(&problem)?.solved(solver.name())?;
    // ANCHOR_END: solve
    let seconds = clock.elapsed().as_secs_f64();
    let error = state
        .pressure
        .iter()
        .zip(&gap)
        .map(|(p, h)| (p - k * (exact.delta - h).max(0.0)).abs() / exact.p0)
        .fold(0.0, f64::max);
    Ok(Row {
        method: solver.name().into(),
        p_max: state.p_max(),
        a: contact_radius(bed.interface(), &state.pressure),
        force: bed.interface().resultant(&state.pressure),
        error,
        seconds,
    })
}

/// How an optimisation is run.
type Method = fn(&Optimisation) -> Result<Optimum>;

// ANCHOR: methods
/// The optimisations: the iteration of §3.2 under the given load, the LP (3.5) and the load
/// split, each with its contact solver.
fn optimisations() -> [(&'static str, Method); 3] {
    [
        ("iteration §3.2 (active set)", |o| {
            o.iterate(Mode::GivenLoad, &ActiveSet, 1e-12, 10)
        }),
        ("LP (3.5) (active set)", |o| o.linear_programme(&ActiveSet)),
        ("load split (Polonsky-Keer)", |o| {
            o.load_split(&PolonskyKeer::default(), 1e-10, 50)
        }),
    ]
}
// ANCHOR_END: methods

/// The gap that makes the sphere's pressure uniform (v = 1 on every point), one design value
/// per point. The gap may only open (Δh ≥ 0, eq. 3.5), so the point that keeps its gap is the
/// rim, where the sphere's gap is largest: Δh(r) = (r_N² − r²)/2R, and p = F/A everywhere.
fn optimise_row(method: &str, run: Method) -> Result<(Row, Optimum)> {
    let (bed, gap, sphere) = setup(K)?;
    let clock = Instant::now();
    let problem = InterfaceProblem::new(&bed, &sphere, &gap)?;
    // ANCHOR: optimise
    let shape = GapShape::pointwise(bed.interface());
    let optimisation =
        Optimisation::new(&problem, &shape, &Constant::new(1.0)?)?.with_reference(RINGS - 1)?;
    let optimum = run(&optimisation)?;
    // ANCHOR_END: optimise
    let seconds = clock.elapsed().as_secs_f64();
    let uniform = F / bed.interface().area();
    let error = optimum
        .pressure
        .iter()
        .map(|p| (p - uniform).abs() / uniform)
        .fold(0.0, f64::max);
    let row = Row {
        method: method.into(),
        p_max: optimum.p_max,
        a: contact_radius(bed.interface(), &optimum.pressure),
        force: bed.interface().resultant(&optimum.pressure),
        error,
        seconds,
    };
    Ok((row, optimum))
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
    let print = |r: &Row| {
        println!(
            "| {} | {:.6} | {:.6} | {:.4} | {:.1e} | {:.1} ms |",
            r.method,
            r.p_max,
            r.a,
            r.force,
            r.error,
            1e3 * r.seconds
        )
    };
    println!(
        "| closed form | {:.6} | {:.6} | {F:.4} | | |",
        exact.p0, exact.a
    );
    for solver in solvers(K) {
        print(&contact_row(K, K, solver.as_ref())?);
    }
    println!(
        "| optimum, closed form | {:.6} | {B:.6} | {F:.4} | | |",
        F / (PI * B * B)
    );
    for (method, run) in optimisations() {
        print(&optimise_row(method, run)?.0);
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
        for solver in solvers(K) {
            let row = contact_row(K, K, solver.as_ref()).unwrap();
            let name = solver.name();
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
        for wrong in [0.99 * K, 1.01 * K] {
            let row = contact_row(wrong, K, &ActiveSet).unwrap();
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
        for (method, run) in optimisations() {
            let (row, optimum) = optimise_row(method, run).unwrap();
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

    #[test]
    fn the_bed_is_diagonal_and_rejects_bad_input() {
        let bed = Winkler::rings("bed", 2.0, &[0.0, 1.0, 2.0]).unwrap();
        let a = bed.influence_matrix();
        let w = &bed.interface().weights;
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
        let e = Winkler::rings("bed", -1.0, &[0.0, 1.0])
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("winkler.k = -1"), "{e}");
        let e = Winkler::rings("bed", 1.0, &[0.0, 2.0, 1.0])
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("winkler.edges"), "{e}");
        assert!(Winkler::rings("bed", f64::NAN, &[0.0, 1.0]).is_err());
        assert!(Winkler::rings("bed", 1.0, &[-1.0, 1.0]).is_err());
        assert!(Winkler::rings("bed", 1.0, &[0.0]).is_err());
    }
}
