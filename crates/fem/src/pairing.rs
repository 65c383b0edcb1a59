//! Contact between two finite-element bodies whose contact faces are meshed independently
//! (non-matching nodes, curved quadratic faces): the segment-to-segment pairing of their faces
//! along the first body's normal n¹ (eq. 2.1).
//!
//! The paper measures the gap and both bodies' displacements along n¹, the outward normal of
//! the first body (eq. 2.1: d = u²_N − u¹_N + h, u^α_N = u^α·n¹). A [`ContactPairing`] places
//! the interface points on the first body's faces and finds, for each, the point of the second
//! body that its normal line meets; the second body's displacement is interpolated there, and
//! h = (x² − x¹)·n¹ is the initial gap between the two meshes.
//!
//! The first body's face chain is cut where the second body's face nodes project onto it, a
//! common refinement of the two chains as in mortar and segment-to-segment methods (Puso &
//! Laursen 2004, *A mortar segment-to-segment contact method for large deformation solid
//! mechanics*, CMAME 193; Zavarise & De Lorenzis 2009, *A modified node-to-segment algorithm
//! passing the contact patch test*, IJNME 79), and each sub-segment is sampled at the three
//! Gauss points of its own parameter. Every sub-segment then lies inside one face of each body,
//! so that on straight faces the nodal forces ∫ N p dS of a pressure quadratic along the first
//! body's faces are integrated exactly on both sides: two blocks stacked on non-matching meshes
//! pass the patch test (a uniform pressure is transmitted uniformly, to round-off).
//!
//! The sub-segments' points are where the pairing integrates, not where contact is checked:
//! they outnumber what the two faces' displacements can close (the sum of two traces,
//! quadratic on the faces of each body, spans fewer values than there are points), so contact
//! checked at each of them is over-constrained. The condensed compliance at the points is then
//! only semi-definite, of the rank of the first body's face nodes, and the exact contact
//! problem degenerates: its gap is open at points inside the contact and its pressure jumps
//! from point to point, which an exact solver (Kalker's active set, an interior point) finds
//! or cycles on; only a penalty's regularisation hides it. Contact is therefore checked at the
//! first body's face nodes, mortar fashion (Puso & Laursen 2004; Wohlmuth 2000, *A mortar
//! finite element method using dual spaces for the Lagrange multiplier*, SINUM 38): the
//! pressure is the C⁰ field p = Σₖ N¹ₖ pₖ of the first body's faces' quadratic shape functions
//! N¹ₖ (the pressure basis of eq. 2.9 and the gap shape of §3), node k carries the force
//! w̃ₖpₖ with w̃ₖ = ∫ N¹ₖ dS, and its gap is the weighted gap d̃ₖ = ∫ N¹ₖ d dS / w̃ₖ, both
//! integrated at the sub-segments' points. With T = W̃⁻¹ Bᵀ W the map from the points'
//! values to the nodes' (B the shape functions at the points, W the points' measures), each
//! body's compliance at the nodes is T A Tᵀ: symmetric, and positive definite once its rigid
//! modes are held, so the contact problem at the nodes has one solution, which the penalty
//! method approaches and the exact solvers reach.
//!
//! The force at each node acts on the two bodies along n¹ and −n¹ through the same
//! distribution N¹ₖ/w̃ₖ, so momentum is conserved; a uniform pressure gives every node its
//! consistent force ∫ N¹ₖ p dS on both sides (the patch test). The gap shape of the
//! optimisation (§3, [`FeBody::gap_shape`]) is the first body's field h = Σⱼ N¹ⱼ hⱼ on its face
//! nodes that check contact, weighted onto them (T B): its design values are the field's
//! nodal values, as on a body's own faces.

use std::collections::{HashMap, HashSet};

use contopt_core::{check, memory, Error, GapShape, Interface, Result, GEOMETRY_TOLERANCE};
use faer::Mat;

use crate::element::GAUSS3;
use crate::samples::{gap_basis, nodes_of, FaceSample, Mortar};
use crate::{Analysis, Face, FeBody, FeModel};

/// Sub-segments shorter than this part of their face's parameter range [−1, 1] merge with a
/// neighbour: a node of the second body that projects this close to another cut or to the
/// face's end (the end of a curved chain, whose quadratic edges tilt the normal a little) would
/// leave a sliver whose points weigh nothing. Merging it leaves a kink of the second body's
/// interpolation (continuous, its slope jumps) within ε of the sub-segment's end, which the
/// Gauss points extrapolate over: an error of O(ε²) in ∫ N p dS, 10⁻⁸ of the face.
const SLIVER: f64 = 1e-4;

/// A face parameter within this of [−1, 1] counts as on the face (round-off of a root).
const ON_FACE: f64 = GEOMETRY_TOLERANCE;

/// Sign changes of the normal-projection function are looked for on this many equal parts of a
/// face's parameter range (the function is cubic: at most three roots).
const PROJECTION_BRACKETS: usize = 8;

/// Safeguarded Newton steps allowed for one root (bisection alone would need about 50).
const ROOT_STEPS: usize = 100;

/// A face node of the first body checks contact when its weight w̃ₖ = ∫ N¹ₖ dS over the paired
/// part of its faces is at least this share of ∫ |N¹ₖ| dS there (2/3 on a whole quadratic edge
/// for a corner node, 1 for a middle one). A corner node whose faces are paired only near
/// their far end, where N¹ₖ < 0, would have a weight near zero or negative, and its gap
/// d̃ₖ = ∫ N¹ₖ d dS / w̃ₖ would divide by it: its shape function joins its face's middle
/// node's ([`ties`]).
const NODE_SHARE: f64 = 0.1;

/// How a [`ContactPairing`] searches.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PairingSettings {
    /// The farthest a partner may lie from a point of the first body along its normal, on
    /// either side \[mm\]: larger initial gaps or interferences are not paired. `None`: half
    /// the smaller of the two face chains' extents (the diagonals of their bounding boxes),
    /// which keeps a full ring's far side out of reach.
    pub search_distance: Option<f64>,
}

