//! A finite-element body condensed to its contact face.

use std::time::{Duration, Instant};

use contopt_core::{
    check, BodyFields, ElasticBody, Error, GapShape, Interface, Result, RigidMode, Subsurface,
    SubsurfaceRequest,
};
use faer::Mat;

use crate::samples::{gap_basis, nodes_of, FaceSample, Mortar};
use crate::system::System;
use crate::{Face, FeModel};

/// One interface point's normal-displacement operator: the into-body displacement at the
/// point is −Σ_k `coef[k]`·u(`dofs[k]`) over the face nodes' global DOFs (the row of L in
/// H = L K⁻¹ Lᵀ, eq. 2.22).
#[derive(Clone, Debug)]
pub(crate) struct PointRow {
    pub dofs: [usize; 6],
    pub coef: [f64; 6],
}

impl PointRow {
    /// The row of a point at which the face's shape functions are `shape` and the outward
    /// normal along which displacement is measured is `normal`.
    fn new(model: &FeModel, face: Face, shape: [f64; 3], normal: [f64; 2]) -> Self {
        let nodes = model.mesh.face_nodes(face);
        let mut row = PointRow {
            dofs: [0; 6],
            coef: [0.0; 6],
        };
        for (k, &node) in nodes.iter().enumerate() {
            for (c, n) in normal.iter().enumerate() {
                row.dofs[2 * k + c] = 2 * node + c;
                row.coef[2 * k + c] = shape[k] * n;
            }
        }
        row
    }

    /// Displacement into the body, −n·u, from global nodal displacements.
    fn normal_into(&self, u: &[f64]) -> f64 {
        -self
            .dofs
            .iter()
            .zip(&self.coef)
            .map(|(&g, c)| c * u[g])
            .sum::<f64>()
    }
}

/// Sizes and wall-clock times of building an [`FeBody`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BuildStats {
    /// Free unknowns of the stiffness system.
    pub unknowns: usize,
    /// Unknowns on the contact face (ordered last).
    pub face_unknowns: usize,
    /// Nonzeros of the Cholesky factor L.
    pub factor_nnz: usize,
    /// Element integration and sparse assembly.
    pub assembly: Duration,
    /// Ordering, symbolic and numeric Cholesky factorisation.
    pub factorisation: Duration,
    /// The influence matrix A = L K⁻¹ Lᵀ from the factor's trailing block.
    pub condensation: Duration,
    /// The solve for the displacement under the given loads.
    pub load_solve: Duration,
}

/// A finite-element body whose contact zone Ω is a set of boundary faces.
///
/// Construction assembles K, factorises it once with the face unknowns ordered last,
/// condenses it to the face (the influence matrix A = L K⁻¹ Lᵀ at the Gauss points of every
/// contact face, §2.2) and solves once for the displacement under the given loads.
///
/// Contact is checked at the three Gauss points of every contact face, as in the paper
/// ([`FeBody::new`]), or at points given one by one ([`FeBody::sampled`]; a
/// [`crate::ContactPairing`] samples two bodies meshed apart). The Gauss points outnumber the face's normal displacement unknowns (3 per face against 2 per face plus
/// one), so A is only semi-definite: gaps and rigid motions are unique, Gauss-point pressures
/// are not. The solvers of `contopt-contact` return the pressure of least Σ wᵢpᵢ², the limit
/// of the penalty method, which is the paper's C⁰ pressure field (eq. 2.9) sampled at the
/// points. (Two points per face would make A definite but let the pressure checkerboard from
/// point to point under a flat punch: the classical inf-sup failure.)
/// Free rigid-body modes are detected from the supports, removed by holding one unknown each,
/// and reported through [`ElasticBody::rigid_modes`].
pub struct FeBody {
    name: String,
    pub(crate) model: FeModel,
    pub(crate) system: System,
    interface: Interface,
    pub(crate) rows: Vec<PointRow>,
    influence: Mat<f64>,
    load_displacement: Vec<f64>,
    rigid_modes: Vec<RigidMode>,
    gap_shape: GapShape,
    /// The map T of a paired body's point values onto the first body's face nodes
    /// ([`crate::ContactPairing::bodies`]): forces pass through Tᵀ, displacements through T.
    pub(crate) mortar: Option<Mortar>,
    stats: BuildStats,
}

