use faer::Mat;

use crate::{check, ElasticBody, InfluenceShape, Interface, Result, RigidMode};

/// A rigid body facing another body's contact surface: no compliance, and either held in
/// place or free to translate along one axis under a given force (a punch, an indenter).
///
/// Its interface mirrors the partner's: the same points and weights, opposite normals. Its
/// shape enters the contact problem through the initial gap h.
#[derive(Clone, Debug)]
pub struct RigidBody {
    name: String,
    interface: Interface,
    modes: Vec<RigidMode>,
}

impl RigidBody {
    /// A rigid body held in place (its approach is prescribed through the initial gap).
    pub fn fixed(name: impl Into<String>, partner: &Interface) -> Self {
        Self {
            name: name.into(),
            interface: partner.mirrored(),
            modes: vec![],
        }
    }

    /// A rigid body free to translate along the unit vector `axis` that points away from
    /// the partner, pressed towards it by `force` \[N\] > 0. In axisymmetry only the axial
    /// translation (0, 1, 0) is a rigid mode.
    pub fn pressed(
        name: impl Into<String>,
        partner: &Interface,
        axis: [f64; 3],
        force: f64,
    ) -> Result<Self> {
        check::unit_vector("rigid.axis", axis)?;
        check::positive("force_n", force)?;
        // Moving away from the partner along `axis` moves each point into this body by
        // axis · n_partner.
        let interface_displacement = partner
            .normals()
            .iter()
            .map(|n| (0..3).map(|c| axis[c] * n[c]).sum())
            .collect();
        let mode = RigidMode {
            name: "translation".into(),
            interface_displacement,
            load: -force,
        };
        Ok(Self {
            name: name.into(),
            interface: partner.mirrored(),
            modes: vec![mode],
        })
    }
}

impl ElasticBody for RigidBody {
    fn name(&self) -> &str {
        &self.name
    }

    fn interface(&self) -> &Interface {
        &self.interface
    }

    fn apply_influence(&self, _force: &[f64], displacement: &mut [f64]) {
        displacement.fill(0.0);
    }

    fn influence_matrix(&self) -> Mat<f64> {
        Mat::zeros(self.interface.len(), self.interface.len())
    }

    fn influence_block(&self, points: &[usize]) -> Option<Mat<f64>> {
        let on = points.iter().all(|&i| i < self.interface.len());
        on.then(|| Mat::zeros(points.len(), points.len()))
    }

    /// A = 0·A₀: no compliance, whatever the shape.
    fn influence_shape(&self) -> Option<(InfluenceShape, f64)> {
        Some((InfluenceShape::Zero, 0.0))
    }

    fn load_displacement(&self) -> Result<Vec<f64>> {
        Ok(vec![0.0; self.interface.len()])
    }

    /// Exactly the kept points: a rigid body costs nothing per point, so no margin is needed.
    /// Its modes keep their loads (the points left out carry no pressure).
    fn restrict(&self, keep: &[bool]) -> Option<(Box<dyn ElasticBody>, Vec<usize>)> {
        let index: Vec<usize> = (0..self.interface.len()).filter(|&i| keep[i]).collect();
        if index.len() == self.interface.len() {
            return None;
        }
        let interface = self.interface.subset(keep)?;
        let pick = |v: &[f64]| index.iter().map(|&i| v[i]).collect::<Vec<f64>>();
        let modes = self
            .modes
            .iter()
            .map(|m| RigidMode {
                name: m.name.clone(),
                interface_displacement: pick(&m.interface_displacement),
                load: m.load,
            })
            .collect();
        let part = Self {
            name: self.name.clone(),
            interface,
            modes,
        };
        Some((Box::new(part), index))
    }

    fn rigid_modes(&self) -> &[RigidMode] {
        &self.modes
    }
}
