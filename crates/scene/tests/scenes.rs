//! Scenes as compositions: sweeps and cases, builds shared between cases (counted, not timed),
//! checks that build nothing, the pairing of bodies, supports and materials, Ω_v, the observer
//! of a run, and JSON scenes read as TOML ones.

use std::cell::RefCell;
use std::path::Path;

use contopt_core::observe::{Event, Flow, Method};
use contopt_core::Termination;
use contopt_scene::{Format, Scene, SceneError, BUNDLED};

fn text(name: &str) -> &'static str {
    BUNDLED.iter().find(|b| b.name == name).unwrap().text
}

fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::parse(text, Format::Toml, Path::new("mine.toml"))
}

/// The message of a scene that must not parse.
fn refused(text: &str) -> String {
    parse(text)
        .expect_err("the scene must be refused")
        .to_string()
}

/// A sweep over an integer key gives integers: `contact.zone.elements = [4, 6, 8]` makes three
/// meshes, built three times (counted); a whole float is taken, a fraction refused at its
/// value with the key.
#[test]
fn a_sweep_over_an_integer_key_sets_integers() {
    let swept = text("paper-table1").replace(
        "key = \"optimisation.controller.l1_mm\"\nvalues = [0.0, 20.0, 30.0, 40.0, 50.0]",
        "key = \"contact.zone.elements\"\nvalues = [4, 6.0, 8]",
    );
    let scene = parse(&swept).unwrap();
    let labels: Vec<&str> = scene.cases().iter().map(|c| c.label.as_str()).collect();
    assert_eq!(labels, ["elements = 4", "elements = 6", "elements = 8"]);
    let mut run = scene.run();
    assert_eq!(run.distinct_bodies(), 3);
    let reports: Vec<_> = run.by_ref().map(Result::unwrap).collect();
    assert_eq!(run.builds(), 3);
    let points: Vec<usize> = reports.iter().map(|r| r.interface.len()).collect();
    assert_eq!(points, [12, 18, 24]);
    let fraction = swept.replace("values = [4, 6.0, 8]", "values = [4, 6.5]");
    let message = refused(&fraction);
    assert!(
        message.contains("mine.toml:")
            && message.contains("sweep.values[1]")
            && message.contains("6.5")
            && message.contains("whole numbers"),
        "{message}"
    );
}

/// `scene` with a `[[case]]` of `label` that sets `set` (a TOML inline table's inside).
fn with_case(scene: &str, label: &str, set: &str) -> String {
    format!("{scene}\n[[case]]\nlabel = {label:?}\nset = {{ {set} }}\n")
}

