//! The wrong answers and unclear errors a new user found in minutes with scenes written from the
//! book alone (issue 22), each a test: a contact that runs off its grid, a contact resolved by
//! three cells, stresses below a punch, a NaN or a string where a number belongs, a value
//! reported on another body's line, a scene `check` passed that `run` refused, a controller's
//! L2 written as a roller's whole length.

use std::path::Path;

use contopt_results::CaseStatus;
use contopt_scene::{Format, Scene, SceneError};

fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::parse(text, Format::Toml, Path::new("mine.toml"))
}

/// The error's text and its place (line, column).
fn refused(text: &str) -> (String, (usize, usize)) {
    let e = parse(text).expect_err("the scene must be refused");
    let place = e
        .located()
        .and_then(|l| l.place)
        .expect("a place in the file");
    (e.to_string(), place)
}

/// The line (from 1) of the first line of `text` holding `needle`.
fn line_of(text: &str, needle: &str) -> usize {
    1 + text.lines().position(|l| l.contains(needle)).expect(needle)
}

/// A rigid sphere (R = 50 mm) at `force` N on a half-space grid of `cells` × `cells` cells of
/// `cell` mm, steel.
fn sphere(force: f64, cells: usize, cell: f64) -> String {
    format!(
        r#"name = "sphere"
[contact]
zone = {{ kind = "grid", cells = [{cells}, {cells}], cell_mm = [{cell}, {cell}] }}
gap = {{ kind = "sphere", radius_mm = 50.0 }}
load = {{ force_n = {force:?} }}

[[body]]
kind = "half_space"
material = {{ e_mpa = 2.0e5, nu = 0.3 }}

[[body]]
kind = "rigid"
"#
    )
}

/// Hertz's contact radius of the sphere of [`sphere`] \[mm\].
fn hertz_radius(force: f64) -> f64 {
    let e_star = 2.0e5 / (1.0 - 0.09);
    (3.0 * force * 50.0 / (4.0 * e_star)).cbrt()
}

/// 20 kN on a ±1.25 mm grid: Hertz's contact (a = 1.51 mm) runs off it. The old answer was a
/// p_max 59 % above Hertz's with exit 0; now the case is outside the model, naming the edge and
/// the size the grid needs, and it does not pass for solved.
#[test]
fn a_contact_that_runs_off_its_grid_is_outside_the_model() {
    let scene = parse(&sphere(20_000.0, 100, 0.025)).unwrap();
    let report = scene.cases()[0].run().unwrap();
    assert_eq!(report.status, CaseStatus::OutsideModel, "{report:#?}");
    assert!(!report.is_solved());
    let limit = report.limit.as_ref().unwrap();
    let a = hertz_radius(20_000.0);
    assert!((limit.extent_mm - 1.25).abs() < 1e-9, "{limit:?}");
    assert!(limit.needed_mm >= 1.25 * a, "{limit:?}");
    assert!(
        limit.message.contains("edge") && limit.edge.contains("1.25"),
        "{limit:?}"
    );
    let hertz = report.hertz.as_ref().unwrap();
    assert!((hertz.half_width_mm / a - 1.0).abs() < 1e-12);
    // On a grid that holds it, the same contact is solved and within 1 % of Hertz's p₀.
    let fits = parse(&sphere(20_000.0, 100, 0.04)).unwrap().cases()[0]
        .run()
        .unwrap();
    assert_eq!(fits.status, CaseStatus::Solved, "{:?}", fits.limit);
    let p0 = fits.hertz.as_ref().unwrap().p0_mpa;
    assert!(
        (fits.p_max_mpa.unwrap() / p0 - 1.0).abs() < 0.01,
        "{:?} vs {p0}",
        fits.p_max_mpa
    );
}

