//! Solids read from the committed `meshes/solid-*.msh`: kinds, groups, volumes, the patch
//! test through the reader, and every refusal naming its element or group.

use contopt_core::Material;
use contopt_fem::solid::{Axis, SolidKind, SolidModel};

use super::committed;
use crate::Volumes;

/// Relative round-off of a volume, an area or a patch-test displacement.
const ROUND_OFF: f64 = 1e-10;

/// The blocks in each element kind: their kind, their volume 4 × 4 × 6, every named face
/// group on the boundary with the area of its side, and the extent check.
#[test]
fn blocks_read_with_their_groups() {
    for (file, kind, elements) in [
        ("solid-block-tet10.msh", SolidKind::Tet10, None),
        ("solid-block-hex20.msh", SolidKind::Hex20, Some(12)),
        ("solid-block-hex27.msh", SolidKind::Hex27, Some(12)),
    ] {
        let solid = committed(file)
            .import_solid(Volumes::Group("block"))
            .unwrap();
        let mesh = &solid.mesh;
        assert!(
            (0..mesh.n_elements()).all(|e| mesh.kind(e) == kind),
            "{file}"
        );
        if let Some(n) = elements {
            assert_eq!(mesh.n_elements(), n);
        }
        assert!((mesh.volume() / 96.0 - 1.0).abs() < ROUND_OFF, "{file}");
        for (name, area) in [("top", 16.0), ("bottom", 16.0), ("x0", 24.0), ("y4", 24.0)] {
            let faces = solid.faces(name).unwrap();
            let a: f64 = faces
                .iter()
                .flat_map(|&f| {
                    let fk = mesh.face_kind(f);
                    fk.contact_points()
                        .into_iter()
                        .map(move |(st, w)| (f, st, w))
                })
                .map(|(f, st, w)| mesh.face_point(f, st).da * w)
                .sum();
            assert!((a / area - 1.0).abs() < ROUND_OFF, "{file} {name}: {a}");
        }
        solid.check_extent([4.0, 4.0, 6.0], 1e-6).unwrap();
        assert_eq!(solid.element_tags.len(), mesh.n_elements());
        assert_eq!(solid.node_tags.len(), mesh.nodes().len());
    }
}

/// The patch test on Gmsh's unstructured tetrahedra: uniform pressure on the top, symmetry
/// planes on x = 0, y = 0 and the bottom; u = (νpx, νpy, −pz)/E at every node to round-off.
#[test]
fn patch_test_on_gmsh_tetrahedra() {
    let solid = committed("solid-block-tet10.msh")
        .import_solid(Volumes::All)
        .unwrap();
    let (e, nu, p) = (2e5, 0.3, 10.0);
    let mut model = SolidModel::new(solid.mesh.clone(), Material::new(e, nu).unwrap());
    for (name, axis) in [("x0", Axis::X), ("y0", Axis::Y), ("bottom", Axis::Z)] {
        model.fix(solid.nodes(name).unwrap(), axis).unwrap();
    }
    model.add_pressure(solid.faces("top").unwrap(), p).unwrap();
    let u = model.solve().unwrap();
    let scale = p * 6.0 / e;
    for (k, x) in model.mesh().nodes().iter().enumerate() {
        let want = [nu * p * x[0] / e, nu * p * x[1] / e, -p * x[2] / e];
        for c in 0..3 {
            assert!(
                (u[3 * k + c] - want[c]).abs() < ROUND_OFF * scale,
                "node {k}"
            );
        }
    }
}

/// Gmsh's curved tetrahedra of a quarter cylinder: its volume π(20² − 10²)·4/4 within the
/// chord error of the arcs, and Lamé's radial displacement at the bore within 0.5 %.
#[test]
fn cylinder_from_gmsh_matches_lame() {
    let solid = committed("solid-cylinder-tet10.msh")
        .import_solid(Volumes::All)
        .unwrap();
    let volume = std::f64::consts::PI * 300.0;
    assert!((solid.mesh.volume() / volume - 1.0).abs() < 1e-3);
    let (e, nu, p, a, b) = (2e5, 0.3, 100.0, 10.0, 20.0);
    let mut model = SolidModel::new(solid.mesh.clone(), Material::new(e, nu).unwrap());
    model.fix(solid.nodes("x0").unwrap(), Axis::X).unwrap();
    model.fix(solid.nodes("y0").unwrap(), Axis::Y).unwrap();
    model.fix(solid.nodes("ends").unwrap(), Axis::Z).unwrap();
    model.add_pressure(solid.faces("bore").unwrap(), p).unwrap();
    let u = model.solve().unwrap();
    let (c1, c2) = (
        p * a * a / (b * b - a * a),
        p * a * a * b * b / (b * b - a * a),
    );
    let u_r = |r: f64| {
        let (sr, st) = (c1 - c2 / (r * r), c1 + c2 / (r * r));
        r * ((1.0 - nu * nu) * st - nu * (1.0 + nu) * sr) / e
    };
    let mut worst = 0.0f64;
    for (k, x) in model.mesh().nodes().iter().enumerate() {
        let r = x[0].hypot(x[1]);
        let radial = (u[3 * k] * x[0] + u[3 * k + 1] * x[1]) / r;
        worst = worst.max((radial / u_r(r) - 1.0).abs());
    }
    assert!(worst < 5e-3, "worst {worst}");
}

/// Each refusal names what is wrong: a plane mesh, linear tetrahedra, a mesh in metres, a
/// volume group or a surface group the file does not have, and an inverted element (two
/// corners swapped in the file) by its Gmsh tag.
#[test]
fn bad_solids_are_refused_by_name() {
    let plane = committed("rectangle-q8.msh")
        .import_solid(Volumes::All)
        .unwrap_err();
    assert!(plane.to_string().contains("no volume elements"), "{plane}");
    let linear = committed("solid-block-linear.msh")
        .import_solid(Volumes::All)
        .unwrap_err();
    assert!(
        linear
            .to_string()
            .contains("Tetrahedron 4), a linear element"),
        "{linear}"
    );
    let metres = committed("solid-block-metres.msh")
        .import_solid(Volumes::All)
        .unwrap();
    let e = metres.check_extent([4.0, 4.0, 6.0], 0.01).unwrap_err();
    assert!(e.to_string().contains("is it in metres?"), "{e}");
    let hex = committed("solid-block-hex20.msh");
    let e = hex.import_solid(Volumes::Group("punch")).unwrap_err();
    assert!(
        e.to_string()
            .contains("named \"punch\"; the file names volumes \"block\""),
        "{e}"
    );
    let solid = hex.import_solid(Volumes::All).unwrap();
    let e = solid.faces("contact").unwrap_err();
    assert!(
        e.to_string().contains("\"contact\"; the file's are \"x0\""),
        "{e}"
    );

    // The first hexahedron with its corners 0 and 1 swapped.
    let path = format!(
        "{}/../../meshes/solid-block-hex20.msh",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let block = lines.iter().position(|l| l.starts_with("3 1 17 ")).unwrap();
    let mut fields: Vec<&str> = lines[block + 1].split_whitespace().collect();
    let tag = fields[0].to_string();
    fields.swap(1, 2);
    lines[block + 1] = fields.join(" ");
    let bad = crate::parse(lines.join("\n").as_bytes(), "swapped.msh").unwrap();
    let e = bad.import_solid(Volumes::All).unwrap_err();
    assert!(
        e.to_string()
            .contains(&format!("Gmsh element {tag} is inverted")),
        "{e}"
    );
}