/// A `[[case]]` that sets a table where the scene has one sets the keys it names, key by key,
/// and keeps the scene's others: the scene's TOLH (2·10⁻⁶ mm²) stays in a case that sets
/// another method setting or the controller (it fell back to the default 0.5·10⁻⁶ mm²), the
/// zone and load in a case that sets the gap. A table naming another `kind` is another
/// choice, with that kind's own keys: it replaces the scene's.
#[test]
fn a_case_setting_a_table_sets_its_keys_only() {
    let sweep =
        "[sweep]\nkey = \"optimisation.controller.l1_mm\"\nvalues = [0.0, 20.0, 30.0, 40.0, 50.0]";
    let base = text("paper-table1")
        .replace(sweep, "")
        .replace("tolh_mm2 = 0.5e-6", "tolh_mm2 = 2e-6");
    let cases = [
        ("iterations", "optimisation.method.max_iterations = 7"),
        (
            "controller",
            "optimisation = { controller = { l1_mm = 20.0 } }",
        ),
        (
            "programme",
            "\"optimisation.method\" = { kind = \"linear_programme\" }",
        ),
        (
            "dotted",
            "\"optimisation.method\" = { kind = \"given_load\", max_iterations = 9 }",
        ),
    ];
    let studied = cases
        .iter()
        .fold(base, |text, (label, set)| with_case(&text, label, set));
    let scene = parse(&studied).unwrap();
    let method = |k: usize| scene.cases()[k].input()["optimisation"]["method"].clone();
    let controller = |k: usize| scene.cases()[k].input()["optimisation"]["controller"].clone();
    assert_eq!(method(0)["given_load"]["tolh_mm2"], 2e-6, "{}", method(0));
    assert_eq!(method(0)["given_load"]["max_iterations"], 7);
    assert_eq!(method(1)["given_load"]["tolh_mm2"], 2e-6, "{}", method(1));
    assert_eq!(controller(1)["cubic"]["l1_mm"], 20.0, "{}", controller(1));
    assert_eq!(controller(1)["cubic"]["l2_mm"], 50.0, "{}", controller(1));
    let programme = method(2)
        .as_object()
        .map(|m| m.keys().cloned().collect::<Vec<_>>());
    assert_eq!(programme, Some(vec!["linear_programme".to_string()]));
    assert_eq!(method(3)["given_load"]["tolh_mm2"], 2e-6, "{}", method(3));
    assert_eq!(
        method(3)["given_load"]["max_iterations"],
        9,
        "{}",
        method(3)
    );

    let large = with_case(
        text("hertz"),
        "large",
        "contact = { gap = { radius_mm = 40.0 } }",
    );
    let scene = parse(&large).unwrap();
    let contact = scene.cases()[0].input()["contact"].clone();
    assert_eq!(contact["gap"]["sphere"]["radius_mm"], 40.0, "{contact}");
    assert_eq!(contact["load"]["force_n"], 1000.0, "{contact}");
}

/// A case's `params` name each number it sets by its dotted path, with its value, however the
/// case writes it: a dotted key (a TOML table), a table, a table of another kind, an array (by
/// index, as a dotted path indexes one). They used to list only a number set at the top of
/// `set`: a case setting `optimisation.method.max_iterations = 7` had no params at all. A
/// value that is not a number (a kind) is not one; the case's `input` holds it.
#[test]
fn a_cases_params_name_every_number_it_sets() {
    let sweep =
        "[sweep]\nkey = \"optimisation.controller.l1_mm\"\nvalues = [0.0, 20.0, 30.0, 40.0, 50.0]";
    let cases = [
        ("dotted", "optimisation.method.max_iterations = 7"),
        (
            "table",
            "optimisation = { controller = { l1_mm = 20.0, l2_mm = 40.0 } }",
        ),
        (
            "another kind",
            "\"optimisation.method\" = { kind = \"linear_programme\" }",
        ),
        ("quoted", "\"optimisation.controller.l1_mm\" = 30.0"),
    ];
    let studied = cases.iter().fold(
        text("paper-table1").replace(sweep, ""),
        |text, (label, set)| with_case(&text, label, set),
    );
    let scene = parse(&studied).unwrap();
    let params = |k: usize| {
        let case = &scene.cases()[k];
        case.params
            .iter()
            .map(|(k, v)| (k.as_str(), *v))
            .collect::<Vec<_>>()
    };
    assert_eq!(params(0), [("optimisation.method.max_iterations", 7.0)]);
    assert_eq!(
        params(1),
        [
            ("optimisation.controller.l1_mm", 20.0),
            ("optimisation.controller.l2_mm", 40.0)
        ]
    );
    assert_eq!(params(2), []);
    assert_eq!(params(3), [("optimisation.controller.l1_mm", 30.0)]);

    let cells = with_case(text("hertz"), "cells", "contact.zone.cells = [32, 48]");
    let scene = parse(&cells).unwrap();
    let params: Vec<_> = scene.cases()[0].params.clone().into_iter().collect();
    assert_eq!(
        params,
        [
            ("contact.zone.cells.0".to_string(), 32.0),
            ("contact.zone.cells.1".to_string(), 48.0)
        ]
    );
    let input = scene.cases()[0].input();
    assert_eq!(input["contact"]["zone"]["grid"]["cells"][1], 48, "{input}");
}

