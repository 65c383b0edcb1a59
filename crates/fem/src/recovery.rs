//! Stresses recovered at the nodes: the integration-point stresses of each element
//! extrapolated to its nodes and averaged where elements meet (Hinton & Campbell 1974,
//! "Local and global smoothing of discontinuous finite element functions using a least squares
//! method"; Zienkiewicz, Taylor & Zhu, *The Finite Element Method*, 7th ed., §15.2), and the
//! stresses of a condensed [`FeBody`] under a contact pressure.
//!
//! Quadrilaterals: the Gauss points of the 3 × 3 rule are the optimal sampling points of
//! quadratic elements: the stress there is accurate to one order more than elsewhere (Barlow
//! 1976). Through them, in each natural direction, passes one quadratic Lagrange polynomial per
//! abscissa (−√0.6, 0, √0.6); their tensor product is a 9-term field that takes the Gauss-point
//! values, and evaluated at a node's natural coordinates it gives the element's value there. A
//! field that is a tensor-product quadratic in (ξ, η) (a uniform or linear stress in a
//! parallelogram element) is recovered exactly.
//!
//! Triangles: the stress of a straight-sided 6-node triangle is linear (B is), so the stresses
//! at its 6 integration points are fitted by the linear field c₁L₁ + c₂L₂ + c₃L₃ of least
//! squares and the fit is evaluated at the corners and mid-sides. A linear stress (uniform
//! stress, pure bending) is recovered exactly; in a curved triangle, or for the hoop stress
//! u/r of axisymmetry, the fit is the linear field nearest the six values.

use contopt_core::{
    check, ElasticBody, Error, Result, Section, SectionAxis, SectionField, StressPeaks,
    StressTensor, Subsurface, SubsurfaceRequest,
};

use crate::element::{lagrange2, ElementKind, GAUSS3, MAX_POINTS};
use crate::{FeBody, FeModel, Solution, Stress};

/// The outer abscissa √0.6 of the 3-point Gauss rule, which the extrapolation maps to ±1.
const GAUSS_ABSCISSA: f64 = GAUSS3[2].0;

/// Largest relative imbalance Σ fᵢ gᵢ + q of a free rigid mode that a pressure may leave
/// (the contact solvers meet equilibrium to far less): a floating body's leftover force would
/// be carried by the unknown held to remove the mode, a point force that no contact exerts.
const EQUILIBRIUM_TOLERANCE: f64 = 1e-6;

/// Two node coordinates closer than this \[mm\] are one grid line of a section.
const SAME_COORDINATE: f64 = 1e-9;

/// The recovery's stress tensor of a Gauss-point [`Stress`], by the convention of
/// [`StressTensor`] for plane and axisymmetric bodies: the model's x (r) to `xx`, its y (z) to
/// `zz`, τ_xy (τ_rz) to `xz`, and the out-of-plane stress (hoop σ_θ, plane strain ν(σ_x + σ_y),
/// plane stress 0) to `yy`.
impl From<Stress> for StressTensor {
    fn from(s: Stress) -> Self {
        StressTensor {
            xx: s.xx,
            yy: s.zz,
            zz: s.yy,
            xy: 0.0,
            xz: s.xy,
            yz: 0.0,
        }
    }
}

/// Extrapolation weights from an element's integration points to its nodes, for each kind:
/// the stress at local node a is Σₖ `weights[a][k]` σₖ over the integration points k, in the
/// order of [`ElementKind::integration_points`] (and of [`FeModel::stresses`]).
struct Extrapolation {
    /// The 9 nodes of a Q9 (a Q8 takes the first 8) from the 3 × 3 Gauss points.
    quadrilateral: Vec<[f64; MAX_POINTS]>,
    /// The 6 nodes of a T6 from its 6 integration points.
    triangle: Vec<[f64; MAX_POINTS]>,
}

impl Extrapolation {
    fn new() -> Self {
        Self {
            quadrilateral: quadrilateral_extrapolation(),
            triangle: triangle_extrapolation(),
        }
    }

    /// The weights of an element of `kind`, one row per local node.
    fn of(&self, kind: ElementKind) -> &[[f64; MAX_POINTS]] {
        match kind {
            ElementKind::Q8 | ElementKind::Q9 => &self.quadrilateral,
            ElementKind::T6 => &self.triangle,
        }
    }
}

