//! The optimisation of the initial gap (§3) against equilibrium, closed forms and itself:
//! the optimised gap put back into the contact problem reproduces v·p_max with every solver;
//! the iteration and the linear programme agree; a rigid punch on a half-space (or a strip on
//! a half-plane) under constant pressure needs the closed-form gap change.

use std::f64::consts::PI;

use contopt::greens::{AxisymmetricHalfSpace, HalfPlane, PlaneState};
use contopt::prelude::*;
use contopt::scene::{CaseReport, Scene};
use contopt_validation::closed_form::{contact_modulus, FlamantStrip, HertzLine, UniformCircle};
use contopt_validation::fixtures::Exact;
use contopt_validation::paper;
use contopt_validation::roller::{CylinderGrid, Roller};

const E: f64 = 2.0e5;
const NU: f64 = 0.3;

/// Kalker's active set with exact dense solves, its default settings.
fn active_set() -> ActiveSet {
    ActiveSet::new(ActiveSetSettings::default()).unwrap()
}

/// Polonsky–Keer, its default settings.
fn polonsky_keer() -> PolonskyKeer {
    PolonskyKeer::new(PolonskyKeerSettings::default()).unwrap()
}

/// `solver`'s solution of `problem`, which must have met its tolerance.
fn solve(solver: &dyn ContactSolver, problem: &InterfaceProblem) -> ContactState {
    let st = solver.solve(problem).unwrap();
    assert!(st.is_converged(), "{}: {}", st.method, st.termination);
    st
}

/// An optimum whose method met its tolerance.
fn converged(name: &str, optimum: Optimum) -> Optimum {
    assert!(
        optimum.is_converged(),
        "{name}: {}: {}",
        optimum.method,
        optimum.termination
    );
    optimum
}

/// The iteration of §3.2 to TOLH ≤ `tolh_mm2` within `max_iterations` passes.
fn iteration(tolh_mm2: f64, max_iterations: usize) -> IterationSettings {
    IterationSettings {
        tolh_mm2,
        max_iterations,
    }
}

/// The load split to a miss of `tolerance` within `max_iterations` updates.
fn split_to(tolerance: f64, max_iterations: usize) -> LoadSplitSettings {
    LoadSplitSettings {
        tolerance,
        max_iterations,
    }
}

/// One L1 of a bundled paper scene, run through the scene on 18 elements, with its contact
/// problem (the scene's bodies, the initial gap zero).
struct PaperCase {
    l1: f64,
    report: CaseReport,
    problem: InterfaceProblem<'static>,
}

impl PaperCase {
    /// The scene `name` at `l1`, by its own method or by the linear programme when `lp`.
    fn run(name: &str, l1: f64, lp: bool) -> Self {
        let report = paper::case(name, 18, l1, lp).unwrap();
        assert!(
            report.is_solved(),
            "{name}, L1 = {l1}: {}",
            report.termination
        );
        let scene = paper::scene(name, 18, &[("sweep", None)]).unwrap();
        let problem = scene.cases()[0].problem().unwrap();
        let points = problem.interface().points();
        assert_eq!(report.interface.len(), points.len());
        assert!(report
            .interface
            .iter()
            .zip(points)
            .all(|(q, x)| q.x_mm == *x));
        Self {
            l1,
            report,
            problem,
        }
    }

    /// The level p_max of p ≤ v·p_max \[MPa\].
    fn p_max(&self) -> f64 {
        self.report.bound_p_max_mpa.unwrap()
    }

    /// The optimised pressure at the interface points.
    fn pressure(&self) -> Vec<f64> {
        self.report.interface.iter().map(|q| q.p_mpa).collect()
    }
}

/// Puts the reported gap change back into the contact problem and solves it from scratch with
/// every solver. The loop closes: each reproduces the reported pressure (the scene solved with
/// the paper's penalty, c = E·10⁴, whose pressure is off the exact solvers' by O(1/c):
/// measured up to 7e-5 of p_max; 2e-4 allowed); the pressure follows v·p_max within `within`
/// of p_max and peaks at p_max within 0.5 %. The pressure is read as a field
/// ([`InterfaceProblem::recovered_pressure`]): three Gauss points per quadratic face leave a
/// part of the point values that moves nothing, which the interior-point QP does not set to
/// zero.
fn close_the_loop(case: &PaperCase, within: f64) {
    let p_max = case.p_max();
    // The report's gap change is in µm.
    let gap: Vec<f64> = case
        .report
        .interface
        .iter()
        .map(|q| 1e-3 * q.dh_um)
        .collect();
    let problem = case.problem.with_initial_gap(&gap).unwrap();
    let controller = Profile::cubic(case.l1, paper::PUNCH_RADIUS).unwrap();
    let target: Vec<f64> = problem
        .interface()
        .points()
        .iter()
        .map(|&x| controller.value(x) * p_max)
        .collect();
    let qp = Qp::new(QpSettings::default()).unwrap();
    let augmented = AugmentedLagrangian::new(AugmentedLagrangianSettings::new(E * 1e4)).unwrap();
    for solver in [&qp as &dyn ContactSolver, &active_set(), &augmented] {
        let name = solver.method();
        let st = solve(solver, &problem);
        let field = problem.recovered_pressure(&st.pressure).unwrap();
        let deviation = field
            .iter()
            .zip(&target)
            .map(|(p, t)| (p - t).abs())
            .fold(0.0, f64::max)
            / p_max;
        eprintln!(
            "L1 = {}: {name}: deviation {:.2e} of p_max, peak {:+.4} %",
            case.l1,
            deviation,
            100.0 * (st.p_max() / p_max - 1.0)
        );
        assert!(deviation < within, "{name}: deviation {deviation}");
        let reported = problem.recovered_pressure(&case.pressure()).unwrap();
        let off = field
            .iter()
            .zip(&reported)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / p_max;
        assert!(
            off < 2e-4,
            "{name}: {off:e} of p_max off the reported pressure"
        );
        assert!(
            (st.p_max() / p_max - 1.0).abs() < 0.005,
            "{name}: peak {} vs {p_max}",
            st.p_max()
        );
    }
}