/// A case's label is one line: a line break in it split the printed table's row and the
/// error lines that name the case (it ran, exit 3, the row broken in two).
#[test]
fn a_label_with_a_line_break_is_refused() {
    let scene = with_case(
        text("hertz"),
        "2 kN\nheavy",
        "\"contact.load.force_n\" = 2000.0",
    );
    let message = refused(&scene);
    assert!(
        message.contains("mine.toml:")
            && message.contains("case[0].label")
            && message.contains("control"),
        "{message}"
    );
}

/// A scene's `name` names its one results folder and its `description` heads its report: a
/// case that set them renamed the whole scene's folder (the first case: `contopt run` wrote
/// every case into `results/other/`) or was ignored (a later case), both without a word. Now
/// refused at the case's key.
#[test]
fn a_case_cannot_rename_the_scene() {
    for (set, key) in [
        ("name = \"other\"", "case[0].set.name"),
        ("description = \"mine\"", "case[0].set.description"),
    ] {
        let message = refused(&with_case(text("hertz"), "renamed", set));
        assert!(
            message.contains("mine.toml:") && message.contains(key) && message.contains("scene's"),
            "{message}"
        );
    }
}

/// A case that sets one key twice, written two ways, is refused: the last value was solved
/// while the case's numbers (`params` in result.json) reported the first (radius 20 mm
/// reported, 40 mm solved). A table setting two keys of one table is not twice.
#[test]
fn a_case_setting_a_key_twice_is_refused() {
    let set = "\"contact.gap.radius_mm\" = 20.0, contact = { gap = { radius_mm = 40.0 } }";
    let message = refused(&with_case(text("hertz"), "twice", set));
    assert!(
        message.contains("case[0].set")
            && message.contains("`contact.gap.radius_mm` and `contact.gap.radius_mm`"),
        "{message}"
    );
    let whole = "\"contact.gap\" = { kind = \"cylinder\", radius_mm = 5.0 }, \
                 \"contact.gap.radius_mm\" = 6.0";
    assert!(refused(&with_case(text("hertz"), "whole", whole)).contains("twice"));
    let both = "contact = { gap = { radius_mm = 40.0 }, load = { force_n = 10.0 } }";
    parse(&with_case(text("hertz"), "both", both)).unwrap();
}

/// A table of another kind replaces the scene's whole: a key of the scene's table it leaves
/// out is missing, and the error says why. A choice written under its name (a load) merged
/// into the scene's another is two choices, refused with why.
#[test]
fn a_case_setting_another_kind_is_told_it_replaces_the_table() {
    let rings = with_case(
        text("hertz"),
        "rings",
        "contact = { zone = { kind = \"rings\" } }",
    );
    let message = refused(&rings);
    assert!(
        message.contains("[rings] contact.zone") && message.contains("another `kind`"),
        "{message}"
    );
    let set = "contact = { load = { approach_mm = 0.01 } }";
    let message = refused(&with_case(text("hertz"), "approach", set));
    assert!(
        message.contains("[approach] contact.load") && message.contains("merged into the scene's"),
        "{message}"
    );
}

/// Cases that differ only in the controller share one build of their bodies (one
/// factorisation per body), and each gives what it gives on bodies built for it alone.
#[test]
fn cases_that_share_their_bodies_build_once() {
    let scene =
        Scene::bundled_with("paper-table1", &[("contact.zone.elements", Some("6"))]).unwrap();
    let before = contopt_fem::factorisations();
    let mut run = scene.run();
    let together: Vec<_> = run.by_ref().map(Result::unwrap).collect();
    assert_eq!((run.distinct_bodies(), run.builds()), (1, 1));
    assert_eq!(contopt_fem::factorisations() - before, 2, "one per body");
    for (case, shared) in scene.cases().iter().zip(&together) {
        let alone = case.run().unwrap();
        assert_eq!(
            alone.bound_p_max_mpa, shared.bound_p_max_mpa,
            "{}",
            case.label
        );
        assert_eq!(alone.interface, shared.interface, "{}", case.label);
    }
    let build = |k: usize| together[k].timings_ms["build"];
    assert!(build(0) > 0.0 && (1..5).all(|k| build(k) < build(0)));
}