/// A roller's load typed in kN for N (12 instead of 12 000), ISO's crown: the crown for the
/// nominal load squeezes the contact to a few cells along the axis (10 of 40, 5 across its
/// half-length) at 2.5 times Hertz's p₀. It used to report 222 MPa with exit 0 and nothing
/// else; now the case carries the warning that its peak is not resolved along x, beside
/// Hertz's nominal figures.
#[test]
fn a_roller_load_in_the_wrong_unit_does_not_pass() {
    let text = r#"name = "roller"
[contact]
zone = { kind = "grid", cells = [40, 21] }
gap = { kind = "roller", diameter_mm = 10.0, length_mm = 10.0, profile = "iso" }
load = { force_n = 12.0 }

[[body]]
kind = "half_space"
material = { e_mpa = 2.1e5, nu = 0.3 }

[[body]]
kind = "half_space"
material = { e_mpa = 2.1e5, nu = 0.3 }
"#;
    let report = parse(text).unwrap().cases()[0].run().unwrap();
    assert!(
        report.termination.is_converged(),
        "{:?}",
        report.termination
    );
    let resolution = report.resolution.as_ref().unwrap();
    assert_eq!(resolution.along, "x", "{resolution:?}");
    assert!(resolution.cells < 8.0, "{resolution:?}");
    assert!(
        report
            .warnings
            .iter()
            .any(|w| w.contains("half-width along x") && w.contains("not resolved")),
        "{:?}",
        report.warnings
    );
    let hertz = report.hertz.as_ref().unwrap();
    assert_eq!(hertz.contact, "line");
    let p_max = report.p_max_mpa.unwrap();
    assert!(
        p_max > 2.0 * hertz.p0_mpa,
        "{p_max} against {}",
        hertz.p0_mpa
    );
}

/// A Hertz contact three cells wide: solved, with a warning that gives the number of cells
/// and the cell size that would resolve it.
#[test]
fn a_contact_of_a_few_cells_warns_with_the_number() {
    let report = parse(&sphere(1000.0, 16, 0.2)).unwrap().cases()[0]
        .run()
        .unwrap();
    assert!(
        report.is_solved(),
        "{:?} {:?}",
        report.termination,
        report.limit
    );
    let resolution = report.resolution.as_ref().unwrap();
    assert!(resolution.cells < 8.0, "{resolution:?}");
    let warning = report
        .warnings
        .iter()
        .find(|w| w.contains("cells"))
        .unwrap();
    assert!(
        warning.contains(&format!("{:.1} cells", resolution.cells)),
        "{warning}"
    );
    let fine = parse(&sphere(1000.0, 64, 0.02)).unwrap().cases()[0]
        .run()
        .unwrap();
    assert!(
        fine.is_solved() && fine.warnings.is_empty(),
        "{:?}",
        fine.warnings
    );
}

/// A rigid cylinder (R = 10 mm) as long as its grid (4 mm), at 10 kN on a half-space: its
/// straight ends are sharp edges, where the pressure is singular. The old answer was a p_max
/// three times Hertz's line p₀ (4182 MPa) with no word, and a larger one on finer cells; now
/// each case names the edge, and Hertz's p₀ beside it as the line contact's (a cylinder without
/// ends: the pressure along its middle, not its ends'), and its p_max grows by about √2 per
/// halving of the cells while the pressure at the middle does not move.
#[test]
fn a_peak_at_a_sharp_edge_is_named() {
    let run = |cells: usize| {
        let cell = 4.0 / cells as f64;
        let text = format!(
            r#"name = "cylinder"
[contact]
zone = {{ kind = "grid", cells = [{cells}, 40], cell_mm = [{cell}, 0.03] }}
gap = {{ kind = "cylinder", radius_mm = 10.0 }}
load = {{ force_n = 10000.0 }}

[[body]]
kind = "half_space"
material = {{ e_mpa = 2.0e5, nu = 0.3 }}

[[body]]
kind = "rigid"
"#
        );
        let report = parse(&text).unwrap().cases()[0].run().unwrap();
        assert!(report.is_solved(), "{:?}", report.termination);
        let warning = report.warnings.iter().find(|w| w.contains("sharp edge"));
        let warning = warning.unwrap_or_else(|| panic!("{:?}", report.warnings));
        // Hertz's p₀ reported beside the case is the line contact's: the warning says so, and
        // how far the end's peak stands above it (it used to say nothing of it).
        let p0 = report.hertz.as_ref().unwrap().p0_mpa;
        let times = report.p_max_mpa.unwrap() / p0;
        let said = format!("Hertz's p₀ = {p0:.1} MPa beside the case is the line contact's");
        assert!(warning.contains(&said), "{warning}");
        assert!(
            warning.contains(&format!("{times:.2} times it")),
            "{warning}"
        );
        let middle = (report.interface.iter())
            .filter(|q| q.x_mm[0].abs() < cell)
            .map(|q| q.p_mpa)
            .fold(0.0f64, f64::max);
        (report.p_max_mpa.unwrap(), middle)
    };
    let (coarse, coarse_middle) = run(40);
    let (fine, fine_middle) = run(80);
    assert!(fine > 1.25 * coarse, "{coarse} → {fine} MPa");
    assert!(
        (fine_middle / coarse_middle - 1.0).abs() < 0.02,
        "{coarse_middle} → {fine_middle} MPa"
    );
}

