//! A finite-element model: mesh, material, analysis type, supports and loads.

use std::collections::BTreeMap;

use contopt_core::{check, Error, Result, GEOMETRY_TOLERANCE};

use crate::element::{lagrange2, GAUSS3};
use crate::{Analysis, Face, Material, Mesh};

/// A displacement component: x (= r in axisymmetry) or y (= z).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Component {
    /// x, or the radial component r.
    X = 0,
    /// y, or the axial component z.
    Y = 1,
}

/// Geometry of one point of a face, from the face's three nodes and the 1-D quadratic
/// interpolation along it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FacePoint {
    /// Coordinates.
    pub x: [f64; 2],
    /// Unit outward normal (faces run counter-clockwise around their element).
    pub normal: [f64; 2],
    /// Length of the tangent |dx/ds|.
    pub jacobian: f64,
    /// 1-D shape functions of the (start, middle, end) nodes.
    pub shape: [f64; 3],
}

/// Linear-elastic finite-element model of one body.
#[derive(Clone, Debug)]
pub struct FeModel {
    pub(crate) mesh: Mesh,
    pub(crate) material: Material,
    pub(crate) analysis: Analysis,
    /// Prescribed displacement of (node, component).
    pub(crate) prescribed: BTreeMap<(usize, Component), f64>,
    /// Given nodal forces (already integrated face loads included), length 2·nodes.
    pub(crate) forces: Vec<f64>,
}

impl FeModel {
    /// A model without supports or loads. In axisymmetry the radial displacement of nodes on
    /// the axis (r = 0) is held, and nodes at r < 0 are rejected.
    pub fn new(mesh: Mesh, material: Material, analysis: Analysis) -> Result<Self> {
        analysis.validate()?;
        let mut model = Self {
            forces: vec![0.0; 2 * mesh.nodes().len()],
            mesh,
            material,
            analysis,
            prescribed: BTreeMap::new(),
        };
        if analysis == Analysis::Axisymmetric {
            let scale = model
                .mesh
                .nodes()
                .iter()
                .fold(0.0f64, |m, p| m.max(p[0].abs()));
            let tol = GEOMETRY_TOLERANCE * scale;
            if let Some(i) = model.mesh.nodes().iter().position(|p| p[0] < -tol) {
                return Err(Error::invalid(
                    format!("mesh.nodes[{i}].r"),
                    model.mesh.nodes()[i][0],
                    "axisymmetric meshes need r >= 0",
                ));
            }
            for n in model.mesh.nodes_where(|p| p[0].abs() <= tol) {
                model.prescribed.insert((n, Component::X), 0.0);
            }
        }
        Ok(model)
    }

    /// The mesh.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The material.
    pub fn material(&self) -> &Material {
        &self.material
    }

    /// The analysis type.
    pub fn analysis(&self) -> Analysis {
        self.analysis
    }

    fn check_nodes(&self, nodes: &[usize], what: &str) -> Result<()> {
        if nodes.is_empty() {
            return Err(Error::invalid(what, "[]", "selects no node"));
        }
        if let Some(&n) = nodes.iter().find(|&&n| n >= self.mesh.nodes().len()) {
            return Err(Error::invalid(
                what,
                n,
                format!("no such node (mesh has {})", self.mesh.nodes().len()),
            ));
        }
        Ok(())
    }

    fn check_faces(&self, faces: &[Face], what: &str) -> Result<()> {
        if faces.is_empty() {
            return Err(Error::invalid(what, "[]", "selects no face"));
        }
        let mesh = &self.mesh;
        if let Some(f) = faces.iter().find(|f| {
            f.element >= mesh.elements().len() || f.local >= mesh.element_kind(f.element).n_faces()
        }) {
            return Err(Error::invalid(what, format!("{f:?}"), "no such face"));
        }
        Ok(())
    }

    /// Holds `component` of `nodes` at zero.
    pub fn fix(&mut self, nodes: &[usize], component: Component) -> Result<&mut Self> {
        self.prescribe(nodes, component, 0.0)
    }

    /// Prescribes `component` of `nodes` to `value` \[mm\].
    pub fn prescribe(
        &mut self,
        nodes: &[usize],
        component: Component,
        value: f64,
    ) -> Result<&mut Self> {
        self.check_nodes(nodes, "support.nodes")?;
        check::finite("support.value", value)?;
        for &n in nodes {
            self.prescribed.insert((n, component), value);
        }
        Ok(self)
    }

    /// A uniform pressure `p` \[MPa\] on `faces`, positive when it pushes into the body.
    pub fn pressure(&mut self, faces: &[Face], p: f64) -> Result<&mut Self> {
        self.check_faces(faces, "pressure.faces")?;
        check::finite("pressure.value", p)?;
        let load = |fp: &FacePoint| [-p * fp.normal[0], -p * fp.normal[1]];
        self.face_load(faces, ("pressure.value", p.to_string()), load)?;
        Ok(self)
    }

    /// A uniform traction `t` = (t_x, t_y) \[MPa\] on `faces`.
    pub fn traction(&mut self, faces: &[Face], t: [f64; 2]) -> Result<&mut Self> {
        self.traction_with(faces, |_| t)
    }

    /// A traction that varies along the faces: `t(x)` \[MPa\] at the point x.
    pub fn traction_with(
        &mut self,
        faces: &[Face],
        t: impl Fn([f64; 2]) -> [f64; 2],
    ) -> Result<&mut Self> {
        self.check_faces(faces, "traction.faces")?;
        for v in faces
            .iter()
            .flat_map(|&f| GAUSS3.map(|(s, _)| self.face_point(f, s).x))
            .map(&t)
        {
            check::all_finite("traction.value", &v)?;
        }
        let value = ("traction.value", "t(x) on the faces".to_string());
        self.face_load(faces, value, |fp| t(fp.x))?;
        Ok(self)
    }

