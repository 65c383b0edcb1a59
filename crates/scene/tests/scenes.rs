//! Scenes of real geometry: per-body materials and dimensions, the base's supports, Ω_v as a
//! region, integer sweeps, and the run that builds each distinct set of bodies once.

use std::path::Path;
use std::time::Instant;

use contopt_contact::{ActiveSet, ContactSolver, InterfaceProblem};
use contopt_core::{ElasticBody, Material};
use contopt_fem::ElementKind;
use contopt_optimise::{Controller, Profile};
use contopt_scene::geometry::{PunchMesh, PunchOnBase, Support};
use contopt_scene::{Format, OmegaVSpec, Problem, Scene, SceneError, BUNDLED};

/// The text of the bundled scene `name` with each `(from, to)` replaced once.
fn bundled(name: &str, changes: &[(&str, &str)]) -> String {
    let mut text = BUNDLED
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| t.to_string())
        .unwrap();
    for (from, to) in changes {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    text
}

fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::parse(text, Format::Toml, Path::new("test.toml"))
}

/// The error of a scene that must not parse.
fn refused(text: &str) -> String {
    parse(text)
        .expect_err("the scene must be refused")
        .to_string()
}

/// The approach of the punch (−λ of its rigid mode) and the contact pressure under `geometry`,
/// by the exact active set.
fn contact(geometry: &PunchOnBase) -> (f64, Vec<f64>) {
    let (base, punch) = geometry.bodies().unwrap();
    let n = base.interface().len();
    let problem = InterfaceProblem::new(&base, &punch, &vec![0.0; n]).unwrap();
    let state = ActiveSet.solve(&problem).unwrap();
    (-state.rigid[0], state.pressure)
}

fn coarse(name: &str) -> PunchOnBase {
    PunchOnBase {
        mesh: PunchMesh::uniform(ElementKind::Q8, 6),
        ..PunchOnBase::bundled(name).unwrap()
    }
}

/// A sweep over an integer key gives integer values: `problem.mesh.elements = [4, 6, 8]`
/// makes three meshes (and three builds); whole floats are taken, a fraction is refused with
/// the key and the value.
#[test]
fn a_sweep_over_an_integer_key_sets_integers() {
    let sweep = |values: &str| {
        let text = bundled("paper-table1", &[("elements = 18", "elements = 4")]);
        let cut = text.find("[sweep]").unwrap();
        format!(
            "{}[sweep]\nkey = \"problem.mesh.elements\"\nvalues = {values}\n",
            &text[..cut]
        )
    };
    let elements = |scene: &Scene| -> Vec<usize> {
        let cases = scene.cases().unwrap();
        cases
            .iter()
            .map(|c| match &c.spec.problem {
                Problem::PunchOnBase(p) => p.mesh.elements,
                _ => 0,
            })
            .collect()
    };
    let scene = parse(&sweep("[4, 6, 8]")).unwrap();
    assert_eq!(elements(&scene), [4, 6, 8]);
    let cases = scene.cases().unwrap();
    assert_eq!(cases[1].label, "elements = 6");
    assert_eq!(cases[1].params["elements"], 6.0);
    assert_eq!(scene.run().unwrap().builds(), 3);

    let whole = parse(&sweep("[4.0, 6]")).unwrap();
    assert_eq!(elements(&whole), [4, 6]);
    let e = refused(&sweep("[4, 6.5]"));
    assert!(
        e.contains("problem.mesh.elements") && e.contains("6.5"),
        "{e}"
    );
    let e = refused(&sweep("[-4]"));
    assert!(
        e.contains("problem.mesh.elements") && e.contains("-4"),
        "{e}"
    );
}

/// Cases that differ only in the controller share one build, and give what each case gives on
/// its own bodies, to the last bit; the later cases' build is only their interface.
#[test]
fn cases_that_share_the_problem_build_once() {
    let text = bundled("paper-table2", &[("elements = 18", "elements = 8")]);
    let scene = parse(&text).unwrap();
    let run = scene.run().unwrap();
    assert_eq!((run.cases().len(), run.builds()), (5, 1));
    let shared: Vec<_> = run.map(Result::unwrap).collect();
    for (case, together) in scene.cases().unwrap().iter().zip(&shared) {
        let alone = case.run().unwrap();
        assert_eq!(alone.bound_p_max, together.bound_p_max, "{}", case.label);
        assert_eq!(alone.dh_max_um, together.dh_max_um, "{}", case.label);
        let p = |r: &contopt_scene::CaseReport| r.interface.iter().map(|q| q.p).collect::<Vec<_>>();
        assert_eq!(p(&alone), p(together), "{}", case.label);
    }
    let build = |k: usize| shared[k].timings_ms["build"];
    assert!((1..5).all(|k| build(k) < 0.1 * build(0)), "{shared:#?}");
}