/// A rigid cylinder as long as its grid (6 mm on 12 cells of 0.5 mm, R = 5 mm, 2 kN): its
/// contact runs the zone's whole length, where the cylinder itself ends, so the length has no
/// edge of the contact to resolve: the resolution is judged across it, Hertz's b = 0.1356 mm
/// on cells of 0.0125 mm. It used to say "the contact's half-width along x (3.0000 mm) spans
/// 6.0 cells, fewer than 8: its peak is not resolved; refine the zone", though finer cells
/// along the length resolve nothing more (the Python package's check already skipped it).
#[test]
fn a_contact_along_the_whole_zone_is_judged_across_it() {
    let text = r#"name = "cylinder"
[contact]
zone = { kind = "grid", cells = [12, 41], cell_mm = [0.5, 0.0125] }
gap = { kind = "cylinder", radius_mm = 5.0 }
load = { force_n = 2000.0 }

[[body]]
kind = "half_space"
material = { e_mpa = 1.05e5, nu = 0.3 }

[[body]]
kind = "rigid"
"#;
    let report = parse(text).unwrap().cases()[0].run().unwrap();
    assert!(report.is_solved(), "{:?}", report.termination);
    let unresolved = report.warnings.iter().find(|w| w.contains("not resolved"));
    assert!(unresolved.is_none(), "{:?}", report.warnings);
    let resolution = report.resolution.as_ref().unwrap();
    assert_eq!(resolution.along, "y", "{resolution:?}");
    let b = report.hertz.as_ref().unwrap().half_width_mm;
    assert!(
        (resolution.half_width_mm / b - 1.0).abs() < 0.25,
        "{resolution:?} against b = {b}"
    );
}

/// A sphere pressed 10⁻⁹ mm into a grid whose cell centres miss its apex: no point carries
/// pressure. It used to report p_max 0 and nothing else; now the case warns, with Hertz's
/// contact in cells (a = 7·10⁻⁵ mm against cells of 0.02 mm).
#[test]
fn a_contact_smaller_than_a_cell_is_warned() {
    let text = sphere(1000.0, 64, 0.02).replace("force_n = 1000.0", "approach_mm = 1e-9");
    let report = parse(&text).unwrap().cases()[0].run().unwrap();
    assert!(report.is_solved(), "{:?}", report.termination);
    assert_eq!(report.p_max_mpa, Some(0.0));
    let a = (50.0f64 * 1e-9).sqrt();
    let warning = report
        .warnings
        .iter()
        .find(|w| w.contains("no point of the zone carries pressure"))
        .unwrap_or_else(|| panic!("{:?}", report.warnings));
    assert!(
        warning.contains(&format!("{a:.4e} mm")) && warning.contains("0.0200 mm"),
        "{warning}"
    );
}

/// Stresses below the surface of the paper's punch on its base: the run used to refuse them
/// ("a resultant off by 6.42e2 N … (solve the contact first)") after `check` passed.
#[test]
fn subsurface_stresses_under_the_papers_punch() {
    let scene = Scene::bundled_with(
        "paper-table1",
        &[
            ("sweep", None),
            ("contact.zone.elements", Some("6")),
            ("output", Some("{ subsurface = { depths = 8 } }")),
        ],
    )
    .unwrap();
    let report = scene.cases()[0].run().unwrap();
    assert!(report.is_solved(), "{:?}", report.termination);
    let sub = report
        .subsurface
        .as_ref()
        .expect("stresses below the surface");
    let names: Vec<&str> = sub.bodies.iter().map(|b| b.body.as_str()).collect();
    assert_eq!(names, ["base", "punch"]);
    // Under 100 MPa the punch's compression is of the order of the load.
    let punch = &sub.bodies[1].peaks.min_principal;
    assert!(
        punch.value_mpa < -50.0 && punch.value_mpa > -2000.0,
        "{punch:?}"
    );
}