/// Table 1 (given load, the scene `paper-table1`): v·p_max carries the punch's load exactly on
/// the mesh, p_max is the equilibrium value of the continuous controller to four significant
/// figures (the Gauss points integrate v to 1e-5), and the loop closes.
#[test]
fn given_load_closes_the_loop() {
    for l1 in [0.0, 30.0, 50.0] {
        let case = PaperCase::run("paper-table1", l1, false);
        let carried = case.problem.interface().resultant(&case.pressure());
        assert!(
            (carried / (100.0 * PI * 2500.0) - 1.0).abs() < 1e-9,
            "L1 = {l1}: {carried}"
        );
        let expected = paper::equilibrium_p_max(true, 100.0, l1);
        assert!(
            (case.p_max() / expected - 1.0).abs() < 5e-5,
            "L1 = {l1}: {} vs {expected}",
            case.p_max()
        );
        // The second pass changes nothing: the loop is closed.
        assert_eq!(case.report.passes.len(), 2, "L1 = {l1}");
        close_the_loop(&case, 0.01);
    }
}

/// Table 3's L1 = 0 (plane stress, the scene `paper-table3`): equilibrium gives p_max = 200 MPa,
/// not the printed 283.3.
#[test]
fn plane_stress_given_load_is_equilibrium() {
    let case = PaperCase::run("paper-table3", 0.0, false);
    assert!((case.p_max() - 200.0).abs() < 1e-4, "{}", case.p_max());
    close_the_loop(&case, 0.01);
}

/// How far the reported pressure of a given displacement may miss v·p_max \[of p_max\]. The
/// reported gap change is the one the reported pressure was solved with, Δh⁽ᵏ⁻¹⁾ of the last
/// pass k (the optimiser returns a consistent pair), not the Δh⁽ᵏ⁾ that pass computed:
/// TOLH ≤ 0.5·10⁻⁶ mm² lets the two differ by up to 0.7 µm, which moves the pressure by about
/// 1 % of p_max. Measured 1.36 % at L1 = 40 and 1.10 % at L1 = 20 (with Δh⁽ᵏ⁾, which the
/// reports held before issue 22: 0.58 % and 0.24 %); 1.5 % allowed, the 1 % of a given load
/// (whose second pass changes nothing) otherwise.
const GIVEN_DISPLACEMENT_MISS: f64 = 0.015;

/// Table 2 (given displacement, the scene `paper-table2`), every L1: the iteration of §3.2
/// (penalty contact, as the paper) stops on TOLH within the paper's number of steps and agrees
/// with the linear programme on p_max and Δh_max within 0.5 %; the loop closes. L1 ≤ 40 needs
/// both Kalker's safeguard against cycling and step 4's pressure read as a field (a receding
/// contact edge leaves a Gauss-point sawtooth that moves nothing).
#[test]
fn given_displacement_iteration_matches_the_lp() {
    for (l1, paper_steps) in [(50.0, 4), (40.0, 5), (30.0, 6), (20.0, 6), (0.0, 7)] {
        let iterated = PaperCase::run("paper-table2", l1, false);
        let lp = PaperCase::run("paper-table2", l1, true);
        let (a, b) = (&iterated.report, &lp.report);
        let (dh_a, dh_b) = (a.dh_max_um.unwrap(), b.dh_max_um.unwrap());
        eprintln!(
            "L1 = {l1}: iteration p_max {:.3} Δh_max {dh_a:.3} µm in {} steps; LP {:.3}, {dh_b:.3} µm",
            iterated.p_max(),
            a.passes.len(),
            lp.p_max(),
        );
        assert!(a.passes.last().unwrap().tolh_mm2 <= paper::TOLH);
        assert!(a.passes.len() <= paper_steps, "L1 = {l1}");
        assert!(
            (iterated.p_max() / lp.p_max() - 1.0).abs() < 0.005,
            "L1 = {l1}"
        );
        assert!((dh_a / dh_b - 1.0).abs() < 0.005, "L1 = {l1}");
        close_the_loop(&iterated, GIVEN_DISPLACEMENT_MISS);
    }
}

/// A steel half-space on `n` rings out to radius `a`, their edges a·sin(πk/2n), clustered at
/// the rim where a flat punch's pressure changes fastest.
fn clustered_half_space(a: f64, n: usize) -> AxisymmetricHalfSpace {
    let edges: Vec<f64> = (0..=n)
        .map(|k| a * (0.5 * PI * k as f64 / n as f64).sin())
        .collect();
    AxisymmetricHalfSpace::new("half-space", Material::new(E, NU).unwrap(), &edges).unwrap()
}

/// A rigid flat punch (a = 1 mm) held at an approach of 1 µm on a half-space (axisymmetric
/// rings clustered at the rim), v = 1: the iteration of §3.2 under the given displacement
/// agrees with the linear programme. Its gap changes are a fraction of a micrometre, so the
/// paper's TOLH (0.5·10⁻⁶ mm², absolute) was met while the rim still carried 0.58 of p_max
/// (the grid's case from Python: p_max 121.07 against the LP's 116.37 MPa, +4.0 %, "converged");
/// the loop now also asks Ω_v to carry v·p_max to 5 % before it stops.
#[test]
fn a_small_given_displacement_iterates_to_the_lp() {
    let (a, approach) = (1.0, 1e-3);
    let n = 60;
    let body = clustered_half_space(a, n);
    let punch = RigidBody::fixed("punch", body.interface());
    let problem = InterfaceProblem::new(&body, &punch, &vec![-approach; n]).unwrap();
    let shape = GapShape::pointwise(body.interface());
    let optimisation = Optimisation::new(&problem, &shape, &Constant::new(1.0).unwrap()).unwrap();
    let solver = active_set();
    let iterated = optimisation
        .iterate(
            Mode::GivenDisplacement,
            &solver,
            &IterationSettings::default(),
        )
        .unwrap();
    let iterated = converged("iteration", iterated);
    let lp = optimisation
        .linear_programme(&solver, &LinearProgrammeSettings::default())
        .unwrap();
    let lp = converged("LP", lp);
    let least = iterated
        .pressure
        .iter()
        .fold(f64::INFINITY, |m, &p| m.min(p));
    eprintln!(
        "given displacement: iteration p_max {:.4} in {} passes, least p {:.4}; LP {:.4}",
        iterated.p_max,
        iterated.passes.len(),
        least,
        lp.p_max
    );
    assert!(
        (iterated.p_max / lp.p_max - 1.0).abs() < 0.005,
        "{} against {}",
        iterated.p_max,
        lp.p_max
    );
    assert!(least > 0.95 * iterated.p_max, "{least}");
}

