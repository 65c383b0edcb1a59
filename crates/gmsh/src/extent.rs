//! The units check: a mesh's extent against the extent the user states, in mm.

use contopt_core::{check, Error, Result};

use crate::ImportedMesh;

/// Length units a mesh may be drawn in by mistake: how many mm one of them is, and its name.
const UNITS: [(f64, &str); 4] = [
    (1000.0, "metres"),
    (25.4, "inches"),
    (10.0, "centimetres"),
    (0.001, "micrometres"),
];

impl ImportedMesh {
    /// Checks the mesh's extent (the sides of its bounding box) against `expected_mm`, each
    /// to the relative `tolerance` (in (0, 1)). Gmsh has no units and contopt reads
    /// coordinates in mm: a mesh drawn in metres is 1000 times too small, and the error says
    /// so ("the mesh is 1000 times smaller than stated: is it in metres?"); likewise inches,
    /// centimetres and micrometres.
    pub fn check_extent(&self, expected_mm: [f64; 2], tolerance: f64) -> Result<()> {
        let [lo, hi] = self.bounding_box();
        let extent = [hi[0] - lo[0], hi[1] - lo[1]];
        check_units(self.source(), &extent, &expected_mm, tolerance)
    }
}

/// The sides `extent` of a mesh's bounding box against the `expected_mm` the user states, each
/// to the relative `tolerance`; an error naming `source` and, when every side is off by one
/// factor, the unit that factor suggests.
pub(crate) fn check_units(
    source: &str,
    extent: &[f64],
    expected_mm: &[f64],
    tolerance: f64,
) -> Result<()> {
    check::all_positive("expected_mm", expected_mm)?;
    check::between("tolerance", tolerance, 0.0, 1.0)?;
    let near = |a: f64, b: f64| (a / b - 1.0).abs() <= tolerance;
    if extent.iter().zip(expected_mm).all(|(&e, &x)| near(e, x)) {
        return Ok(());
    }
    let ratio: Vec<f64> = expected_mm.iter().zip(extent).map(|(x, e)| x / e).collect();
    let unit = UNITS
        .iter()
        .find(|(mm, _)| ratio.iter().all(|&r| near(r, *mm)));
    let join = |v: &[f64]| {
        v.iter()
            .map(|x| x.to_string())
            .collect::<Vec<_>>()
            .join(" × ")
    };
    let stated = format!(
        "its extent is {}, stated {} mm",
        join(extent),
        join(expected_mm)
    );
    let message = match unit {
        Some(&(mm, name)) if mm > 1.0 => format!(
            "the mesh is {mm} times smaller than stated: is it in {name}? ({stated}; scale \
             it with `Mesh.ScalingFactor = {mm};` in Gmsh)"
        ),
        Some(&(mm, name)) => format!(
            "the mesh is {} times larger than stated: is it in {name}? ({stated}; scale it \
             with `Mesh.ScalingFactor = {mm};` in Gmsh)",
            1.0 / mm
        ),
        None => format!(
            "the mesh's extent differs from the stated one by more than {}%: {stated}",
            100.0 * tolerance
        ),
    };
    Err(Error::Mesh(format!("{source}: {message}")))
}
