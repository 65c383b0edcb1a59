//! A solid body on a 2-D contact region: its contact faces sampled at points, and its
//! influence A = L K⁻¹ Lᵀ (eq. 2.22) either condensed to a dense matrix (a small region) or
//! applied through the sparse factorisation, one forward and backward solve per product (a
//! large one), so that the matrix-free solvers and the load split see a body like any other.

use std::time::{Duration, Instant};

use contopt_core::{
    check, memory, BodyFields, ElasticBody, Error, GapShape, Geometry, Interface, Result,
    RigidMode, Spares, Subsurface, SubsurfaceRequest,
};

use faer::Mat;

use super::mesh::SolidFace;
use super::model::SolidModel;
use super::precondition::HalfSpaceInverse;
use super::sample::{Row, SolidSample};
use super::system::Pinning;
use crate::factor::{Ordering, TailWork};
use crate::system::{Dof, System};

/// Below this many contact points the influence is condensed to a dense matrix by default
/// (3000² doubles: 72 MB); above, it is applied through the factorisation.
pub const DENSE_POINTS: usize = 3000;

/// How the body applies its influence.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Condensation {
    /// Dense up to [`DENSE_POINTS`] contact points, products above.
    #[default]
    Auto,
    /// The dense matrix A = L K⁻¹ Lᵀ from the factor's trailing block (the face unknowns
    /// ordered last).
    Dense,
    /// One forward and backward solve per product through the factor's trailing block (the
    /// face unknowns ordered last), nothing dense stored.
    Products,
}

/// Options of a solid body's build.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SolidSettings {
    /// Dense matrix or products.
    pub condensation: Condensation,
    /// The fill-reducing ordering of the unknowns ahead of the contact face's (nested
    /// dissection by default).
    pub ordering: Ordering,
    /// The most memory the build may take \[bytes\], checked before anything large is
    /// allocated: the factor's size counted on the nodes' graph before the assembly (nested
    /// dissection and natural orderings), the assembly's estimate, and the factor's size again
    /// after its symbolic analysis, before its values are allocated (a scene passes its own
    /// `memory_limit_mb`).
    pub memory_limit_bytes: u64,
}

impl Default for SolidSettings {
    /// Nested dissection (on the scaling block of `examples/solid_scaling.rs` it needs 0.44
    /// of AMD's factor flops at 7 465 nodes, 0.31 at 23 653), the influence dense up to
    /// [`DENSE_POINTS`] points, [`memory::BODY_LIMIT_BYTES`].
    fn default() -> Self {
        Self {
            condensation: Condensation::default(),
            ordering: Ordering::Dissection,
            memory_limit_bytes: memory::BODY_LIMIT_BYTES,
        }
    }
}

/// Sizes and wall-clock times of a solid body's build.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SolidStats {
    /// Nodes of the mesh.
    pub nodes: usize,
    /// Free unknowns.
    pub unknowns: usize,
    /// Nonzeros of the Cholesky factor.
    pub factor_nnz: usize,
    /// Floating-point operations of the numeric factorisation.
    pub factor_flops: f64,
    /// Whether the influence is a dense matrix.
    pub dense: bool,
    /// Element integration and assembly.
    pub assembly: Duration,
    /// Ordering (with the factor's size counted on the nodes' graph), symbolic and numeric
    /// factorisation.
    pub factorisation: Duration,
    /// The dense influence matrix (zero for products).
    pub condensation: Duration,
    /// One influence product (solve) as measured on the load vector.
    pub solve: Duration,
}

/// A solid of quadratic elements whose contact zone is a set of boundary faces, sampled at
/// points ([`SolidSample`]): the Gauss points of its faces ([`SolidBody::new`]), or cells —
/// a half-space grid's, another body's — each read as its mean over the faces
/// ([`SolidBody::sampled`]). Rigid motions its supports leave free are pinned and reported as
/// its rigid modes (a sphere pressed along its symmetry axis floats along it).
pub struct SolidBody {
    name: String,
    pub(crate) model: SolidModel,
    pub(crate) system: System,
    interface: Interface,
    pub(crate) rows: Vec<Row>,
    dense: Option<Mat<f64>>,
    load_displacement: Vec<f64>,
    rigid_modes: Vec<RigidMode>,
    gap_shape: GapShape,
    /// The largest face each interface point's cell reads \[mm\].
    element_sizes: Vec<f64>,
    stats: SolidStats,
    /// Built at the first preconditioned step.
    preconditioner: std::sync::OnceLock<Option<HalfSpaceInverse>>,
    /// The products' work buffers, a set per product running at once.
    work: Spares<ProductWork>,
}