/// A rigid flat punch of radius a under pressure p on an elastic half-space (axisymmetric
/// rings clustered at the edge), v = 1: the gap change that makes the pressure uniform is the
/// deflection difference of a uniformly loaded circle, Δh_max = 4(1 − ν²)pa(π/2 − 1)/(πE),
/// within 0.5 %, by the iteration and by the linear programme.
#[test]
fn constant_pressure_on_a_half_space() {
    let (a, p) = (10.0, 100.0);
    let n = 120;
    let body = clustered_half_space(a, n);
    let force = p * PI * a * a;
    let punch = RigidBody::pressed("punch", body.interface(), [0.0, 1.0, 0.0], force).unwrap();
    let problem = InterfaceProblem::new(&body, &punch, &vec![0.0; n]).unwrap();
    let shape = GapShape::pointwise(body.interface());
    let optimisation = Optimisation::new(&problem, &shape, &Constant::new(1.0).unwrap()).unwrap();
    // The closed form at the outermost ring's centre, whose average deflection the Galerkin
    // rings give.
    let exact = UniformCircle {
        radius: a,
        pressure: p,
        modulus: contact_modulus(&[Material::new(E, NU).unwrap()]),
    }
    .centre_minus_edge();
    let solver = active_set();
    let iterated = optimisation
        .iterate(Mode::GivenLoad, &solver, &iteration(1e-20, 10))
        .unwrap();
    let iterated = converged("iteration", iterated);
    let lp = optimisation
        .linear_programme(&solver, &LinearProgrammeSettings::default())
        .unwrap();
    let lp = converged("LP", lp);
    for (name, opt) in [("iteration", &iterated), ("LP", &lp)] {
        eprintln!(
            "half-space, {name}: p_max {:.6}, Δh_max {:+.3} % from the closed form",
            opt.p_max,
            100.0 * (opt.dh_max() / exact - 1.0)
        );
        assert!((opt.p_max / p - 1.0).abs() < 1e-6, "{name}: {}", opt.p_max);
        assert!(
            (opt.dh_max() / exact - 1.0).abs() < 0.005,
            "{name}: {} vs {exact}",
            opt.dh_max()
        );
    }
}

/// The same for a rigid strip of half-width a on a plane-stress half-plane: Δh_max =
/// 4pa·ln2/(πE) within 0.5 %.
#[test]
fn constant_pressure_on_a_half_plane() {
    let (a, p, thickness) = (5.0, 100.0, 10.0);
    let n = 160;
    let edges: Vec<f64> = (0..=n)
        .map(|k| -a * (PI * k as f64 / n as f64).cos())
        .collect();
    let body = HalfPlane::new(
        "half-plane",
        Material::new(E, NU).unwrap(),
        PlaneState::Stress,
        thickness,
        &edges,
        100.0,
    )
    .unwrap();
    let force = p * 2.0 * a * thickness;
    let strip = RigidBody::pressed("strip", body.interface(), [0.0, 1.0, 0.0], force).unwrap();
    let problem = InterfaceProblem::new(&body, &strip, &vec![0.0; n]).unwrap();
    let shape = GapShape::pointwise(body.interface());
    let optimisation = Optimisation::new(&problem, &shape, &Constant::new(1.0).unwrap()).unwrap();
    // Plane stress: the half-plane's modulus is E.
    let exact = FlamantStrip {
        half_width: a,
        pressure: p,
        modulus: E,
    }
    .centre_minus_edge();
    let solver = active_set();
    for (name, opt) in [
        (
            "iteration",
            optimisation.iterate(Mode::GivenLoad, &solver, &iteration(1e-20, 10)),
        ),
        (
            "LP",
            optimisation.linear_programme(&solver, &LinearProgrammeSettings::default()),
        ),
    ] {
        let opt = converged(name, opt.unwrap());
        eprintln!(
            "half-plane, {name}: Δh_max {:+.3} % from the closed form",
            100.0 * (opt.dh_max() / exact - 1.0)
        );
        assert!(
            (opt.dh_max() / exact - 1.0).abs() < 0.005,
            "{name}: {} vs {exact}",
            opt.dh_max()
        );
    }
}

/// Bad input is named: a controller above 1, a given load without a floating body.
#[test]
fn optimisation_errors_are_named() {
    let scene = paper::scene("paper-table2", 18, &[("sweep", None)]).unwrap();
    let problem = scene.cases()[0].problem().unwrap();
    // The base's face nodes and shape functions, the map Q of the paper's gap change.
    let shape = problem.pressure_basis().unwrap();
    let too_high = |_: [f64; 3]| 1.5;
    let e = Optimisation::new(&problem, shape, &too_high)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("controller") && e.contains("1.5"), "{e}");
    let opt = Optimisation::new(&problem, shape, &Constant::new(1.0).unwrap()).unwrap();
    let e = opt
        .iterate(Mode::GivenLoad, &active_set(), &iteration(1e-6, 10))
        .unwrap_err()
        .to_string();
    assert!(e.contains("no body floats"), "{e}");
}

/// The crowned roller's half-space: 20 × 21 cells of 0.5 × 0.04 mm over the roller's length
/// (10 mm) and ±0.4 mm across it, centred on the roller, the centre row on y = 0.
fn crowned_roller_grid() -> CylinderGrid {
    CylinderGrid::steel(20, 21, 0.5, 0.04, 10.0).unwrap()
}

/// A crown of the roller against Hertz's line contact: p_max is Hertz's p₀ within 2 %, and
/// p ≤ p_max on Ω_nv.
fn assert_hertzian_crown(
    name: &str,
    opt: &Optimum,
    regions: &[Region],
    hertz: f64,
    uncrowned: f64,
) {
    let over = regions
        .iter()
        .zip(&opt.pressure)
        .filter(|(region, _)| **region == Region::OmegaNv)
        .map(|(_, p)| p / opt.p_max - 1.0)
        .fold(f64::NEG_INFINITY, f64::max);
    eprintln!(
        "roller, {name}: p_max {:.1} MPa ({:+.2} % from Hertz's {hertz:.1}; uncrowned peak {uncrowned:.1}), \
         crown {:.3} µm, {} steps, largest p/p_max − 1 on Ω_nv {over:.2e}",
        opt.p_max,
        100.0 * (opt.p_max / hertz - 1.0),
        1e3 * opt.dh_max(),
        opt.passes.last().map_or(0, |r| r.k),
    );
    assert!((opt.p_max / hertz - 1.0).abs() < 0.02, "{name}");
    assert!(over < 1e-6, "{name}: {over}");
}