/// Parsing checks a finite-element problem without factorising it: on 72 elements the parse
/// takes a small fraction of one build.
#[test]
fn parse_does_not_factorise() {
    let text = bundled("paper-table2", &[("elements = 18", "elements = 72")]);
    let start = Instant::now();
    let scene = parse(&text).unwrap();
    let parsed = start.elapsed().as_secs_f64();
    let case = &scene.cases().unwrap()[0];
    let start = Instant::now();
    let report = scene.run().unwrap().next().unwrap().unwrap();
    let built = 1e-3 * report.timings_ms["build"];
    assert!(start.elapsed().as_secs_f64() >= built);
    assert!(parsed < 0.2 * built, "parse {parsed} s, build {built} s");
    case.check().unwrap();
}

/// The supports are checked against the analysis: one bottom support, symmetry only in a
/// plane model, a plane base held axially needs its symmetry line; each error names the key.
#[test]
fn supports_are_checked() {
    let table1 = |supports: &str| {
        bundled(
            "paper-table1",
            &[(
                "supports = [\"clamped\"]",
                &format!("supports = {supports}"),
            )],
        )
    };
    let e = refused(&table1("[\"clamped\", \"symmetry\"]"));
    assert!(
        e.contains("base.supports") && e.contains("axisymmetric body"),
        "{e}"
    );
    let e = refused(&table1("[]"));
    assert!(
        e.contains("base.supports") && e.contains("one support"),
        "{e}"
    );
    let e = refused(&table1("[\"clamped\", \"axial\"]"));
    assert!(e.contains("base.supports"), "{e}");
    let e = refused(&table1("[\"pinned\"]"));
    assert!(e.contains("pinned") && e.contains("clamped"), "{e}");
    let table3 = |supports: &str| {
        bundled(
            "paper-table3",
            &[(
                "supports = [\"axial\", \"symmetry\"]",
                &format!("supports = {supports}"),
            )],
        )
    };
    let e = refused(&table3("[\"axial\"]"));
    assert!(
        e.contains("base.supports") && e.contains("slides sideways"),
        "{e}"
    );
    parse(&table3("[\"clamped\"]")).unwrap();
    parse(&table3("[\"clamped\", \"symmetry\"]")).unwrap();
}

/// A base held axially only is softer than a clamped one: the punch sinks further under the
/// same load, in both analyses (which would not hold if the support were ignored).
#[test]
fn an_axial_support_is_softer_than_a_clamp() {
    for (name, from, to) in [
        ("paper-table1", Support::Clamped, Support::Axial),
        ("paper-table3", Support::Axial, Support::Clamped),
    ] {
        let given = coarse(name);
        let other = PunchOnBase {
            supports: given
                .supports
                .iter()
                .map(|&s| if s == from { to } else { s })
                .collect(),
            ..given.clone()
        };
        let (a, _) = contact(&given);
        let (b, _) = contact(&other);
        let (clamped, axial) = if from == Support::Clamped {
            (a, b)
        } else {
            (b, a)
        };
        assert!(axial > 1.01 * clamped, "{name}: {axial} vs {clamped}");
    }
}

/// Per-body materials: doubling both moduli leaves the pressure and halves the approach
/// (linear elasticity); a steel punch on an aluminium base sinks further than on steel and
/// less than aluminium on aluminium.
#[test]
fn each_body_has_its_material() {
    let steel = Material::new(2.0e5, 0.3).unwrap();
    let aluminium = Material::new(7.0e4, 0.3).unwrap();
    let with = |punch: Material, base: Material| {
        let mut g = coarse("paper-table1");
        g.punch.material = punch;
        g.base.material = base;
        contact(&g)
    };
    let (steel_steel, p) = with(steel, steel);
    let stiff = Material::new(4.0e5, 0.3).unwrap();
    let (stiff_stiff, q) = with(stiff, stiff);
    assert!((stiff_stiff / steel_steel - 0.5).abs() < 1e-9);
    let scale = p.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(p.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9 * scale));
    let (mixed, _) = with(steel, aluminium);
    let (soft, _) = with(aluminium, aluminium);
    assert!(
        steel_steel < mixed && mixed < soft,
        "{steel_steel} {mixed} {soft}"
    );
    // Each body reports the material it was given.
    let mut g = coarse("paper-table1");
    g.base.material = aluminium;
    let (base, punch) = g.bodies().unwrap();
    assert_eq!(*base.model().material(), aluminium);
    assert_eq!(*punch.model().material(), steel);
}