impl FeBody {
    /// Builds the body with contact zone `contact` (boundary faces of the model's mesh),
    /// checked at the three Gauss points of every face ([`FaceSample::gauss`]).
    pub fn new(name: impl Into<String>, model: FeModel, contact: &[Face]) -> Result<Self> {
        let name = name.into();
        check_contact(&name, &model, contact)?;
        let samples: Vec<FaceSample> = contact
            .iter()
            .flat_map(|&f| FaceSample::gauss(&model, f))
            .collect();
        Self::build(name, model, contact, &samples)
    }

    /// Builds the body with its interface points given one by one: each [`FaceSample`] names
    /// a boundary face and a parameter on it, where the body's displacement is interpolated,
    /// and the point, weight and normal the interface reports. [`FeBody::new`] samples each
    /// face at its Gauss points; a [`crate::ContactPairing`] samples the second body where
    /// the first body's normals meet it (eq. 2.1: displacements along n¹), and its
    /// [`bodies`](crate::ContactPairing::bodies) also condense them onto the first body's face
    /// nodes, which bodies built here from its samples are not.
    pub fn sampled(
        name: impl Into<String>,
        model: FeModel,
        samples: &[FaceSample],
    ) -> Result<Self> {
        let name = name.into();
        let mut contact: Vec<Face> = Vec::new();
        for s in samples {
            if !contact.contains(&s.face) {
                contact.push(s.face);
            }
        }
        check_contact(&name, &model, &contact)?;
        if let Some(i) = samples.iter().position(|s| !(-1.0..=1.0).contains(&s.s)) {
            return Err(Error::invalid(
                format!("{name}.samples[{i}].s"),
                samples[i].s,
                "must lie in [-1, 1], the face's parameter range",
            ));
        }
        Self::build(name, model, &contact, samples)
    }

    /// The body of `model` with the interface of `samples` on the (checked) faces `contact`.
    fn build(
        name: String,
        model: FeModel,
        contact: &[Face],
        samples: &[FaceSample],
    ) -> Result<Self> {
        let face_nodes = nodes_of(&model, contact);
        let system = System::new(&model, &name, &face_nodes, samples.len())?;
        let condensation_start = Instant::now();
        let Sampled {
            interface,
            gap_shape,
            rows,
        } = Sampled::new(&model, samples, &face_nodes)?;
        let influence = system.condense(rows.iter().map(|r| r.dofs.into_iter().zip(r.coef)));
        let condensation = condensation_start.elapsed();

        let solve_start = Instant::now();
        let u = system.solve(&model.forces, None);
        let load_solve = solve_start.elapsed();
        let load_displacement = rows.iter().map(|r| r.normal_into(&u)).collect();
        let rigid_modes: Vec<RigidMode> = system
            .modes
            .iter()
            .map(|m| RigidMode {
                name: m.name.clone(),
                interface_displacement: rows.iter().map(|r| r.normal_into(&m.values)).collect(),
                load: m.values.iter().zip(&model.forces).map(|(a, b)| a * b).sum(),
            })
            .collect();
        check_outputs(&model, &influence, &u, &rigid_modes)?;
        let stats = BuildStats {
            unknowns: system.n_free,
            face_unknowns: system.n_tail,
            factor_nnz: system.factor.factor_nnz(),
            assembly: system.assembly_time,
            factorisation: system.factorisation_time,
            condensation,
            load_solve,
        };
        Ok(Self {
            name,
            model,
            system,
            interface,
            rows,
            influence,
            load_displacement,
            rigid_modes,
            gap_shape,
            mortar: None,
            stats,
        })
    }

    /// The body whose point values are read at the nodes of `interface` through `mortar`
    /// (T, [`crate::ContactPairing`]): influence T A Tᵀ, load and rigid-mode displacements
    /// T f, forces Tᵀ f, and `shape` as its gap shape.
    pub(crate) fn mortar(
        mut self,
        mortar: &Mortar,
        interface: Interface,
        shape: &GapShape,
    ) -> Self {
        self.influence = mortar.congruence(&self.influence);
        self.load_displacement = mortar.apply(&self.load_displacement);
        for mode in &mut self.rigid_modes {
            mode.interface_displacement = mortar.apply(&mode.interface_displacement);
        }
        self.gap_shape = shape.clone();
        self.interface = interface;
        self.mortar = Some(mortar.clone());
        self
    }