/// The load split reaches the LP's optimum `lp` itself, with the dense active set and with the
/// matrix-free solver: p_max and every Δh within 1e-6.
fn assert_load_split_reaches(optimisation: &Optimisation, lp: &Optimum) {
    for solver in [&active_set() as &dyn ContactSolver, &polonsky_keer()] {
        let name = solver.method();
        let split = optimisation
            .load_split(solver, &split_to(1e-10, 50))
            .unwrap();
        let split = converged(&format!("load split with {name}"), split);
        let dh_error = split
            .dh
            .iter()
            .zip(&lp.dh)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / lp.dh_max();
        eprintln!(
            "roller, load split with {name}: p_max {:.6} MPa (LP {:.6}), Δh off by {dh_error:.2e} of Δh_max, {} solves",
            split.p_max,
            lp.p_max,
            split.passes.len()
        );
        assert!((split.p_max / lp.p_max - 1.0).abs() < 1e-6, "{name}");
        assert!(dh_error < 1e-6, "{name}: {dh_error:e}");
    }
}

/// The bearing roller (§3.2, the two-dimensional region): a rigid cylinder of radius R and
/// length L pressed by W into an elastic half-space (a grid of cells), the profile changed
/// along the axis only (Δh_nv = f(Δh), [`GapShape::extruded`]). Ω_v is the centre line,
/// where p = p_max is prescribed; the rest of the strip is Ω_nv (d ≥ 0, p ≤ p_max). The crowned
/// roller carries a uniform line load W/L with Hertz's half-width along its whole length, so
/// p_max is the line-contact value p₀ = √(W E* / (π L R)) (within 2 %: the grid samples the
/// ellipse at 0.04 mm against b ≈ 0.26 mm), far below the uncrowned roller's end peak; the
/// iteration and the LP agree on p_max and the crown within 0.5 %, and p ≤ p_max on Ω_nv.
#[test]
fn crowned_roller_on_a_half_space() {
    let (radius, load, length) = (10.0, 12_000.0, 10.0);
    let grid = crowned_roller_grid();
    let iface = grid.body.interface();
    let roller = RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], load).unwrap();
    let line = HertzLine {
        radius,
        modulus: contact_modulus(&[Material::new(E, NU).unwrap()]),
    };
    let problem = InterfaceProblem::new(&grid.body, &roller, &grid.gap).unwrap();
    let regions = grid.centre_row(Region::OmegaNv);
    let shape = GapShape::extruded(iface, 0).unwrap();
    let optimisation = Optimisation::new(&problem, &shape, &Constant::new(1.0).unwrap())
        .unwrap()
        .with_regions(regions.clone())
        .unwrap();
    let hertz = line.peak_pressure(load / length);
    let solver = active_set();
    let uncrowned = solve(&solver, &problem).p_max();
    let iterated = optimisation
        .iterate(Mode::GivenLoad, &solver, &iteration(1e-12, 100))
        .unwrap();
    let iterated = converged("iteration", iterated);
    let lp = optimisation
        .linear_programme(&solver, &LinearProgrammeSettings::default())
        .unwrap();
    let lp = converged("LP", lp);
    for (name, opt) in [("iteration", &iterated), ("LP", &lp)] {
        assert_hertzian_crown(name, opt, &regions, hertz, uncrowned);
    }
    assert!(uncrowned > 1.25 * hertz, "{uncrowned}");
    assert!((iterated.p_max / lp.p_max - 1.0).abs() < 0.005);
    assert!((iterated.dh_max() / lp.dh_max() - 1.0).abs() < 0.005);
    assert_load_split_reaches(&optimisation, &lp);
}

/// The straight roller on 100 × 53 cells (10 across Hertz's half-width), matrix-free: the
/// centre carries less than the nominal 544.6 N/mm (the ends take more on a half-space), and
/// its peak is Hertz's p₀ for the local centre line load within 0.2 % (measured −0.009 %; the
/// nominal p₀ = 2000.1 MPa is 5 % off, the wrong test).
#[test]
fn straight_roller_against_local_line_contact() {
    let CylinderGrid { body, gap: h, .. } = Roller::grid(100, 53).unwrap();
    let roller = RigidBody::pressed("roller", body.interface(), [0.0, 0.0, 1.0], Roller::LOAD);
    let roller = roller.unwrap();
    let problem = InterfaceProblem::new(&body, &roller, &h).unwrap();
    let st = solve(&polonsky_keer(), &problem);
    let iface = body.interface();
    let dx = 0.1;
    let centre: Vec<usize> = (0..iface.len())
        .filter(|&i| iface.points()[i][0].abs() < dx)
        .collect();
    let q = centre
        .iter()
        .map(|&i| iface.weights()[i] * st.pressure[i])
        .sum::<f64>()
        / (2.0 * dx);
    let p = centre.iter().map(|&i| st.pressure[i]).fold(0.0, f64::max);
    let p0 = Roller::line().peak_pressure(q);
    eprintln!(
        "straight roller: centre {q:.2} N/mm, p {p:.1} MPa against local Hertz {p0:.1} ({:+.3} %)",
        100.0 * (p / p0 - 1.0)
    );
    assert!(q < 0.97 * 544.6, "centre line load {q}");
    assert!((p / p0 - 1.0).abs() < 2e-3, "{p} vs {p0}");
}

/// The roller's crown on `grid` for the cubic controller of L1 = `l1` \[mm\] (L2 half the
/// length), Ω_v the centre row: the load split with Polonsky–Keer to 1e-8, converged.
fn roller_crown(grid: &CylinderGrid, l1: f64) -> Optimum {
    roller_crown_by(grid, l1, &polonsky_keer(), &Silent)
}

/// [`roller_crown`] by `solver`, observed by `observer`.
fn roller_crown_by(
    grid: &CylinderGrid,
    l1: f64,
    solver: &dyn ContactSolver,
    observer: &dyn Observer,
) -> Optimum {
    let iface = grid.body.interface();
    let roller = RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], Roller::LOAD).unwrap();
    let problem = InterfaceProblem::new(&grid.body, &roller, &grid.gap).unwrap();
    let v = Profile::cubic(l1, 0.5 * Roller::LENGTH).unwrap();
    let shape = GapShape::extruded(iface, 0).unwrap();
    let opt = Optimisation::new(&problem, &shape, &v)
        .unwrap()
        .with_regions(grid.centre_row(Region::OmegaNv))
        .unwrap()
        .with_observer(observer)
        .load_split(solver, &split_to(1e-8, 50))
        .unwrap();
    converged("load split", opt)
}