/// The pairing of two finite-element bodies' contact faces along the first body's normal
/// n¹ (eq. 2.1), segment to segment (see the [module](self)).
///
/// The first body lies below the contact (its outward normal is n¹); the second body's faces
/// face it. Build it from the two models and their contact faces (each a connected chain of
/// boundary faces, in any order), then the two bodies with [`ContactPairing::bodies`] and the
/// problem with `contopt_contact::InterfaceProblem::new(&first, &second,
/// pairing.initial_gap())`, which pairs their interfaces one to one: both are the first body's
/// face nodes that check contact ([`ContactPairing::nodes`]). A gap of the caller's own, given
/// at the pairing's points ([`ContactPairing::first_samples`]), is weighted onto the nodes by
/// [`ContactPairing::project`].
///
/// A point of the first body whose normal line meets none of the second body's faces within
/// the search distance cannot touch it: it is left out ([`ContactPairing::left_out`]). Only
/// faces that face the point count (their outward normal against n¹): a line that leaves
/// through the second body's far side is no contact.
///
/// ```
/// use contopt_fem::{
///     Analysis, Component, ContactPairing, ElementKind, FeModel, Material, Mesh,
///     PairingSettings, Spacing,
/// };
///
/// // A block 10 mm wide on 3 elements under one 10 mm wide on 7, touching at y = 0.
/// let block = |n: usize, y: (f64, f64)| -> contopt_core::Result<FeModel> {
///     let x = Spacing::uniform(0.0, 10.0, n)?;
///     let mesh = Mesh::rectangle(ElementKind::Q8, &x, &Spacing::uniform(y.0, y.1, 2)?)?;
///     let analysis = Analysis::PlaneStrain { thickness: 1.0 };
///     FeModel::new(mesh, Material::new(2e5, 0.3)?, analysis)
/// };
/// let mut lower = block(3, (-5.0, 0.0))?;
/// let bottom = lower.mesh().nodes_on_y(-5.0, 0.0, 10.0);
/// lower.fix(&bottom, Component::X)?.fix(&bottom, Component::Y)?;
/// let mut upper = block(7, (0.0, 4.0))?;
/// let top = upper.mesh().nodes_on_y(4.0, 0.0, 10.0);
/// upper.prescribe(&top, Component::Y, -0.01)?.fix(&top, Component::X)?;
/// let below = lower.mesh().faces_on_y(0.0, 0.0, 10.0);
/// let above = upper.mesh().faces_on_y(0.0, 0.0, 10.0);
/// let pairing = ContactPairing::new((&lower, &below), (&upper, &above), &PairingSettings::default())?;
/// // The lower faces are cut where the upper nodes at 10k/7 project: 9 sub-segments of 3
/// // points each; contact is checked at the lower faces' 7 nodes.
/// assert_eq!((pairing.segments(), pairing.first_samples().len()), (9, 27));
/// assert_eq!((pairing.len(), pairing.left_out()), (7, 0));
/// let (first, second) = pairing.bodies(("lower", lower), ("upper", upper))?;
/// // contopt_contact::InterfaceProblem::new(&first, &second, pairing.initial_gap())
/// # Ok::<(), contopt_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct ContactPairing {
    first: Vec<FaceSample>,
    second: Vec<FaceSample>,
    /// Where each partner lies on the second body's face (x²).
    partners: Vec<[f64; 2]>,
    /// (x² − x¹)·n¹ at each point.
    measured_gap: Vec<f64>,
    /// The first body's face nodes that check contact, and T from the points to them.
    nodes: Nodes,
    mortar: Mortar,
    /// The first body's field weighted onto the nodes, T B: the bodies' gap shape.
    shape: GapShape,
    initial_gap: Vec<f64>,
    segments: usize,
    left_out: usize,
    search_distance: f64,
}

impl ContactPairing {
    /// Pairs the contact faces `first.1` of the model `first.0` (the body below, whose normal
    /// is n¹) with the faces `second.1` of `second.0`.
    ///
    /// Errors name what is wrong: a face chain that is empty, not on the boundary of its mesh
    /// or not connected (the face where it breaks), a face whose geometry is degenerate or
    /// beyond f64, a search distance that is not positive and finite, and two chains with no
    /// point paired at all (no overlap along n¹).
    pub fn new(
        first: (&FeModel, &[Face]),
        second: (&FeModel, &[Face]),
        settings: &PairingSettings,
    ) -> Result<Self> {
        let (paired, search_distance) = pair(first, second, settings)?;
        let (nodes, shares) = Nodes::new(first.0, &paired.first)?;
        let mortar = mortar(&nodes, &shares, paired.first.len())?;
        let shape = shares.shape;
        Ok(Self {
            initial_gap: mortar.apply(&paired.measured_gap),
            first: paired.first,
            second: paired.second,
            partners: paired.partners,
            measured_gap: paired.measured_gap,
            nodes,
            mortar,
            shape,
            segments: paired.segments,
            left_out: paired.left_out,
            search_distance,
        })
    }

    /// The points [`ContactPairing::new`] would pair and the nodes that would check contact,
    /// with its errors, without the map between them (points × nodes): what a caller checks
    /// before anything is built.
    pub fn survey(
        first: (&FeModel, &[Face]),
        second: (&FeModel, &[Face]),
        settings: &PairingSettings,
    ) -> Result<PairingSurvey> {
        let (paired, search_distance) = pair(first, second, settings)?;
        let (nodes, _) = Nodes::new(first.0, &paired.first)?;
        Ok(PairingSurvey {
            nodes: nodes.points,
            node_faces: nodes.faces,
            first: paired.first,
            segments: paired.segments,
            left_out: paired.left_out,
            search_distance,
        })
    }
}

/// The points and nodes of a [`ContactPairing`] before it is built ([`ContactPairing::survey`]).
#[derive(Clone, Debug, PartialEq)]
pub struct PairingSurvey {
    /// The first body's face nodes that check contact \[mm\]: the interface, in its order.
    pub nodes: Vec<[f64; 2]>,
    /// The first body's faces that hold each node (one, or two where faces meet).
    pub node_faces: Vec<Vec<Face>>,
    /// The points on the first body's faces where the pairing integrates, in its order.
    pub first: Vec<FaceSample>,
    /// Sub-segments of the first body's faces that hold paired points.
    pub segments: usize,
    /// Points of the first body's faces left out (no partner within the search distance).
    pub left_out: usize,
    /// The search distance used \[mm\].
    pub search_distance: f64,
}

/// The pairing's points and the search distance: the first body's faces cut where the second
/// body's face nodes project and sampled, each point with its partner. Errors: see
/// [`ContactPairing::new`].
fn pair(
    first: (&FeModel, &[Face]),
    second: (&FeModel, &[Face]),
    settings: &PairingSettings,
) -> Result<(Paired, f64)> {
    let chains = [
        Chain::new("first", first.0, first.1)?,
        Chain::new("second", second.0, second.1)?,
    ];
    let search_distance = settings
        .search_distance
        .unwrap_or_else(|| 0.5 * chains[0].extent().min(chains[1].extent()));
    check::positive("pairing.search_distance", search_distance)?;
    let mut paired = Paired::default();
    let corners = chains[1].corners();
    for curve in &chains[0].curves {
        for (a, b) in curve.segments(&corners, search_distance) {
            paired.sample_segment(&chains, curve, (a, b), search_distance)?;
        }
    }
    if paired.first.is_empty() {
        return Err(Error::invalid(
            "pairing",
            format!(
                "{} faces of the first body, {} of the second",
                first.1.len(),
                second.1.len()
            ),
            format!(
                "no point of the first body's faces meets the second body's faces along \
                 its normal within the search distance {search_distance} mm: the faces do \
                 not overlap, or they face away from each other"
            ),
        ));
    }
    Ok((paired, search_distance))
}

