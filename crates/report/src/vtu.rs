//! Fields for a viewer (ParaView): a case's finite-element meshes with their displacements and
//! stresses, `fields_<case>.vtu`, and its contact points with the pressure, the gap and the gap
//! change, `contact_<case>.vtu`; both VTK XML unstructured grids written by `vtkio`, their
//! values as Float64 (base64 inline, little-endian), one piece each.
//!
//! Units as in `result.json`, written in the array names, except the displacement: positions
//! and displacements in mm (a viewer adds one to the other to draw the deformed body), stresses
//! and pressures in MPa, the gap and the gap change in µm.

use std::io;

use contopt_core::{BodyFields, CellKind, StressTensor};
use contopt_results::CaseReport;
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataSet, IOBuffer, UnstructuredGridPiece,
    Version, VertexNumbers, Vtk,
};

/// The displacement of each node \[mm\], the rigid-body motion included: three components
/// (z = 0 for a plane or axisymmetric body), the grid's active vectors (ParaView's Warp By
/// Vector takes it).
pub const DISPLACEMENT: &str = "displacement_mm";
/// The nodal stress tensor \[MPa\], six components in VTK's order of a symmetric tensor:
/// XX, YY, ZZ, XY, YZ, XZ (ParaView names them so). In the model's plane x (r) and y (z); ZZ
/// is the out-of-plane stress (the hoop stress σ_θ in axisymmetry); XY the in-plane shear.
pub const STRESS: &str = "stress_mpa";
/// The von Mises stress at each node \[MPa\], the active scalars.
pub const VON_MISES: &str = "von_mises_mpa";
/// The largest shear stress (σ₁ − σ₃)/2 at each node \[MPa\] (Tresca).
pub const TRESCA: &str = "tresca_mpa";
/// The principal stresses σ₁ ≥ σ₂ ≥ σ₃ at each node \[MPa\], one array each.
pub const PRINCIPAL: [&str; 3] = ["sigma_1_mpa", "sigma_2_mpa", "sigma_3_mpa"];
/// Which body a cell belongs to: 1 below the contact zone, 2 above it (cell data, Int32).
pub const BODY: &str = "body";
/// The contact pressure at each interface point \[MPa\].
pub const PRESSURE: &str = "p_mpa";
/// The gap after deformation at each interface point \[µm\].
pub const GAP: &str = "d_um";
/// The gap change Δh at each interface point \[µm\] (a case that designed the gap).
pub const GAP_CHANGE: &str = "dh_um";

/// VTK's cell type of a cell kind: the node orders agree ([`CellKind`]).
fn cell_type(kind: CellKind) -> CellType {
    match kind {
        CellKind::QuadraticQuad => CellType::QuadraticQuad,
        CellKind::BiquadraticQuad => CellType::BiquadraticQuad,
        CellKind::QuadraticTriangle => CellType::QuadraticTriangle,
        CellKind::QuadraticTetra => CellType::QuadraticTetra,
        CellKind::QuadraticHexahedron => CellType::QuadraticHexahedron,
        CellKind::TriquadraticHexahedron => CellType::TriquadraticHexahedron,
    }
}

/// The meshes of the case's bodies with their fields, one grid (`fields_<case>.vtu`); `None`
/// when the case has none.
pub fn fields_vtu(case: &CaseReport) -> io::Result<Option<Vec<u8>>> {
    if case.fields.is_empty() {
        return Ok(None);
    }
    let bodies: Vec<(usize, &BodyFields)> =
        case.fields.iter().map(|m| (m.body, &m.fields)).collect();
    let (mut points, mut connectivity, mut offsets, mut types, mut body) =
        (vec![], vec![], vec![], vec![], vec![]);
    let mut start = 0u64;
    for &(number, fields) in &bodies {
        for cell in &fields.cells {
            connectivity.extend(cell.nodes.iter().map(|&n| start + n as u64));
            offsets.push(connectivity.len() as u64);
            types.push(cell_type(cell.kind));
            body.push(number as i32);
        }
        points.extend(fields.points.iter().flatten());
        start += fields.points.len() as u64;
    }
    let all = || bodies.iter().flat_map(|(_, f)| f.stress.iter());
    let per_node = |f: fn(&StressTensor) -> f64| all().map(f).collect::<Vec<f64>>();
    let principal: Vec<[f64; 3]> = all().map(StressTensor::principal).collect();
    let mut point = vec![
        Attribute::vectors(DISPLACEMENT).with_data(
            bodies
                .iter()
                .flat_map(|(_, f)| f.displacement.iter().flatten().copied())
                .collect::<Vec<f64>>(),
        ),
        Attribute::generic(STRESS, 6).with_data(
            all()
                .flat_map(|s| [s.xx, s.yy, s.zz, s.xy, s.yz, s.xz])
                .collect::<Vec<f64>>(),
        ),
        Attribute::scalars(VON_MISES, 1).with_data(per_node(StressTensor::von_mises)),
        Attribute::generic(TRESCA, 1).with_data(per_node(StressTensor::tresca)),
    ];
    for (k, name) in PRINCIPAL.iter().enumerate() {
        let values: Vec<f64> = principal.iter().map(|s| s[k]).collect();
        point.push(Attribute::generic(*name, 1).with_data(values));
    }
    let cells = Cells {
        cell_verts: VertexNumbers::XML {
            connectivity,
            offsets,
        },
        types,
    };
    let data = Attributes {
        point,
        cell: vec![Attribute::generic(BODY, 1).with_data(body)],
    };
    write(points, cells, data).map(Some)
}

/// The case's interface points as vertices with the pressure, the gap and (a designed gap) the
/// gap change, one grid (`contact_<case>.vtu`); `None` when the case has no fields.
///
/// The values stay at the points where the contact was solved (the Gauss points of the first
/// body's contact faces), each a vertex: interpolating them to the face nodes would extrapolate
/// the pressure past the outer Gauss points, overshooting at a flat punch's singular rim and
/// smearing the edge of the contact.
pub fn contact_vtu(case: &CaseReport) -> io::Result<Option<Vec<u8>>> {
    if case.fields.is_empty() || case.interface.is_empty() {
        return Ok(None);
    }
    let n = case.interface.len();
    let points: Vec<f64> = case.interface.iter().flat_map(|q| q.x_mm).collect();
    let cells = Cells {
        cell_verts: VertexNumbers::XML {
            connectivity: (0..n as u64).collect(),
            offsets: (1..=n as u64).collect(),
        },
        types: vec![CellType::Vertex; n],
    };
    let field = |f: fn(&contopt_results::Point) -> f64| -> Vec<f64> {
        case.interface.iter().map(f).collect()
    };
    let mut point = vec![
        Attribute::scalars(PRESSURE, 1).with_data(field(|q| q.p_mpa)),
        Attribute::generic(GAP, 1).with_data(field(|q| q.d_um)),
    ];
    if case.dh_max_um.is_some() {
        point.push(Attribute::generic(GAP_CHANGE, 1).with_data(field(|q| q.dh_um)));
    }
    let data = Attributes {
        point,
        cell: vec![],
    };
    write(points, cells, data).map(Some)
}

/// One unstructured grid as VTK XML.
fn write(points: Vec<f64>, cells: Cells, data: Attributes) -> io::Result<Vec<u8>> {
    let vtk = Vtk {
        version: Version::new_xml(1, 0),
        byte_order: ByteOrder::LittleEndian,
        title: String::new(),
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: IOBuffer::F64(points),
            cells,
            data,
        }),
    };
    let mut bytes = vec![];
    vtk.write_xml(&mut bytes).map_err(io::Error::other)?;
    Ok(bytes)
}