/// On several threads the halves of a sweep over one pair of bodies share one build of it, and
/// every case gives the bits it gives on one thread.
#[test]
fn threads_share_one_build() {
    let scene =
        Scene::bundled_with("paper-table2", &[("contact.zone.elements", Some("6"))]).unwrap();
    let one: Vec<_> = scene.run().map(Result::unwrap).collect();
    for jobs in [2, 3] {
        let ran = scene.run_parallel(0..5, jobs, &|| {}).unwrap();
        assert_eq!(ran.builds, 1, "{jobs} threads");
        for (alone, shared) in one.iter().zip(ran.results) {
            let shared = shared.unwrap();
            assert_eq!(alone.interface, shared.interface, "{}", alone.label);
            assert_eq!(alone.bound_p_max_mpa, shared.bound_p_max_mpa);
        }
    }
}

/// Reading a scene checks its finite-element bodies without factorising them: not one
/// factorisation on 72 elements, and the run factorises both bodies.
#[test]
fn reading_a_scene_factorises_nothing() {
    let before = contopt_fem::factorisations();
    let scene = Scene::bundled_with(
        "paper-table2",
        &[("contact.zone.elements", Some("72")), ("sweep", None)],
    )
    .unwrap();
    assert_eq!(contopt_fem::factorisations(), before);
    scene.cases()[0].build().unwrap();
    assert_eq!(contopt_fem::factorisations() - before, 2);
}

/// The pairing of bodies follows the physics and the zone, each refusal naming the key: a
/// half-space does not mesh faces, a punch stands above a base, two rigid bodies share no
/// compliance, a bed cannot float under a force, a punch takes no contact force.
#[test]
fn bodies_pair_where_the_physics_allows() {
    let hertz = text("hertz");
    let table1 = text("paper-table1");
    let cases = [
        (
            hertz.replace(
                "kind = \"half_space\"\nmaterial = { e_mpa = 2.0e5, nu = 0.3 }",
                "kind = \"rigid\"",
            ),
            "body[1].kind",
        ),
        (
            hertz.replace(
                "kind = \"rigid\"",
                "kind = \"winkler\"\nmodulus_mpa_per_mm = 10.0",
            ),
            "contact.load.force_n",
        ),
        (
            table1
                .replace("kind = \"fe_base\"", "kind = \"half_space\"")
                .replace(
                    "radius_mm = 100.0\nheight_mm = 50.0\nsupports = [\"clamped\"]\n",
                    "",
                ),
            "body[0].kind",
        ),
        (
            table1.replace("[contact]", "[contact]\nload = { force_n = 1000.0 }"),
            "contact.load.force_n",
        ),
    ];
    for (scene, key) in cases {
        let message = refused(&scene);
        assert!(message.contains(key), "{key}: {message}");
    }
    // A punch below the zone and a base above it.
    let parts: Vec<&str> = table1.split("[[body]]").collect();
    let (punch, rest) = parts[2].split_at(parts[2].find("\n#").unwrap());
    let swapped = format!("{}[[body]]{punch}\n[[body]]{}{rest}", parts[0], parts[1]);
    let message = refused(&swapped);
    assert!(
        message.contains("body[0].kind") && message.contains("punch stands"),
        "{message}"
    );
}