/// The shared material is a shorthand: a body without its own takes it; a body without any is
/// refused, and so is a shared material that neither body uses.
#[test]
fn materials_are_checked() {
    let e = refused(&bundled(
        "paper-table1",
        &[("material = { e_mpa = 2.0e5, nu = 0.3 }\n", "")],
    ));
    assert!(e.contains("punch.material") && e.contains("missing"), "{e}");
    let both = bundled(
        "paper-table1",
        &[
            (
                "height_mm = 50.0 }",
                "height_mm = 50.0, material = { e_mpa = 2.1e5, nu = 0.3 } }",
            ),
            (
                "supports = [\"clamped\"] }",
                "supports = [\"clamped\"], material = { e_mpa = 7.0e4, nu = 0.33 } }",
            ),
        ],
    );
    let e = refused(&both);
    assert!(
        e.contains("material") && e.contains("remove the shared one"),
        "{e}"
    );
    let own = both.replacen("material = { e_mpa = 2.0e5, nu = 0.3 }\n", "", 1);
    let scene = parse(&own).unwrap();
    let Problem::PunchOnBase(spec) = &scene.spec.problem else {
        panic!("a punch on a base")
    };
    let g = spec.geometry().unwrap();
    assert_eq!((g.punch.material.e(), g.base.material.nu()), (2.1e5, 0.33));
    let e = refused(&bundled("paper-table1", &[("nu = 0.3", "nu = 0.5")]));
    assert!(e.contains("nu") && e.contains("0.5"), "{e}");
}

/// Dimensions, mesh and load are checked at parse, each error naming its key and value; keys
/// of the old schema and unknown keys are refused.
#[test]
fn dimensions_and_keys_are_checked() {
    for (from, to, key) in [
        ("radius_mm = 100.0", "radius_mm = 40.0", "base.radius_mm"),
        (
            "height_mm = 50.0 }",
            "height_mm = -1.0 }",
            "punch.height_mm",
        ),
        ("elements = 18", "elements = 0", "mesh.elements"),
        (
            "mesh = { elements = 18",
            "mesh = { grading = 0.0, elements = 18",
            "mesh.grading",
        ),
        (
            "pressure_mpa = 100.0",
            "pressure_mpa = 0.0",
            "not pressed into contact",
        ),
        (
            "height_mm = 50.0 }",
            "height_mm = 50.0, depth_mm = 1.0 }",
            "depth_mm",
        ),
        (
            "kind = \"punch_on_base\"",
            "kind = \"punch_on_base\"\npunch_radius_mm = 50.0",
            "punch_radius_mm",
        ),
        (
            "analysis = \"axisymmetric\"",
            "analysis = { plane_stress = { thickness_mm = -2.0 } }",
            "thickness_mm",
        ),
        (
            "analysis = \"axisymmetric\"",
            "analysis = \"plane_stress\"",
            "plane_stress",
        ),
    ] {
        let e = refused(&bundled("paper-table1", &[(from, to)]));
        assert!(e.contains(key), "{to}: {e}");
    }
}

/// Ω_v's shapes on the contact surface: a finite-element face's points (r, z) with normal y
/// are placed by r; a grid's (x, y) with normal z by both.
#[test]
fn omega_v_regions_contain_their_points() {
    let face = |r: f64| ([r, 50.0, 0.0], [0.0, -1.0, 0.0]);
    let disc = OmegaVSpec::Disc {
        centre_mm: [0.0, 0.0],
        radius_mm: 30.0,
    };
    let strip = OmegaVSpec::Strip {
        axis: 0,
        from_mm: 0.0,
        to_mm: 30.0,
    };
    for r in [0.0, 10.0, 29.9, 30.1, 49.0] {
        let (x, n) = face(r);
        assert_eq!(disc.contains(x, n), r <= 30.0, "{r}");
        assert_eq!(strip.contains(x, n), r <= 30.0, "{r}");
    }
    let grid = |x: f64, y: f64| ([x, y, 0.0], [0.0, 0.0, 1.0]);
    let unit = OmegaVSpec::Box {
        from_mm: [-1.0, -0.5],
        to_mm: [1.0, 0.5],
    };
    let across = OmegaVSpec::Strip {
        axis: 1,
        from_mm: -0.5,
        to_mm: 0.5,
    };
    let round = OmegaVSpec::Disc {
        centre_mm: [1.0, 0.0],
        radius_mm: 1.0,
    };
    for (x, y, in_box, in_strip, in_disc) in [
        (0.0, 0.0, true, true, true),
        (1.5, 0.2, false, true, true),
        (0.5, 0.8, false, false, true),
        (-0.5, 0.4, true, true, false),
    ] {
        let (p, n) = grid(x, y);
        assert_eq!(
            (
                unit.contains(p, n),
                across.contains(p, n),
                round.contains(p, n)
            ),
            (in_box, in_strip, in_disc),
            "({x}, {y})"
        );
    }
    for (region, key) in [
        (
            OmegaVSpec::Disc {
                centre_mm: [0.0, 0.0],
                radius_mm: 0.0,
            },
            "omega_v.radius_mm",
        ),
        (
            OmegaVSpec::Strip {
                axis: 2,
                from_mm: 0.0,
                to_mm: 1.0,
            },
            "omega_v.axis",
        ),
        (
            OmegaVSpec::Box {
                from_mm: [0.0, 1.0],
                to_mm: [1.0, 0.0],
            },
            "omega_v.to_mm",
        ),
    ] {
        let e = region.check().unwrap_err().to_string();
        assert!(e.contains(key), "{e}");
    }
}