/// The buffers of one influence product through the factor: the face's forces and
/// displacements, and the trailing sweep's.
#[derive(Debug, Default)]
struct ProductWork {
    face: Vec<f64>,
    tail: TailWork,
}

impl SolidBody {
    /// The body with contact zone `contact` (boundary faces), checked at each face's contact
    /// points ([`crate::solid::FaceKind::contact_points`]).
    pub fn new(
        name: impl Into<String>,
        model: SolidModel,
        contact: &[SolidFace],
        settings: SolidSettings,
    ) -> Result<Self> {
        let name = name.into();
        check_contact(&name, &model, contact)?;
        let samples = SolidSample::gauss(model.mesh(), contact);
        Self::sampled(name, model, &samples, settings)
    }

    /// The body with its interface points given one by one: each point's displacement is its
    /// cell's mean, and its force a uniform pressure on the cell ([`SolidSample`]).
    pub fn sampled(
        name: impl Into<String>,
        model: SolidModel,
        samples: &[SolidSample],
        settings: SolidSettings,
    ) -> Result<Self> {
        let name = name.into();
        let mut contact: Vec<SolidFace> = (samples.iter())
            .flat_map(|s| s.parts.iter().map(|p| p.face))
            .collect();
        contact.sort();
        contact.dedup();
        check_contact(&name, &model, &contact)?;
        let n = samples.len();
        let dense = match settings.condensation {
            Condensation::Auto => n <= DENSE_POINTS,
            Condensation::Dense => true,
            Condensation::Products => false,
        };
        let face_nodes = model.mesh().nodes_of(&contact);
        if dense {
            memory::require(
                format!("{name}: a dense influence of {n} contact points"),
                memory::bytes(&[n, n + 3 * face_nodes.len()], 8),
                settings.memory_limit_bytes,
                "apply the influence through the factorisation (condensation = products)",
            )?;
        }
        let system = System::solid(
            &model,
            &name,
            &face_nodes,
            Pinning::Pin,
            settings.ordering,
            settings.memory_limit_bytes,
        )?;
        let rows: Vec<Row> = samples.iter().map(|s| s.row(model.mesh())).collect();
        let element_sizes = samples.iter().map(|s| s.face_size(model.mesh())).collect();
        let interface = Interface::new(
            Geometry::Surface,
            samples.iter().map(|s| s.point).collect(),
            samples.iter().map(|s| s.weight).collect(),
            samples.iter().map(|s| s.normal).collect(),
        )?;
        let gap_shape = gap_basis(&model, samples, &face_nodes)?;
        let start = Instant::now();
        let dense = dense.then(|| system.condense(rows.iter().map(|r| r.entries.iter().copied())));
        let condensation = start.elapsed();
        let start = Instant::now();
        let u = system.solve(&model.forces, None);
        let solve = start.elapsed();
        model.check_displacement(&u)?;
        let load_displacement = rows.iter().map(|r| r.normal_into(&u)).collect();
        let rigid_modes = system
            .modes
            .iter()
            .map(|m| RigidMode {
                name: m.name.clone(),
                interface_displacement: rows.iter().map(|r| r.normal_into(&m.values)).collect(),
                load: m.values.iter().zip(&model.forces).map(|(a, b)| a * b).sum(),
            })
            .collect();
        let stats = SolidStats {
            nodes: model.mesh().nodes().len(),
            unknowns: system.n_free,
            factor_nnz: system.factor.factor_nnz(),
            factor_flops: system.factor.flops(),
            dense: dense.is_some(),
            assembly: system.assembly_time,
            factorisation: system.factorisation_time,
            condensation,
            solve,
        };
        let body = Self {
            name,
            model,
            system,
            interface,
            rows,
            dense,
            load_displacement,
            rigid_modes,
            gap_shape,
            element_sizes,
            stats,
            preconditioner: std::sync::OnceLock::new(),
            work: Spares::default(),
        };
        if let Some(a) = &body.dense {
            let flat: Vec<f64> = (0..n)
                .flat_map(|j| a.col(j).iter().copied().collect::<Vec<_>>())
                .collect();
            check::all_derived(
                "material.e_mpa",
                "the material and the mesh",
                "the influence matrix",
                &flat,
            )?;
        }
        Ok(body)
    }

