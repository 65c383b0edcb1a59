//! Bodies of one's own in scenes (`fe_mesh` on a zone of kind `mesh`): checks that build
//! nothing, every error at the key a user can act on, the memory estimated from the mesh, the
//! model's limits at the ends of imported contact faces, a given gap read through the
//! pairing's projection, and a rigid body on an imported one. (Hertz and the paper's tables
//! on Gmsh meshes: `tests/mesh_scenes.rs` of the workspace.)

use std::path::{Path, PathBuf};

use contopt_results::CaseStatus;
use contopt_scene::{Format, Scene, SceneError, BUNDLED};

/// The repository's `scenes/` folder, from which the scenes here are read (their meshes are
/// `../meshes/…`).
fn scene_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/cylinder-on-block.toml")
}

/// The bundled cylinder on a block with `edits`, read as the file in `scenes/`.
fn cylinder(edits: &[(&str, Option<&str>)]) -> Result<Scene, SceneError> {
    let text = BUNDLED
        .iter()
        .find(|b| b.name == "cylinder-on-block")
        .unwrap()
        .text;
    Scene::parse_with(text, Format::Toml, &scene_file(), edits)
}

/// Edits of a scene: dotted keys and their TOML values.
type Edits<'a> = Vec<(&'a str, Option<&'a str>)>;

/// The message of a scene that must be refused.
fn refused(edits: &[(&str, Option<&str>)]) -> String {
    cylinder(edits)
        .expect_err("the scene must be refused")
        .to_string()
}

/// The block of the bundled scene with another `mesh`, surface, contact and extent.
fn block(mesh: &str, surface: &str, contact: &str, extent: &str, supports: &str) -> String {
    format!(
        r#"{{ kind = "fe_mesh", mesh = "{mesh}", surface = "{surface}", contact = "{contact}",
             extent_mm = {extent}, material = {{ e_mpa = 2.1e5, nu = 0.3 }},
             supports = {supports} }}"#
    )
}

/// Reading checks the imported bodies without factorising them (on the finest mesh of the
/// series, 14 535 nodes), the build factorises each once; the mesh file is read once for
/// both bodies and every case.
#[test]
fn reading_an_imported_scene_factorises_nothing() {
    let mesh = "\"../meshes/cylinder-on-block-b32.msh\"";
    let before = contopt_fem::factorisations();
    let scene = cylinder(&[("body.0.mesh", Some(mesh)), ("body.1.mesh", Some(mesh))]).unwrap();
    assert_eq!(contopt_fem::factorisations(), before);
    let built = scene.cases()[0].build().unwrap();
    assert_eq!(contopt_fem::factorisations() - before, 2);
    assert!(built.pairing().is_some_and(|p| p.left_out() == 0));
}

/// Each scene of `cases` (edits of the bundled one) is refused at its key, with its words.
fn refused_at(cases: Vec<(Edits, &str, Vec<&str>)>) {
    for (edits, key, needles) in cases {
        let message = refused(&edits);
        assert!(
            message.contains("cylinder-on-block.toml:") && message.contains(&format!(" {key}: ")),
            "{key}: {message}"
        );
        for needle in needles {
            assert!(message.contains(needle), "{key}: {needle:?} in {message}");
        }
    }
}