/// Supports against the analysis: one support of the bottom face, symmetry only in a plane
/// model, a plane base held axially needs its symmetry line; each error at the base's key.
#[test]
fn supports_are_checked() {
    let axisymmetric = text("paper-table1");
    let plane = text("paper-table3");
    let cases = [
        (
            axisymmetric.replace("[\"clamped\"]", "[\"clamped\", \"axial\"]"),
            "one support",
        ),
        (
            axisymmetric.replace("[\"clamped\"]", "[\"clamped\", \"symmetry\"]"),
            "symmetric about its axis",
        ),
        (
            plane.replace("[\"axial\", \"symmetry\"]", "[\"axial\"]"),
            "slides sideways",
        ),
    ];
    for (scene, needle) in cases {
        let message = refused(&scene);
        assert!(
            message.contains("body[0].supports") && message.contains(needle),
            "{message}"
        );
    }
    assert!(parse(&plane.replace("[\"axial\", \"symmetry\"]", "[\"clamped\"]")).is_ok());
}

/// The approach of the punch under 100 MPa on six elements.
fn approach(scene: &str, edits: &[(&str, Option<&str>)]) -> f64 {
    let mut all = vec![
        ("contact.zone.elements", Some("6")),
        ("sweep", None),
        ("optimisation", None),
    ];
    all.extend_from_slice(edits);
    let scene = Scene::bundled_with(scene, &all).unwrap();
    let report = scene.cases()[0].run().unwrap();
    assert!(report.is_solved(), "{:?}", report.termination);
    report.approach_um.unwrap()
}

/// A base held axially only is softer than a clamped one (the punch sinks further), and
/// doubling both moduli halves the approach (linear elasticity, but for the penalty's p/c
/// of 10⁻⁶ of it): neither would hold if the support or a body's material were ignored.
#[test]
fn supports_and_materials_act() {
    let clamped = approach("paper-table1", &[]);
    let axial = approach("paper-table1", &[("body.0.supports", Some("[\"axial\"]"))]);
    assert!(axial > clamped * 1.01, "{axial} vs {clamped}");
    let stiff = approach(
        "paper-table1",
        &[
            ("body.0.material", Some("{ e_mpa = 4.0e5, nu = 0.3 }")),
            ("body.1.material", Some("{ e_mpa = 4.0e5, nu = 0.3 }")),
        ],
    );
    assert!((stiff / clamped - 0.5).abs() < 1e-5, "{stiff} vs {clamped}");
    let soft_base = approach(
        "paper-table1",
        &[("body.0.material", Some("{ e_mpa = 7.0e4, nu = 0.33 }"))],
    );
    assert!(soft_base > clamped, "{soft_base} vs {clamped}");
}

/// Unknown keys and keys of the old schema are refused at their line with the keys allowed;
/// a base no wider than the zone is refused at its radius.
#[test]
fn keys_and_dimensions_are_checked() {
    let table1 = text("paper-table1");
    let typo = table1.replace("height_mm = 50.0\nload", "heigth_mm = 50.0\nload");
    let message = refused(&typo);
    assert!(
        message.contains("body[1].heigth_mm") && message.contains("height_mm"),
        "{message}"
    );
    let old = format!("[problem]\nkind = \"punch_on_base\"\n{table1}");
    assert!(refused(&old).contains("problem"), "{}", refused(&old));
    let narrow = table1.replace("radius_mm = 100.0", "radius_mm = 40.0");
    let message = refused(&narrow);
    assert!(
        message.contains("body[0].radius_mm") && message.contains("40"),
        "{message}"
    );
}

/// A block little wider than its near-surface layer builds (size 50 mm on a zone of 10 mm in
/// four elements: more than twice the radius, as documented; its outer elements start below
/// the zone's edge size), and a grading f64 cannot lay out is refused at the zone's
/// `grading`, not at a spacing's coordinates.
#[test]
fn a_block_and_a_grading_are_checked_in_the_scene_s_words() {
    let block = text("punch-on-block")
        .replace("elements = 20", "elements = 4")
        .replace("size_mm = 200.0", "size_mm = 50.0");
    let scene = parse(&block).expect("a block of 50 mm on 10 mm reads");
    let built = scene.cases()[0].build().expect("and builds");
    assert_eq!(built.first().name(), "block");
    let narrow = block.replace("size_mm = 50.0", "size_mm = 20.0");
    let message = refused(&narrow);
    assert!(message.contains("body[0].size_mm"), "{message}");
    for grading in ["1e300", "5e-324"] {
        let zone = format!("elements = 4, grading = {grading}");
        let message = refused(&block.replace("elements = 4", &zone));
        assert!(
            message.contains("contact.zone.grading") && !message.contains("coords"),
            "{message}"
        );
    }
}