/// The points paired so far.
#[derive(Default)]
struct Paired {
    first: Vec<FaceSample>,
    second: Vec<FaceSample>,
    partners: Vec<[f64; 2]>,
    measured_gap: Vec<f64>,
    segments: usize,
    left_out: usize,
}

impl Paired {
    /// Samples the sub-segment [a, b] of the first body's face `curve` at the Gauss points of
    /// its own parameter and pairs each with its partner on the second body, if any.
    fn sample_segment(
        &mut self,
        chains: &[Chain; 2],
        curve: &Curve,
        (a, b): (f64, f64),
        reach: f64,
    ) -> Result<()> {
        let model = chains[0].model;
        let mut paired = false;
        for &(xi, w) in &GAUSS3 {
            let s = 0.5 * (a + b) + 0.5 * (b - a) * xi;
            let fp = model.face_point(curve.face, s);
            let weight = 0.5 * (b - a) * w * fp.jacobian * model.analysis.measure(fp.x[0]);
            if !(weight > 0.0 && weight.is_finite()) {
                return Err(Error::invalid(
                    "pairing.first.faces",
                    format!("{:?}", curve.face),
                    format!("has the weight {weight:e} at s = {s}: degenerate or beyond f64"),
                ));
            }
            let Some(hit) = chains[1].hit(fp.x, fp.normal, reach) else {
                self.left_out += 1;
                continue;
            };
            check::derived(
                "pairing.second.faces",
                format!("{:?}", hit.face),
                "the distance between the meshes",
                hit.t,
            )?;
            let sample = FaceSample {
                face: curve.face,
                s,
                point: fp.x,
                weight,
                normal: fp.normal,
            };
            self.first.push(sample);
            self.second.push(FaceSample {
                face: hit.face,
                s: hit.s,
                normal: fp.normal.map(|c| -c),
                ..sample
            });
            self.partners.push(hit.x);
            self.measured_gap.push(hit.t);
            paired = true;
        }
        self.segments += usize::from(paired);
        Ok(())
    }
}

impl ContactPairing {
    /// The initial gap h̃ₖ at each node of the interface \[mm\] (eq. 2.1), negative for an
    /// interference: the [measured](ContactPairing::measured_gap) distance between the meshes
    /// weighted onto the nodes, ∫ N¹ₖ h dS / w̃ₖ ([`ContactPairing::project`]).
    pub fn initial_gap(&self) -> &[f64] {
        &self.initial_gap
    }

    /// The distance between the meshes along the first body's normal at each paired point,
    /// h = (x² − x¹)·n¹ \[mm\]. Where the two chains approximate one curve by different
    /// quadratic edges, it holds a ripple that no displacement of the bodies' faces follows.
    pub fn measured_gap(&self) -> &[f64] {
        &self.measured_gap
    }

    /// Values at the pairing's points ([`ContactPairing::first_samples`]; a gap of the
    /// caller's own) weighted onto the interface's nodes, T v: ∫ N¹ₖ v dS / w̃ₖ at node k.
    pub fn project(&self, values: &[f64]) -> Result<Vec<f64>> {
        check::gap(values, self.first.len())?;
        Ok(self.mortar.apply(values))
    }

    /// The number of interface points: the first body's face nodes that check contact.
    pub fn len(&self) -> usize {
        self.nodes.points.len()
    }

    /// Never true: a pairing has at least one node.
    pub fn is_empty(&self) -> bool {
        self.nodes.points.is_empty()
    }

    /// The interface's nodes on the first body's faces (x, y) \[mm\] ((r, z) in axisymmetry),
    /// in the interface's order.
    pub fn nodes(&self) -> &[[f64; 2]] {
        &self.nodes.points
    }

    /// The interface's weights w̃ₖ = ∫ N¹ₖ dS over the paired faces \[mm²\].
    pub fn node_weights(&self) -> &[f64] {
        &self.nodes.weights
    }

    /// The number of points of the first body's faces left out: their normal line meets none
    /// of the second body's faces within the search distance, so they cannot touch it.
    pub fn left_out(&self) -> usize {
        self.left_out
    }

    /// The number of sub-segments of the first body's faces that hold paired points: its faces
    /// cut where the second body's face nodes project onto them.
    pub fn segments(&self) -> usize {
        self.segments
    }

    /// The search distance used \[mm\].
    pub fn search_distance(&self) -> f64 {
        self.search_distance
    }

    /// The points on the first body's faces where the pairing integrates.
    pub fn first_samples(&self) -> &[FaceSample] {
        &self.first
    }

    /// Their partners on the second body's faces: the first body's points, weights and
    /// reversed normals, with the faces and parameters where the second body is met.
    pub fn second_samples(&self) -> &[FaceSample] {
        &self.second
    }

    /// Where each partner lies on the second body's face, x² \[mm\].
    pub fn partner_points(&self) -> &[[f64; 2]] {
        &self.partners
    }

    /// The two bodies, `first` and `second` each a name and the model that was paired (moved
    /// into its body), sampled at the paired points ([`FeBody::sampled`]) and condensed onto
    /// the interface's nodes (T A Tᵀ). A model whose faces do not lie where the paired one's
    /// did is refused.
    pub fn bodies(
        &self,
        first: (impl Into<String>, FeModel),
        second: (impl Into<String>, FeModel),
    ) -> Result<(FeBody, FeBody)> {
        let first_points: Vec<[f64; 2]> = self.first.iter().map(|s| s.point).collect();
        check_model("first", &first.1, &self.first, &first_points)?;
        check_model("second", &second.1, &self.second, &self.partners)?;
        let geometry = first.1.analysis.geometry();
        let nodes = &self.nodes;
        let interface = |sign: f64| {
            let at = |x: [f64; 2]| [x[0], x[1], 0.0];
            let normals = nodes.normals.iter().map(|n| at(n.map(|c| sign * c)));
            Interface::new(
                geometry,
                nodes.points.iter().copied().map(at).collect(),
                nodes.weights.clone(),
                normals.collect(),
            )
        };
        let (m, shape) = (&self.mortar, &self.shape);
        Ok((
            FeBody::sampled(first.0, first.1, &self.first)?.mortar(m, interface(1.0)?, shape),
            FeBody::sampled(second.0, second.1, &self.second)?.mortar(m, interface(-1.0)?, shape),
        ))
    }
}

