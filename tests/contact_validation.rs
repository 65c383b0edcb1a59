//! Contact solvers on finite-element bodies against closed forms (Boussinesq/Sneddon flat
//! punch, Hertz), against each other, and over a sweep of the penalty parameter.

use std::path::Path;

use contopt::core::FullSystem;
use contopt::fem::coupled::JointSystem;
use contopt::fem::{Analysis, Component, ElementKind, FeBody, FeModel, Mesh, Spacing};
use contopt::prelude::*;
use contopt::scene::{FacesZone, FeBase, FePunch, Format, PunchLoad, Support};
use contopt_validation::closed_form::{contact_modulus, FlatPunch, HertzSphere};
use contopt_validation::fixtures::hertz_on_block;

const E: f64 = 2.0e5;
const NU: f64 = 0.3;

/// The paper's punch on its base as the bundled scene `name` defines it (`paper-table1`:
/// axisymmetric, 100 MPa; `paper-table2`: axisymmetric, pressed down by 0.05 mm;
/// `paper-table3`: plane stress, 100 MPa), with `elements` quadratic elements across the
/// contact radius and as many layers through each body: its contact problem, the gap zero.
fn paper(name: &str, elements: usize) -> InterfaceProblem<'static> {
    let scene = contopt_validation::paper::scene(name, elements, &[("sweep", None)]).unwrap();
    scene.cases()[0].problem().unwrap()
}

/// A rigid flat punch of radius `a` pressed by `force` into the half-space stand-in block of
/// the scene kind `fe_block` (radius and depth `size`, clamped bottom), with `nz` uniform
/// faces under the punch: the contact problem.
fn punch_on_block(a: f64, nz: usize, size: f64, force: f64) -> InterfaceProblem<'static> {
    let text = format!(
        r#"name = "punch-on-block"
[contact]
zone = {{ kind = "faces", analysis = "axisymmetric", radius_mm = {a:?}, elements = {nz} }}
gap = {{ kind = "flat_punch", radius_mm = {a:?} }}
load = {{ force_n = {force:?} }}
[[body]]
kind = "fe_block"
material = {{ e_mpa = {E:?}, nu = {NU:?} }}
size_mm = {size:?}
[[body]]
kind = "rigid"
name = "punch"
"#
    );
    let scene = Scene::parse(&text, Format::Toml, Path::new("punch-on-block")).unwrap();
    scene.cases()[0].problem().unwrap()
}