/// A steel sphere on an aluminium half-space, both half-spaces of their own Poisson's ratio:
/// each gets its own stresses below the surface, and each its own label (both were
/// "half-space", their rows of one `subsurface_1.csv` told apart by nothing). The steel's
/// Tresca is Hertz's 0.31 p₀ (ν = 0.3) within the coarse grid's 3 %.
#[test]
fn two_half_spaces_have_stresses_of_their_own() {
    let aluminium = "material = { e_mpa = 7.0e4, nu = 0.33 }";
    let steel = "kind = \"half_space\"\nmaterial = { e_mpa = 2.1e5, nu = 0.3 }";
    let scene = sphere(500.0, 40, 0.05)
        .replace("material = { e_mpa = 2.0e5, nu = 0.3 }", aluminium)
        .replace("kind = \"rigid\"", steel)
        + "[output.subsurface]\nmax_depth_mm = 0.66\ndepths = 12\n";
    let report = parse(&scene).unwrap().cases()[0].run().unwrap();
    let sub = report
        .subsurface
        .as_ref()
        .expect("stresses below the surface");
    let names: Vec<&str> = sub.bodies.iter().map(|b| b.body.as_str()).collect();
    assert_eq!(names, ["half-space (below)", "half-space (above)"]);
    let p0 = report.hertz.as_ref().expect("Hertz's figures").p0_mpa;
    let steel = sub.bodies[1].peaks.tresca.value_mpa;
    assert!(
        (steel / (0.31 * p0) - 1.0).abs() < 0.03,
        "{steel} against {p0}"
    );
}

/// `pressure_mpa = nan` in a swept scene: the error names the key and its own line, not the
/// sweep's key (it was "sweep value 0.0 for optimisation.controller.l1_mm: invalid type: null").
#[test]
fn a_nan_is_refused_at_its_key() {
    let text = contopt_scene::BUNDLED[0].text.replace(
        "load = { pressure_mpa = 100.0 }",
        "load = { pressure_mpa = nan }",
    );
    let (message, (line, _)) = refused(&text);
    assert_eq!(line, line_of(&text, "pressure_mpa = nan"), "{message}");
    assert!(message.contains("body[1].load.pressure_mpa"), "{message}");
    assert!(
        message.contains("NaN") && !message.contains("sweep"),
        "{message}"
    );
}

/// `force_n = "1 kN"`: the key, its line and column, the value and the type wanted (it was
/// "TOML parse error at line 4 … [problem] … invalid type: string").
#[test]
fn a_string_for_a_number_is_refused_at_its_key() {
    let text = sphere(1000.0, 16, 0.05).replace("force_n = 1000.0", "force_n = \"1 kN\"");
    let (message, (line, column)) = refused(&text);
    let at = line_of(&text, "\"1 kN\"");
    assert_eq!(line, at, "{message}");
    let expected = text.lines().nth(at - 1).unwrap().find("\"1 kN\"").unwrap() + 1;
    assert_eq!(column, expected, "{message}");
    assert!(
        message.contains("contact.load.force_n")
            && message.contains("\"1 kN\"")
            && message.contains("f64"),
        "{message}"
    );
}

/// An invalid ν of the base is reported on the base's line, not on the first `nu =` of the
/// file (the punch's).
#[test]
fn a_bad_material_is_reported_on_its_own_body() {
    let text = contopt_scene::BUNDLED[0]
        .text
        .replacen("nu = 0.3", "nu = 0.3 ", 1);
    let base = text.find("kind = \"fe_base\"").unwrap();
    let bad = format!(
        "{}{}",
        &text[..base],
        text[base..].replacen("nu = 0.3", "nu = 0.5", 1)
    );
    let (message, (line, _)) = refused(&bad);
    let base_line = line_of(&bad, "kind = \"fe_base\"");
    assert!(
        line > base_line && line < base_line + 4,
        "{line}: {message}"
    );
    assert!(
        message.contains("body[0].material") && message.contains("0.5"),
        "{message}"
    );
    // The same as data, for a caller that acts on it (the Python binding's attributes).
    let e = parse(&bad).unwrap_err();
    let field = e
        .located()
        .and_then(|l| l.field.clone())
        .expect("a field error");
    assert_eq!((field.field.as_str(), field.value.as_str()), ("nu", "0.5"));
    assert!(message.ends_with(&field.allowed), "{message}");
}