/// `model` places each sample's face point where the paired model did (`at`), within
/// [`GEOMETRY_TOLERANCE`] of the points' extent.
fn check_model(
    which: &str,
    model: &FeModel,
    samples: &[FaceSample],
    at: &[[f64; 2]],
) -> Result<()> {
    let boundary: HashSet<Face> = model.mesh.boundary_faces().into_iter().collect();
    let size = at
        .iter()
        .flatten()
        .fold(0.0f64, |m, c| m.max(c.abs()))
        .max(f64::MIN_POSITIVE);
    for (sample, x) in samples.iter().zip(at) {
        let moved = || {
            let y = model.face_point(sample.face, sample.s).x;
            (y[0] - x[0]).hypot(y[1] - x[1]) > GEOMETRY_TOLERANCE * size
        };
        if !boundary.contains(&sample.face) || moved() {
            return Err(Error::invalid(
                format!("pairing.bodies.{which}"),
                format!("face {:?}", sample.face),
                "is not where the paired model's was: give each body the model it was paired with",
            ));
        }
    }
    Ok(())
}

/// A face's quadratic edge in monomial form, x(s) = m + d·s + c·s² (the Lagrange interpolation
/// of its start, middle and end nodes, [`FeModel::face_point`]).
#[derive(Clone, Copy, Debug)]
struct Curve {
    face: Face,
    m: [f64; 2],
    d: [f64; 2],
    c: [f64; 2],
}

/// Where a line along a normal meets a face of the second body.
#[derive(Clone, Copy, Debug)]
struct Hit {
    face: Face,
    s: f64,
    /// The point met, x².
    x: [f64; 2],
    /// The signed distance (x² − x)·n along the line.
    t: f64,
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

impl Curve {
    fn new(model: &FeModel, face: Face) -> Self {
        let [a, m, b] = model.mesh.face_nodes(face).map(|k| model.mesh.nodes()[k]);
        Self {
            face,
            m,
            d: [0.5 * (b[0] - a[0]), 0.5 * (b[1] - a[1])],
            c: [0.5 * (a[0] + b[0]) - m[0], 0.5 * (a[1] + b[1]) - m[1]],
        }
    }

    fn at(&self, s: f64) -> [f64; 2] {
        [0, 1].map(|k| self.m[k] + s * (self.d[k] + s * self.c[k]))
    }

    fn tangent(&self, s: f64) -> [f64; 2] {
        [0, 1].map(|k| self.d[k] + 2.0 * s * self.c[k])
    }

    /// The corner nodes (start and end).
    fn ends(&self) -> [[f64; 2]; 2] {
        [self.at(-1.0), self.at(1.0)]
    }

    /// A box that holds the edge (its nodes, and the bulge |c| of the parabola) grown by
    /// `margin` on every side.
    fn holds(&self, x: [f64; 2], margin: f64) -> bool {
        let [a, b] = self.ends();
        (0..2).all(|k| {
            let bulge = self.c[k].abs() + margin;
            x[k] >= a[k].min(b[k]).min(self.m[k]) - bulge
                && x[k] <= a[k].max(b[k]).max(self.m[k]) + bulge
        })
    }

    /// The parameters, at least [`SLIVER`] inside (−1, 1), of the points whose normal line passes
    /// through `y` within `reach` of it: the roots of g(s) = (y − x(s))·x'(s), a cubic,
    /// bracketed on [`PROJECTION_BRACKETS`] parts of the range and polished by safeguarded
    /// Newton steps.
    fn projections(&self, y: [f64; 2], reach: f64) -> Vec<f64> {
        let g = |s: f64| dot(sub(y, self.at(s)), self.tangent(s));
        let dg = |s: f64| {
            let t = self.tangent(s);
            -dot(t, t) + 2.0 * dot(sub(y, self.at(s)), self.c)
        };
        let mut roots = vec![];
        let step = 2.0 / PROJECTION_BRACKETS as f64;
        for k in 0..PROJECTION_BRACKETS {
            let (a, b) = (-1.0 + k as f64 * step, -1.0 + (k + 1) as f64 * step);
            if let Some(s) = root(&g, &dg, a, b) {
                let x = self.at(s);
                if s.abs() < 1.0 - SLIVER && sub(y, x)[0].hypot(sub(y, x)[1]) <= reach {
                    roots.push(s);
                }
            }
        }
        roots
    }

    /// Where the line x + t·n meets the edge: the roots in [−1, 1] of (x(s) − x)·τ = 0 with τ
    /// ⊥ n, a quadratic in s solved in closed form (the stable formula on coefficients scaled
    /// to one, so that no product overflows).
    fn crossings(&self, x: [f64; 2], n: [f64; 2]) -> Vec<f64> {
        let tau = [-n[1], n[0]];
        let coef = [dot(sub(self.m, x), tau), dot(self.d, tau), dot(self.c, tau)];
        let scale = coef.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if !(scale > 0.0 && scale.is_finite()) {
            return vec![];
        }
        let [a, b, c] = coef.map(|v| v / scale);
        let candidates = if c == 0.0 {
            vec![-a / b]
        } else {
            let disc = b * b - 4.0 * a * c;
            if disc < 0.0 {
                return vec![];
            }
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            vec![q / c, a / q]
        };
        candidates
            .into_iter()
            .filter(|s| s.is_finite() && s.abs() <= 1.0 + ON_FACE)
            .map(|s| s.clamp(-1.0, 1.0))
            .collect()
    }
}

/// A root of `g` in [a, b] when g changes sign there: Newton steps kept inside the bracket,
/// bisection when a step would leave it.
fn root(g: &impl Fn(f64) -> f64, dg: &impl Fn(f64) -> f64, a: f64, b: f64) -> Option<f64> {
    let (ga, gb) = (g(a), g(b));
    if !(ga.is_finite() && gb.is_finite()) || ga * gb > 0.0 {
        return None;
    }
    if ga == 0.0 {
        return Some(a);
    }
    // The bracket's ends, g(lo) ≤ 0 ≤ g(hi) (lo may lie above hi).
    let (mut lo, mut hi) = if ga < 0.0 { (a, b) } else { (b, a) };
    let mut s = 0.5 * (a + b);
    for _ in 0..ROOT_STEPS {
        let (v, dv) = (g(s), dg(s));
        if v == 0.0 {
            return Some(s);
        }
        if v < 0.0 {
            lo = s;
        } else {
            hi = s;
        }
        let newton = s - v / dv;
        let next = if newton.is_finite() && (newton - lo) * (newton - hi) < 0.0 {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - s).abs() <= f64::EPSILON * s.abs().max(1.0) {
            return Some(next);
        }
        s = next;
    }
    Some(s)
}

/// A body's contact faces, checked to be boundary faces forming one connected chain.
struct Chain<'m> {
    model: &'m FeModel,
    curves: Vec<Curve>,
}