/// `solver`'s solution of `problem`, which must have met its tolerance.
fn solve(solver: &dyn ContactSolver, problem: &InterfaceProblem) -> ContactState {
    let st = solver.solve(problem).unwrap();
    assert!(st.is_converged(), "{}: {}", st.method, st.termination);
    st
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// A rigid flat punch of radius a pressed by F into a large block: away from the edge the
/// pressure is Sneddon's F / (2πa√(a² − r²)), and the approach tends to the half-space value
/// F(1 − ν²)/(2aE) as the block grows (its clamped bottom makes it stiffer).
#[test]
fn flat_punch_matches_sneddon() {
    let (a, f) = (10.0, 1e4);
    let sneddon = FlatPunch {
        radius: a,
        modulus: contact_modulus(&[Material::new(E, NU).unwrap()]),
    };
    let half_space = sneddon.approach(f);
    let active_set = ActiveSet::new(ActiveSetSettings::default()).unwrap();
    let mut ratios = vec![];
    for size in [20.0 * a, 40.0 * a] {
        let problem = punch_on_block(a, 40, size, f);
        let st = solve(&active_set, &problem);
        let mut worst: f64 = 0.0;
        for (i, x) in problem.interface().points().iter().enumerate() {
            if x[0] < 0.8 * a {
                let exact = sneddon.pressure(f, x[0]);
                worst = worst.max((st.pressure[i] / exact - 1.0).abs());
            }
        }
        assert!(
            worst < 0.02,
            "size {size}: pressure off Sneddon's by {worst:.4} for r < 0.8a"
        );
        assert!((problem.interface().resultant(&st.pressure) - f).abs() < 1e-9 * f);
        ratios.push(st.approach().unwrap() / half_space);
    }
    // Measured: 0.956 (20a) and 0.972 (40a): within 5 % and closing in on the half-space.
    assert!(
        ratios[0] > 0.94 && ratios[0] < ratios[1] && ratios[1] < 1.0,
        "approach / half-space: {ratios:?}"
    );
}

/// Hertz's rigid sphere of radius R = 100 mm on the steel block.
fn steel_sphere() -> HertzSphere {
    HertzSphere {
        radius: 100.0,
        modulus: contact_modulus(&[Material::new(E, NU).unwrap()]),
    }
}

/// Hertz: a rigid sphere of radius R = 100 mm pressed into the block (1.5 mm zone of 45
/// faces, 30 mm block) with the force that gives a = 1 mm (the benchmarks' fixture). p₀ and a
/// are fitted from p² = p₀²(1 − r²/a²) on r < 0.8a.
fn fit_hertz(interface: &Interface, st: &ContactState) -> (f64, f64) {
    let (mut sx, mut sy, mut sxx, mut sxy, mut k) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (i, x) in interface.points().iter().enumerate() {
        if x[0] < 0.8 {
            let (r2, y) = (x[0] * x[0], st.pressure[i].powi(2));
            sx += r2;
            sy += y;
            sxx += r2 * r2;
            sxy += r2 * y;
            k += 1.0;
        }
    }
    let slope = (k * sxy - sx * sy) / (k * sxx - sx * sx);
    let intercept = (sy - slope * sx) / k;
    (intercept.sqrt(), (-intercept / slope).sqrt())
}

#[test]
fn hertz_sphere_and_solver_agreement() {
    let problem = hertz_on_block(45).unwrap();
    let force = steel_sphere().force(1.0);
    assert!((problem.load()[0] + force).abs() < 1e-12 * force);
    let p0 = steel_sphere().peak_pressure(1.0);
    let reference = solve(&Qp::new(QpSettings::default()).unwrap(), &problem);
    // Tolerances: the active set and the QP solve the same QP from different starts (1e-7);
    // the augmented Lagrangian to the issue's 1e-6; the penalty within its O(1/c) error.
    let solvers = [
        (SolverSettings::Qp(QpSettings::default()), 0.0),
        (
            SolverSettings::ActiveSet(ActiveSetSettings::default()),
            1e-7,
        ),
        (
            SolverSettings::AugmentedLagrangian(AugmentedLagrangianSettings::new(E * 1e4)),
            1e-6,
        ),
        (
            SolverSettings::Penalty(PenaltySettings {
                c_mpa_per_mm: E * 1e6,
            }),
            1e-4,
        ),
    ];
    for (settings, tol) in solvers {
        let solver = settings.build().unwrap();
        let name = solver.method();
        let st = solve(solver.as_ref(), &problem);
        let (p0_fe, a_fe) = fit_hertz(problem.interface(), &st);
        assert!(
            (p0_fe / p0 - 1.0).abs() < 0.01 && (a_fe - 1.0).abs() < 0.01,
            "{name}: p0 {p0_fe} (Hertz {p0}), a {a_fe} (Hertz 1)"
        );
        assert!(st.residuals.equilibrium < 1e-6 * force);
        let dp = max_diff(&st.pressure, &reference.pressure) / reference.p_max();
        assert!(
            dp <= tol,
            "{name}: pressure differs from the QP by {dp:e} of p_max"
        );
        assert_eq!(st.active, reference.active, "{name}");
    }
}

/// The penalty parameter sweep c = E·10ᵏ, k = 0…12, on the paper's axisymmetric punch
/// under 100 MPa (18 contact elements), with plain Uzawa steps. The paper's claim: the
/// augmented Lagrangian needs only a relatively small c; it reaches the QP's pressure for every
/// k. The plain penalty's error falls like 1/c and does not break down at large c. The table
/// is printed (`cargo test --release --test validation contact_validation:: -- --nocapture`).
#[test]
fn penalty_parameter_sweep() {
    let problem = paper("paper-table1", 18);
    let reference = solve(&Qp::new(QpSettings::default()).unwrap(), &problem);
    let rel = |st: &ContactState| max_diff(&st.pressure, &reference.pressure) / reference.p_max();
    eprintln!(
        "{:>3} {:>12} {:>6} {:>6} {:>6} {:>14} {:>15}",
        "k", "AL error", "steps", "iterp", "iterd", "penalty error", "penetration mm"
    );
    let mut penalty = vec![];
    for k in 0..=12 {
        let c = E * 10f64.powi(k);
        let settings = AugmentedLagrangianSettings {
            max_steps: 5000,
            accelerate: false,
            ..AugmentedLagrangianSettings::new(c)
        };
        let al = solve(&AugmentedLagrangian::new(settings).unwrap(), &problem);
        let pen = solve(
            &Penalty::new(PenaltySettings { c_mpa_per_mm: c }).unwrap(),
            &problem,
        );
        eprintln!(
            "{k:>3} {:>12.3e} {:>6} {:>6} {:>6} {:>14.3e} {:>15.3e}",
            rel(&al),
            al.iterations,
            al.iterp,
            al.iterd,
            rel(&pen),
            pen.residuals.penetration
        );
        assert!(
            rel(&al) < 1e-6,
            "k = {k}: augmented Lagrangian off the QP by {:e}",
            rel(&al)
        );
        penalty.push(rel(&pen));
    }
    // Measured: 0.14, 0.023, 2.4e-3 … 2.6e-9 at k = 8: from k = 1 on (c above the contact
    // stiffness) each decade of c divides the error by ten, until it meets the QP reference's
    // own accuracy of about 2e-9 (where the augmented Lagrangian sits too); it stays there up
    // to k = 12: no breakdown.
    for k in 2..=12 {
        assert!(
            penalty[k] < (0.15 * penalty[k - 1]).max(1e-8),
            "penalty errors {penalty:?}"
        );
    }
    assert!(penalty[12] < 1e-8, "no breakdown at large c: {penalty:?}");
}

/// The base of the bundled scene's punch on its base: its `fe_base` on `x` (the zone's faces,
/// then growing to the rim), `layers` uniform layers, its supports.
fn paper_base(zone: &FacesZone, base: &FeBase, x: &Spacing, layers: usize) -> FeModel {
    let (radius, height) = (base.radius_mm, base.height_mm);
    let y = Spacing::uniform(-height, 0.0, layers).unwrap();
    let mesh = Mesh::rectangle(zone.element, x, &y).unwrap();
    let mut model = FeModel::new(mesh, base.material, zone.analysis).unwrap();
    let bottom = model.mesh().nodes_on_y(-height, 0.0, radius);
    for support in &base.supports {
        match support {
            Support::Clamped => {
                model.fix(&bottom, Component::X).unwrap();
                model.fix(&bottom, Component::Y).unwrap();
            }
            Support::Axial => {
                model.fix(&bottom, Component::Y).unwrap();
            }
            Support::Symmetry => {
                let axis = model.mesh().nodes_on_x(0.0, -height, 0.0);
                model.fix(&axis, Component::X).unwrap();
            }
        }
    }
    model
}

/// The punch of the bundled scene's punch on its base: its `fe_punch` on the zone's faces,
/// `layers` uniform layers, held on its symmetry line in a plane analysis, its load on top.
fn paper_punch(zone: &FacesZone, punch: &FePunch, layers: usize) -> FeModel {
    let (radius, height) = (zone.radius_mm, punch.height_mm);
    let x = zone.spacing().unwrap();
    let y = Spacing::uniform(0.0, height, layers).unwrap();
    let mesh = Mesh::rectangle(zone.element, &x, &y).unwrap();
    let mut model = FeModel::new(mesh, punch.material, zone.analysis).unwrap();
    if zone.analysis != Analysis::Axisymmetric {
        let axis = model.mesh().nodes_on_x(0.0, 0.0, height);
        model.fix(&axis, Component::X).unwrap();
    }
    match punch.load {
        PunchLoad::PressureMpa(p) => {
            let top = model.mesh().faces_on_y(height, 0.0, radius);
            model.pressure(&top, p).unwrap();
        }
        PunchLoad::DisplacementMm(w) => {
            let top = model.mesh().nodes_on_y(height, 0.0, radius);
            model.prescribe(&top, Component::Y, w).unwrap();
        }
    }
    model
}

/// The paper's punch on its base as the bundled scene `name` defines it (zone, dimensions,
/// materials, supports, load), meshed as its bodies mesh `elements` uniform elements across
/// the zone and through each body (whose heights equal the zone's radius, so the layers are
/// uniform), the base's 4 elements outside the zone growing from the edge size; built here as
/// `FeBody`s, which the joint system needs (a scene builds `dyn ElasticBody`s). Returns the
/// analysis, the zone's radius and the bodies, base first.
fn paper_fe_bodies(name: &str, elements: usize) -> (Analysis, f64, FeBody, FeBody) {
    let scene = contopt_validation::paper::scene(name, elements, &[("sweep", None)]).unwrap();
    let spec = &scene.cases()[0].spec;
    let (Some(zone), Some(base), Some(punch)) = (
        spec.contact.zone.downcast::<FacesZone>(),
        spec.body[0].downcast::<FeBase>(),
        spec.body[1].downcast::<FePunch>(),
    ) else {
        panic!("{name} is not a punch on a base");
    };
    let edge = zone.edge_size().unwrap();
    let outside = Spacing::geometric_first(zone.radius_mm, base.radius_mm, 4, edge).unwrap();
    let x = zone.spacing().unwrap().then(&outside).unwrap();
    let lower = paper_base(zone, base, &x, elements);
    let upper = paper_punch(zone, punch, elements);
    let (faces_below, faces_above) = (
        lower.mesh().faces_on_y(0.0, 0.0, zone.radius_mm),
        upper.mesh().faces_on_y(0.0, 0.0, zone.radius_mm),
    );
    (
        zone.analysis,
        zone.radius_mm,
        FeBody::new("base", lower, &faces_below).unwrap(),
        FeBody::new("punch", upper, &faces_above).unwrap(),
    )
}

/// The penalty method condensed to the interface and on the full joint finite-element system
/// (2.22) give the same pressure and gap, axisymmetric and in plane stress, on the paper's
/// punch and base with 9 elements (the bodies checked against the scene's own first).
#[test]
fn condensed_penalty_matches_the_full_system() {
    for scene in ["paper-table1", "paper-table3"] {
        let (analysis, radius, base, punch) = paper_fe_bodies(scene, 9);
        // A crowned punch, h = 0.1 mm (r/R)², so the contact set shrinks and the joint
        // system is refactorised as it changes.
        let gap: Vec<f64> = base
            .interface()
            .points()
            .iter()
            .map(|x| 0.1 * (x[0] / radius).powi(2))
            .collect();
        let settings = PenaltySettings {
            c_mpa_per_mm: E * 1e4,
        };
        let penalty = Penalty::new(settings).unwrap();
        let condensed = solve(
            &penalty,
            &InterfaceProblem::new(&base, &punch, &gap).unwrap(),
        );
        // The bodies built here are the scene's: its problem with the same crown gives the
        // same pressure (both meshes alike, to round-off).
        let scene_problem = paper(scene, 9).with_initial_gap(&gap).unwrap();
        let ds = max_diff(
            &solve(&penalty, &scene_problem).pressure,
            &condensed.pressure,
        );
        assert!(
            ds < 1e-9 * condensed.p_max(),
            "{analysis:?}: {ds:e} MPa off the scene's"
        );
        let mut joint = JointSystem::new(&base, &punch, &gap).unwrap();
        let full = FullPenalty::new(settings)
            .unwrap()
            .solve(&mut joint)
            .unwrap();
        assert!(full.is_converged(), "{analysis:?}: {}", full.termination);
        assert!(
            full.iterp > 1 && full.active.iter().any(|a| !a),
            "{analysis:?}: the contact set must change"
        );
        let dp = max_diff(&full.pressure, &condensed.pressure) / condensed.p_max();
        let dd = max_diff(&full.gap, &condensed.gap);
        eprintln!(
            "{analysis:?}: dp {dp:e}, dd {dd:e} mm, lambda {:?} vs {:?}, solves {}",
            full.rigid, condensed.rigid, full.iterp
        );
        assert!(
            dp < 1e-6,
            "{analysis:?}: pressures differ by {dp:e} of p_max"
        );
        assert!(dd < 1e-9, "{analysis:?}: gaps differ by {dd:e} mm");
        assert_eq!(full.active, condensed.active);
        assert!((full.rigid[0] - condensed.rigid[0]).abs() < 1e-9 * condensed.rigid[0].abs());
        assert!(full.residuals.equilibrium < 1e-6 * 100.0 * radius.powi(2));
    }
}

/// Three Gauss points per quadratic face: a pressure outside the span of the face shape
/// functions at zero nodal force moves nothing (its gap change is at round-off against that of
/// the uniform pressure), and reading the pressure as a field removes it exactly.
#[test]
fn gauss_point_sawtooth_moves_nothing_and_is_recovered() {
    let problem = paper("paper-table2", 18);
    let n = problem.len();
    // A sawtooth of 50 MPa: the part of (0, 0, 1) on every face outside the field's span.
    let ramp: Vec<f64> = (0..n)
        .map(|i| if i % 3 == 2 { 50.0 } else { 0.0 })
        .collect();
    let smooth = problem.recovered_pressure(&ramp).unwrap();
    let sawtooth: Vec<f64> = ramp.iter().zip(&smooth).map(|(r, s)| r - s).collect();
    let amplitude = sawtooth.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(amplitude > 10.0, "{amplitude}");
    let uniform = vec![100.0; n];
    let with: Vec<f64> = uniform.iter().zip(&sawtooth).map(|(u, s)| u + s).collect();
    let (d0, d1) = (problem.gap(&uniform, &[]), problem.gap(&with, &[]));
    let change = max_diff(&d0, &problem.free_gap());
    eprintln!(
        "sawtooth {amplitude:.1} MPa: gap change {:.2e} of the uniform pressure's {change:.3e} mm",
        max_diff(&d0, &d1) / change
    );
    assert!(max_diff(&d0, &d1) < 1e-9 * change);
    let recovered = problem.recovered_pressure(&with).unwrap();
    assert!(max_diff(&recovered, &uniform) < 1e-9 * 100.0);
}

// The joint system of two finite-element bodies (eq. 2.22), built by contopt-fem and solved
// by contopt-contact: the cross-check of the condensation.

/// A plane-stress punch, 10 × 5 mm, on a 20 × 10 mm base (half-models, x = 0 held in x;
/// the base's bottom clamped), pressed by 100 MPa on its top: the punch floats (one
/// vertical mode). Their contact faces, y = 0 for x ≤ 10, have matching nodes.
fn plane_punch_and_base() -> (FeBody, FeBody) {
    let analysis = Analysis::PlaneStress { thickness: 2.0 };
    let material = Material::new(E, 0.3).unwrap();
    let y = Spacing::uniform(-10.0, 0.0, 3).unwrap();
    let x = Spacing::uniform(0.0, 20.0, 8).unwrap();
    let mut base = FeModel::new(
        Mesh::rectangle(ElementKind::Q8, &x, &y).unwrap(),
        material,
        analysis,
    )
    .unwrap();
    let bottom = base.mesh().nodes_on_y(-10.0, 0.0, 20.0);
    let axis = base.mesh().nodes_on_x(0.0, -10.0, 0.0);
    base.fix(&bottom, Component::X).unwrap();
    base.fix(&bottom, Component::Y).unwrap();
    base.fix(&axis, Component::X).unwrap();
    let top = base.mesh().faces_on_y(0.0, 0.0, 10.0);
    let base = FeBody::new("base", base, &top).unwrap();
    let (x, y) = (
        Spacing::uniform(0.0, 10.0, 4).unwrap(),
        Spacing::uniform(0.0, 5.0, 2).unwrap(),
    );
    let mut punch = FeModel::new(
        Mesh::rectangle(ElementKind::Q8, &x, &y).unwrap(),
        material,
        analysis,
    )
    .unwrap();
    let axis = punch.mesh().nodes_on_x(0.0, 0.0, 5.0);
    let (loaded, contact) = (
        punch.mesh().faces_on_y(5.0, 0.0, 10.0),
        punch.mesh().faces_on_y(0.0, 0.0, 10.0),
    );
    punch.fix(&axis, Component::X).unwrap();
    punch.pressure(&loaded, 100.0).unwrap();
    (base, FeBody::new("punch", punch, &contact).unwrap())
}

/// The penalty method on the joint system (2.22) and on the condensed interface give the
/// same pressure, gap, contact set and approach of the floating punch, under a crowned
/// gap that opens the punch's edge; the joint system carries the punch's load.
#[test]
fn joint_system_matches_the_condensed_penalty() {
    let (base, punch) = plane_punch_and_base();
    let gap: Vec<f64> = base
        .interface()
        .points()
        .iter()
        .map(|x| 0.05 * (x[0] / 10.0).powi(2))
        .collect();
    let c = E * 1e4;
    let settings = PenaltySettings { c_mpa_per_mm: c };
    let condensed = Penalty::new(settings)
        .unwrap()
        .solve(&InterfaceProblem::new(&base, &punch, &gap).unwrap())
        .unwrap();
    let mut joint = JointSystem::new(&base, &punch, &gap).unwrap();
    assert_eq!(joint.free_modes(), 1);
    let solves = std::cell::Cell::new(0);
    let count = |e: &Event| {
        if e.end.is_some() {
            return Flow::Continue;
        }
        solves.set(solves.get() + 1);
        Flow::Continue
    };
    let full = FullPenalty::new(settings)
        .unwrap()
        .solve_observed(&mut joint, &count)
        .unwrap();
    let p_max = condensed.p_max();
    let dp = full
        .pressure
        .iter()
        .zip(&condensed.pressure)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let dd = full
        .gap
        .iter()
        .zip(&condensed.gap)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let touching = full.active.iter().filter(|&&a| a).count();
    eprintln!(
        "{touching} of {} points in contact after {} solves: dp {dp:.2e} MPa, dd {dd:.2e} mm",
        full.active.len(),
        full.iterp
    );
    assert!(touching < full.active.len(), "the edge must open");
    assert!(dp < 1e-6 * p_max, "pressures differ by {dp:e} MPa");
    assert!(dd < 1e-9, "gaps differ by {dd:e} mm");
    assert_eq!(full.active, condensed.active);
    assert_eq!(solves.get(), full.iterp);
    assert!((full.rigid[0] - condensed.rigid[0]).abs() < 1e-9 * condensed.rigid[0].abs());
    // The contact force carries the 100 MPa on the punch's top, 10 mm × 2 mm.
    let force: f64 = full
        .pressure
        .iter()
        .zip(base.interface().weights())
        .map(|(p, w)| p * w)
        .sum();
    assert!((force - 2000.0).abs() < 1e-6 * 2000.0, "{force} N");
    assert!(full.residuals.equilibrium < 1e-9 * 2000.0);
}

#[test]
fn joint_system_refuses_a_wrong_gap() {
    let (base, punch) = plane_punch_and_base();
    let n = base.interface().len();
    let err = JointSystem::new(&base, &punch, &vec![0.0; n - 1])
        .err()
        .unwrap();
    assert!(err.to_string().contains("initial_gap"), "{err}");
    let mut gap = vec![0.0; n];
    gap[1] = f64::NAN;
    let err = JointSystem::new(&base, &punch, &gap).err().unwrap();
    assert!(err.to_string().contains("initial_gap[1]"), "{err}");
}