    /// The model.
    pub fn model(&self) -> &SolidModel {
        &self.model
    }

    /// Sizes and timings of the build.
    pub fn stats(&self) -> &SolidStats {
        &self.stats
    }

    /// Nodal displacements (3 per node) under the given loads, compressive normal forces
    /// `force` at the interface points \[N\] and rigid-mode amplitudes `rigid`.
    pub fn displacement(&self, force: &[f64], rigid: &[f64]) -> Result<Vec<f64>> {
        let n = self.interface.len();
        if force.len() != n {
            return Err(Error::invalid(
                format!("{}.force", self.name),
                force.len(),
                format!("one per interface point ({n})"),
            ));
        }
        if rigid.len() != self.rigid_modes.len() {
            return Err(Error::invalid(
                format!("{}.rigid", self.name),
                rigid.len(),
                format!("one per rigid mode ({})", self.rigid_modes.len()),
            ));
        }
        let mut u = self
            .system
            .solve(&self.model.forces, Some(&self.nodal_forces(force)));
        for (m, a) in self.system.modes.iter().zip(rigid) {
            for (ui, v) in u.iter_mut().zip(&m.values) {
                *ui += a * v;
            }
        }
        check::all_derived(
            &format!("{}.force", self.name),
            "the interface forces",
            "the displacements",
            &u,
        )?;
        Ok(u)
    }

    /// The nodal forces (3 per node) of compressive forces `force` at the interface points:
    /// −Σ coef·f on each row's DOFs (Lᵀ f, pressing into the body).
    fn nodal_forces(&self, force: &[f64]) -> Vec<f64> {
        let mut extra = vec![0.0; self.model.forces.len()];
        for (r, f) in self.rows.iter().zip(force) {
            for &(g, c) in &r.entries {
                extra[g] -= c * f;
            }
        }
        extra
    }

    /// The influence product through the factorisation: L K⁻¹ Lᵀ f, the face unknowns being
    /// ordered last, through the factor's trailing block alone
    /// ([`crate::factor::Factor::tail_solve_in_place`]), in a spare set of work buffers:
    /// a body used by one thread allocates nothing after its first product.
    fn product(&self, force: &[f64], displacement: &mut [f64]) {
        self.work.with(ProductWork::default, |work| {
            self.product_in(force, displacement, work)
        });
    }

    fn product_in(&self, force: &[f64], displacement: &mut [f64], work: &mut ProductWork) {
        let system = &self.system;
        let first = system.n_free - system.n_tail;
        let face = |g: usize| match system.dofs[g] {
            Dof::Free(i) => Some(i - first),
            _ => None,
        };
        let face_u = &mut work.face;
        face_u.clear();
        face_u.resize(system.n_tail, 0.0);
        for (r, f) in self.rows.iter().zip(force) {
            for &(g, c) in &r.entries {
                if let Some(k) = face(g) {
                    face_u[k] -= c * f;
                }
            }
        }
        system.factor.tail_solve_in_place(face_u, &mut work.tail);
        for (d, r) in displacement.iter_mut().zip(&self.rows) {
            *d = -(r.entries.iter())
                .filter_map(|&(g, c)| face(g).map(|k| c * face_u[k]))
                .sum::<f64>();
        }
    }
}

/// The contact zone is a non-empty set of boundary faces of the mesh.
fn check_contact(name: &str, model: &SolidModel, contact: &[SolidFace]) -> Result<()> {
    if contact.is_empty() {
        return Err(Error::invalid(
            format!("{name}.contact"),
            "[]",
            "select at least one face",
        ));
    }
    let boundary: std::collections::HashSet<SolidFace> =
        model.mesh().boundary_faces().into_iter().collect();
    match contact.iter().find(|f| !boundary.contains(f)) {
        Some(f) => Err(Error::invalid(
            format!("{name}.contact"),
            format!("{f:?}"),
            "is not a boundary face of the mesh",
        )),
        None => Ok(()),
    }
}