/// Extrapolation weights from the 3 × 3 Gauss points to each local node of a Q9:
/// `weights[a][3i + j]` = Lᵢ(ξ_a) Lⱼ(η_a), with Lₖ the quadratic Lagrange polynomial through
/// the Gauss abscissae that is 1 at abscissa k, and Gauss point 3i + j at (ξ, η) = (gᵢ, gⱼ).
fn quadrilateral_extrapolation() -> Vec<[f64; MAX_POINTS]> {
    let kind = ElementKind::Q9;
    (0..kind.n_nodes())
        .map(|a| {
            let [xi, eta] = kind.natural(a);
            let mut w = [0.0; MAX_POINTS];
            for (i, &(gi, _)) in GAUSS3.iter().enumerate() {
                for (j, &(gj, _)) in GAUSS3.iter().enumerate() {
                    w[GAUSS3.len() * i + j] = gauss_lagrange(gi, xi) * gauss_lagrange(gj, eta);
                }
            }
            w
        })
        .collect()
}

/// Extrapolation weights from the 6 integration points of a T6 to its nodes by the linear
/// least-squares fit σ ≈ cᵀλ in the area coordinates λ = (L₁, L₂, L₃): with λₖ those of
/// point k and M = Σₖ λₖλₖᵀ, the fit at node a is λ_aᵀ M⁻¹ Σₖ λₖσₖ. The rule is symmetric
/// under permutations of (L₁, L₂, L₃), so M = d I + o (J − I) (J all ones) with d = Σₖ L₁ₖ²
/// and o = Σₖ L₁ₖL₂ₖ, whose inverse is (I − o J/(d + 2o))/(d − o); as Σλ = 1, the weight
/// λ_aᵀ M⁻¹ λₖ is (λ_a·λₖ − o/(d + 2o))/(d − o).
fn triangle_extrapolation() -> Vec<[f64; MAX_POINTS]> {
    let kind = ElementKind::T6;
    let area = |[xi, eta]: [f64; 2]| [1.0 - xi - eta, xi, eta];
    let points: Vec<[f64; 3]> = kind
        .integration_points()
        .iter()
        .map(|p| area([p.xi, p.eta]))
        .collect();
    let d: f64 = points.iter().map(|l| l[0] * l[0]).sum();
    let o: f64 = points.iter().map(|l| l[0] * l[1]).sum();
    let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    (0..kind.n_nodes())
        .map(|a| {
            let node = area(kind.natural(a));
            let mut w = [0.0; MAX_POINTS];
            for (wk, l) in w.iter_mut().zip(&points) {
                *wk = (dot(&node, l) - o / (d + 2.0 * o)) / (d - o);
            }
            w
        })
        .collect()
}

/// The 1-D quadratic Lagrange polynomial through the Gauss abscissae (−√0.6, 0, √0.6) that is
/// 1 at `abscissa`, at natural coordinate `s`: in t = s/√0.6 the abscissae are −1, 0, 1.
fn gauss_lagrange(abscissa: f64, s: f64) -> f64 {
    lagrange2(abscissa, s / GAUSS_ABSCISSA).0
}

/// Scales every component of `s` by `w`.
fn scaled(s: &StressTensor, w: f64) -> StressTensor {
    StressTensor {
        xx: w * s.xx,
        yy: w * s.yy,
        zz: w * s.zz,
        xy: w * s.xy,
        xz: w * s.xz,
        yz: w * s.yz,
    }
}

/// Adds `s` to `sum` component by component.
fn accumulate(sum: &mut StressTensor, s: &StressTensor) {
    sum.xx += s.xx;
    sum.yy += s.yy;
    sum.zz += s.zz;
    sum.xy += s.xy;
    sum.xz += s.xz;
    sum.yz += s.yz;
}

