//! The kinds of one's own crate in scenes and behind the command, against their closed forms.

use std::path::{Path, PathBuf};

use contopt_core::observe::Method;
use contopt_results::{CaseReport, Report};
use contopt_scene::Registry;

/// Relative tolerance of the closed forms: the strips' discretisation is about 10⁻³ off; a
/// bed without its shear layer, or a relief ignored, is off by tens of per cent.
const CLOSED_FORM: f64 = 0.01;

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(format!("{name}.toml"))
}

fn run(name: &str) -> CaseReport {
    let scene = contopt_own_kinds::registry().load(&scene(name)).unwrap();
    let mut reports = scene.run();
    let report = reports.next().unwrap().unwrap();
    assert!(report.termination.is_converged(), "{}", report.termination);
    report
}

fn close(computed: f64, expected: f64) -> bool {
    (computed / expected - 1.0).abs() < CLOSED_FORM
}

/// A rigid flat punch (half-width a) on a Pasternak bed ending at |x| = L: the bed sinks by
/// δ under it, carrying k·δ, and the shear layer beyond carries δ·√(k·G_p)·tanh((L − a)/ℓ)
/// at each rim (ℓ = √(G_p/k)): F = 2·b·δ·(k·a + √(k·G_p)·tanh((L − a)/ℓ)).
#[test]
fn a_punch_on_a_pasternak_bed_sinks_as_the_closed_form() {
    let (k, shear, a, length, b, force): (f64, f64, f64, f64, f64, f64) =
        (50.0, 5000.0, 10.0, 40.0, 10.0, 10_000.0);
    let ell: f64 = (shear / k).sqrt();
    let rim = (k * shear).sqrt() * ((length - a) / ell).tanh();
    let delta = force / (2.0 * b * (k * a + rim));
    let report = run("pasternak-punch");
    let approach = 1e-3 * report.approach_um.unwrap();
    assert!(
        close(approach, delta),
        "δ {approach} mm, closed form {delta} mm"
    );
    // Inside the punch, away from its rims, the springs alone carry k·δ.
    let centre = report
        .interface
        .iter()
        .min_by(|p, q| p.x_mm[0].abs().total_cmp(&q.x_mm[0].abs()))
        .unwrap();
    assert!(close(centre.p_mpa, k * delta), "p(0) {} MPa", centre.p_mpa);
    // Beyond the punch the bed is out of contact.
    assert!(report
        .interface
        .iter()
        .filter(|p| p.x_mm[0].abs() > a * 1.01)
        .all(|p| p.p_mpa == 0.0));
}

/// A rigid block relieved by Δh = c·x² on a Winkler bed: p = k·(δ − c·x²) within |x| < s,
/// F = (4/3)·b·k·c·s³ and δ = c·s².
#[test]
fn a_design_of_ones_own_relieves_as_the_closed_form() {
    let (k, c, b, force): (f64, f64, f64, f64) = (50.0, 0.5 / 100.0, 10.0, 2000.0);
    let s: f64 = (3.0 * force / (4.0 * b * k * c)).cbrt();
    let delta = c * s * s;
    let report = run("relieved-block");
    assert_eq!(report.method, Some(Method::Other("parabolic_relief")));
    let approach = 1e-3 * report.approach_um.unwrap();
    assert!(
        close(approach, delta),
        "δ {approach} mm, closed form {delta} mm"
    );
    let reach = report
        .interface
        .iter()
        .filter(|p| p.p_mpa > 0.0)
        .map(|p| p.x_mm[0].abs())
        .fold(0.0, f64::max);
    assert!(
        (reach - s).abs() < 0.1,
        "contact to {reach} mm, closed form {s} mm"
    );
    // The report's Δh_max is the relief at the outermost strip.
    let outermost = (report.interface.iter())
        .map(|p| c * p.x_mm[0].powi(2))
        .fold(0.0, f64::max);
    assert!((1e-3 * report.dh_max_um.unwrap() - outermost).abs() < 1e-9);
}

/// A solver of one's own on the library's driver: a rigid sphere on a Winkler bed sinks by
/// δ = √(F/(πkR)), p = k(δ − r²/2R) within a = √(2Rδ).
#[test]
fn a_solver_of_ones_own_solves_the_bed_as_the_closed_form() {
    let (k, r, force): (f64, f64, f64) = (50.0, 20.0, 1000.0);
    let delta = (force / (std::f64::consts::PI * k * r)).sqrt();
    let report = run("winkler-pgs");
    assert_eq!(report.solver, Some(Method::Other("projected_gauss_seidel")));
    let approach = 1e-3 * report.approach_um.unwrap();
    assert!(
        (approach / delta - 1.0).abs() < 1e-3,
        "δ {approach} mm, closed form {delta} mm"
    );
    for point in &report.interface {
        let x = point.x_mm[0];
        let expected = (k * (delta - x * x / (2.0 * r))).max(0.0);
        assert!(
            (point.p_mpa - expected).abs() < 1e-3 * k * delta,
            "p({x}) {}",
            point.p_mpa
        );
    }
}

/// The library's own registry does not know the crate's kinds, and says which it knows.
#[test]
fn an_unknown_kind_lists_the_registered_ones() {
    let error = Registry::standard()
        .load(&scene("pasternak-punch"))
        .unwrap_err()
        .to_string();
    assert!(error.contains("body[0].kind"), "{error}");
    assert!(error.contains("unknown variant `pasternak`"), "{error}");
    assert!(error.contains("`winkler`, `fe_mesh`"), "{error}");
}

/// `contopt-own` keeps every command of `contopt`: a run writes its files, and its
/// `result.json` reads back, the design of one's own named in it.
#[test]
fn the_own_command_runs_and_its_results_read_back() {
    let out = std::env::temp_dir().join(format!("contopt-own-{}", std::process::id()));
    for name in ["pasternak-punch", "relieved-block"] {
        assert_cmd::Command::cargo_bin("contopt-own")
            .unwrap()
            .args(["run", "--quiet", "--jobs", "1", "--out"])
            .arg(&out)
            .arg(scene(name))
            .assert()
            .success();
        let text = std::fs::read_to_string(out.join(name).join("result.json")).unwrap();
        let report: Report = serde_json::from_str(&text).unwrap();
        assert_eq!(report.cases.len(), 1);
    }
    let text = std::fs::read_to_string(out.join("relieved-block/result.json")).unwrap();
    let report: Report = serde_json::from_str(&text).unwrap();
    assert_eq!(
        report.cases[0].method,
        Some(Method::Other("parabolic_relief"))
    );
    assert_cmd::Command::cargo_bin("contopt-own")
        .unwrap()
        .args(["check"])
        .arg(scene("pasternak-punch"))
        .assert()
        .success();
    std::fs::remove_dir_all(&out).unwrap();
}