/// The observer of a run sees the optimisation at level 0 and its contact solves at level 1,
/// each ending with an event that says how it ended; a stop ends the case, not converged,
/// saying that an observer stopped it.
#[test]
fn a_run_reports_to_its_observer() {
    let scene = Scene::bundled_with(
        "paper-table2",
        &[("contact.zone.elements", Some("6")), ("sweep", None)],
    )
    .unwrap();
    let seen = RefCell::new(vec![]);
    let watch = |e: &Event| {
        seen.borrow_mut().push((e.method, e.level, e.end.is_some()));
        Flow::Continue
    };
    let report = scene.cases()[0].run_observed(&watch).unwrap();
    assert!(report.is_solved());
    let seen = seen.into_inner();
    assert!(seen.contains(&(Method::GapIteration, 0, false)));
    assert!(seen.contains(&(Method::GapIteration, 0, true)));
    assert!(seen.contains(&(Method::Penalty, 1, false)));
    let stop = |e: &Event| {
        if e.method == Method::GapIteration && e.iteration == 2 {
            Flow::Stop
        } else {
            Flow::Continue
        }
    };
    let stopped = scene.cases()[0].run_observed(&stop).unwrap();
    assert!(!stopped.is_solved());
    assert_eq!(stopped.termination, Termination::Stopped { after: 2 });
}

/// A contact analysis reports its solve's steps by method and level, as its observer saw
/// them, and Kalker's counts: Polonsky–Keer's on the zone's grid and its nested start's
/// coarser grids apart; the augmented Lagrangian's Uzawa updates and its Kalker solves.
#[test]
fn a_contact_analysis_reports_its_steps_by_level() {
    for (solver, inner) in [
        ("\"polonsky_keer\"", Method::PolonskyKeer),
        (
            "{ kind = \"augmented_lagrangian\", c_mpa_per_mm = 2e6 }",
            Method::Kalker,
        ),
    ] {
        let edits = [
            ("contact.zone.cells", Some("[24, 24]")),
            ("contact.zone.cell_mm", Some("[0.04, 0.04]")),
            ("output", None),
            ("solver", Some(solver)),
        ];
        let scene = Scene::bundled_with("hertz", &edits).unwrap();
        let seen = RefCell::new(std::collections::BTreeMap::new());
        let watch = |e: &Event| {
            if e.end.is_none() {
                *seen.borrow_mut().entry((e.level, e.method)).or_insert(0) += 1;
            }
            Flow::Continue
        };
        let report = scene.cases()[0].run_observed(&watch).unwrap();
        assert!(report.is_solved(), "{solver}: {}", report.message);
        let solve = report.solve.expect("an analysis reports its solve");
        let mut reported: Vec<_> = solve
            .steps
            .iter()
            .map(|s| ((s.level, s.method), s.steps))
            .collect();
        reported.sort();
        let seen: Vec<_> = seen.into_inner().into_iter().collect();
        assert_eq!(reported, seen, "{solver}");
        let deeper: usize = solve
            .steps
            .iter()
            .filter(|s| s.level > 0)
            .map(|s| s.steps)
            .sum();
        assert!(
            solve
                .steps
                .iter()
                .any(|s| s.level == 1 && s.method == inner)
                && deeper > 0,
            "{solver}: {:?}",
            solve.steps
        );
        if inner == Method::Kalker {
            assert_eq!(deeper, solve.iterp, "{solver}: each Kalker solve is a step");
            assert!(solve.iterd >= 1 && solve.iterd <= solve.iterp);
        } else {
            assert_eq!([solve.iterp, solve.iterd], [0, 0]);
        }
    }
}