impl<'m> Chain<'m> {
    fn new(which: &str, model: &'m FeModel, faces: &[Face]) -> Result<Self> {
        let field = format!("pairing.{which}.faces");
        if faces.is_empty() {
            return Err(Error::invalid(field, "[]", "select at least one face"));
        }
        let boundary: HashSet<Face> = model.mesh.boundary_faces().into_iter().collect();
        if let Some(f) = faces.iter().find(|f| !boundary.contains(f)) {
            return Err(Error::invalid(
                field,
                format!("{f:?}"),
                "is not a boundary face of the mesh",
            ));
        }
        check_connected(&field, model, faces)?;
        for &f in faces {
            for s in [-1.0, 0.0, 1.0] {
                let fp = model.face_point(f, s);
                let finite = fp.normal.iter().chain(&fp.x).all(|v| v.is_finite());
                if !finite || fp.jacobian.is_nan() || fp.jacobian <= 0.0 {
                    return Err(Error::invalid(
                        field,
                        format!("{f:?}"),
                        format!(
                            "has no finite normal at s = {s} (tangent length {:e}): the face is \
                             degenerate or its coordinates are beyond f64",
                            fp.jacobian
                        ),
                    ));
                }
            }
        }
        let curves = faces.iter().map(|&f| Curve::new(model, f)).collect();
        Ok(Self { model, curves })
    }

    /// The diagonal of the bounding box of the faces' nodes \[mm\].
    fn extent(&self) -> f64 {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for curve in &self.curves {
            for x in curve.ends().into_iter().chain([curve.m]) {
                for k in 0..2 {
                    lo[k] = lo[k].min(x[k]);
                    hi[k] = hi[k].max(x[k]);
                }
            }
        }
        (hi[0] - lo[0]).hypot(hi[1] - lo[1])
    }

    /// The corner nodes of the faces (those shared by two faces twice).
    fn corners(&self) -> Vec<[f64; 2]> {
        self.curves.iter().flat_map(Curve::ends).collect()
    }

    /// The nearest point (least |t|) where the line `x` + t·`n` meets a face that faces it
    /// (outward normal against `n`) within `reach`.
    fn hit(&self, x: [f64; 2], n: [f64; 2], reach: f64) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        for curve in self.curves.iter().filter(|c| c.holds(x, reach)) {
            for s in curve.crossings(x, n) {
                let fp = self.model.face_point(curve.face, s);
                let t = dot(sub(fp.x, x), n);
                if dot(fp.normal, n) >= 0.0 || t.abs() > reach {
                    continue;
                }
                if best.is_none_or(|b| t.abs() < b.t.abs()) {
                    best = Some(Hit {
                        face: curve.face,
                        s,
                        x: fp.x,
                        t,
                    });
                }
            }
        }
        best
    }
}

impl Curve {
    /// The sub-segments [a, b] of the parameter range: cut where the normal lines of the
    /// edge pass through one of `corners` within `reach`, cuts closer than [`SLIVER`]
    /// merged.
    fn segments(&self, corners: &[[f64; 2]], reach: f64) -> Vec<(f64, f64)> {
        let mut cuts: Vec<f64> = corners
            .iter()
            .filter(|&&y| self.holds(y, reach))
            .flat_map(|&y| self.projections(y, reach))
            .collect();
        cuts.sort_by(f64::total_cmp);
        // `dedup_by` passes the later cut first.
        cuts.dedup_by(|later, earlier| *later - *earlier < SLIVER);
        cuts.insert(0, -1.0);
        cuts.push(1.0);
        cuts.windows(2).map(|w| (w[0], w[1])).collect()
    }
}

/// The faces form one chain: each face's end node is the start node of at most one other and
/// the faces, walked from the one whose start no face ends at (any, for a closed loop), are
/// all reached. The error names the face where the chain breaks.
fn check_connected(field: &str, model: &FeModel, faces: &[Face]) -> Result<()> {
    let ends = |f: Face| {
        let n = model.mesh.face_nodes(f);
        (n[0], n[2])
    };
    let mut starting: HashMap<usize, Face> = HashMap::new();
    for &f in faces {
        if let Some(other) = starting.insert(ends(f).0, f) {
            return Err(Error::invalid(
                field,
                format!("{f:?}"),
                format!("starts at the node where {other:?} starts: list each face once"),
            ));
        }
    }
    let ending: HashSet<usize> = faces.iter().map(|&f| ends(f).1).collect();
    let head = faces
        .iter()
        .copied()
        .find(|&f| !ending.contains(&ends(f).0))
        .unwrap_or(faces[0]);
    let mut reached = HashSet::from([head]);
    let mut at = head;
    while let Some(&next) = starting.get(&ends(at).1) {
        if !reached.insert(next) {
            break;
        }
        at = next;
    }
    if let Some(&f) = faces.iter().find(|f| !reached.contains(f)) {
        let at_node = |k: usize| {
            let x = model.mesh.nodes()[k];
            format!("node {k} ({}, {})", x[0], x[1])
        };
        return Err(Error::invalid(
            field,
            format!("{f:?}"),
            format!(
                "is not connected to the chain of {} faces from {head:?}, which runs from {} to \
                 {}: the contact faces must form one connected chain",
                reached.len(),
                at_node(ends(head).0),
                at_node(ends(at).1),
            ),
        ));
    }
    Ok(())
}

/// The memory the map of a pairing of `points` points onto `nodes` face nodes takes to build
/// \[bytes\] (T, n × m, and a body's A Tᵀ beside it), `None` when the count overflows; each of
/// the two bodies holds its own copy of T.
pub fn mortar_bytes(points: usize, nodes: usize) -> Option<u64> {
    memory::bytes(&[points, nodes], 2 * 8)
}