impl FeModel {
    /// Stresses at every node, recovered from the integration-point stresses
    /// ([`FeModel::stresses`]): extrapolated to each element's nodes (corner and mid-side
    /// nodes; the Q9 centre too), on a quadrilateral with the quadratic Lagrange polynomials
    /// through the Gauss abscissae (±√0.6, 0) in ξ and η, on a triangle by the linear
    /// least-squares fit of its six values (see the module), then averaged over the elements
    /// that share a node, whatever their kinds (Hinton & Campbell 1974). Components follow
    /// [`StressTensor`]'s convention for plane and axisymmetric bodies (see
    /// `From<Stress> for StressTensor`): x (r) → `xx`, y (z) → `zz`, τ_xy (τ_rz) → `xz`,
    /// out-of-plane or hoop → `yy`.
    ///
    /// Where the stress jumps between elements (a material interface, which a model of one
    /// material does not have) or is singular (a punch edge), the average smooths the jump;
    /// elsewhere the nodal values converge with the Gauss-point ones.
    ///
    /// Errors: a solution of the wrong length, a singular Jacobian, or a stress that is not
    /// finite (a non-finite displacement).
    pub fn nodal_stresses(&self, solution: &Solution) -> Result<Vec<StressTensor>> {
        let n_nodes = self.mesh.nodes().len();
        if solution.displacement.len() != 2 * n_nodes {
            return Err(Error::invalid(
                "solution.displacement",
                solution.displacement.len(),
                format!("two per node ({})", 2 * n_nodes),
            ));
        }
        let (sum, count) = self.extrapolated_sums(solution)?;
        sum.iter()
            .zip(&count)
            .enumerate()
            .map(|(node, (s, &c))| average(node, s, c))
            .collect()
    }

    /// Per node, the sum of the element extrapolations that reach it and their number.
    fn extrapolated_sums(&self, solution: &Solution) -> Result<(Vec<StressTensor>, Vec<usize>)> {
        let n_nodes = self.mesh.nodes().len();
        let extrapolation = Extrapolation::new();
        let gauss = self.stresses(solution)?;
        let mut sum = vec![StressTensor::default(); n_nodes];
        let mut count = vec![0usize; n_nodes];
        let mut first = 0;
        for (e, conn) in self.mesh.elements().iter().enumerate() {
            let kind = self.mesh.element_kind(e);
            let n = kind.integration_points().len();
            let points: Vec<StressTensor> =
                gauss[first..first + n].iter().map(|&s| s.into()).collect();
            first += n;
            for (&node, w) in conn.iter().zip(extrapolation.of(kind)) {
                for (s, &wk) in points.iter().zip(w) {
                    accumulate(&mut sum[node], &scaled(s, wk));
                }
                count[node] += 1;
            }
        }
        Ok((sum, count))
    }
}

/// The mean of `count` extrapolations summed in `sum` at `node`, checked finite (every node
/// of a [`crate::Mesh`] belongs to an element, so `count` ≥ 1).
fn average(node: usize, sum: &StressTensor, count: usize) -> Result<StressTensor> {
    let mean = scaled(sum, 1.0 / count as f64);
    if !mean.is_finite() {
        return Err(Error::invalid(
            format!("solution (stress at node {node})"),
            format!("{mean:?}"),
            "is not finite: the displacements must be finite",
        ));
    }
    Ok(mean)
}

impl FeBody {
    /// Stresses at every node of the body (in the order of its mesh's nodes, with the
    /// components of [`FeModel::nodal_stresses`]) under the contact pressure `pressure` \[MPa\],
    /// one value per interface point, and the body's given loads: the whole field, e.g. for a
    /// CSV of the mesh.
    ///
    /// The interface forces pᵢwᵢ are applied through the factorisation made when the body was
    /// built (no new factorisation). Rigid-mode amplitudes do not strain the body and are
    /// taken as zero; a floating body's pressure must balance its given loads on each free
    /// mode (eq. 2.10, as a contact solution does), to a relative 10⁻⁶, or the leftover
    /// would be carried by the unknown held to remove the mode.
    pub fn nodal_stresses(&self, pressure: &[f64]) -> Result<Vec<StressTensor>> {
        let force = self.interface_forces(pressure)?;
        self.check_equilibrium(&force)?;
        let displacement = self.displacement(&force, &vec![0.0; self.rigid_modes().len()])?;
        self.model.nodal_stresses(&Solution { displacement })
    }

    /// Compressive normal forces pᵢwᵢ \[N\] at the interface points, the pressure checked.
    pub(crate) fn interface_forces(&self, pressure: &[f64]) -> Result<Vec<f64>> {
        let weights = self.interface().weights();
        if pressure.len() != weights.len() {
            return Err(Error::invalid(
                format!("{}.pressure.len()", self.name()),
                pressure.len(),
                format!("one pressure per interface point ({})", weights.len()),
            ));
        }
        check::all_finite(&format!("{}.pressure", self.name()), pressure)?;
        Ok(pressure.iter().zip(weights).map(|(p, w)| p * w).collect())
    }