/// A scene written in JSON reads as its TOML, and its errors are placed in the JSON text.
#[test]
fn json_scenes_read_as_toml_ones() {
    let json = r#"{
  "name": "hertz-json",
  "contact": {
    "zone": { "kind": "grid", "cells": [16, 16], "cell_mm": [0.05, 0.05] },
    "gap": { "kind": "sphere", "radius_mm": 10.0 },
    "load": { "force_n": 1000.0 }
  },
  "body": [
    { "kind": "half_space", "material": { "e_mpa": 2.0e5, "nu": 0.3 } },
    { "kind": "rigid" }
  ]
}"#;
    let scene = Scene::parse(json, Format::Json, Path::new("mine.json")).unwrap();
    let report = scene.cases()[0].run().unwrap();
    assert!(report.is_solved() && report.p_max_mpa.unwrap() > 0.0);
    let bad = json.replace("\"nu\": 0.3", "\"nu\": 0.7");
    let e = Scene::parse(&bad, Format::Json, Path::new("mine.json")).unwrap_err();
    let message = e.to_string();
    assert!(
        message.starts_with("mine.json:9:") && message.contains("body[0].material"),
        "{message}"
    );
}

/// The bundled validation scenes carry their closed form and lie within a few per cent of it
/// along the plotted row: Hertz on the grid (within 2 % of p₀ for r < 0.8 a; its label with
/// p₀ and a), Sneddon on the rings (within 3 % for r < 8 mm of 10), the Winkler bed's
/// p = k(δ − r²/2R) on its rings (within 0.1 % of p(0)); the paper's punch has none.
#[test]
fn validation_scenes_match_their_closed_forms() {
    let run = |name: &str| Scene::bundled(name).unwrap().cases()[0].run().unwrap();
    let hertz = run("hertz");
    let curve = hertz.reference.as_ref().unwrap();
    assert!(
        curve
            .label
            .starts_with("Hertz: p₀ = 4538 MPa, a = 0.3244 mm"),
        "{}",
        curve.label
    );
    let (p0, a) = (4538.297, 0.324358);
    let row = hertz
        .interface
        .iter()
        .map(|q| q.x_mm[1].abs())
        .fold(f64::INFINITY, f64::min);
    for q in hertz
        .interface
        .iter()
        .filter(|q| q.x_mm[1].abs() <= row + 1e-9)
    {
        let r = q.x_mm[0].hypot(q.x_mm[1]);
        if r < 0.8 * a {
            let exact = p0 * (1.0 - (r / a).powi(2)).sqrt();
            assert!((q.p_mpa - exact).abs() < 0.02 * p0, "{q:?} {exact}");
        }
    }
    let punch = run("flat-punch");
    let curve = punch.reference.as_ref().unwrap();
    assert!(curve.label.contains("p(0) = 50.0 MPa"), "{}", curve.label);
    for q in punch.interface.iter().filter(|q| q.x_mm[0] < 8.0) {
        let exact = 50.0 / (1.0 - (q.x_mm[0] / 10.0).powi(2)).sqrt();
        assert!((q.p_mpa / exact - 1.0).abs() < 0.03, "{q:?} {exact}");
    }
    let bed = run("winkler-bed");
    let (k, r) = (50.0, 20.0);
    let delta = (1000.0 / (std::f64::consts::PI * k * r)).sqrt();
    for q in &bed.interface {
        let exact = (k * (delta - q.x_mm[0].powi(2) / (2.0 * r))).max(0.0);
        assert!((q.p_mpa - exact).abs() < 1e-3 * k * delta, "{q:?} {exact}");
    }
    assert!((bed.approach_um.unwrap() / (1e3 * delta) - 1.0).abs() < 1e-4);
    assert!(run("paper-table1").reference.is_none());
}