/// The crown of the roller on 100 × 53 cells, L1 = 3 mm, by the load split with Polonsky–Keer:
/// the centre row follows v·p_max within 1e-6 wherever v > 1 %, Δh ≥ 0 and zero at x = 0, and
/// p_max is the 400 × 209 grid's 2316.94 MPa (examples/roller_scaling) within 0.05 %.
#[test]
fn optimised_roller_crown_by_the_load_split() {
    let grid = Roller::grid(100, 53).unwrap();
    let opt = roller_crown(&grid, 3.0);
    let iface = grid.body.interface();
    let regions = grid.centre_row(Region::OmegaNv);
    let v = Profile::cubic(3.0, 5.0).unwrap();
    let shape = GapShape::extruded(iface, 0).unwrap();
    let points = iface.points();
    let miss = (0..iface.len())
        .filter(|&i| regions[i] == Region::OmegaV && v.value(points[i]) > 0.01)
        .map(|i| (opt.pressure[i] / (v.value(points[i]) * opt.p_max) - 1.0).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "roller crown 100 × 53: p_max {:.2} MPa, Δh_max {:.3} µm, {} solves, miss {miss:.1e}",
        opt.p_max,
        1e3 * opt.dh_max(),
        opt.passes.len()
    );
    assert!(miss < 1e-6, "{miss}");
    assert!(opt.dh.iter().all(|&d| d >= -1e-12), "Δh < 0");
    let centre = shape
        .nodes()
        .iter()
        .position(|x| x[0].abs() < 0.06)
        .unwrap();
    assert!(opt.dh[centre].abs() < 1e-12);
    assert!((opt.p_max / 2316.94 - 1.0).abs() < 5e-4, "{}", opt.p_max);
}

/// The load split's updates do not grow with the grid: the roller's crown for L1 = 0, 3 and
/// 5 mm on 50 × 27 to 400 × 209 cells converges to 1e-8 in at most 10 updates on every grid
/// (the exponents read from each column's contact; with exponents from secants of the first
/// updates L1 = 3 mm took 11 on 50 × 27, and L1 = 5 mm 12 on 200 × 105 and 16 on 800 × 417),
/// and in no more on 400 × 209 (and 800 × 417 for L1 = 0 and 3 mm) than on 200 × 105
/// (L1 = 0: 9, 9, 8; L1 = 3 mm: 9, 9, 9; L1 = 5 mm: 10, 10): the updates of exact solves,
/// which the inexact solves' forcing of 5·10⁻⁴ keeps (with 10⁻³, L1 = 5 mm took 9 on
/// 200 × 105 and 10 on 400 × 209, which this would catch). The columns a few points
/// wide at the roller's ends take their own contact's exponent (with the line contact's ½
/// there, 800 × 417 took 11 updates against 9).
#[test]
fn the_load_splits_updates_do_not_grow_with_the_grid() {
    for l1 in [0.0, 3.0, 5.0] {
        let finest = if l1 < 5.0 { 5 } else { 4 };
        let grids = [(50, 27), (100, 53), (200, 105), (400, 209), (800, 417)];
        let mut updates = vec![];
        for &(nx, ny) in &grids[..finest] {
            let opt = roller_crown(&Roller::grid(nx, ny).unwrap(), l1);
            eprintln!("L1 = {l1} mm, {nx} × {ny}: {} updates", opt.passes.len());
            assert!(opt.passes.len() <= 10, "L1 = {l1}, {nx} × {ny}");
            updates.push(opt.passes.len());
        }
        assert!(
            updates[2..].iter().all(|&u| u <= updates[2]),
            "L1 = {l1}: {updates:?}"
        );
    }
}

/// Each contact solve's tolerance: that of its last step (the events at level 1; the last of
/// a solve says how it ended).
#[derive(Default)]
struct SolveTolerances(std::sync::Mutex<(f64, Vec<f64>)>);

impl Observer for SolveTolerances {
    fn observe(&self, e: &Event) -> Flow {
        let mut seen = self.0.lock().unwrap();
        match (e.level, e.end) {
            (1, None) => seen.0 = e.tolerance,
            (1, Some(_)) => {
                let step = seen.0;
                seen.1.push(step);
            }
            _ => {}
        }
        Flow::Continue
    }
}

/// The load split's inexact solves: the roller's crown on 100 × 53 cells (L1 = 3 mm) solved
/// with Polonsky–Keer's tolerance loosened to 10⁻³ of each update's miss is the crown of exact
/// solves (p_max within 10⁻⁹, Δh within 10⁻⁹ of its largest: the split's tolerance is 10⁻⁸)
/// in no more updates and under two thirds of their conjugate-gradient steps (56 against 91);
/// the updates before the last solve to looser tolerances, the last to at most 10⁻² of the
/// split's tolerance.
#[test]
fn the_load_splits_inexact_solves_keep_its_optimum_in_fewer_steps() {
    let grid = Roller::grid(100, 53).unwrap();
    let tolerances = SolveTolerances::default();
    let loose = roller_crown_by(&grid, 3.0, &polonsky_keer(), &tolerances);
    let exact = roller_crown_by(&grid, 3.0, &Exact(polonsky_keer()), &Silent);
    let steps = |o: &Optimum| o.passes.iter().map(|p| p.iterp).sum::<usize>();
    eprintln!(
        "inexact: {} updates, {} steps; exact: {} updates, {} steps",
        loose.passes.len(),
        steps(&loose),
        exact.passes.len(),
        steps(&exact)
    );
    assert!((loose.p_max / exact.p_max - 1.0).abs() < 1e-9);
    let dh = loose.dh.iter().zip(&exact.dh);
    let worst = dh.map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    assert!(worst < 1e-9 * exact.dh_max(), "{worst}");
    assert!(loose.passes.len() <= exact.passes.len());
    assert!(3 * steps(&loose) < 2 * steps(&exact));
    let tolerances = tolerances.0.into_inner().unwrap().1;
    let last = *tolerances.last().unwrap();
    assert!(last <= 1e-2 * 1e-8, "{tolerances:?}");
    let own = PolonskyKeerSettings::TOLERANCE;
    assert!(tolerances.iter().filter(|&&t| t > own).count() >= loose.passes.len() / 2);
}