/// The errors of the files and groups a body names, each at its key with what to do: a
/// missing mesh file (with where it was looked for), a file that is a folder, a group that
/// does not exist (with the groups there are), a group of the wrong dimension, a load of two
/// kinds, a mesh in metres, a contact group inside the body.
#[test]
fn errors_of_files_and_groups_name_the_key() {
    let metres = block(
        "../meshes/rectangle-metres.msh",
        "body",
        "top",
        "[40.0, 20.0]",
        r#"[{ group = "bottom", fix = ["x", "y"] }]"#,
    );
    let inner = block(
        "../meshes/block-inner-curve.msh",
        "block",
        "inner",
        "[20.0, 10.0]",
        r#"[{ group = "bottom", fix = ["x", "y"] }]"#,
    );
    let two_loads = "[{ group = \"cylinder_axis\", pressure_mpa = 1.0, displacement_mm = 0.1 }]";
    refused_at(vec![
        (
            vec![("body.0.mesh", Some("\"nowhere/block.msh\""))],
            "body[0].mesh",
            vec![
                "nowhere/block.msh",
                "cannot read",
                "relative to the scene's folder",
                "scenes",
            ],
        ),
        (
            vec![("body.0.mesh", Some("\"../meshes\""))],
            "body[0].mesh",
            vec!["not a regular file"],
        ),
        (
            vec![("body.0.contact", Some("\"block_top_face\""))],
            "body[0].contact",
            vec![
                "cylinder-on-block-b8.msh",
                "no physical group",
                "\"block_face\"",
            ],
        ),
        (
            vec![("body.0.surface", Some("\"blocks\""))],
            "body[0].surface",
            vec!["no 2-D physical group", "\"cylinder\""],
        ),
        (
            vec![(
                "body.0.supports",
                Some("[{ group = \"block\", fix = [\"y\"] }]"),
            )],
            "body[0].supports[0].group",
            vec!["group of surfaces", "points or curves"],
        ),
        (
            vec![("body.1.loads", Some(two_loads))],
            "body[1].loads[0]",
            vec!["exactly one"],
        ),
        (
            vec![("body.0", Some(&*metres))],
            "body[0].extent_mm",
            vec!["1000 times smaller", "metres"],
        ),
        (
            vec![("body.0", Some(&*inner))],
            "body[0].contact",
            vec!["\"inner\"", "inside the body", "boundary faces"],
        ),
    ]);
}

