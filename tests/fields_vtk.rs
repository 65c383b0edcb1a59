//! The fields a finite-element case writes for ParaView (`fields_<case>.vtu`,
//! `contact_<case>.vtu`), read back with `vtkio` and checked against closed forms: a punch
//! in uniform compression on a rigid flat, and the paper's punch on its base, whose two meshes
//! must meet where they touch once each is displaced (the punch by its approach too).

use std::collections::BTreeMap;
use std::path::Path;

use contopt::core::StressTensor;
use contopt::report::vtu;
use contopt::results::CaseReport;
use contopt::scene::{Format, Scene};
use vtkio::model::{Attribute, CellType, DataSet, UnstructuredGridPiece, VertexNumbers, Vtk};

const E: f64 = 2.0e5;
const NU: f64 = 0.3;
const P: f64 = 100.0;
/// The punch's radius and height \[mm\].
const SIZE: f64 = 10.0;
/// Elements across the punch and through its height.
const ELEMENTS: usize = 4;

/// The only case of the scene `text`, run, and the files its report writes.
fn run(text: &str) -> (CaseReport, BTreeMap<String, Vec<u8>>) {
    let scene = Scene::parse(text, Format::Toml, Path::new("fields.toml")).unwrap();
    let case = scene.cases()[0].run().unwrap();
    assert!(case.is_solved(), "{:?}", case.termination);
    let report = contopt::results::Report {
        schema_version: contopt::results::SCHEMA_VERSION,
        scene: scene.name.clone(),
        description: String::new(),
        cases: vec![case.clone()],
    };
    let mut files = BTreeMap::new();
    contopt::report::write(&report, &mut files).unwrap();
    (case, files)
}

/// The one piece of an unstructured grid, read back.
fn piece(bytes: &[u8]) -> UnstructuredGridPiece {
    let vtk = Vtk::parse_xml(bytes).unwrap();
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        panic!("not an unstructured grid");
    };
    assert_eq!(pieces.len(), 1);
    pieces[0].load_piece_data(None).unwrap()
}

/// The array `name` with `components` components, as f64.
fn array(attributes: &[Attribute], name: &str, components: u32) -> Vec<f64> {
    attributes
        .iter()
        .find_map(|a| match a {
            Attribute::DataArray(d) if d.name == name => {
                assert_eq!(d.elem.num_comp(), components, "{name}");
                Some(d.data.cast_into::<f64>().unwrap())
            }
            _ => None,
        })
        .unwrap_or_else(|| panic!("no array {name}"))
}

/// Each cell's type and nodes.
fn cells(piece: &UnstructuredGridPiece) -> Vec<(CellType, Vec<u64>)> {
    let VertexNumbers::XML {
        connectivity,
        offsets,
    } = piece.cells.cell_verts.clone()
    else {
        panic!("cells not in the XML form");
    };
    let mut start = 0;
    offsets
        .iter()
        .zip(&piece.cells.types)
        .map(|(&end, &kind)| {
            let nodes = connectivity[start as usize..end as usize].to_vec();
            start = end;
            (kind, nodes)
        })
        .collect()
}

/// The six components (VTK's order XX, YY, ZZ, XY, YZ, XZ) as a tensor.
fn tensor(c: &[f64]) -> StressTensor {
    StressTensor {
        xx: c[0],
        yy: c[1],
        zz: c[2],
        xy: c[3],
        yz: c[4],
        xz: c[5],
    }
}