    /// The change of initial gap described by its values at the contact face's nodes and the
    /// faces' quadratic shape functions (Δh = L(x)Δh, §4): the map Q from the nodes to the
    /// Gauss points. Displacements are interpolated the same way, so a gap change that closes
    /// a displacement field exactly at the points exists. Both bodies of a
    /// [`crate::ContactPairing`] have the first body's, weighted onto the nodes that check
    /// contact.
    pub fn gap_shape(&self) -> &GapShape {
        &self.gap_shape
    }

    /// The model.
    pub fn model(&self) -> &FeModel {
        &self.model
    }

    /// Nodal displacements (u_x, u_y per node) under the given loads, compressive normal
    /// forces `force` at the interface points \[N\] and rigid-mode amplitudes `rigid`
    /// (one per [`ElasticBody::rigid_modes`]).
    pub fn displacement(&self, force: &[f64], rigid: &[f64]) -> Result<Vec<f64>> {
        if force.len() != self.interface.len() {
            return Err(Error::invalid(
                format!("{}.force", self.name),
                force.len(),
                format!("one per interface point ({})", self.interface.len()),
            ));
        }
        if rigid.len() != self.system.modes.len() {
            return Err(Error::invalid(
                format!("{}.rigid", self.name),
                rigid.len(),
                format!("one per rigid mode ({})", self.system.modes.len()),
            ));
        }
        let projected;
        let force = match &self.mortar {
            Some(t) => {
                projected = t.apply_transpose(force);
                &projected
            }
            None => force,
        };
        let mut extra = vec![0.0; self.model.forces.len()];
        for (r, f) in self.rows.iter().zip(force) {
            for (&g, &c) in r.dofs.iter().zip(&r.coef) {
                extra[g] -= c * f;
            }
        }
        let mut u = self.system.solve(&self.model.forces, Some(&extra));
        for (m, a) in self.system.modes.iter().zip(rigid) {
            for (ui, v) in u.iter_mut().zip(&m.values) {
                *ui += a * v;
            }
        }
        let field = format!("{}.force", self.name);
        check::all_derived(&field, "the interface forces", "the displacements", &u)?;
        Ok(u)
    }

    /// Normal displacement into the body at the interface points of a nodal displacement
    /// field (e.g. from [`FeBody::displacement`]).
    pub fn interface_displacement(&self, u: &[f64]) -> Vec<f64> {
        let at_points: Vec<f64> = self.rows.iter().map(|r| r.normal_into(u)).collect();
        match &self.mortar {
            Some(t) => t.apply(&at_points),
            None => at_points,
        }
    }

    /// Sizes and timings of the build.
    pub fn stats(&self) -> &BuildStats {
        &self.stats
    }
}

/// What a body is built from is finite: the influence matrix (else the material and the
/// mesh are beyond f64: E·size far from physical), the nodal displacement `u` under the given
/// loads and the loads on the rigid modes (else the loads are).
fn check_outputs(
    model: &FeModel,
    influence: &Mat<f64>,
    u: &[f64],
    modes: &[RigidMode],
) -> Result<()> {
    let n = influence.nrows();
    if let Some(v) = (0..influence.ncols())
        .flat_map(|j| (0..n).map(move |i| influence[(i, j)]))
        .find(|v| !v.is_finite())
    {
        let what = "the influence matrix L K⁻¹ Lᵀ on this mesh";
        check::derived("material.e_mpa", model.material.e(), what, v)?;
    }
    model.check_displacement(u)?;
    let loads: Vec<f64> = modes.iter().map(|m| m.load).collect();
    check::all_derived("loads", "the given loads", "a rigid mode's load", &loads)
}