/// A bed's modulus refused by the library's own check (not the reader) carries its field as
/// data too, at the scene's key.
#[test]
fn a_library_check_carries_its_field() {
    let text = sphere(1000.0, 16, 0.05).replace(
        "kind = \"half_space\"\nmaterial = { e_mpa = 2.0e5, nu = 0.3 }",
        "kind = \"winkler\"\nmodulus_mpa_per_mm = -1.0",
    );
    let e = parse(&text).expect_err("a negative modulus");
    let located = e.located().expect("a place");
    assert_eq!(located.path, "body[0].modulus_mpa_per_mm", "{e}");
    let field = located.field.clone().expect("a field error");
    assert_eq!(field.field, "modulus_mpa_per_mm");
    assert_eq!(field.value, "-1");
    assert_eq!(field.allowed, "must be positive and finite");
}

/// What `run` refuses, `check` (reading the scene) refuses first, in words — not a Rust enum's
/// name: a given load where nothing floats, a robust crown without an envelope.
#[test]
fn check_refuses_what_run_would() {
    let displaced = contopt_scene::BUNDLED[1]
        .text
        .replace("kind = \"given_displacement\"", "kind = \"given_load\"");
    let (message, _) = refused(&displaced);
    assert!(
        message.contains("floating body") && !message.contains("GivenLoad"),
        "{message}"
    );
    let roller = contopt_scene::BUNDLED
        .iter()
        .find(|b| b.name == "roller-study")
        .unwrap()
        .text;
    let robust = roller.replace(
        "optimisation = { method = \"load_split\", controller = { kind = \"cubic\", l1_mm = 0.0",
        "optimisation = { method = \"envelope_split\", controller = { kind = \"cubic\", l1_mm = 0.0",
    );
    let (message, _) = refused(&robust);
    assert!(message.contains("[envelope]"), "{message}");
}

/// A controller whose L2 is a roller's whole length (10 mm) where it is measured from the
/// middle (5 mm) is refused, naming the key.
#[test]
fn a_controller_beyond_the_zone_is_refused() {
    let roller = contopt_scene::BUNDLED
        .iter()
        .find(|b| b.name == "roller-study")
        .unwrap()
        .text;
    let long = roller.replace("l1_mm = 2.0, l2_mm = 5.0", "l1_mm = 2.0, l2_mm = 10.0");
    let (message, _) = refused(&long);
    assert!(
        message.contains("optimisation.controller.l2_mm") && message.contains("half length"),
        "{message}"
    );
}

/// A rigid cylinder (R = 20 mm) on a plane-strain block of a faces zone, whose bodies are the
/// half x ≥ 0 of symmetric ones: 400 N on the half is 800 N on the whole contact. Hertz's
/// nominal p₀ used to take the half's force for the whole (q = F/t: 1183 MPa beside a solved
/// p_max of 1673, √2 apart); the line load is 2F/t.
#[test]
fn a_half_models_hertz_is_the_whole_contacts() {
    let text = r#"name = "cylinder on a half block"
[contact]
zone = { kind = "faces", analysis = { plane_strain = { thickness_mm = 1.0 } }, radius_mm = 1.0, elements = 40 }
gap = { kind = "cylinder", radius_mm = 20.0 }
load = { force_n = 400.0 }

[[body]]
kind = "fe_block"
material = { e_mpa = 2.0e5, nu = 0.3 }
size_mm = 40.0

[[body]]
kind = "rigid"

[solver]
kind = "active_set"
"#;
    let report = parse(text).unwrap().cases()[0].run().unwrap();
    let hertz = report.hertz.as_ref().expect("Hertz's nominal contact");
    // Johnson eq. 4.45: p₀ = √(q E*/(π R)), q = 2F/t on the whole contact.
    let e_star = 2.0e5 / (1.0 - 0.09);
    let p0 = (2.0 * 400.0 * e_star / (std::f64::consts::PI * 20.0)).sqrt();
    assert!(
        (hertz.p0_mpa - p0).abs() < 1e-9 * p0,
        "{} against {p0}",
        hertz.p0_mpa
    );
    // The block stands in for the half-space: its p_max within 1 % of Hertz's.
    let p_max = report.p_max_mpa.expect("a solved pressure");
    assert!((p_max - p0).abs() < 0.01 * p0, "{p_max}");
}

