use faer::Mat;

use crate::{BodyFields, GapShape, Interface, Result, Subsurface, SubsurfaceRequest};

/// A rigid-body mode that a body's supports leave free (the floating punch of Table 1 has
/// one: the axial translation).
///
/// The contact problem carries its amplitude λ as an unknown, with the equilibrium row
/// G_Rᵀ p = q of eqs. (2.10)–(2.11).
#[derive(Clone, Debug, PartialEq)]
pub struct RigidMode {
    /// A short name, e.g. `"axial translation"`.
    pub name: String,
    /// Normal displacement *into the body* at each interface point per unit amplitude
    /// (the column of G_R before weighting, eq. 2.6).
    pub interface_displacement: Vec<f64>,
    /// Work of the given external loads on the mode per unit amplitude: the component of
    /// the load resultant q (eq. 2.10) that the contact pressure must balance.
    pub load: f64,
}

/// The fixed operator A₀ of which a body's influence is a multiple, A = scale·A₀
/// ([`ElasticBody::influence_shape`]): two bodies of equal shapes, paired point for point, have
/// proportional operators, so the interface problem applies one product for the summed
/// H = H¹ + H² (eqs. 2.8–2.15) and scales it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InfluenceShape {
    /// A₀ = 0: no compliance, whatever the points (a rigid body, of scale 0).
    Zero,
    /// Love's influence of uniform pressure on the rectangular cells of a grid on a
    /// half-space, at unit (1 − ν²)/E.
    CellGrid {
        /// Cells along x and y.
        cells: [usize; 2],
        /// Distance between cell centres along x and y \[mm\] (0 along a side of one cell).
        spacing: [f64; 2],
        /// A cell's area \[mm²\].
        cell_area: f64,
        /// Whether the surface repeats the grid in both directions.
        periodic: bool,
    },
}

/// The entries of a dense influence matrix among `points`, `block[(a, b)]` =
/// `matrix[(points[a], points[b])]`: [`ElasticBody::influence_block`] of a body that holds its
/// matrix. `None` when a point is not among the matrix's rows.
pub fn block_among(matrix: &Mat<f64>, points: &[usize]) -> Option<Mat<f64>> {
    let m = points.len();
    let on = points
        .iter()
        .all(|&i| i < matrix.nrows().min(matrix.ncols()));
    on.then(|| Mat::from_fn(m, m, |a, b| matrix[(points[a], points[b])]))
}

/// A linear-elastic body as contact sees it: its contact surface, how normal forces on that
/// surface move it, where its given loads move it, and which rigid motions it is free to make
/// (eqs. 2.5–2.6).
///
/// Conventions (the book's chapter "Write your own body"): normal displacements are measured *into* the body, along −n,
/// where n is the body's outward normal at the point, so that pressing a surface moves it by a
/// positive amount; a force is a compressive normal force (pressure × weight). A body with free
/// rigid modes reports displacements relative to an internal reference that removes those
/// modes; the modes themselves are listed by [`ElasticBody::rigid_modes`].
///
/// Finite-element bodies, Green's-function bodies (half-space, half-plane), rigid bodies and
/// user types implement it.
///
/// A body is `Send + Sync`: the contact solves of an envelope's load cases under one crown
/// share one body and run at once on several threads (`contopt_contact::parallel`), each
/// calling its `&self` methods. A body that reuses work buffers between products keeps them
/// where threads cannot meet: a set per product running at once ([`crate::Spares`]), not one
/// behind a `RefCell` (which is not `Sync`) nor one behind a lock (the products would wait for
/// each other, one thread at a time). A product must give the same bits on any thread and
/// whatever ran before it (no state carried from one call to the next), so that results are
/// the same for any number of threads.
pub trait ElasticBody: Send + Sync {
    /// Name used in messages and reports.
    fn name(&self) -> &str;

    /// The points of the proposed contact zone.
    fn interface(&self) -> &Interface;

    /// Applies the influence (Green's function) operator, eq. (2.5): given compressive normal
    /// forces `force[j]` at the interface points, writes the normal displacement into the body
    /// at every point to `displacement`. Both slices have the interface's length.
    fn apply_influence(&self, force: &[f64], displacement: &mut [f64]);