/// One load case of the roller's envelope: the `nominal` problem with its load times `factor`
/// and the roller tilted by `tilt` \[rad\] about the centre (the initial gap `h` plus tilt·x).
fn roller_case<'a>(
    nominal: &InterfaceProblem<'a>,
    h: &[f64],
    factor: f64,
    tilt: f64,
) -> InterfaceProblem<'a> {
    let mut modes = nominal.modes().to_vec();
    modes[0].load *= factor;
    let gap: Vec<f64> = h
        .iter()
        .zip(nominal.interface().points())
        .map(|(h, x)| h + tilt * x[0])
        .collect();
    nominal
        .with_modes(modes)
        .unwrap()
        .with_initial_gap(&gap)
        .unwrap()
}

/// The worst case's peak pressure \[MPa\] over `cases` with `gap_change` added to each initial
/// gap, by Polonsky–Keer.
fn worst_case(cases: &[&InterfaceProblem], gap_change: &[f64]) -> f64 {
    cases
        .iter()
        .map(|c| {
            let gap: Vec<f64> = c
                .initial_gap()
                .iter()
                .zip(gap_change)
                .map(|(a, b)| a + b)
                .collect();
            solve(&polonsky_keer(), &c.with_initial_gap(&gap).unwrap()).p_max()
        })
        .fold(0.0, f64::max)
}

/// No case's pressure in `states` exceeds v·p_max anywhere, and their envelope closes on
/// v·p_max on Ω_v within 1e-6 of p_max.
fn assert_envelope_closes(
    iface: &Interface,
    v: &Profile,
    regions: &[Region],
    p_max: f64,
    states: &[&[f64]],
) {
    let mut envelope = vec![0.0f64; iface.len()];
    for p in states {
        for i in 0..iface.len() {
            let allowed = v.value(iface.points()[i]) * p_max;
            assert!(p[i] <= allowed + 1e-6 * p_max, "{} > {allowed}", p[i]);
            envelope[i] = envelope[i].max(p[i]);
        }
    }
    let miss = (0..iface.len())
        .filter(|&i| regions[i] == Region::OmegaV)
        .map(|i| (envelope[i] - v.value(iface.points()[i]) * p_max).abs() / p_max)
        .fold(0.0, f64::max);
    assert!(miss < 1e-6, "{miss}");
}

/// The crown `gap_change` is a minimax optimum of `cases`: each of eight symmetric bumps of
/// ±0.3 µm (at |x| = 0.5, 2, 3.5, 4.5 mm) raises the worst case above its `p_max`.
fn assert_bumps_raise_the_worst_case(
    cases: &[&InterfaceProblem],
    iface: &Interface,
    gap_change: &[f64],
    p_max: f64,
) {
    for centre in [0.5, 2.0, 3.5, 4.5] {
        for amplitude in [-3e-4, 3e-4] {
            let bumped: Vec<f64> = iface
                .points()
                .iter()
                .zip(gap_change)
                .map(|(x, d)| d + amplitude * (-((x[0].abs() - centre) / 0.5).powi(2)).exp())
                .collect();
            let w = worst_case(cases, &bumped);
            eprintln!("bump {amplitude:+.0e} mm at |x| = {centre}: worst {w:.2} MPa vs {p_max:.2}");
            assert!(
                w > p_max,
                "a bump at {centre} lowers the worst case: {w} < {p_max}"
            );
        }
    }
}

/// The robust crown of the roller on 80 × 41 cells for the envelope {1.5 Q tilted ±2′, Q,
/// ½ Q} by the envelope load split (symmetric crown, design case 1.5 Q at +2′, flat
/// controller up to L1 = 4.5 mm): no case exceeds v·p_max anywhere, the envelope of the cases'
/// centre rows closes on v·p_max, and the crown is a minimax optimum: each of eight symmetric
/// bumps of ±0.3 µm raises the worst case's p_max (measured +0.4 to +1.8 %). The single-load
/// crown at Q, the comparison, has a worst case 7.5 % higher (2861.5 against 2661.4 MPa).
#[test]
fn robust_roller_crown_over_an_envelope() {
    let grid = Roller::grid(80, 41).unwrap();
    let (iface, h) = (grid.body.interface(), &grid.gap);
    let gamma = (2.0f64 / 60.0).to_radians();
    let roller = RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], Roller::LOAD).unwrap();
    let nominal = InterfaceProblem::new(&grid.body, &roller, h).unwrap();
    let design = roller_case(&nominal, h, 1.5, gamma);
    let others = [
        roller_case(&nominal, h, 1.5, -gamma),
        roller_case(&nominal, h, 1.0, 0.0),
        roller_case(&nominal, h, 0.5, 0.0),
    ];
    let regions = grid.centre_row(Region::OmegaNv);
    let v = Profile::cubic(4.5, 5.0).unwrap();
    let shape = GapShape::symmetric(iface, 0).unwrap();
    let pk = polonsky_keer();
    let robust = Optimisation::new(&design, &shape, &v)
        .unwrap()
        .with_regions(regions.clone())
        .unwrap()
        .envelope_split(&others, &pk, &split_to(1e-7, 60))
        .unwrap();
    assert!(
        robust.optimum.is_converged(),
        "envelope split: {}",
        robust.optimum.termination
    );
    let p_max = robust.optimum.p_max;
    let states: Vec<&[f64]> = std::iter::once(robust.optimum.pressure.as_slice())
        .chain(robust.cases.iter().map(|s| s.pressure.as_slice()))
        .collect();
    assert_envelope_closes(iface, &v, &regions, p_max, &states);
    let all: Vec<&InterfaceProblem> = std::iter::once(&design).chain(&others).collect();
    let at_optimum = worst_case(&all, &robust.optimum.gap_change);
    assert!(
        (at_optimum / p_max - 1.0).abs() < 1e-6,
        "{at_optimum} vs {p_max}"
    );
    assert_bumps_raise_the_worst_case(&all, iface, &robust.optimum.gap_change, p_max);
    let single = Optimisation::new(&nominal, &GapShape::extruded(iface, 0).unwrap(), &v)
        .unwrap()
        .with_regions(regions)
        .unwrap()
        .load_split(&pk, &split_to(1e-8, 50))
        .unwrap();
    let single = converged("single-load split", single);
    let single_worst = worst_case(&all, &single.gap_change);
    eprintln!(
        "robust crown 80 × 41: worst {p_max:.2} MPa in {} updates; single-load crown {:.2} at Q, \
         worst {single_worst:.2}",
        robust.optimum.passes.len(),
        single.p_max
    );
    assert!(single_worst > 1.03 * p_max, "{single_worst} vs {p_max}");
}