/// A rigid cylinder (R = 20 mm) on a plane-stress block of a faces zone, 400 N on the half
/// x ≥ 0 of 5 mm thickness. Three Gauss points per quadratic face outnumber its nodes and a
/// rigid partner adds no compliance, so the exact solution of the points closed one by one can
/// open every third point by a gap that grows eightfold per face (10⁻⁶ to 10⁻³ µm here) and
/// carry its load on the other two: the solvers returned that sawtooth, p_max 1303 MPa
/// (active set) and 1279 MPa (QP) against Hertz's 731, as converged. The pressure is the faces'
/// field; read as one, p_max is Hertz's within the block's 1 %, whichever exact solver ran.
#[test]
fn a_rigid_body_on_element_faces_reports_the_pressure_field() {
    let text = r#"name = "cylinder on a plane-stress block"
[contact]
zone = { kind = "faces", analysis = { plane_stress = { thickness_mm = 5.0 } }, radius_mm = 0.6, elements = 24 }
gap = { kind = "cylinder", radius_mm = 20.0 }
load = { force_n = 400.0 }

[[body]]
kind = "fe_block"
material = { e_mpa = 2.1e5, nu = 0.3 }
size_mm = 40.0

[[body]]
kind = "rigid"

[solver]
kind = "active_set"
"#;
    // Johnson eq. 4.45 in plane stress: E* = E, q = 2F/t on the whole contact.
    let p0 = (2.0 * 400.0 / 5.0 * 2.1e5 / (std::f64::consts::PI * 20.0)).sqrt();
    for solver in ["active_set", "qp"] {
        let scene = text.replace("kind = \"active_set\"", &format!("kind = \"{solver}\""));
        let report = parse(&scene).unwrap().cases()[0].run().unwrap();
        assert_eq!(report.status, CaseStatus::Solved, "{solver}");
        let hertz = report.hertz.as_ref().expect("Hertz's nominal contact");
        assert!((hertz.p0_mpa - p0).abs() < 1e-9 * p0, "{}", hertz.p0_mpa);
        let p_max = report.p_max_mpa.expect("a solved pressure");
        assert!(
            (p_max - p0).abs() < 0.01 * p0,
            "{solver}: p_max {p_max} against {p0}"
        );
    }
}

/// A roller pair on a grid sized for 2 kN (Fujiwara–Kawase's crown fixed, so that every load
/// sees the same roller) with an envelope of `factors` of its load.
fn roller_envelope(factors: &str) -> String {
    format!(
        r#"name = "envelope"
[contact]
zone = {{ kind = "grid", cells = [30, 25] }}
gap = {{ kind = "roller", diameter_mm = 10.0, length_mm = 10.0, profile = {{ kind = "fujiwara_kawase", k1 = 1.0, k2 = 0.5, z_m_mm = 0.02 }} }}
load = {{ force_n = 2000.0 }}

[[body]]
kind = "half_space"
material = {{ e_mpa = 2.1e5, nu = 0.3 }}

[[body]]
kind = "half_space"
material = {{ e_mpa = 2.1e5, nu = 0.3 }}

[envelope]
load_factors = {factors}
tilts_arcmin = [0.0]
"#
    )
}

/// An envelope's load case whose contact outgrows the grid across: 12 times the load the grid
/// is sized for (±3 Hertz half-widths of 2 kN) widens Hertz's b by √12 = 3.5, off the grid. It
/// was solved on the cut grid to p_max 11 924 MPa (the same load on its own grid: 4 877 MPa),
/// its worst p_max reported as the envelope's with exit 0; now the case is outside the model,
/// naming the envelope's case, the edge and the reach its load needs. 1.5 times the load
/// stays within the grid.
#[test]
fn an_envelope_case_that_outgrows_its_grid_is_outside_the_model() {
    let heavy = parse(&roller_envelope("[1.0, 12.0]")).unwrap().cases()[0]
        .run()
        .unwrap();
    assert_eq!(
        heavy.status,
        CaseStatus::OutsideModel,
        "{:?}",
        heavy.warnings
    );
    let limit = heavy.limit.as_ref().expect("a limit");
    assert!(limit.message.contains("24000.0 N"), "{limit:?}");
    assert!(limit.edge.starts_with("y = "), "{limit:?}");
    let b = heavy.hertz.as_ref().unwrap().half_width_mm;
    assert!(
        limit.needed_mm >= 12f64.sqrt() * b,
        "{limit:?} against b = {b}"
    );
    let within = parse(&roller_envelope("[1.0, 1.5]")).unwrap().cases()[0]
        .run()
        .unwrap();
    assert_eq!(within.status, CaseStatus::Solved, "{:?}", within.limit);
}