    /// The dense influence matrix A (n × n, symmetric positive semi-definite) with
    /// `A[(i, j)]` the displacement into the body at point i under a unit force at point j:
    /// A = L K⁻¹ Lᵀ for a finite-element body. The default applies
    /// [`ElasticBody::apply_influence`] to each unit vector; bodies that hold the matrix
    /// return it directly.
    fn influence_matrix(&self) -> Mat<f64> {
        let n = self.interface().len();
        let mut a = Mat::zeros(n, n);
        let mut unit = vec![0.0; n];
        let mut column = vec![0.0; n];
        for j in 0..n {
            unit[j] = 1.0;
            self.apply_influence(&unit, &mut column);
            unit[j] = 0.0;
            for (i, v) in column.iter().enumerate() {
                a[(i, j)] = *v;
            }
        }
        a
    }

    /// The influence matrix's entries among a few `points` (indices of the interface):
    /// `block[(a, b)]` = `A[(points[a], points[b])]`, the displacement at `points[a]` under a
    /// unit force at `points[b]`. A model of a small contact reads it (the load split's
    /// exponent of a column a few points wide). `None` (the default) when the body cannot give
    /// entries without influence products, and when a point is not on the interface; bodies
    /// that hold the matrix or a kernel return them.
    fn influence_block(&self, points: &[usize]) -> Option<Mat<f64>> {
        let _ = points;
        None
    }

    /// An approximate inverse of the influence operator, for preconditioning iterative
    /// solvers: writes to `force` forces that roughly produce `displacement`, and returns
    /// `true`; bodies without one return `false` (the default) and leave `force` alone.
    fn precondition(&self, displacement: &[f64], force: &mut [f64]) -> bool {
        let _ = (displacement, force);
        false
    }

    /// An approximate inverse of the influence operator on the points marked in `contact`
    /// while the others carry no force, A_CC⁻¹ (what an iterative solver on a contact set
    /// needs): writes forces on the marked points (zero elsewhere) that roughly produce
    /// `displacement` there (it is zero elsewhere), and returns `true`; `false` when the body
    /// has no inverse.
    ///
    /// The default is [`ElasticBody::precondition`], masked: the whole operator's inverse on
    /// the set, (A⁻¹)_CC. With A⁻¹ = K it exceeds A_CC⁻¹ by K_CN K_NN⁻¹ K_NC, the set's ties
    /// to the unloaded points around it, which sit on the set's edge: small for a half-space
    /// grid's circulant, but large for a bed whose points are tied strongly to their
    /// neighbours (a Pasternak layer), whose directions it then swamps at the edge. A body
    /// whose inverse K is local gives the exact A_CC⁻¹ = K_CC − K_CN K_NN⁻¹ K_NC.
    fn precondition_on(&self, displacement: &[f64], contact: &[bool], force: &mut [f64]) -> bool {
        if !self.precondition(displacement, force) {
            return false;
        }
        for (f, &c) in force.iter_mut().zip(contact) {
            if !c {
                *f = 0.0;
            }
        }
        true
    }

    /// The influence operator as a multiple of a fixed one: `(shape, scale)` when A = scale·A₀
    /// with A₀ given by `shape` (a half-space grid: its cells and spacing; scale (1 − ν²)/E).
    /// Two bodies of one shape, paired point for point, share one product: the interface
    /// problem applies one of them and scales it. A scale of 0 says the operator is zero (a
    /// rigid body): the problem applies the partner's alone. `None` (the default) when the body
    /// does not say.
    fn influence_shape(&self) -> Option<(InfluenceShape, f64)> {
        None
    }

    /// A part of the influence operator that is a multiple of a fixed one: `(shape, scale)`
    /// when A = scale·A₀ + R, A₀ given by `shape` as in [`ElasticBody::influence_shape`], and
    /// [`ElasticBody::apply_influence_adding`] adds a partner's multiple of A₀ inside this
    /// body's own product. A partner of that shape, paired point for point, then costs no
    /// product of its own (a roller with free ends on its raceway's grid). The default is the
    /// whole operator's [`ElasticBody::influence_shape`] (R = 0).
    fn base_shape(&self) -> Option<(InfluenceShape, f64)> {
        self.influence_shape()
    }