/// The first body's face nodes that check contact (their weight a [`NODE_SHARE`] of their
/// shape functions' reach over the paired faces), in the order of their mesh numbers.
#[derive(Clone, Debug)]
struct Nodes {
    points: Vec<[f64; 2]>,
    /// w̃ₖ = Σᵢ N¹ₖ(xᵢ) wᵢ \[mm²\].
    weights: Vec<f64>,
    /// The unit normal Σᵢ N¹ₖ(xᵢ) wᵢ n¹ᵢ, normalised: n¹ averaged as the node's force spreads.
    normals: Vec<[f64; 2]>,
    /// The faces that hold each node.
    faces: Vec<Vec<Face>>,
}

impl Nodes {
    /// The nodes of the faces of `samples`, with each node's shares N¹ₖ(xᵢ) wᵢ of the points
    /// (point, share). A node whose weight is short of [`NODE_SHARE`] of its reach passes its
    /// shape function to the middle node of the face that holds most of it: the functions
    /// still sum to one, so a uniform pressure is still a nodal field.
    fn new(model: &FeModel, samples: &[FaceSample]) -> Result<(Self, Shares)> {
        let faces: Vec<Face> = samples.iter().map(|s| s.face).collect();
        let face_nodes = nodes_of(model, &faces);
        let basis = gap_basis(model, samples, &face_nodes)?;
        let m = face_nodes.len();
        let mut shares: Vec<Vec<(usize, f64)>> = vec![vec![]; m];
        // Each node's reach Σ|N¹ₖ wᵢ| on each of its faces.
        let mut reach: Vec<Vec<(Face, f64)>> = vec![vec![]; m];
        for (i, sample) in samples.iter().enumerate() {
            for &(k, b) in basis.row(i) {
                shares[k].push((i, b * sample.weight));
                match reach[k].iter_mut().find(|(f, _)| *f == sample.face) {
                    Some((_, r)) => *r += (b * sample.weight).abs(),
                    None => reach[k].push((sample.face, (b * sample.weight).abs())),
                }
            }
        }
        let ties = ties(model, &face_nodes, &shares, &reach);
        let kept: Vec<bool> = (0..m).map(|k| ties[k] == [(k, 1.0)]).collect();
        // The number of each kept node among the kept ones.
        let mut column = vec![0; m];
        for (count, k) in (0..m).filter(|&k| kept[k]).enumerate() {
            column[k] = count;
        }
        for k in (0..m).filter(|&k| !kept[k]) {
            let moved = std::mem::take(&mut shares[k]);
            for &(target, factor) in &ties[k] {
                shares[target].extend(moved.iter().map(|&(i, w)| (i, factor * w)));
            }
        }
        let mut nodes = Nodes {
            points: vec![],
            weights: vec![],
            normals: vec![],
            faces: vec![],
        };
        let mut held = vec![];
        let mut design = vec![];
        for (k, share) in shares.into_iter().enumerate().filter(|&(k, _)| kept[k]) {
            let weight: f64 = share.iter().map(|s| s.1).sum();
            let n = share.iter().fold([0.0; 2], |n, &(i, w)| {
                [0, 1].map(|c| n[c] + w * samples[i].normal[c])
            });
            let length = n[0].hypot(n[1]);
            nodes.points.push(model.mesh.nodes()[face_nodes[k]]);
            nodes.weights.push(weight);
            nodes.normals.push(n.map(|c| c / length));
            nodes.faces.push(reach[k].iter().map(|r| r.0).collect());
            let tied = |j: usize| ties[j].iter().map(|&(t, f)| (column[t], f));
            design.push(design_row(&share, &basis, tied, weight));
            held.push(share);
        }
        let at = |x: &[f64; 2]| [x[0], x[1], 0.0];
        let shape = GapShape::new(nodes.points.iter().map(at).collect(), design)?;
        Ok((
            nodes,
            Shares {
                points: held,
                shape,
            },
        ))
    }
}

/// How each face node's shape function is carried (face node, factor). In axisymmetry the
/// face at the axis carries the quadratic of zero slope there (symmetry), a + c r²: its middle
/// node's value is 3/4 of the axis node's and 1/4 of the far node's, so that the node on the
/// axis, whose own weight ∫ N¹ₖ 2πr dr is zero on a quadratic edge, checks contact with the
/// weight the middle node gives it. Any other node whose weight is short of [`NODE_SHARE`] of
/// its reach passes its function to the middle node of the face that holds most of it (a flat
/// pressure there). The factors sum to one: the functions still sum to one, so a uniform
/// pressure is still a nodal field.
fn ties(
    model: &FeModel,
    face_nodes: &[usize],
    shares: &[Vec<(usize, f64)>],
    reach: &[Vec<(Face, f64)>],
) -> Vec<Vec<(usize, f64)>> {
    let index = |node: usize| face_nodes.partition_point(|&j| j < node);
    let m = face_nodes.len();
    let mut ties: Vec<Vec<(usize, f64)>> = (0..m).map(|k| vec![(k, 1.0)]).collect();
    let mut axis = vec![false; m];
    if model.analysis == Analysis::Axisymmetric {
        for k in 0..m {
            for &(face, _) in &reach[k] {
                let [a, middle, b] = model.mesh.face_nodes(face).map(index);
                let r = model.mesh.nodes()[face_nodes[k]][0];
                let length = model.face_point(face, 0.0).jacobian;
                if middle != k && r.abs() <= GEOMETRY_TOLERANCE * length {
                    let far = if a == k { b } else { a };
                    ties[middle] = vec![(k, 0.75), (far, 0.25)];
                    axis[k] = true;
                }
            }
        }
    }
    for k in 0..m {
        if axis[k] || ties[k] != [(k, 1.0)] {
            continue;
        }
        let weight: f64 = shares[k].iter().map(|s| s.1).sum();
        let total: f64 = reach[k].iter().map(|r| r.1).sum();
        let face = reach[k]
            .iter()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|r| r.0);
        if let Some(face) = face.filter(|_| !(weight > 0.0 && weight >= NODE_SHARE * total)) {
            let middle = index(model.mesh.face_nodes(face)[1]);
            // The middle node of the face at the axis is itself carried by two others.
            let carried = match ties[middle].as_slice() {
                [(j, _)] if *j == middle => vec![(middle, 1.0)],
                carried => carried.to_vec(),
            };
            ties[k] = carried;
        }
    }
    ties
}

/// The row of T B of a node with `share` of the points and weight `weight`: its weighted gap
/// of the field of the nodes that check contact, the face nodes' functions carried by `tied`.
fn design_row<I: Iterator<Item = (usize, f64)>>(
    share: &[(usize, f64)],
    basis: &GapShape,
    tied: impl Fn(usize) -> I,
    weight: f64,
) -> Vec<(usize, f64)> {
    let mut row: Vec<(usize, f64)> = vec![];
    for &(i, w) in share {
        for &(j, b) in basis.row(i) {
            for (l, factor) in tied(j) {
                let v = factor * w * b / weight;
                match row.iter_mut().find(|(c, _)| *c == l) {
                    Some((_, sum)) => *sum += v,
                    None => row.push((l, v)),
                }
            }
        }
    }
    row
}