/// The envelope split with levels against the load split it must reduce to: a further case
/// identical to the design case at level s is the design case's pressure over s, so at
/// s = 0.8 the envelope is p/0.8 and the crown is the load split's with p_max 1/0.8 times
/// its, and at s = 1.25 it never leads and the optimum is the load split's (24 × 9 cells of
/// the bearing roller tilted by 2′, both to 1e-5 of p_max and of the crown's largest drop:
/// ten times the contact solves' accuracy, as the case is solved apart from the columns). A
/// level of 0 or a missing one is refused.
#[test]
fn envelope_levels_reduce_to_the_load_split() {
    let grid = Roller::grid(24, 9).unwrap();
    let iface = grid.body.interface();
    let roller = RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], Roller::LOAD).unwrap();
    let nominal = InterfaceProblem::new(&grid.body, &roller, &grid.gap).unwrap();
    let design = roller_case(&nominal, &grid.gap, 1.5, (2.0f64 / 60.0).to_radians());
    let v = Profile::cubic(4.5, 5.0).unwrap();
    let shape = GapShape::symmetric(iface, 0).unwrap();
    let pk = polonsky_keer();
    let opt = Optimisation::new(&design, &shape, &v)
        .unwrap()
        .with_regions(grid.centre_row(Region::OmegaNv))
        .unwrap();
    let single = converged(
        "load split",
        opt.load_split(&pk, &split_to(1e-9, 60)).unwrap(),
    );
    for (s, ratio) in [(0.8, 1.0 / 0.8), (1.25, 1.0)] {
        let found = opt
            .envelope_split_levels(
                std::slice::from_ref(&design),
                &[s],
                &pk,
                &split_to(1e-9, 60),
            )
            .unwrap();
        let optimum = converged("levels", found.optimum);
        let p = optimum.p_max / (ratio * single.p_max);
        let dh = dh_difference(&optimum, &single);
        eprintln!(
            "level {s}: p_max {:.3} MPa (ratio {p:.9}), crown off by {dh:.2e}",
            optimum.p_max
        );
        assert!((p - 1.0).abs() < 1e-5, "level {s}: {p}");
        assert!(dh < 1e-5, "level {s}: {dh}");
    }
    for levels in [&[0.0][..], &[]] {
        let e = opt
            .envelope_split_levels(
                std::slice::from_ref(&design),
                levels,
                &pk,
                &split_to(1e-9, 60),
            )
            .unwrap_err()
            .to_string();
        assert!(e.contains("levels"), "{e}");
    }
}

/// The bearing roller (L1 = 3 mm) on `nx` × `ny` cells: its optimisation with Ω_v the centre
/// row and the rest `outside`, run by `run`.
fn with_bearing_roller<T>(
    nx: usize,
    ny: usize,
    omega_v: impl Fn(&[f64; 3], f64) -> bool,
    run: impl FnOnce(&Optimisation, &Interface) -> T,
) -> T {
    let grid = Roller::grid(nx, ny).unwrap();
    let iface = grid.body.interface();
    let roller = RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], Roller::LOAD).unwrap();
    let problem = InterfaceProblem::new(&grid.body, &roller, &grid.gap).unwrap();
    let regions = iface
        .points()
        .iter()
        .map(|x| match omega_v(x, grid.dy) {
            true => Region::OmegaV,
            false => Region::OmegaNv,
        })
        .collect();
    let v = Profile::cubic(3.0, 5.0).unwrap();
    let shape = GapShape::extruded(iface, 0).unwrap();
    let opt = Optimisation::new(&problem, &shape, &v)
        .unwrap()
        .with_regions(regions)
        .unwrap();
    run(&opt, iface)
}

/// The largest |Δh_a − Δh_b| over the design nodes, relative to the largest Δh_b.
fn dh_difference(a: &Optimum, b: &Optimum) -> f64 {
    a.dh.iter()
        .zip(&b.dh)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / b.dh_max()
}

/// The linear programme (3.5) on the bearing roller where its relaxed first pass used to stall
/// (40 × 21 and 26 × 31 cells, L1 = 3 mm): it solves them in one pass and equals the load
/// split with the matrix-free solver, p_max and every Δh within 1e-6 (measured 1e-11 and
/// 4e-9: the programme's one point is the closed-form solution of its contact set, the split
/// a fixed point reached to 1e-8), with p ≤ v·p_max on Ω_nv. The 100 × 53 grid is in
/// `cargo run --release --example linear_programme -- roller large`.
#[test]
fn roller_programme_equals_the_load_split() {
    for (nx, ny) in [(40, 21), (26, 31)] {
        with_bearing_roller(
            nx,
            ny,
            |x, dy| x[1].abs() < 0.5 * dy,
            |opt, _| {
                let split = opt.load_split(&polonsky_keer(), &split_to(1e-8, 50));
                let split = converged("load split", split.unwrap());
                let lp =
                    opt.linear_programme(&polonsky_keer(), &LinearProgrammeSettings::default());
                let lp = converged("LP", lp.unwrap());
                let (dp, ddh) = (lp.p_max / split.p_max - 1.0, dh_difference(&lp, &split));
                let excess = lp.omega_nv_excess.unwrap();
                eprintln!(
                    "roller {nx} × {ny}: LP p_max {:.4} MPa in {} pass, {dp:+.1e} from the split, \
                 Δh {ddh:.1e}; largest p − v·p_max on Ω_nv {excess:.3} MPa",
                    lp.p_max,
                    lp.passes.len()
                );
                assert_eq!(lp.passes.len(), 1);
                assert!(dp.abs() < 1e-6 && ddh < 1e-6, "{dp:e} {ddh:e}");
                assert!(excess <= 1e-6 * lp.p_max, "{excess}");
                assert!(split.omega_nv_excess.unwrap() <= 1e-6 * split.p_max);
            },
        );
    }
}