    /// Checks that the interface forces balance the given loads on every free rigid mode:
    /// Σ fᵢ gᵢ + q = 0 (eq. 2.10) to [`EQUILIBRIUM_TOLERANCE`] of the larger side.
    fn check_equilibrium(&self, force: &[f64]) -> Result<()> {
        for mode in self.rigid_modes() {
            let work: Vec<f64> = force
                .iter()
                .zip(&mode.interface_displacement)
                .map(|(f, g)| f * g)
                .collect();
            let imbalance = work.iter().sum::<f64>() + mode.load;
            let scale = work
                .iter()
                .map(|w| w.abs())
                .sum::<f64>()
                .max(mode.load.abs());
            if imbalance.abs() > EQUILIBRIUM_TOLERANCE * scale {
                return Err(Error::invalid(
                    format!("{}.pressure", self.name()),
                    format!("a resultant off by {imbalance:.6e} N on the {}", mode.name),
                    "the pressure on a floating body must balance its given loads \
                     (solve the contact first)",
                ));
            }
        }
        Ok(())
    }

    /// [`ElasticBody::subsurface`] of a finite-element body: the peaks over every node of the
    /// mesh (see the trait implementation).
    pub(crate) fn nodal_subsurface(
        &self,
        pressure: &[f64],
        request: &SubsurfaceRequest,
    ) -> Result<Subsurface> {
        // A mesh has its own points below the surface: the request's depths and sections
        // would need a search for the element that holds each point, which nodes make moot.
        let stresses = self.nodal_stresses(pressure)?;
        let mut peaks = StressPeaks::default();
        for (s, x) in stresses.iter().zip(self.model.mesh.nodes()) {
            peaks.record(s, x[0], x[1], self.depth(*x));
        }
        let sections = match request.sections.is_empty() {
            true => vec![],
            false => self.grid_section(&stresses).into_iter().collect(),
        };
        Ok(Subsurface {
            peaks: peaks.finite(self.name())?,
            sections,
        })
    }

    /// The whole mesh as one section, when its nodes (with each Q8 element's centre,
    /// interpolated) fill a grid of distinct x × distinct y, each grid point once, and its
    /// contact face is a line y = const, as a structured rectangle's do (of Q8, Q9 or T6
    /// elements): the model's plane is its vertical section, positions its x (or r) and depths
    /// the distance from the face. `None` for any other mesh (a distorted or imported one).
    fn grid_section(&self, stresses: &[StressTensor]) -> Option<SectionField> {
        let face = self.interface().points().first()?[1];
        let points = self.interface().points().iter();
        if points
            .clone()
            .any(|p| (p[1] - face).abs() > SAME_COORDINATE)
        {
            return None;
        }
        let mut samples: Vec<([f64; 2], StressTensor)> = self
            .model
            .mesh
            .nodes()
            .iter()
            .copied()
            .zip(stresses.iter().copied())
            .collect();
        samples.extend(self.serendipity_centres(stresses));
        let distinct = |axis: usize| {
            let mut v: Vec<f64> = samples.iter().map(|(x, _)| x[axis]).collect();
            v.sort_by(f64::total_cmp);
            v.dedup_by(|a, b| (*a - *b).abs() < SAME_COORDINATE);
            v
        };
        let (xs, ys) = (distinct(0), distinct(1));
        if xs.len() * ys.len() != samples.len() {
            return None;
        }
        let index = |v: &[f64], c: f64| v.partition_point(|&t| t < c - SAME_COORDINATE);
        // Rows by depth: the face first.
        let mut depths: Vec<(usize, f64)> =
            (0..ys.len()).map(|j| (j, (ys[j] - face).abs())).collect();
        depths.sort_by(|a, b| a.1.total_cmp(&b.1));
        let row: Vec<usize> = {
            let mut r = vec![0; ys.len()];
            for (k, (j, _)) in depths.iter().enumerate() {
                r[*j] = k;
            }
            r
        };
        let mut tensors = vec![StressTensor::default(); samples.len()];
        let mut filled = vec![false; samples.len()];
        for (x, s) in &samples {
            let k = row[index(&ys, x[1])] * xs.len() + index(&xs, x[0]);
            if std::mem::replace(&mut filled[k], true) {
                return None;
            }
            tensors[k] = *s;
        }
        Some(SectionField {
            section: Section {
                axis: SectionAxis::X,
                at: 0.0,
            },
            positions: xs,
            depths: depths.into_iter().map(|(_, d)| d).collect(),
            tensors,
        })
    }