/// The errors of the model, each at its key with what to do: contact faces that face away from
/// each other (nothing pairs), nodes at r < 0 in axisymmetry, supports that leave a body free
/// in a motion no load presses or its contact cannot hold, the measured gap without two
/// meshes, an imported body off a zone of meshes and a zone of meshes without one, and two
/// bodies that both float (which `check` used to pass and the run refused).
#[test]
fn errors_of_the_model_name_the_key() {
    let rigid_on_block = format!(
        "[{}, {{ kind = \"rigid\" }}]",
        block(
            "../meshes/cylinder-on-block-b8.msh",
            "block",
            "block_face",
            "[40.0, 40.0]",
            r#"[{ group = "block_bottom", fix = ["x", "y"] }, { group = "block_axis", fix = ["x"] }]"#,
        )
    );
    let left_of_axis = block(
        "../meshes/two-bodies.msh",
        "base",
        "base_top",
        "[60.0, 20.0]",
        r#"[{ group = "base_bottom", fix = ["x", "y"] }]"#,
    );
    let flat_punch = r#"{ kind = "fe_mesh", mesh = "../meshes/paper-punch.msh", contact = "punch_face",
        extent_mm = [50.0, 50.0], material = { e_mpa = 2.1e5, nu = 0.3 },
        loads = [{ group = "punch_top", pressure_mpa = 10.0 }] }"#;
    let faces_zone =
        "{ kind = \"faces\", analysis = \"axisymmetric\", radius_mm = 1.0, elements = 4 }";
    let axisymmetric = "{ kind = \"mesh\", analysis = \"axisymmetric\" }";
    let no_import = "[{ kind = \"rigid\" }, { kind = \"winkler\", modulus_mpa_per_mm = 1.0 }]";
    refused_at(vec![
        (
            vec![("body.1.contact", Some("\"cylinder_top\""))],
            "contact.zone",
            vec!["do not overlap, or they face away"],
        ),
        (
            vec![
                ("contact.zone", Some(axisymmetric)),
                ("body.0", Some(&*left_of_axis)),
            ],
            "body[0].mesh",
            vec!["r = -30", "r ≥ 0", "plane"],
        ),
        (
            vec![("body.1.supports", Some("[]"))],
            "body[1].supports",
            vec!["x translation", "no load presses it"],
        ),
        (
            vec![("body.1", Some(flat_punch))],
            "body[1].supports",
            vec!["x translation", "cannot hold", "symmetry line"],
        ),
        // A pulling pressure on a part free along y names the load, the motion along y and
        // a support along y (issue 35, point 5), not one along x.
        (
            vec![(
                "body.1.loads",
                Some(r#"[{ group = "cylinder_top", pressure_mpa = -40.0 }]"#),
            )],
            "body[1].loads",
            vec![
                "{ group = \"cylinder_top\", pressure_mpa = -40 }",
                "pull the body away",
                "y translation",
                "fix = [\"y\"]",
                "turn the load round",
            ],
        ),
        (
            vec![
                ("body", Some(&*rigid_on_block)),
                ("contact.gap", Some("\"measured\"")),
                ("contact.load", Some("{ force_n = 10.0 }")),
            ],
            "contact.gap",
            vec!["two imported meshes"],
        ),
        (
            vec![("contact.zone", Some(faces_zone))],
            "body[0].kind",
            vec!["zone of imported meshes"],
        ),
        (
            vec![("body", Some(no_import))],
            "contact.zone.kind",
            vec!["fe_mesh"],
        ),
        (
            vec![
                (
                    "body.0.supports",
                    Some(r#"[{ group = "block_axis", fix = ["x"] }]"#),
                ),
                (
                    "body.0.loads",
                    Some(r#"[{ group = "block_bottom", pressure_mpa = 40.0 }]"#),
                ),
            ],
            "body[1].supports",
            vec!["both imported bodies float", "hold one of them"],
        ),
    ]);
}

/// The memory of the bodies is estimated from the mesh's nodes and the contact's points before
/// anything is built, and a case past the scene's limit is refused with the number.
#[test]
fn memory_is_estimated_from_the_mesh() {
    let message = refused(&[("memory_limit_mb", Some("1.0"))]);
    assert!(
        message.contains("memory_limit_mb") || message.contains("contact.zone"),
        "{message}"
    );
    assert!(
        message.contains("would take") && message.contains("1 MB"),
        "{message}"
    );
}

/// A contact group drawn shorter than the contact (the block's top to 0.2 mm, the contact's
/// half-width 0.3 mm, the block's top going on beyond) is outside the model: the case says
/// which group ends where, and how far it must reach; the full group (to 2 mm) is within it,
/// and so is a contact that reaches a corner of its body (the axis x = 0 here).
#[test]
fn a_contact_group_drawn_too_short_is_outside_the_model() {
    let short = cylinder(&[("body.0.contact", Some("\"block_short\""))]).unwrap();
    let report = short.cases()[0].run().unwrap();
    assert_eq!(report.status, CaseStatus::OutsideModel, "{report:?}");
    let limit = report.limit.unwrap();
    assert!(
        limit.edge.contains("block_short")
            && limit.message.contains("goes on")
            && limit.message.contains("`block`")
            && limit.needed_mm > limit.extent_mm,
        "{limit:?}"
    );
    let full = cylinder(&[]).unwrap().cases()[0].run().unwrap();
    assert_eq!(full.status, CaseStatus::Solved);
}

/// A rubber-like ν on the bundled cylinder on a block is named with its body: its quadratic
/// displacement elements lock (ν = 0.4995 on both bodies gave p_max +19 % of Hertz's scaling
/// of the ν = 0.3 result, without a word); ν = 0.3 is not named.
#[test]
fn a_nearly_incompressible_body_is_named() {
    let rubber = "{ e_mpa = 2.1e5, nu = 0.4995 }";
    let edits = [("body.1.material", Some(rubber))];
    let report = cylinder(&edits).unwrap().cases()[0].run().unwrap();
    let locking: Vec<_> = report
        .warnings
        .iter()
        .filter(|w| w.contains("lock"))
        .collect();
    assert!(
        locking.len() == 1 && locking[0].starts_with("body[1] (fe_mesh): ν = 0.4995"),
        "{:?}",
        report.warnings
    );
    let steel = cylinder(&[]).unwrap().cases()[0].run().unwrap();
    assert!(steel.warnings.iter().all(|w| !w.contains("lock")));
}

/// A gap given for two imported bodies is weighted onto the nodes as the measured one is: the
/// cylinder's own shape given as a gap (the meshes then only pair the points) gives the
/// contact of the gap measured between the meshes, within 0.1 % (the quadratic arcs' geometry
/// against the exact parabola).
#[test]
fn a_given_gap_is_projected() {
    let run = |scene: Scene| scene.cases()[0].run().unwrap();
    let measured = run(cylinder(&[]).unwrap());
    let given = run(cylinder(&[(
        "contact.gap",
        Some("{ kind = \"cylinder\", radius_mm = 10.0 }"),
    )])
    .unwrap());
    let (a, b) = (measured.p_max_mpa.unwrap(), given.p_max_mpa.unwrap());
    assert!((a / b - 1.0).abs() < 1e-3, "{a} against {b}");
}

/// On a coarse mesh (elements of b/4 at the contact) the contact spans fewer than 8 of the
/// block's faces, and the case says so; on the bundled one (b/8) it does not.
#[test]
fn a_contact_on_few_faces_is_warned() {
    let mesh = "\"../meshes/cylinder-on-block-b4.msh\"";
    let coarse = cylinder(&[("body.0.mesh", Some(mesh)), ("body.1.mesh", Some(mesh))]).unwrap();
    let report = coarse.cases()[0].run().unwrap();
    let resolution = report.resolution.unwrap();
    assert!(resolution.cells < 8.0, "{resolution:?}");
    assert!(report.warnings.iter().any(|w| w.contains("not resolved")));
    let fine = cylinder(&[]).unwrap().cases()[0].run().unwrap();
    assert!(fine.resolution.unwrap().cells >= 8.0);
}

/// Lamé's shrink-fit pressure on a solid shaft of radius `bs` in a hub of bore `bh` and outer
/// radius `c` \[mm\], in plane strain (Timoshenko & Goodier ch. 4: the hub's bore moves out by
/// b_h·p_h·(K_h + ν'_h)/E'_h under p_h = p·b_s/b_h, K_h = (c² + b_h²)/(c² − b_h²), the solid
/// shaft's surface in by b_s·p·(1 − ν'_s)/E'_s; E' = E/(1 − ν²), ν' = ν/(1 − ν)), with
/// (E, ν) of the shaft and of the hub.
fn lame(bs: f64, bh: f64, c: f64, shaft: (f64, f64), hub: (f64, f64)) -> f64 {
    let plane = |(e, nu): (f64, f64)| (e / (1.0 - nu * nu), nu / (1.0 - nu));
    let ((es, nus), (eh, nuh)) = (plane(shaft), plane(hub));
    let kh = (c * c + bh * bh) / (c * c - bh * bh);
    (bs - bh) / (bs * ((kh + nuh) / eh + (1.0 - nus) / es))
}

/// A shrink fit held only by its interference (issue 35, point 4): the bundled steel shaft
/// in an aluminium hub, two `fe_mesh` bodies each held on its symmetry lines, no load. The
/// measured gap is −0.05 mm, the interference, at every node; the contact closes it and the
/// pressure at every node of the shaft's arc is Lamé's 66.62 MPa within 1 % (measured
/// 66.25–66.80 MPa, 16 faces on the arc). An approach of 0 is the same scene.
#[test]
fn a_shrink_fit_is_pressed_by_its_interference_alone() {
    let text = BUNDLED
        .iter()
        .find(|b| b.name == "shrink-fit")
        .unwrap()
        .text;
    let file = scene_file().with_file_name("shrink-fit.toml");
    let want = lame(25.05, 25.0, 50.0, (2.1e5, 0.3), (7.0e4, 0.33));
    assert!((want - 66.62).abs() < 5e-3, "{want}");
    for edits in [
        vec![],
        vec![("contact.load", Some("{ approach_mm = 0.0 }"))],
    ] {
        let scene = Scene::parse_with(text, Format::Toml, &file, &edits).unwrap();
        let report = scene.cases()[0].run().unwrap();
        assert!(report.is_solved(), "{:?}", report.termination);
        assert!(report.warnings.is_empty(), "{:?}", report.warnings);
        for q in &report.interface {
            assert!((q.h_um + 50.0).abs() < 0.05, "h = {} µm", q.h_um);
            assert!(q.d_um.abs() < 1e-3, "d = {} µm", q.d_um);
            assert!((q.p_mpa / want - 1.0).abs() < 0.01, "{} vs {want}", q.p_mpa);
        }
    }
}