/// Ω_v a row off the roller's centre (y = 2 cells): the centre row, in Ω_nv, carries more than
/// Ω_v in every column, and Ω_v fixes each column's gap change, so no crown keeps p ≤ v·p_max
/// there: (3.5) has no feasible point. The LP, the load split and the iteration each end as
/// infeasible, naming χ ≥ 0 on Ω_nv, and report the excess.
#[test]
fn an_infeasible_programme_is_reported_as_such() {
    with_bearing_roller(
        20,
        21,
        |x, dy| (x[1] - 2.0 * dy).abs() < 0.5 * dy,
        |opt, _| {
            let pk = polonsky_keer();
            let lp = opt
                .linear_programme(&pk, &LinearProgrammeSettings::default())
                .unwrap();
            let split = opt.load_split(&pk, &split_to(1e-8, 50)).unwrap();
            let iterated = opt
                .iterate(Mode::GivenLoad, &pk, &iteration(1e-10, 100))
                .unwrap();
            for (name, o) in [
                ("LP", &lp),
                ("load split", &split),
                ("iteration", &iterated),
            ] {
                let excess = o.omega_nv_excess.unwrap();
                eprintln!("{name}: {} (excess {excess:.1} MPa)", o.termination);
                match &o.termination {
                    Termination::Infeasible { cause } => {
                        assert!(cause.on_omega_nv(), "{name}: {cause}")
                    }
                    other => panic!("{name}: {other}"),
                }
                assert!(o.pressure.iter().all(|p| p.is_finite()), "{name}");
            }
            for o in [&split, &iterated] {
                assert!(o.omega_nv_excess.unwrap() > 0.01 * o.p_max);
            }
        },
    );
}

/// The bundled steel punch on its aluminium base with the outermost Gauss point (r = 19.89 mm)
/// left out of Ω_v, by `method`: one report per case (the base clamped, held axially, the
/// materials swapped).
fn rim_in_omega_nv(method: &str) -> Vec<CaseReport> {
    let method = format!("\"{method}\"");
    let edits = [
        ("optimisation.omega_v.radius_mm", Some("19.8")),
        ("optimisation.method", Some(method.as_str())),
    ];
    let scene = Scene::bundled_with("steel-on-aluminium", &edits).unwrap();
    let reports: Vec<CaseReport> = scene.run().map(|r| r.unwrap()).collect();
    for r in &reports {
        assert!(r.is_solved(), "{method}, {}: {}", r.label, r.termination);
    }
    reports
}

/// The rim of the punch in Ω_nv, where the iteration of §3.2 once left an edge peak of 236.6
/// MPa against a bound of 75.6: the iteration prescribes χ = 0 where p passes v·p̂ (the rim
/// joins its fit) and the LP (3.5) bounds it, and both find the optimum of the whole face in
/// Ω_v: the equilibrium level p̂ = 50·πR²/∫v dA = 86.957 MPa (to its five digits; a free rim
/// carrying more than v·p̂ lowers it), the same p̂ within 1e-6 (measured 1e-15), p ≤ v·p̂ on
/// Ω_nv within 1e-6 of p̂, and the same gap change within 1e-6 of Δh_max (measured 4e-12).
#[test]
fn rim_in_omega_nv_iteration_and_programme_agree() {
    let iterated = rim_in_omega_nv("given_load");
    let lp = rim_in_omega_nv("linear_programme");
    for (a, b) in iterated.iter().zip(&lp) {
        let (pa, pb) = (a.bound_p_max_mpa.unwrap(), b.bound_p_max_mpa.unwrap());
        let (ea, eb) = (
            a.omega_nv_excess_mpa.unwrap(),
            b.omega_nv_excess_mpa.unwrap(),
        );
        let top = b.dh_max_um.unwrap();
        let ddh = a
            .interface
            .iter()
            .zip(&b.interface)
            .map(|(x, y)| (x.dh_um - y.dh_um).abs())
            .fold(0.0, f64::max)
            / top;
        eprintln!(
            "{}: p̂ {pa:.6} (iteration) {pb:.6} (LP) MPa; p − v·p̂ on Ω_nv {ea:.2e} / {eb:.2e} \
             MPa; Δh_max {top:.4} µm, apart by {ddh:.1e}",
            a.label
        );
        for p in [pa, pb] {
            assert!((p / 86.957 - 1.0).abs() < 1e-4, "{p}");
        }
        assert!((pa / pb - 1.0).abs() < 1e-6, "{pa} {pb}");
        assert!(ea <= 1e-6 * pa && eb <= 1e-6 * pb, "{ea} {eb}");
        assert!(ddh < 1e-6, "{ddh:e}");
    }
}

/// A strip of 1000 points (40 × 25 cells of 0.25 × 0.04 mm under the roller of R = 10 mm and
/// 12 kN, v = 1) whose centre row is Ω_v and whose other points are only in contact
/// (Region::Contact: p ≥ 0, d ≥ 0, pd = 0, no χ), their gap following their column. The
/// relaxed first pass of the old programme was unbounded here (it ended after 22 s in 'did
/// not converge'); the LP now equals the load split (p_max and Δh within 1e-6, measured 1e-12)
/// and the iteration of §3.2 (within 1e-5: the iteration contracts slowly, TOLH 1e-16 mm²).
#[test]
fn points_only_in_contact_on_a_strip() {
    let strip = CylinderGrid::steel(40, 25, 0.25, 0.04, 10.0).unwrap();
    let iface = strip.body.interface();
    let roller = RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], 12_000.0).unwrap();
    let problem = InterfaceProblem::new(&strip.body, &roller, &strip.gap).unwrap();
    let regions = strip.centre_row(Region::Contact);
    let shape = GapShape::extruded(iface, 0).unwrap();
    let opt = Optimisation::new(&problem, &shape, &Constant::new(1.0).unwrap())
        .unwrap()
        .with_regions(regions)
        .unwrap();
    let pk = polonsky_keer();
    let lp = opt.linear_programme(&pk, &LinearProgrammeSettings::default());
    let lp = converged("LP", lp.unwrap());
    let split = converged("split", opt.load_split(&pk, &split_to(1e-8, 50)).unwrap());
    let iterated = opt.iterate(Mode::GivenLoad, &pk, &iteration(1e-16, 300));
    let iterated = converged("iteration", iterated.unwrap());
    for (name, o, within) in [("split", &split, 1e-6), ("iteration", &iterated, 1e-5)] {
        let (dp, ddh) = (o.p_max / lp.p_max - 1.0, dh_difference(o, &lp));
        eprintln!("strip of 1000, {name}: p_max {dp:+.1e} from the LP's, Δh {ddh:.1e}");
        assert!(dp.abs() < within && ddh < within, "{name}: {dp:e} {ddh:e}");
    }
    assert_eq!(lp.omega_nv_excess, None);
}