    /// The centre of every Q8 element and the nodal stresses interpolated there (a Q8
    /// element has no centre node).
    fn serendipity_centres(&self, stresses: &[StressTensor]) -> Vec<([f64; 2], StressTensor)> {
        let mesh = &self.model.mesh;
        let shape = ElementKind::Q8.shape(0.0, 0.0);
        (0..mesh.elements().len())
            .filter(|&e| mesh.element_kind(e) == ElementKind::Q8)
            .map(|e| {
                let mut x = [0.0; 2];
                let mut s = StressTensor::default();
                for (&node, &n) in mesh.elements()[e].iter().zip(&shape.n) {
                    x[0] += n * mesh.nodes()[node][0];
                    x[1] += n * mesh.nodes()[node][1];
                    accumulate(&mut s, &scaled(&stresses[node], n));
                }
                (x, s)
            })
            .collect()
    }

    /// Distance \[mm\] from `x` to the nearest interface point: the depth of a node below the
    /// contact surface.
    fn depth(&self, x: [f64; 2]) -> f64 {
        self.interface()
            .points()
            .iter()
            .map(|p| (x[0] - p[0]).hypot(x[1] - p[1]))
            .fold(f64::INFINITY, f64::min)
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;
    use crate::{Analysis, Component, ElementKind, Material, Mesh, Spacing};

    const E: f64 = 2.0e5;
    const NU: f64 = 0.3;
    const P: f64 = 100.0;
    const WIDTH: f64 = 40.0;
    const HEIGHT: f64 = 20.0;

    fn steel() -> Material {
        Material::new(E, NU).unwrap()
    }

    /// The kind of each cell of a structured mesh.
    type Cells = fn(usize, usize) -> ElementKind;

    /// The meshes the recovery is tested on: one kind each, and a column of Q8 next to T6
    /// cells (their shared faces carry a quadrilateral's and a triangle's extrapolations).
    const MESHES: [(&str, Cells); 4] = [
        ("Q8", |_, _| ElementKind::Q8),
        ("Q9", |_, _| ElementKind::Q9),
        ("T6", |_, _| ElementKind::T6),
        ("Q8+T6", |i, _| match i {
            0 => ElementKind::Q8,
            _ => ElementKind::T6,
        }),
    ];

    const ANALYSES: [Analysis; 3] = [
        Analysis::PlaneStress { thickness: 2.0 },
        Analysis::PlaneStrain { thickness: 1.0 },
        Analysis::Axisymmetric,
    ];

    /// A WIDTH × HEIGHT rectangle of 3 × 2 unequal elements whose interior nodes are moved
    /// (curved inner edges), the boundary kept straight; bottom held in y, left edge in x
    /// (in axisymmetry the left edge is the axis, held by the model).
    fn distorted_block(cells: Cells, analysis: Analysis) -> FeModel {
        block(cells, analysis, 1.0)
    }

    /// The block with its interior nodes moved by `distortion` times the bump.
    fn block(cells: Cells, analysis: Analysis, distortion: f64) -> FeModel {
        let x = Spacing::from_coords(vec![0.0, 11.0, 27.0, WIDTH]).unwrap();
        let y = Spacing::from_coords(vec![0.0, 8.0, HEIGHT]).unwrap();
        let bump =
            |p: [f64; 2]| distortion * (PI * p[0] / WIDTH).sin() * (PI * p[1] / HEIGHT).sin();
        let mesh = Mesh::rectangle_with(&x, &y, cells)
            .unwrap()
            .map(|p| [p[0] + 3.0 * bump(p), p[1] + 2.0 * bump(p)])
            .unwrap();
        let mut model = FeModel::new(mesh, steel(), analysis).unwrap();
        let bottom = model.mesh().nodes_on_y(0.0, 0.0, WIDTH);
        let left = model.mesh().nodes_on_x(0.0, 0.0, HEIGHT);
        model.fix(&bottom, Component::Y).unwrap();
        model.fix(&left, Component::X).unwrap();
        model
    }

    /// Uniaxial compression −p along y: σ_x = 0, σ_y = −p, and out of plane 0 (plane stress,
    /// axisymmetric hoop) or −νp (plane strain).
    fn uniaxial(analysis: Analysis) -> StressTensor {
        let out = match analysis {
            Analysis::PlaneStrain { .. } => -NU * P,
            _ => 0.0,
        };
        StressTensor {
            zz: -P,
            yy: out,
            ..StressTensor::default()
        }
    }

    fn largest_difference(got: &[StressTensor], want: impl Fn(usize) -> StressTensor) -> f64 {
        got.iter()
            .enumerate()
            .flat_map(|(n, s)| {
                let w = want(n);
                [
                    s.xx - w.xx,
                    s.yy - w.yy,
                    s.zz - w.zz,
                    s.xy - w.xy,
                    s.xz - w.xz,
                    s.yz - w.yz,
                ]
            })
            .fold(0.0, |m, d| m.max(d.abs()))
    }

    /// Patch test: uniform pressure on the top of a distorted block (curved interior edges)
    /// gives the uniform stress at every node, whether applied as a model load or as a contact
    /// pressure on an [`FeBody`] (which checks the force = pressure × weight and the sign), on
    /// every mesh of [`MESHES`]: the triangles' least-squares extrapolation and the average
    /// across kinds keep a uniform stress to 1e-10 of p.
    #[test]
    fn uniform_pressure_gives_uniform_nodal_stress() {
        for (kind, cells) in MESHES {
            for analysis in ANALYSES {
                let want = uniaxial(analysis);
                let mut model = distorted_block(cells, analysis);
                let top = model.mesh().faces_on_y(HEIGHT, 0.0, WIDTH);
                let body = FeBody::new("block", model.clone(), &top).unwrap();
                model.pressure(&top, P).unwrap();
                let loaded = model.nodal_stresses(&model.solve().unwrap()).unwrap();
                let pressed = body
                    .nodal_stresses(&vec![P; body.interface().len()])
                    .unwrap();
                for (how, got) in [("load", loaded), ("contact", pressed)] {
                    let err = largest_difference(&got, |_| want) / P;
                    assert!(err < 1e-10, "{kind} {analysis:?} {how}: {err:e} p");
                }
            }
        }
    }

    /// Pure bending of a plane-stress beam, u = κxy, v = −κ(x² + νy²)/2, lies in the Q8, Q9
    /// and T6 spaces (it is quadratic): σ_x = Eκy is exact at the integration points, and the
    /// extrapolation, exact for a linear stress, must give it at every node, on every mesh of
    /// [`MESHES`]. A transposed Gauss-point order, or a triangle fit that were not exact for a
    /// linear field, would not.
    #[test]
    fn pure_bending_is_recovered_exactly() {
        let (length, half, kappa) = (60.0, 5.0, 1e-5);
        for (kind, cells) in MESHES {
            let x = Spacing::from_coords(vec![0.0, 10.0, 30.0, length]).unwrap();
            let y = Spacing::from_coords(vec![-half, 0.0, 2.0, half]).unwrap();
            let mesh = Mesh::rectangle_with(&x, &y, cells).unwrap();
            let analysis = Analysis::PlaneStress { thickness: 1.0 };
            let mut model = FeModel::new(mesh, steel(), analysis).unwrap();
            let left = model.mesh().nodes_on_x(0.0, -half, half);
            let origin = model.mesh().nodes_on_x(0.0, 0.0, 0.0);
            let end = model.mesh().faces_on_x(length, -half, half);
            model
                .fix(&left, Component::X)
                .unwrap()
                .fix(&origin, Component::Y)
                .unwrap()
                .traction_with(&end, |p| [E * kappa * p[1], 0.0])
                .unwrap();
            let got = model.nodal_stresses(&model.solve().unwrap()).unwrap();
            let nodes = model.mesh().nodes();
            let err = largest_difference(&got, |n| StressTensor {
                xx: E * kappa * nodes[n][1],
                ..StressTensor::default()
            });
            let peak = E * kappa * half;
            assert!(err < 1e-9 * peak, "{kind}: {err:e} MPa of {peak}");
        }
    }

    /// Lamé's thick-walled cylinder, a = 10, b = 20 mm, internal pressure p, axisymmetric with
    /// the axial displacement held (plane strain): σ_r = k − c/r², σ_θ = k + c/r²,
    /// σ_z = 2νk with k = pa²/(b² − a²), c = kb².
    fn lame(r: f64) -> StressTensor {
        let (a, b) = (10.0, 20.0);
        let k = P * a * a / (b * b - a * a);
        let c = k * b * b;
        StressTensor {
            xx: k - c / (r * r),
            yy: k + c / (r * r),
            zz: 2.0 * NU * k,
            ..StressTensor::default()
        }
    }

    /// Nodal stress errors of the Lamé cylinder with `nr` Q8 elements through the wall,
    /// relative to p: the largest over all nodes of |σ_r − σ_r,exact|, of |σ_θ − σ_θ,exact|,
    /// of every component, and the largest at the mid-wall nodes r = 15 mm.
    fn lame_errors(nr: usize) -> [f64; 4] {
        let (a, b, length) = (10.0, 20.0, 5.0);
        let mesh = Mesh::rectangle(
            ElementKind::Q8,
            &Spacing::uniform(a, b, nr).unwrap(),
            &Spacing::uniform(0.0, length, 2).unwrap(),
        )
        .unwrap();
        let mut model = FeModel::new(mesh, steel(), Analysis::Axisymmetric).unwrap();
        let ends = model
            .mesh()
            .nodes_where(|p| p[1].abs() < 1e-9 || (p[1] - length).abs() < 1e-9);
        let bore = model.mesh().faces_on_x(a, 0.0, length);
        model
            .fix(&ends, Component::Y)
            .unwrap()
            .pressure(&bore, P)
            .unwrap();
        let got = model.nodal_stresses(&model.solve().unwrap()).unwrap();
        let nodes = model.mesh().nodes();
        let exact = |n: usize| lame(nodes[n][0]);
        let component = |f: fn(&StressTensor) -> f64| {
            got.iter()
                .enumerate()
                .map(|(n, s)| (f(s) - f(&exact(n))).abs() / P)
                .fold(0.0, f64::max)
        };
        let mid: Vec<StressTensor> = got
            .iter()
            .zip(nodes)
            .filter(|(_, x)| (x[0] - 0.5 * (a + b)).abs() < 1e-9)
            .map(|(s, _)| *s)
            .collect();
        [
            component(|s| s.xx),
            component(|s| s.yy),
            largest_difference(&got, exact) / P,
            largest_difference(&mid, |_| lame(0.5 * (a + b))) / P,
        ]
    }

    /// Nodal σ_r, σ_θ, σ_z of the Lamé cylinder converge under refinement at O(h²).
    /// Measured, relative to p, for 2, 4, 8, 16 Q8 elements through the wall
    /// (`cargo test -p contopt-fem lame_cylinder_nodal -- --nocapture`): largest σ_r error
    /// 0.154, 0.052, 0.0152, 0.0042 (at the bore, where 1/r² is steepest and the nodal value is
    /// extrapolated); σ_θ 0.049, 0.019, 0.0061, 0.0017; mid-wall nodes (r = 15 mm) 0.071,
    /// 0.015, 0.0036, 0.0009.
    #[test]
    fn lame_cylinder_nodal_stresses_converge() {
        let errors: Vec<[f64; 4]> = [2, 4, 8, 16].map(lame_errors).to_vec();
        eprintln!("Lamé nodal stress errors / p: elements, sigma_r, sigma_theta, any, mid-wall");
        for (nr, e) in [2, 4, 8, 16].iter().zip(&errors) {
            eprintln!(
                "{nr:>3} {:>10.3e} {:>10.3e} {:>10.3e} {:>10.3e}",
                e[0], e[1], e[2], e[3]
            );
        }
        for pair in errors.windows(2) {
            let [coarse, fine] = [pair[0], pair[1]];
            assert!(
                fine.iter().zip(coarse).all(|(f, c)| *f < 0.4 * c),
                "errors {errors:?}"
            );
        }
        assert!(errors[3][2] < 5e-3, "errors {errors:?}");
    }

    /// A floating axisymmetric punch (radius and height 50 mm, 4 × 4 elements) under 100 MPa
    /// on its top, pressed by the same uniform pressure from below, is in uniaxial compression:
    /// σ_z = −100 MPa at every node. Its peaks say so, with the node's coordinates; a pressure
    /// that leaves the punch unbalanced is refused.
    #[test]
    fn balanced_floating_punch_is_in_uniaxial_compression() {
        const SIZE: f64 = 50.0;
        let s = Spacing::uniform(0.0, SIZE, 4).unwrap();
        let mesh = Mesh::rectangle(ElementKind::Q8, &s, &s).unwrap();
        let mut model = FeModel::new(mesh, steel(), Analysis::Axisymmetric).unwrap();
        let top = model.mesh().faces_on_y(SIZE, 0.0, SIZE);
        model.pressure(&top, P).unwrap();
        let bottom = model.mesh().faces_on_y(0.0, 0.0, SIZE);
        let punch = FeBody::new("punch", model, &bottom).unwrap();
        let n = punch.interface().len();
        let got = punch.nodal_stresses(&vec![P; n]).unwrap();
        let err = largest_difference(&got, |_| uniaxial(Analysis::Axisymmetric)) / P;
        assert!(err < 1e-9, "{err:e} p");
        let sub = punch
            .subsurface(&vec![P; n], &SubsurfaceRequest::default())
            .unwrap()
            .expect("a finite-element body computes stresses");
        assert!(sub.sections.is_empty());
        assert!((sub.peaks.von_mises.value - P).abs() < 1e-8 * P);
        assert!((sub.peaks.min_principal.value + P).abs() < 1e-8 * P);
        let peak = sub.peaks.min_principal;
        assert!(peak.depth >= 0.0 && peak.depth <= 2.0 * SIZE);
        assert!(punch
            .model()
            .mesh()
            .nodes()
            .iter()
            .any(|x| x[0] == peak.x && x[1] == peak.y));

        let unbalanced = punch.nodal_stresses(&vec![0.9 * P; n]).unwrap_err();
        assert!(
            unbalanced.to_string().contains("punch.pressure"),
            "{unbalanced}"
        );
    }

    /// A rectangular mesh is its own section: positions its node columns, depths from the
    /// contact face down, every entry (a Q8 element's centre interpolated) the uniform stress,
    /// whatever its elements; a distorted mesh has none.
    #[test]
    fn a_rectangular_mesh_is_its_section() {
        let request = SubsurfaceRequest {
            depths: vec![1.0],
            sections: vec![Section {
                axis: SectionAxis::X,
                at: 0.0,
            }],
        };
        for (kind, cells) in MESHES {
            let analysis = ANALYSES[1];
            for (distortion, sections) in [(0.0, 1), (1.0, 0)] {
                let model = block(cells, analysis, distortion);
                let top = model.mesh().faces_on_y(HEIGHT, 0.0, WIDTH);
                let body = FeBody::new("block", model, &top).unwrap();
                let n = body.interface().len();
                let sub = body.nodal_subsurface(&vec![P; n], &request).unwrap();
                assert_eq!(sub.sections.len(), sections, "{kind}, {distortion}");
                let Some(field) = sub.sections.first() else {
                    continue;
                };
                assert_eq!(field.positions.len(), 7);
                assert_eq!(field.depths, vec![0.0, 6.0, 12.0, 16.0, 20.0]);
                let want = uniaxial(analysis);
                assert!(largest_difference(&field.tensors, |_| want) < 1e-10 * P);
            }
        }
    }

    #[test]
    fn bad_pressure_and_solution_are_named() {
        let model = distorted_block(MESHES[0].1, ANALYSES[0]);
        let top = model.mesh().faces_on_y(HEIGHT, 0.0, WIDTH);
        let body = FeBody::new("block", model.clone(), &top).unwrap();
        let n = body.interface().len();
        let short = body
            .nodal_stresses(&vec![P; n - 1])
            .unwrap_err()
            .to_string();
        assert!(short.contains("block.pressure.len()") && short.contains(&format!("{}", n - 1)));
        let mut nan = vec![P; n];
        nan[4] = f64::NAN;
        let e = body
            .subsurface(&nan, &SubsurfaceRequest::default())
            .unwrap_err();
        assert!(e.to_string().contains("block.pressure[4]"), "{e}");
        let wrong = Solution {
            displacement: vec![0.0; 3],
        };
        let e = model.nodal_stresses(&wrong).unwrap_err().to_string();
        assert!(e.contains("solution.displacement"), "{e}");
        let mut infinite = vec![0.0; 2 * model.mesh().nodes().len()];
        infinite[7] = f64::INFINITY;
        let e = model.nodal_stresses(&Solution {
            displacement: infinite,
        });
        assert!(e.is_err());
    }
}