/// The bundled steel punch on an aluminium base: with Ω_v the whole face the bound is the
/// equilibrium value p̃·πR²/∫v dA of the C¹ controller, whatever the support or the materials;
/// a base held axially only needs a larger gap change, and swapping the materials (the stiff
/// body below) a smaller one.
#[test]
fn steel_on_aluminium() {
    let scene = Scene::bundled("steel-on-aluminium").unwrap();
    let reports: Vec<_> = scene.run().unwrap().map(Result::unwrap).collect();
    let controller = Profile::cubic(10.0, 20.0).unwrap();
    let intervals = 20_000;
    let h = 20.0 / intervals as f64;
    let (mut area, mut carried) = (0.0, 0.0);
    for k in 0..=intervals {
        let r = k as f64 * h;
        let w = match k {
            0 => 1.0,
            k if k == intervals => 1.0,
            k if k % 2 == 1 => 4.0,
            _ => 2.0,
        } * r;
        area += w;
        carried += w * controller.value([r, 0.0, 0.0]);
    }
    let equilibrium = 50.0 * area / carried;
    for r in &reports {
        let bound = r.bound_p_max.unwrap();
        assert!(
            (bound / equilibrium - 1.0).abs() < 1e-3,
            "{}: {bound}",
            r.label
        );
    }
    let dh = |k: usize| reports[k].dh_max_um.unwrap();
    assert!(
        dh(1) > dh(0) && dh(2) < dh(1),
        "{} {} {}",
        dh(0),
        dh(1),
        dh(2)
    );
    // Measured: within 8e-5 p̂ everywhere.
    for r in &reports {
        let bound = r.bound_p_max.unwrap();
        let off = |q: &contopt_scene::PointReport| (q.p - controller.value(q.x) * bound).abs();
        assert!(
            r.interface.iter().all(|q| off(q) < 1e-3 * bound),
            "{}",
            r.label
        );
    }
}

/// The observer of a run sees the contact solves' iterations, and a stop ends the case
/// unconverged with the reason (the optimisation loop reports to it too, as it is wired).
#[test]
fn a_run_reports_to_its_observer() {
    use contopt_core::observe::{Flow, Iteration};
    use std::cell::RefCell;
    let text = bundled(
        "paper-table1",
        &[
            ("elements = 18", "elements = 6"),
            ("kind = \"penalty\"", "kind = \"augmented_lagrangian\""),
            ("c_mpa_per_mm = 2.0e9", "c_mpa_per_mm = 2.0e5"),
        ],
    );
    let contact_only = &text[..text.find("[optimisation]").unwrap()];
    let scene = parse(contact_only).unwrap();
    let seen = RefCell::new(vec![]);
    let count = |it: &Iteration| {
        seen.borrow_mut().push(it.method.to_string());
        Flow::Continue
    };
    let report = scene.run_observed(&count).unwrap().next().unwrap().unwrap();
    assert!(report.converged);
    assert!(!seen.borrow().is_empty());
    let stop = |_: &Iteration| Flow::Stop;
    let case = &scene.cases().unwrap()[0];
    let stopped = case.run_observed(&stop).unwrap();
    assert!(!stopped.converged);
    let error = stopped.error.unwrap_or_default();
    assert!(error.contains("stopped by an observer"), "{error}");
}

/// A swept key is named by its last part, or by as many last parts as tell it from the scene's
/// other keys: `l1_mm`, but `punch.radius_mm` beside the base's `radius_mm`.
#[test]
fn swept_keys_are_named_so_they_tell_apart() {
    let text = bundled("paper-table1", &[]);
    let l1 = parse(&text).unwrap();
    assert_eq!(l1.cases().unwrap()[1].label, "l1_mm = 20");
    let radius = text.replace(
        "key = \"optimisation.controller.l1_mm\"\nvalues = [0.0, 20.0, 30.0, 40.0, 50.0]",
        "key = \"problem.punch.radius_mm\"\nvalues = [40.0]",
    );
    let case = &parse(&radius).unwrap().cases().unwrap()[0];
    assert_eq!(case.label, "punch.radius_mm = 40");
    assert_eq!(case.params["punch.radius_mm"], 40.0);
}