/// The contact zone is a non-empty set of boundary faces of the mesh.
fn check_contact(name: &str, model: &FeModel, contact: &[Face]) -> Result<()> {
    if contact.is_empty() {
        return Err(Error::invalid(
            format!("{name}.contact"),
            "[]",
            "select at least one face",
        ));
    }
    let boundary: std::collections::HashSet<Face> =
        model.mesh.boundary_faces().into_iter().collect();
    if let Some(f) = contact.iter().find(|f| !boundary.contains(f)) {
        return Err(Error::invalid(
            format!("{name}.contact"),
            format!("{f:?}"),
            "is not a boundary face of the mesh",
        ));
    }
    Ok(())
}

/// The contact faces sampled at the points of a body's interface (§2.2): the interface, the
/// map Q from the face nodes to the points, and each point's normal-displacement row of L.
struct Sampled {
    interface: Interface,
    gap_shape: GapShape,
    rows: Vec<PointRow>,
}

impl Sampled {
    /// Samples the faces at `samples`, whose faces' nodes are `face_nodes` (sorted, distinct).
    fn new(model: &FeModel, samples: &[FaceSample], face_nodes: &[usize]) -> Result<Self> {
        let n = samples.len();
        let (mut points, mut weights, mut normals) = (vec![], vec![], vec![]);
        let mut rows = Vec::with_capacity(n);
        for sample in samples {
            let shape = model.face_point(sample.face, sample.s).shape;
            points.push([sample.point[0], sample.point[1], 0.0]);
            weights.push(sample.weight);
            normals.push([sample.normal[0], sample.normal[1], 0.0]);
            rows.push(PointRow::new(model, sample.face, shape, sample.normal));
        }
        let interface = Interface::new(model.analysis.geometry(), points, weights, normals)?;
        Ok(Self {
            interface,
            gap_shape: gap_basis(model, samples, face_nodes)?,
            rows,
        })
    }
}

impl ElasticBody for FeBody {
    fn name(&self) -> &str {
        &self.name
    }

    fn interface(&self) -> &Interface {
        &self.interface
    }

    fn apply_influence(&self, force: &[f64], displacement: &mut [f64]) {
        let n = self.interface.len();
        for (i, d) in displacement.iter_mut().enumerate().take(n) {
            *d = (0..n).map(|j| self.influence[(i, j)] * force[j]).sum();
        }
    }

    fn influence_matrix(&self) -> Mat<f64> {
        self.influence.clone()
    }

    fn influence_block(&self, points: &[usize]) -> Option<Mat<f64>> {
        contopt_core::block_among(&self.influence, points)
    }

    fn load_displacement(&self) -> Result<Vec<f64>> {
        Ok(self.load_displacement.clone())
    }

    fn pressure_basis(&self) -> Option<&GapShape> {
        Some(&self.gap_shape)
    }

    fn rigid_modes(&self) -> &[RigidMode] {
        &self.rigid_modes
    }

    /// The peaks of each criterion over every node of the mesh, with the stresses recovered
    /// at the nodes ([`FeBody::nodal_stresses`]: Gauss-point stresses extrapolated and
    /// averaged) under `pressure` and the body's given loads. Each [`contopt_core::Peak`]
    /// gives the node's model coordinates as `x`, `y` (r, z in axisymmetry) and as `depth`
    /// its distance to the nearest interface point.
    ///
    /// A mesh has its own points below the surface, so the request's `depths` do not apply.
    /// When sections are asked for, the answer is the model's plane itself, one section,
    /// provided the nodes (with each Q8 element's centre) fill a grid of x × y and the contact
    /// face is a line y = const, as a rectangular mesh's are; otherwise none (the whole field
    /// is [`FeBody::nodal_stresses`]). At a singular point (the edge of a flat punch) the nodal
    /// peak grows as the mesh is refined, as the exact stress is unbounded there.
    fn subsurface(
        &self,
        pressure: &[f64],
        request: &SubsurfaceRequest,
    ) -> Result<Option<Subsurface>> {
        self.nodal_subsurface(pressure, request).map(Some)
    }

    /// The mesh, the nodal displacements and the recovered nodal stresses:
    /// [`FeBody::mesh_fields`].
    fn fields(&self, pressure: &[f64], rigid: &[f64]) -> Result<Option<BodyFields>> {
        self.mesh_fields(pressure, rigid).map(Some)
    }
}
