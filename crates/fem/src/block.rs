//! A large axisymmetric block that stands in for an elastic half-space in validation cases
//! (Hertz, Boussinesq/Sneddon) and benchmarks.

use contopt_core::Result;

use crate::{Analysis, Component, ElementKind, Face, FeModel, Material, Mesh, Spacing};

/// An axisymmetric Q8 block of radius and depth `size`, clamped at its bottom (y = −`size`),
/// with its top face at y = 0. The contact zone r < `zone` carries `zone_elements` uniform
/// elements; outside it the elements grow geometrically from that size (40 of them), and a
/// layer of depth 2·`zone` under the surface is meshed with square-ish elements before the
/// depth grading starts. Returns the model and the contact zone's faces, ordered by r.
pub fn half_space_block(
    zone: f64,
    zone_elements: usize,
    size: f64,
    material: Material,
) -> Result<(FeModel, Vec<Face>)> {
    let h = zone / zone_elements as f64;
    let r = Spacing::uniform(0.0, zone, zone_elements)?
        .then(&Spacing::geometric_first(zone, size, 40, h)?)?;
    let near = Spacing::uniform(-2.0 * zone, 0.0, 2 * zone_elements.min(40))?;
    let z =
        Spacing::geometric(-size, -2.0 * zone, 24, (h / (size / 24.0)).min(1.0))?.then(&near)?;
    let mut model = FeModel::new(
        Mesh::rectangle(ElementKind::Q8, &r, &z)?,
        material,
        Analysis::Axisymmetric,
    )?;
    let bottom = model.mesh().nodes_on_y(-size, 0.0, size);
    model
        .fix(&bottom, Component::X)?
        .fix(&bottom, Component::Y)?;
    let contact = model.mesh().faces_on_y(0.0, 0.0, zone);
    Ok((model, contact))
}