/// A floating axisymmetric punch (`kind` elements) under `P` on its top, standing on a rigid
/// flat: uniaxial compression σ_z = −P, and (its bottom on the flat, u_z = 0 there) the
/// displacement u_r = νPr/E, u_z = −Pz/E, its approach included. Q8: 16 cells of 8 nodes,
/// 5 · 9 + 4 · 5 = 65 nodes; Q9: 9² = 81 nodes.
#[test]
fn uniform_compression_reads_back_as_its_closed_form() {
    for (element, vtk_type, nodes) in [
        ("q8", CellType::QuadraticQuad, 65),
        ("q9", CellType::BiquadraticQuad, 81),
    ] {
        let text = format!(
            r#"
name = "column"
[contact]
zone = {{ kind = "faces", analysis = "axisymmetric", radius_mm = {SIZE}, elements = {ELEMENTS}, element = "{element}" }}
[[body]]
kind = "rigid"
[[body]]
kind = "fe_punch"
material = {{ e_mpa = {E}, nu = {NU} }}
height_mm = {SIZE}
load = {{ pressure_mpa = {P} }}
layers = {ELEMENTS}
[solver]
kind = "active_set"
[output]
fields = true
"#
        );
        let (case, files) = run(&text);
        assert!(!files.contains_key("fields_2.vtu"));
        let grid = piece(&files["fields_1.vtu"]);
        assert_eq!(grid.num_points(), nodes, "{element}");
        let grid_cells = cells(&grid);
        assert_eq!(grid_cells.len(), ELEMENTS * ELEMENTS);
        assert!(grid_cells.iter().all(|(t, n)| *t == vtk_type
            && n.len() == vtk_type_nodes(vtk_type)
            && n.iter().all(|&i| (i as usize) < nodes)));
        let body = array(&grid.data.cell, vtu::BODY, 1);
        assert!(body.iter().all(|&b| b == 2.0), "the punch is body 2");

        let x = grid.points.cast_into::<f64>().unwrap();
        let u = array(&grid.data.point, vtu::DISPLACEMENT, 3);
        let scale = P * SIZE / E;
        for (x, u) in x.chunks(3).zip(u.chunks(3)) {
            let want = [NU * P * x[0] / E, -P * x[1] / E, 0.0];
            for k in 0..3 {
                assert!(
                    (u[k] - want[k]).abs() < 1e-9 * scale,
                    "{element} at {x:?}: u = {u:?}, want {want:?}"
                );
            }
        }
        check_stresses(&grid, [0.0, -P, 0.0, 0.0, 0.0, 0.0], element);

        let contact = piece(&files["contact_1.vtu"]);
        assert_eq!(contact.num_points(), case.interface.len());
        assert!(cells(&contact)
            .iter()
            .all(|(t, n)| *t == CellType::Vertex && n.len() == 1));
        let p = array(&contact.data.point, vtu::PRESSURE, 1);
        let d = array(&contact.data.point, vtu::GAP, 1);
        for ((q, p), d) in case.interface.iter().zip(&p).zip(&d) {
            assert_eq!((*p, *d), (q.p_mpa, q.d_um));
            assert!((p - P).abs() < 1e-9 * P, "p = {p}");
        }
        let no_change = contact
            .data
            .point
            .iter()
            .all(|a| a.name() != vtu::GAP_CHANGE);
        assert!(no_change, "an analysis has no gap change");
    }
}

/// Nodes of a VTK cell type used here.
fn vtk_type_nodes(t: CellType) -> usize {
    match t {
        CellType::QuadraticQuad => 8,
        CellType::BiquadraticQuad => 9,
        other => panic!("unexpected cell type {other:?}"),
    }
}

/// The nodal stress tensors equal `want` (XX, YY, ZZ, XY, YZ, XZ) to 1e-9 P, and the von Mises,
/// Tresca and principal arrays are those of the tensor read back.
fn check_stresses(grid: &UnstructuredGridPiece, want: [f64; 6], what: &str) {
    let stress = array(&grid.data.point, vtu::STRESS, 6);
    let mises = array(&grid.data.point, vtu::VON_MISES, 1);
    let tresca = array(&grid.data.point, vtu::TRESCA, 1);
    let principal = vtu::PRINCIPAL.map(|name| array(&grid.data.point, name, 1));
    for (k, c) in stress.chunks(6).enumerate() {
        for (got, want) in c.iter().zip(want) {
            assert!((got - want).abs() < 1e-9 * P, "{what}: node {k}: {c:?}");
        }
        let s = tensor(c);
        assert!((mises[k] - s.von_mises()).abs() < 1e-12 * P);
        assert!((tresca[k] - s.tresca()).abs() < 1e-12 * P);
        let [s1, s2, s3] = s.principal();
        assert_eq!(
            [principal[0][k], principal[1][k], principal[2][k]],
            [s1, s2, s3]
        );
        assert!((0.5 * (s1 - s3) - tresca[k]).abs() < 1e-12 * P);
    }
}

