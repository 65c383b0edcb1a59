//! The fields of a condensed [`FeBody`] under a contact solution, for a viewer: its mesh, the
//! displacement of every node (the rigid-body motion included) and the stresses recovered at
//! the nodes ([`FeBody::nodal_stresses`]).

use contopt_core::{BodyFields, Cell, CellKind, ElasticBody, Result, StressTensor};

use crate::{ElementKind, FeBody};

/// The viewer's cell of an element kind: the local node orders agree (corners
/// counter-clockwise, then the mid-side nodes, then a centre; see [`crate::element`]).
fn cell_kind(kind: ElementKind) -> CellKind {
    match kind {
        ElementKind::Q8 => CellKind::QuadraticQuad,
        ElementKind::Q9 => CellKind::BiquadraticQuad,
        ElementKind::T6 => CellKind::QuadraticTriangle,
    }
}

/// A nodal stress of [`crate::FeModel::nodal_stresses`] (by [`StressTensor`]'s convention
/// below a surface: the model's x → `xx`, y → `zz`, τ_xy → `xz`, out of plane → `yy`) in the
/// model's own frame, as [`BodyFields`] has it: x, y in the plane, z out of it.
fn in_model_frame(s: StressTensor) -> StressTensor {
    StressTensor {
        xx: s.xx,
        yy: s.zz,
        zz: s.yy,
        xy: s.xz,
        xz: 0.0,
        yz: 0.0,
    }
}

impl FeBody {
    /// The body's fields under the contact pressure `pressure` \[MPa\] (one value per interface
    /// point) and its given loads, with rigid-mode amplitudes `rigid` (one per
    /// [`contopt_core::ElasticBody::rigid_modes`]): the mesh (coordinates in the model's
    /// plane, z = 0), the nodal displacements [`FeBody::displacement`] with the rigid motion,
    /// and the nodal stresses [`FeBody::nodal_stresses`] in the model's frame (z out of the
    /// plane: the hoop stress in axisymmetry).
    ///
    /// Errors as [`FeBody::nodal_stresses`]: a pressure of the wrong length or not finite, or
    /// one that leaves a floating body unbalanced; and a `rigid` of the wrong length.
    pub fn mesh_fields(&self, pressure: &[f64], rigid: &[f64]) -> Result<BodyFields> {
        let stress = self.nodal_stresses(pressure)?;
        let force = self.interface_forces(pressure)?;
        let u = self.displacement(&force, rigid)?;
        let mesh = &self.model.mesh;
        let cells = mesh
            .elements()
            .iter()
            .enumerate()
            .map(|(e, nodes)| Cell {
                kind: cell_kind(mesh.element_kind(e)),
                nodes: nodes.clone(),
            })
            .collect();
        BodyFields::new(
            self.name(),
            mesh.nodes().iter().map(|x| [x[0], x[1], 0.0]).collect(),
            cells,
            u.chunks_exact(2).map(|u| [u[0], u[1], 0.0]).collect(),
            stress.into_iter().map(in_model_frame).collect(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Analysis, Component, FeModel, Material, Mesh, Spacing};

    const P: f64 = 100.0;
    const NU: f64 = 0.3;
    const SIZE: f64 = 50.0;

    /// A floating block (4 × 3 elements) under `P` on its top, pressed from below by the same
    /// pressure as a contact: uniaxial compression σ_y = −P, its one rigid mode the axial
    /// translation.
    fn floating_block(kind: ElementKind, analysis: Analysis) -> FeBody {
        let mesh = Mesh::rectangle(
            kind,
            &Spacing::uniform(0.0, SIZE, 4).unwrap(),
            &Spacing::geometric(0.0, SIZE, 3, 1.5).unwrap(),
        )
        .unwrap();
        let material = Material::new(2.0e5, NU).unwrap();
        let mut model = FeModel::new(mesh, material, analysis).unwrap();
        let top = model.mesh().faces_on_y(SIZE, 0.0, SIZE);
        model.pressure(&top, P).unwrap();
        if !matches!(analysis, Analysis::Axisymmetric) {
            let axis = model.mesh().nodes_on_x(0.0, 0.0, SIZE);
            model.fix(&axis, Component::X).unwrap();
        }
        let bottom = model.mesh().faces_on_y(0.0, 0.0, SIZE);
        FeBody::new("punch", model, &bottom).unwrap()
    }

    /// The mesh comes out as it is, in the viewer's cells; the displacement is
    /// [`FeBody::displacement`] with the rigid motion; the stress is the closed form of
    /// uniaxial compression in the model's frame: σ_yy = −P, σ_xx = τ_xy = 0 and out of the
    /// plane 0 (plane stress, the hoop stress in axisymmetry) or −νP (plane strain). A frame
    /// that swapped y and z would put −P in `zz` and fail by P.
    #[test]
    fn uniform_compression_in_the_model_frame() {
        let analyses = [
            Analysis::PlaneStress { thickness: 1.0 },
            Analysis::PlaneStrain { thickness: 1.0 },
            Analysis::Axisymmetric,
        ];
        for kind in ElementKind::ALL {
            for analysis in analyses {
                let body = floating_block(kind, analysis);
                let n = body.interface().len();
                let pressure = vec![P; n];
                assert_eq!(body.rigid_modes().len(), 1, "{kind:?} {analysis:?}");
                let rigid = [-0.01];
                let fields = body.mesh_fields(&pressure, &rigid).unwrap();
                let mesh = body.model().mesh();
                assert_eq!(fields.points.len(), mesh.nodes().len());
                assert_eq!(fields.cells.len(), mesh.elements().len());
                assert!(fields
                    .cells
                    .iter()
                    .zip(mesh.elements())
                    .all(|(c, e)| c.kind == cell_kind(kind) && c.nodes == *e));
                let force: Vec<f64> = body.interface().weights().iter().map(|w| P * w).collect();
                let u = body.displacement(&force, &rigid).unwrap();
                for (k, d) in fields.displacement.iter().enumerate() {
                    assert_eq!(*d, [u[2 * k], u[2 * k + 1], 0.0]);
                }
                let at_rest = body.displacement(&force, &[0.0]).unwrap();
                let moved = (0..u.len()).any(|i| (u[i] - at_rest[i]).abs() > 1e-3);
                assert!(moved, "the rigid motion is in the displacement");
                let out = match analysis {
                    Analysis::PlaneStrain { .. } => -NU * P,
                    _ => 0.0,
                };
                let want = [0.0, -P, out, 0.0, 0.0, 0.0];
                for s in &fields.stress {
                    let got = [s.xx, s.yy, s.zz, s.xy, s.xz, s.yz];
                    let err = got
                        .iter()
                        .zip(want)
                        .fold(0.0f64, |m, (g, w)| m.max((g - w).abs()));
                    assert!(err < 1e-9 * P, "{kind:?} {analysis:?}: {got:?}");
                }
            }
        }
    }

    /// Bad input is named: a rigid vector of the wrong length, a pressure that leaves the
    /// floating block unbalanced.
    #[test]
    fn bad_rigid_and_unbalanced_pressure_are_refused() {
        let body = floating_block(ElementKind::Q8, Analysis::Axisymmetric);
        let n = body.interface().len();
        let e = body.mesh_fields(&vec![P; n], &[]).unwrap_err();
        assert!(e.to_string().contains("punch.rigid"), "{e}");
        let e = body.mesh_fields(&vec![0.5 * P; n], &[0.0]).unwrap_err();
        assert!(e.to_string().contains("punch.pressure"), "{e}");
    }
}