/// A roller grid whose cells the scene gives (`cell_mm`) is not sized by `reach_b`: the limit
/// of a contact that reaches its edge across said "raise contact.gap.reach_b", which changes
/// nothing there (reach_b = 6 gave the same grid and the same limit); now it says to give more
/// or larger cells. A grid sized by the roller keeps the advice.
#[test]
fn a_roller_grid_of_given_cells_is_widened_by_its_cells() {
    let sized = roller_envelope("[1.0]").replace(
        "cells = [30, 25] }",
        "cells = [30, 21], cell_mm = [0.3333, 0.01] }",
    );
    let report = parse(&sized).unwrap().cases()[0].run().unwrap();
    let limit = report.limit.as_ref().expect("a limit");
    assert!(limit.message.contains("more or larger cells"), "{limit:?}");
    assert!(!limit.message.contains("reach_b"), "{limit:?}");
    let heavy = parse(&roller_envelope("[1.0, 12.0]")).unwrap().cases()[0]
        .run()
        .unwrap();
    assert!(heavy.limit.unwrap().message.contains("reach_b"));
}

/// A rigid flat punch of radius 0.3 mm at 1 kN on 32 × 32 cells of 0.025 mm, its face designed
/// by the load split for an even pressure (a constant controller), Ω_v given by `omega_v` (or
/// the default).
fn even_punch(omega_v: &str) -> String {
    format!(
        r#"name = "even-punch"
[contact]
zone = {{ kind = "grid", cells = [32, 32], cell_mm = [0.025, 0.025] }}
gap = {{ kind = "flat_punch", radius_mm = 0.3 }}
load = {{ force_n = 1000.0 }}

[[body]]
kind = "half_space"
material = {{ e_mpa = 2.0e5, nu = 0.3 }}

[[body]]
kind = "rigid"

[optimisation]
method = "load_split"
controller = {{ kind = "constant", level = 1.0 }}
{omega_v}
"#
    )
}

/// The even pressure under a flat punch is the force over its face: 448 cells of 0.025 mm
/// within r = 0.3 mm, 3571.4 MPa, the face's change a few µm (uniform p on a circle sinks
/// (2 − 4/π)·p·a/E* = 3.5 µm more at the centre than at the rim). The design used to close the
/// gap beyond the rim too, where no punch is (Δh = 4384 µm there, the gap's stand-in for 'open
/// for good'), and spread the force over the whole grid: p_max 1562.5 MPa (−56 %) with exit 0;
/// with Ω_v the punch's face it was refused, the nodes beyond the rim undetermined. Now the
/// gap changes only where the bodies face each other, and Ω_v is the face by default.
#[test]
fn a_flat_punch_is_designed_on_its_face_alone() {
    let even = 1000.0 / (448.0 * 0.025 * 0.025);
    for omega_v in [
        "",
        "omega_v = { kind = \"disc\", centre_mm = [0.0, 0.0], radius_mm = 0.3 }",
    ] {
        let report = parse(&even_punch(omega_v)).unwrap().cases()[0]
            .run()
            .unwrap();
        assert_eq!(report.status, CaseStatus::Solved, "{omega_v}: {report:?}");
        let p_max = report.p_max_mpa.unwrap();
        assert!(
            (p_max / even - 1.0).abs() < 1e-6,
            "{omega_v}: {p_max} vs {even}"
        );
        let dh = report.dh_max_um.unwrap();
        assert!(dh > 1.0 && dh < 10.0, "{omega_v}: Δh_max {dh} µm");
    }
}