/// Each node's shares N¹ₖ(xᵢ) wᵢ of the points (point, share), and the gap shape of the first
/// body's field at the nodes, T B: a gap h = Σⱼ N¹ⱼ hⱼ of the nodes' values hⱼ (a node left
/// out takes its middle node's value), weighted onto each node.
struct Shares {
    points: Vec<Vec<(usize, f64)>>,
    shape: GapShape,
}

/// The mortar map T of `nodes` and their `shares` of the `points` (see [`Mortar`]).
fn mortar(nodes: &Nodes, shares: &Shares, points: usize) -> Result<Mortar> {
    let m = nodes.points.len();
    memory::require(
        format!("the map of {points} paired points onto {m} nodes"),
        mortar_bytes(points, m),
        memory::BODY_LIMIT_BYTES,
        "pair fewer faces",
    )?;
    let mut t = Mat::<f64>::zeros(m, points);
    for (k, share) in shares.points.iter().enumerate() {
        for &(i, w) in share {
            t[(k, i)] += w / nodes.weights[k];
        }
    }
    Ok(Mortar::new(t))
}

#[cfg(test)]
mod tests {
    use contopt_core::ElasticBody;

    use super::*;
    use crate::{Analysis, Component, ElementKind, Material, Mesh, Spacing};

    const ANALYSES: [Analysis; 3] = [
        Analysis::PlaneStress { thickness: 2.0 },
        Analysis::PlaneStrain { thickness: 1.0 },
        Analysis::Axisymmetric,
    ];

    /// A block on `x` × [y0, y1], its bottom held in y and its left edge in x (the axis in
    /// axisymmetry), Q8.
    fn block(x: &Spacing, y: (f64, f64), layers: usize, analysis: Analysis) -> FeModel {
        let ys = Spacing::uniform(y.0, y.1, layers).unwrap();
        let mesh = Mesh::rectangle(ElementKind::Q8, x, &ys).unwrap();
        let mut model = FeModel::new(mesh, Material::new(2e5, 0.3).unwrap(), analysis).unwrap();
        let x0 = x.coords()[0];
        let bottom = model.mesh().nodes_on_y(y.0, x0, f64::INFINITY);
        let left = model.mesh().nodes_on_x(x0, y.0, y.1);
        model.fix(&bottom, Component::Y).unwrap();
        model.fix(&left, Component::X).unwrap();
        model
    }

    /// Two blocks stacked at y = 0 on one spacing: the lower (first) body's top faces, the
    /// upper's bottom faces.
    fn matching(analysis: Analysis) -> ((FeModel, Vec<Face>), (FeModel, Vec<Face>)) {
        let x = Spacing::from_coords(vec![0.0, 3.0, 7.5, 10.0]).unwrap();
        let lower = block(&x, (-6.0, 0.0), 2, analysis);
        let upper = block(&x, (0.0, 5.0), 2, analysis);
        let f1 = lower.mesh().faces_on_y(0.0, 0.0, 10.0);
        let f2 = upper.mesh().faces_on_y(0.0, 0.0, 10.0);
        ((lower, f1), (upper, f2))
    }

    /// The interface is the first body's face nodes (but the middle one of the face at the axis
    /// in axisymmetry, whose pressure is symmetric there),
    /// each weighing w̃ₖ = ∫ N¹ₖ dS (a quadratic edge of length L gives its corners L/6 and its
    /// middle 2L/3, times the thickness; the weights sum to the faces' area), on matching meshes and on the second block's 7 faces against the first's 3. Both
    /// bodies' compliance at the nodes, T A Tᵀ, is symmetric and positive definite (both
    /// blocks are held): its smallest eigenvalue is above 10⁻⁶ of its largest. Checked at the
    /// pairing's 27 points (9 sub-segments) instead, the compliance has the rank of the 7
    /// nodes and 20 eigenvalues at round-off; weights at the nodes taken 1/3 of each face
    /// instead of ∫ N¹ₖ dS would miss the corners' by half.
    #[test]
    fn nodes_weigh_their_shape_functions_and_compliance_is_definite() {
        for analysis in ANALYSES {
            let (m1, f1) = matching(analysis).0;
            // Blocks on [0, 5] held at their tops (y = 5) and left edges.
            let above = |x: &Spacing| {
                let ys = Spacing::uniform(0.0, 5.0, 2).unwrap();
                let mesh = Mesh::rectangle(ElementKind::Q8, x, &ys).unwrap();
                let mut model =
                    FeModel::new(mesh, Material::new(2e5, 0.3).unwrap(), analysis).unwrap();
                let top = model.mesh().nodes_on_y(5.0, 0.0, 10.0);
                let left = model.mesh().nodes_on_x(0.0, 0.0, 5.0);
                model.fix(&top, Component::Y).unwrap();
                model.fix(&left, Component::X).unwrap();
                let faces = model.mesh().faces_on_y(0.0, 0.0, 10.0);
                (model, faces)
            };
            let spacings = [
                Spacing::from_coords(vec![0.0, 3.0, 7.5, 10.0]).unwrap(),
                Spacing::uniform(0.0, 10.0, 7).unwrap(),
            ];
            for (second, f) in spacings.iter().map(above) {
                let pairing =
                    ContactPairing::new((&m1, &f1), (&second, &f), &PairingSettings::default())
                        .unwrap();
                // At the axis the face carries a + c r²: its middle node is no unknown.
                let nodes = if analysis == Analysis::Axisymmetric {
                    6
                } else {
                    7
                };
                assert_eq!((pairing.len(), pairing.left_out()), (nodes, 0));
                assert!(pairing.initial_gap().iter().all(|h| h.abs() < 1e-14));
                let x = [0.0, 1.5, 3.0, 5.25, 7.5, 8.75, 10.0];
                // ∫ N_k dS on the faces [0, 3], [3, 7.5], [7.5, 10] along x.
                let along = [
                    0.5,
                    2.0,
                    0.5 + 0.75,
                    3.0,
                    0.75 + 5.0 / 12.0,
                    5.0 / 3.0,
                    5.0 / 12.0,
                ];
                for (&node, &w) in pairing.nodes().iter().zip(pairing.node_weights()) {
                    let k = x.iter().position(|&v| (v - node[0]).abs() < 1e-14).unwrap();
                    assert!(node[1].abs() < 1e-14);
                    if let Analysis::PlaneStress { thickness } = analysis {
                        assert!((w - thickness * along[k]).abs() < 1e-12, "{k}: {w}");
                    }
                }
                let total: f64 = pairing.node_weights().iter().sum();
                let area = match analysis {
                    Analysis::Axisymmetric => std::f64::consts::PI * 100.0,
                    Analysis::PlaneStress { thickness } | Analysis::PlaneStrain { thickness } => {
                        10.0 * thickness
                    }
                };
                assert!((total / area - 1.0).abs() < 1e-13, "{total} against {area}");
                let (b1, b2) = pairing
                    .bodies(("lower", m1.clone()), ("upper", second))
                    .unwrap();
                for body in [&b1, &b2] {
                    let a = body.influence_matrix();
                    let n = a.nrows();
                    assert_eq!(n, nodes);
                    let scale = (0..n).fold(0.0f64, |m, i| m.max(a[(i, i)]));
                    for i in 0..n {
                        for j in 0..n {
                            assert!((a[(i, j)] - a[(j, i)]).abs() <= 1e-12 * scale);
                        }
                    }
                    let eigen = a.self_adjoint_eigenvalues(faer::Side::Lower).unwrap();
                    let (lo, hi) = eigen
                        .iter()
                        .fold((f64::INFINITY, 0.0f64), |(l, h), &e| (l.min(e), h.max(e)));
                    assert!(
                        lo > 1e-6 * hi,
                        "{}: eigenvalues {lo:e} .. {hi:e}",
                        body.name()
                    );
                }
            }
        }
    }