    /// A force `f` = (f_x, f_y) \[N\] at `node` (in axisymmetry: the force of the whole ring).
    pub fn nodal_force(&mut self, node: usize, f: [f64; 2]) -> Result<&mut Self> {
        self.check_nodes(&[node], "force.node")?;
        check::all_finite("force.value", &f)?;
        let sum = [
            self.forces[2 * node] + f[0],
            self.forces[2 * node + 1] + f[1],
        ];
        check::all_derived(
            "force.value",
            format!("{f:?}"),
            "the node's total force",
            &sum,
        )?;
        self.forces[2 * node] = sum[0];
        self.forces[2 * node + 1] = sum[1];
        Ok(self)
    }

    /// Adds the consistent nodal forces ∫ N t dS of a traction field to the load vector; an
    /// error naming the load's `field` and `value` (and the model left as it was) when they
    /// overflow f64.
    fn face_load(
        &mut self,
        faces: &[Face],
        (field, value): (&str, String),
        traction: impl Fn(&FacePoint) -> [f64; 2],
    ) -> Result<()> {
        let mut forces = self.forces.clone();
        for &f in faces {
            let nodes = self.mesh.face_nodes(f);
            for &(s, w) in &GAUSS3 {
                let fp = self.face_point(f, s);
                let t = traction(&fp);
                let ds = w * fp.jacobian * self.analysis.measure(fp.x[0]);
                for (k, &n) in nodes.iter().enumerate() {
                    forces[2 * n] += fp.shape[k] * t[0] * ds;
                    forces[2 * n + 1] += fp.shape[k] * t[1] * ds;
                }
            }
        }
        check::all_derived(field, value, "the nodal forces ∫ N t dS", &forces)?;
        self.forces = forces;
        Ok(())
    }

    /// Position, normal and shape functions at parameter `s` ∈ [−1, 1] along a face.
    pub(crate) fn face_point(&self, f: Face, s: f64) -> FacePoint {
        let nodes = self.mesh.face_nodes(f);
        let mut fp = FacePoint {
            x: [0.0; 2],
            normal: [0.0; 2],
            jacobian: 0.0,
            shape: [0.0; 3],
        };
        let mut t = [0.0; 2];
        for (k, &node) in [-1.0, 0.0, 1.0].iter().enumerate() {
            let (l, dl) = lagrange2(node, s);
            let p = self.mesh.nodes()[nodes[k]];
            fp.shape[k] = l;
            for c in 0..2 {
                fp.x[c] += l * p[c];
                t[c] += dl * p[c];
            }
        }
        fp.jacobian = t[0].hypot(t[1]);
        fp.normal = [t[1] / fp.jacobian, -t[0] / fp.jacobian];
        fp
    }

    /// Total given load vector (length 2·nodes), for resultants and rigid-mode loads.
    pub fn forces(&self) -> &[f64] {
        &self.forces
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ElementKind, Spacing};

    /// One axisymmetric Q8 element 10 mm square of modulus `e`, held at its bottom.
    fn held(e: f64) -> FeModel {
        let x = Spacing::uniform(0.0, 10.0, 1).unwrap();
        let y = Spacing::uniform(-10.0, 0.0, 1).unwrap();
        let mesh = Mesh::rectangle(ElementKind::Q8, &x, &y).unwrap();
        let material = Material::new(e, 0.3).unwrap();
        let mut model = FeModel::new(mesh, material, Analysis::Axisymmetric).unwrap();
        let bottom = model.mesh().nodes_on_y(-10.0, 0.0, 10.0);
        model.fix(&bottom, Component::X).unwrap();
        model.fix(&bottom, Component::Y).unwrap();
        model
    }

    /// A finite pressure whose nodal forces overflow f64 is refused, naming it, and leaves
    /// the loads as they were; so is a force that overflows the node's total.
    #[test]
    fn loads_beyond_f64_are_refused() {
        let mut model = held(2e5);
        let top = model.mesh().faces_on_y(0.0, 0.0, 10.0);
        let e = model.pressure(&top, 1.7e308).unwrap_err().to_string();
        assert!(
            e.contains("pressure.value") && e.contains("beyond f64"),
            "{e}"
        );
        assert!(model.forces().iter().all(|f| *f == 0.0));
        let e = model
            .traction(&top, [0.0, f64::MAX])
            .unwrap_err()
            .to_string();
        assert!(e.contains("traction.value"), "{e}");
        model.nodal_force(2, [0.0, f64::MAX]).unwrap();
        let e = model.nodal_force(2, [0.0, f64::MAX]).unwrap_err();
        assert!(e.to_string().contains("force.value"), "{e}");
        assert_eq!(model.forces()[5], f64::MAX);
    }

    /// Finite loads whose displacements overflow f64 (E = 10⁻³⁰⁰ MPa): an error, not NaN.
    #[test]
    fn a_solve_beyond_f64_is_an_error() {
        let mut model = held(1e-300);
        let top = model.mesh().nodes_on_y(0.0, 0.0, 10.0);
        model.nodal_force(top[0], [0.0, -1e10]).unwrap();
        let e = model.solve().unwrap_err().to_string();
        assert!(e.contains("loads") && e.contains("displacements"), "{e}");
        let mut model = held(2e5);
        model.nodal_force(top[0], [0.0, -1e10]).unwrap();
        assert!(model.solve().is_ok());
    }
}