/// The paper's punch (100 MPa on its top, floating) on its clamped base, analysed without a
/// design by the exact active set on 6 elements across: the fields hold both meshes (base body 1, punch body 2), and
/// where the punch's bottom touches the base's top (zero gap at a face's three points) the two
/// displaced faces coincide: u_z of a base node equals u_z of the punch node above it to
/// round-off. Leaving out the punch's approach would part them by tens of µm.
#[test]
fn punch_and_base_meet_where_they_touch() {
    let scene = contopt_validation::paper::scene(
        "paper-table1",
        6,
        &[
            ("sweep", None),
            ("optimisation", None),
            ("solver", Some("{ kind = \"active_set\" }")),
            ("output", Some("{ fields = true }")),
        ],
    )
    .unwrap();
    let case = scene.cases()[0].run().unwrap();
    assert!(case.is_solved());
    let report = contopt::results::Report {
        schema_version: contopt::results::SCHEMA_VERSION,
        scene: scene.name.clone(),
        description: String::new(),
        cases: vec![case.clone()],
    };
    let mut files = BTreeMap::new();
    contopt::report::write(&report, &mut files).unwrap();
    let grid = piece(&files["fields_1.vtu"]);
    let x = grid.points.cast_into::<f64>().unwrap();
    let u = array(&grid.data.point, vtu::DISPLACEMENT, 3);
    let body = array(&grid.data.cell, vtu::BODY, 1);
    assert_eq!(case.fields.len(), 2);
    let counts = case.fields.iter().map(|f| f.fields.cells.len());
    assert_eq!(body.len(), counts.sum::<usize>());
    let base_cells = case.fields[0].fields.cells.len();
    assert!(body[..base_cells].iter().all(|&b| b == 1.0));
    assert!(body[base_cells..].iter().all(|&b| b == 2.0));
    // Points of the base first, then the punch's.
    let split = case.fields[0].fields.points.len();
    let (surface, approach) = (
        |k: usize| x[3 * k + 1].abs() < 1e-12,
        case.approach_um.unwrap() * 1e-3,
    );
    let largest = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(
        approach > 0.1 * largest,
        "the punch approaches by {approach} mm"
    );
    let contact_r = case
        .interface
        .iter()
        .filter(|q| q.p_mpa > 0.0)
        .map(|q| q.x_mm[0])
        .fold(0.0f64, f64::max);
    let mut compared = 0;
    for i in (0..split).filter(|&i| surface(i)) {
        let Some(j) =
            (split..x.len() / 3).find(|&j| surface(j) && (x[3 * j] - x[3 * i]).abs() < 1e-12)
        else {
            continue;
        };
        if x[3 * i] < contact_r - 1.0 {
            let (below, above) = (u[3 * i + 1], u[3 * j + 1]);
            assert!(
                (below - above).abs() < 1e-6 * largest,
                "r = {}: base {below}, punch {above}",
                x[3 * i]
            );
            compared += 1;
        }
    }
    assert!(compared > 6, "{compared} node pairs compared");
    let contact = piece(&files["contact_1.vtu"]);
    let p = array(&contact.data.point, vtu::PRESSURE, 1);
    let want: Vec<f64> = case.interface.iter().map(|q| q.p_mpa).collect();
    assert_eq!(p, want);
}