    fn pair(first: (&FeModel, &[Face]), second: (&FeModel, &[Face]), d: Option<f64>) -> String {
        let settings = PairingSettings { search_distance: d };
        ContactPairing::new(first, second, &settings)
            .unwrap_err()
            .to_string()
    }

    /// Each error names what is wrong: a gap in a chain (the face cut off and where the chain
    /// before it ends), a face inside the mesh, an empty chain, chains that do not overlap or
    /// face away from each other, bodies built from other models than the paired ones, a
    /// search distance that is not positive and finite.
    #[test]
    fn errors_name_what_is_wrong() {
        let analysis = ANALYSES[0];
        let ((m1, f1), (m2, f2)) = matching(analysis);
        let broken = [f1[0], f1[2]];
        let e = pair((&m1, &broken), (&m2, &f2), None);
        assert!(
            e.contains("pairing.first.faces")
                && e.contains(&format!("{:?}", f1[2]))
                && e.contains("not connected")
                && e.contains("(3, 0) to node")
                && e.contains("(0, 0)"),
            "{e}"
        );
        let inner = Face {
            element: 0,
            local: 2,
        };
        let e = pair((&m1, &f1), (&m2, &[inner]), None);
        assert!(
            e.contains("pairing.second.faces") && e.contains("not a boundary face"),
            "{e}"
        );
        let e = pair((&m1, &[]), (&m2, &f2), None);
        assert!(e.contains("pairing.first.faces = []"), "{e}");
        // The upper block moved 20 mm to the side: no line along n¹ meets it.
        let x = Spacing::uniform(20.0, 30.0, 2).unwrap();
        let aside = block(&x, (0.0, 5.0), 1, analysis);
        let far = aside.mesh().faces_on_y(0.0, 20.0, 30.0);
        let e = pair((&m1, &f1), (&aside, &far), Some(5.0));
        assert!(e.contains("do not overlap") && e.contains("5 mm"), "{e}");
        // The upper block's top faces face away from the lower block.
        let top = m2.mesh().faces_on_y(5.0, 0.0, 10.0);
        let e = pair((&m1, &f1), (&m2, &top), None);
        assert!(e.contains("face away"), "{e}");
        // Bodies built from other models than the paired ones.
        let pairing =
            ContactPairing::new((&m1, &f1), (&m2, &f2), &PairingSettings::default()).unwrap();
        let e = pairing
            .bodies(("a", m2.clone()), ("b", m1.clone()))
            .err()
            .unwrap()
            .to_string();
        assert!(
            e.contains("pairing.bodies.first") && e.contains("paired with"),
            "{e}"
        );
        for d in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = pair((&m1, &f1), (&m2, &f2), Some(d));
            assert!(e.contains("pairing.search_distance"), "{e}");
        }
    }

    /// Geometry f64 cannot hold is refused before it reaches a body: a contact face collapsed to
    /// a point (a degenerate quadrilateral, valid inside) has no normal; axisymmetric
    /// coordinates of 10²⁰⁰ mm give weights 2πr·|dx/ds| beyond f64.
    #[test]
    fn non_finite_geometry_is_refused() {
        let analysis = ANALYSES[0];
        let ((m1, f1), _) = matching(analysis);
        // One Q8 whose top face (nodes 2, 6, 3) is collapsed onto one point.
        let nodes = vec![
            [0.0, 5.0],
            [10.0, 5.0],
            [5.0, 10.0],
            [5.0, 10.0],
            [5.0, 5.0],
            [7.5, 7.5],
            [5.0, 10.0],
            [2.5, 7.5],
        ];
        let mesh = Mesh::new(ElementKind::Q8, nodes, vec![(0..8).collect()]).unwrap();
        let wedge = FeModel::new(mesh, Material::new(2e5, 0.3).unwrap(), analysis).unwrap();
        let top = Face {
            element: 0,
            local: 2,
        };
        let e = pair((&wedge, &[top]), (&m1, &f1), None);
        assert!(
            e.contains("Face { element: 0, local: 2 }") && e.contains("degenerate"),
            "{e}"
        );
        let huge = |y: (f64, f64)| {
            let x = Spacing::uniform(0.0, 1e200, 2).unwrap();
            let mesh =
                Mesh::rectangle(ElementKind::Q8, &x, &Spacing::uniform(y.0, y.1, 1).unwrap())
                    .unwrap();
            FeModel::new(
                mesh,
                Material::new(2e5, 0.3).unwrap(),
                Analysis::Axisymmetric,
            )
            .unwrap()
        };
        let (below, above) = (huge((-1e200, 0.0)), huge((0.0, 1e200)));
        let f = below.mesh().faces_on_y(0.0, 0.0, 1e200);
        let g = above.mesh().faces_on_y(0.0, 0.0, 1e200);
        let e = pair((&below, &f), (&above, &g), None);
        assert!(
            e.contains("pairing.first.faces") && e.contains("beyond f64"),
            "{e}"
        );
    }
}