/// The map from the contact faces' nodes to the points (each the mean of the faces' shape
/// functions over its cell, [`SolidSample`]): the field the points' pressures sample, and the
/// gap change Δh = L(x)Δh.
fn gap_basis(
    model: &SolidModel,
    samples: &[SolidSample],
    face_nodes: &[usize],
) -> Result<GapShape> {
    let mesh = model.mesh();
    let rows = samples
        .iter()
        .map(|s| {
            (s.node_weights(mesh).into_iter())
                .map(|(node, w)| (face_nodes.partition_point(|&j| j < node), w))
                .collect()
        })
        .collect();
    let nodes = face_nodes.iter().map(|&k| mesh.nodes()[k]).collect();
    GapShape::new(nodes, rows)
}

impl ElasticBody for SolidBody {
    fn name(&self) -> &str {
        &self.name
    }

    fn interface(&self) -> &Interface {
        &self.interface
    }

    fn apply_influence(&self, force: &[f64], displacement: &mut [f64]) {
        match &self.dense {
            Some(a) => {
                let n = self.interface.len();
                for (i, d) in displacement.iter_mut().enumerate().take(n) {
                    *d = (0..n).map(|j| a[(i, j)] * force[j]).sum();
                }
            }
            None => self.product(force, displacement),
        }
    }

    fn influence_matrix(&self) -> Mat<f64> {
        match &self.dense {
            Some(a) => a.clone(),
            None => {
                let n = self.interface.len();
                let mut a = Mat::zeros(n, n);
                let mut unit = vec![0.0; n];
                let mut column = vec![0.0; n];
                for j in 0..n {
                    unit[j] = 1.0;
                    self.product(&unit, &mut column);
                    unit[j] = 0.0;
                    a.col_mut(j)
                        .iter_mut()
                        .zip(&column)
                        .for_each(|(x, v)| *x = *v);
                }
                a
            }
        }
    }

    fn influence_block(&self, points: &[usize]) -> Option<Mat<f64>> {
        match &self.dense {
            Some(a) => contopt_core::block_among(a, points),
            None => {
                let n = self.interface.len();
                if points.iter().any(|&i| i >= n) {
                    return None;
                }
                let mut unit = vec![0.0; n];
                let mut column = vec![0.0; n];
                let m = points.len();
                let mut block = Mat::zeros(m, m);
                for (b, &j) in points.iter().enumerate() {
                    unit[j] = 1.0;
                    self.product(&unit, &mut column);
                    unit[j] = 0.0;
                    for (a, &i) in points.iter().enumerate() {
                        block[(a, b)] = column[i];
                    }
                }
                Some(block)
            }
        }
    }

    /// Boussinesq's half-space among the interface points, with the symmetry planes' images
    /// (module `solid::precondition`); none above [`crate::solid::PRECONDITIONED_POINTS`].
    fn precondition(&self, displacement: &[f64], force: &mut [f64]) -> bool {
        let inverse = self
            .preconditioner
            .get_or_init(|| HalfSpaceInverse::new(&self.model, &self.interface));
        inverse
            .as_ref()
            .map(|b| b.apply(displacement, force))
            .is_some()
    }

    fn load_displacement(&self) -> Result<Vec<f64>> {
        Ok(self.load_displacement.clone())
    }

    fn pressure_basis(&self) -> Option<&GapShape> {
        Some(&self.gap_shape)
    }

    fn element_sizes(&self) -> Option<&[f64]> {
        Some(&self.element_sizes)
    }

    fn rigid_modes(&self) -> &[RigidMode] {
        &self.rigid_modes
    }

    /// The peaks of each criterion over every node of the mesh under `pressure` and the
    /// body's given loads ([`SolidBody::nodal_subsurface`]); the request's depths and sections
    /// do not apply to a mesh, which has its own points below the surface.
    fn subsurface(
        &self,
        pressure: &[f64],
        _request: &SubsurfaceRequest,
    ) -> Result<Option<Subsurface>> {
        self.nodal_subsurface(pressure).map(Some)
    }

    /// The mesh, the nodal displacements and the nodal stresses, for ParaView
    /// ([`SolidBody::mesh_fields`]).
    fn fields(&self, pressure: &[f64], rigid: &[f64]) -> Result<Option<BodyFields>> {
        self.mesh_fields(pressure, rigid).map(Some)
    }
}