    /// displacement = A·force + `added`·A₀·force, A₀ the operator of
    /// [`ElasticBody::base_shape`] at unit scale: this body's product and a partner's of that
    /// shape and scale `added`, in one. The default, for a body whose operator is scale·A₀
    /// (R = 0), scales its product by 1 + added/scale; a body with R ≠ 0 that names a base
    /// shape implements it.
    fn apply_influence_adding(&self, force: &[f64], added: f64, displacement: &mut [f64]) {
        self.apply_influence(force, displacement);
        if let Some((_, scale)) = self.base_shape().filter(|(_, s)| *s > 0.0) {
            let factor = 1.0 + added / scale;
            displacement.iter_mut().for_each(|u| *u *= factor);
        }
    }

    /// A body over a subset of this body's points that contains every point marked in `keep`
    /// and whose influence product is cheaper (a grid's bounding box), with the indices of its
    /// points among this body's; `None` (the default) when the body offers none. Iterative
    /// solvers use it to work where contact can occur, and check the answer on the whole body.
    fn restrict(&self, keep: &[bool]) -> Option<(Box<dyn ElasticBody>, Vec<usize>)> {
        let _ = keep;
        None
    }

    /// The same body discretised coarser, about half as finely each way (a grid of cells twice
    /// as large, strips merged in pairs), with the coarse point of each of this body's points
    /// (`parent[i]`, the points of a coarse point being the ones it covers); `None` (the
    /// default) when the body offers none. An iterative solver starts from the coarse body's
    /// solution (nested iteration): where contact is, and its pressure, are then nearly found.
    fn coarsen(&self) -> Option<(Box<dyn ElasticBody>, Vec<usize>)> {
        None
    }

    /// Normal displacement into the body at the interface points under the given loads alone
    /// (no contact force): f^α of eq. (2.5).
    fn load_displacement(&self) -> Result<Vec<f64>>;

    /// The rigid-body modes the supports leave free (empty for a supported body).
    fn rigid_modes(&self) -> &[RigidMode];

    /// The field the point pressures sample, when the points outnumber what the body's
    /// displacements can tell apart: p = B p̄ with p̄ at the rows' nodes. A finite-element body
    /// checks three Gauss points per quadratic face against two displacement unknowns per face
    /// (plus one), so it returns its face nodes and shape functions; pressures that differ by a
    /// part outside the span of B at equal nodal forces Bᵀ W p then move nothing. `None` (the
    /// default) when every point pressure moves the body.
    fn pressure_basis(&self) -> Option<&GapShape> {
        None
    }

    /// The size of the body's own elements under each interface point \[mm\], when the points
    /// do not count them (a solid, its points a grid's cells or its faces' Gauss points: the
    /// largest face each point reads): a contact many cells wide may still span only one or
    /// two of its elements, too few for its deformation there. `None` (the default) when the
    /// interface points are the body's own discretisation (a grid, rings, a plane mesh's
    /// nodes) or it has no mesh.
    fn element_sizes(&self) -> Option<&[f64]> {
        None
    }

    /// The stresses below the surface under the contact pressure `pressure` \[MPa\] at the
    /// interface points (and the body's given loads, if it has any): the peaks of each
    /// criterion over the requested depths, and the requested sections. `None` (the default)
    /// when the body does not compute stresses below its surface: a rigid body, or a user
    /// type that does not say.
    fn subsurface(
        &self,
        pressure: &[f64],
        request: &SubsurfaceRequest,
    ) -> Result<Option<Subsurface>> {
        let _ = (pressure, request);
        Ok(None)
    }

    /// The body's fields over its own mesh under the contact pressure `pressure` \[MPa\] at
    /// the interface points (and the body's given loads) with rigid-mode amplitudes `rigid`
    /// (one per [`ElasticBody::rigid_modes`]): its nodes and cells, and the displacement and
    /// stress at every node, for a viewer. `None` (the default) when the body has no mesh of
    /// its own: a half-space, a rigid body, or a user type that does not say. A body computes
    /// them only when asked: they are as large as its mesh.
    fn fields(&self, pressure: &[f64], rigid: &[f64]) -> Result<Option<BodyFields>> {
        let _ = (pressure, rigid);
        Ok(None)
    }
}
