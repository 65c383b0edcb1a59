//! Meshes of quadratic quadrilaterals and a structured generator with grading.

use contopt_core::{check, memory, Error, Result, GEOMETRY_TOLERANCE};
use nalgebra::Matrix2;

use crate::element::ElementKind;

/// The most elements a [`Spacing`] may have along one axis: far more than a two-dimensional
/// mesh that can be factorised needs, few enough that the coordinates are cheap.
pub const MAX_AXIS_ELEMENTS: usize = 100_000;

/// Relative round-off of a sum of element sizes: spacings whose ends agree to it meet
/// (round-off).
const SPACING_ROUND_OFF: f64 = 1e-12;

/// A generous estimate of the memory a body of `nx` × `ny` quadratic elements takes to build
/// \[bytes\], `None` when it overflows: [`mesh_bytes`] of the (2·nx + 1)(2·ny + 1) nodes of
/// its grid with a contact face of up to 3·nx points.
pub fn body_bytes(nx: usize, ny: usize) -> Option<u64> {
    let side = |n: usize| n.checked_mul(2)?.checked_add(1);
    mesh_bytes(side(nx)?.checked_mul(side(ny)?)?, nx.checked_mul(3)?)
}

/// A generous estimate of the memory a body of `nodes` nodes, of any elements (an imported
/// mesh), takes to build when condensed to `face_points` contact points \[bytes\] (0 for a
/// solve without condensation), `None` when it overflows: the sparse Cholesky factor of its 2
/// unknowns per node (nested dissection on a two-dimensional mesh of N nodes fills about
/// 8·N·log₂N blocks of 2 × 2 values, 12 bytes each with its index) and the dense condensation
/// on the contact points (four n × n matrices). [`body_bytes`] is this estimate for a
/// structured rectangle.
pub fn mesh_bytes(nodes: usize, face_points: usize) -> Option<u64> {
    let nodes = memory::bytes(&[nodes], 1)?;
    let log = u64::from(64 - nodes.leading_zeros());
    let factor = nodes.checked_mul(8 * 4 * 12)?.checked_mul(log)?;
    let face = memory::bytes(&[face_points, face_points], 4 * 8)?;
    factor.checked_add(face)
}

/// Element boundaries along one axis, increasing.
#[derive(Clone, Debug, PartialEq)]
pub struct Spacing {
    coords: Vec<f64>,
}

impl Spacing {
    /// Element boundaries given explicitly (strictly increasing, at least two).
    pub fn from_coords(coords: Vec<f64>) -> Result<Self> {
        if coords.len() < 2 {
            return Err(Error::invalid(
                "spacing.coords",
                coords.len(),
                "at least two boundaries",
            ));
        }
        check::all_finite("spacing.coords", &coords)?;
        if let Some(i) = (1..coords.len()).find(|&i| coords[i] <= coords[i - 1]) {
            return Err(Error::invalid(
                format!("spacing.coords[{i}]"),
                coords[i],
                format!("must exceed the previous boundary {}", coords[i - 1]),
            ));
        }
        Ok(Self { coords })
    }

    /// Refuses more than [`MAX_AXIS_ELEMENTS`] elements, before their coordinates are
    /// allocated.
    fn check_count(n: usize) -> Result<()> {
        if n > MAX_AXIS_ELEMENTS {
            return Err(Error::invalid(
                "spacing.elements",
                n,
                format!("at most {MAX_AXIS_ELEMENTS} along one axis"),
            ));
        }
        Ok(())
    }

    /// The ends a and b of a spacing, finite.
    fn check_ends(a: f64, b: f64) -> Result<()> {
        check::finite("spacing.start", a)?;
        check::finite("spacing.end", b)?;
        Ok(())
    }

    /// `n` equal elements on [a, b].
    pub fn uniform(a: f64, b: f64, n: usize) -> Result<Self> {
        Self::geometric(a, b, n, 1.0)
    }

    /// `n` elements on [a, b] whose sizes form a geometric progression with
    /// (last size) / (first size) = `ratio`; `ratio` < 1 refines towards b.
    pub fn geometric(a: f64, b: f64, n: usize, ratio: f64) -> Result<Self> {
        Self::check_count(n)?;
        if n == 0 {
            return Err(Error::invalid(
                "spacing.elements",
                n,
                "at least one element",
            ));
        }
        check::positive("spacing.ratio", ratio)?;
        Self::check_ends(a, b)?;
        if b <= a {
            return Err(Error::invalid(
                "spacing.end",
                b,
                format!("must exceed the start {a}"),
            ));
        }
        let q = if n > 1 {
            ratio.powf(1.0 / (n - 1) as f64)
        } else {
            1.0
        };
        let sizes: Vec<f64> = (0..n).map(|i| q.powi(i as i32)).collect();
        let total: f64 = sizes.iter().sum();
        let mut coords = Vec::with_capacity(n + 1);
        let mut x = a;
        coords.push(a);
        for s in &sizes[..n - 1] {
            x += (b - a) * s / total;
            coords.push(x);
        }
        coords.push(b);
        Self::from_coords(coords)
    }

    /// `n` elements on [a, b] growing geometrically from a first element of size `first`
    /// (which must be at most (b − a)/n): the outward continuation of a finely meshed zone.
    pub fn geometric_first(a: f64, b: f64, n: usize, first: f64) -> Result<Self> {
        Self::check_count(n)?;
        if n == 0 {
            return Err(Error::invalid(
                "spacing.elements",
                n,
                "at least one element",
            ));
        }
        Self::check_ends(a, b)?;
        check::positive("spacing.first", first)?;
        let len = b - a;
        if first * n as f64 > len * (1.0 + SPACING_ROUND_OFF) {
            return Err(Error::invalid(
                "spacing.first",
                first,
                format!("must lie in (0, {}]", len / n as f64),
            ));
        }
        // First size of a progression with factor q: len (q − 1)/(qⁿ − 1), decreasing in q.
        let first_of = |q: f64| {
            if (q - 1.0).abs() < SPACING_ROUND_OFF {
                len / n as f64
            } else {
                len * (q - 1.0) / (q.powi(n as i32) - 1.0)
            }
        };
        let (mut lo, mut hi) = (1.0, 2.0);
        while first_of(hi) > first {
            hi *= 2.0;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if first_of(mid) > first {
                lo = mid
            } else {
                hi = mid
            }
        }
        let q = 0.5 * (lo + hi);
        Self::geometric(a, b, n, q.powi(n as i32 - 1))
    }

    /// About `n` elements on [a, b], refined towards each of `points` (inside [a, b]) so that
    /// elements far from them are `ratio` times larger than those next to them. The points are
    /// element boundaries: the punch edge gets nodes on both of its sides.
    pub fn graded(a: f64, b: f64, n: usize, points: &[f64], ratio: f64) -> Result<Self> {
        if let Some(p) = points.iter().find(|p| !(a..=b).contains(*p)) {
            return Err(Error::invalid(
                "spacing.points",
                p,
                format!("must lie in [{a}, {b}]"),
            ));
        }
        check::finite("spacing.ratio", ratio)?;
        if ratio < 1.0 {
            return Err(Error::invalid(
                "spacing.ratio",
                ratio,
                "largest/smallest element ratio must be >= 1",
            ));
        }
        // Cut [a, b] into pieces, each graded from one fine end to one coarse end.
        let mut pts: Vec<f64> = points.to_vec();
        pts.sort_by(f64::total_cmp);
        pts.dedup();
        let mut pieces: Vec<(f64, f64, bool)> = Vec::new(); // (start, end, fine at start)
        let mut push = |s: f64, e: f64, fine_start: bool| {
            if e > s {
                pieces.push((s, e, fine_start));
            }
        };
        if pts.is_empty() {
            return Self::uniform(a, b, n);
        }
        push(a, pts[0], false);
        for w in pts.windows(2) {
            let mid = 0.5 * (w[0] + w[1]);
            push(w[0], mid, true);
            push(mid, w[1], false);
        }
        push(*pts.last().unwrap(), b, true);
        let len = b - a;
        let mut coords = vec![a];
        for (s, e, fine_start) in pieces {
            let k = ((n as f64 * (e - s) / len).round() as usize).max(1);
            let r = if fine_start { ratio } else { 1.0 / ratio };
            let piece = Self::geometric(s, e, k, r)?;
            coords.extend_from_slice(&piece.coords[1..]);
        }
        Self::from_coords(coords)
    }

    /// This spacing followed by `next`, which must start where this one ends.
    pub fn then(&self, next: &Spacing) -> Result<Self> {
        let end = *self.coords.last().unwrap();
        if (next.coords[0] - end).abs() > SPACING_ROUND_OFF * end.abs().max(1.0) {
            return Err(Error::invalid(
                "spacing.then.start",
                next.coords[0],
                format!("must equal the end {end}"),
            ));
        }
        let mut coords = self.coords.clone();
        coords.extend_from_slice(&next.coords[1..]);
        Self::from_coords(coords)
    }

    /// Element boundaries.
    pub fn coords(&self) -> &[f64] {
        &self.coords
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.coords.len() - 1
    }

    /// Never true: a spacing has at least one element.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The sub-spacing on [a, b], whose ends must be element boundaries of `self`.
    pub fn restrict(&self, a: f64, b: f64) -> Result<Self> {
        let tol = GEOMETRY_TOLERANCE * (self.coords[self.len()] - self.coords[0]);
        let find = |x: f64, field: &str| {
            self.coords
                .iter()
                .position(|c| (c - x).abs() <= tol)
                .ok_or_else(|| {
                    Error::invalid(field, x, "must be an element boundary of the spacing")
                })
        };
        let (i, j) = (
            find(a, "spacing.restrict.start")?,
            find(b, "spacing.restrict.end")?,
        );
        if j <= i {
            return Err(Error::invalid(
                "spacing.restrict.end",
                b,
                format!("must be a boundary after the start {a}"),
            ));
        }
        Self::from_coords(self.coords[i..=j].to_vec())
    }
}

/// One face (edge) of an element: `(element, local face)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Face {
    /// Element index.
    pub element: usize,
    /// Local face number, below the element's [`ElementKind::n_faces`] (see
    /// [`ElementKind::face_nodes`]).
    pub local: usize,
}

/// A mesh of quadratic elements in the (x, y) plane (x = r for axisymmetry): quadrilaterals
/// and triangles, of one kind or mixed.
#[derive(Clone, Debug)]
pub struct Mesh {
    kinds: Vec<ElementKind>,
    nodes: Vec<[f64; 2]>,
    elements: Vec<Vec<usize>>,
}

impl Mesh {
    /// A mesh of elements of one kind from node coordinates and element connectivity (local
    /// order of [`crate::element`], counter-clockwise). Errors ([`Error::Mesh`], naming the
    /// element or node): no element, a non-finite coordinate, an element with the wrong
    /// number of nodes for its kind or a node the mesh does not have, a Jacobian that is not
    /// positive at one of its integration points (nodes clockwise, or a degenerate element),
    /// a node that belongs to no element.
    pub fn new(kind: ElementKind, nodes: Vec<[f64; 2]>, elements: Vec<Vec<usize>>) -> Result<Self> {
        Self::build(vec![kind; elements.len()], nodes, elements)
    }

    /// A mesh whose elements may be of different kinds (an imported mesh of quadrilaterals
    /// and triangles): each element is its kind and its connectivity, checked as
    /// [`Mesh::new`] checks them. Elements that meet must share their face's three nodes (a
    /// conforming mesh, as Gmsh writes one).
    pub fn mixed(nodes: Vec<[f64; 2]>, elements: Vec<(ElementKind, Vec<usize>)>) -> Result<Self> {
        let (kinds, elements) = elements.into_iter().unzip();
        Self::build(kinds, nodes, elements)
    }

    fn build(
        kinds: Vec<ElementKind>,
        nodes: Vec<[f64; 2]>,
        elements: Vec<Vec<usize>>,
    ) -> Result<Self> {
        let mesh = Self {
            kinds,
            nodes,
            elements,
        };
        mesh.validate()?;
        Ok(mesh)
    }

    fn validate(&self) -> Result<()> {
        if self.elements.is_empty() {
            return Err(Error::Mesh("no elements".into()));
        }
        if let Some(i) = self
            .nodes
            .iter()
            .position(|p| !(p[0].is_finite() && p[1].is_finite()))
        {
            return Err(Error::Mesh(format!(
                "node {i} has a non-finite coordinate {:?}",
                self.nodes[i]
            )));
        }
        (0..self.elements.len()).try_for_each(|e| self.validate_element(e))?;
        let mut used = vec![false; self.nodes.len()];
        for &n in self.elements.iter().flatten() {
            used[n] = true;
        }
        if let Some(i) = used.iter().position(|u| !u) {
            return Err(Error::Mesh(format!(
                "node {i} at {:?} belongs to no element: it would have no stiffness \
                 (leave unused nodes out of the mesh)",
                self.nodes[i]
            )));
        }
        Ok(())
    }

    /// Element `e` has its kind's number of nodes, nodes of the mesh, and a positive Jacobian
    /// at its integration points.
    fn validate_element(&self, e: usize) -> Result<()> {
        let (kind, conn) = (self.kinds[e], &self.elements[e]);
        if conn.len() != kind.n_nodes() {
            return Err(Error::Mesh(format!(
                "element {e} has {} nodes, a {kind:?} needs {}",
                conn.len(),
                kind.n_nodes()
            )));
        }
        if let Some(&n) = conn.iter().find(|&&n| n >= self.nodes.len()) {
            return Err(Error::Mesh(format!(
                "element {e} refers to node {n}, mesh has {}",
                self.nodes.len()
            )));
        }
        for p in kind.integration_points() {
            let det = self.jacobian(e, p.xi, p.eta).1;
            if det.is_nan() || det <= 0.0 {
                return Err(Error::Mesh(format!(
                    "element {e} ({kind:?}) has Jacobian determinant {det:.3e} at (ξ, η) = \
                     ({:.3}, {:.3}): inverted or degenerate (nodes must run counter-clockwise)",
                    p.xi, p.eta
                )));
            }
        }
        Ok(())
    }

    /// Jacobian J = [[∂x/∂ξ, ∂y/∂ξ], [∂x/∂η, ∂y/∂η]] = Σₐ (∂Nₐ/∂ξ, ∂Nₐ/∂η)ᵀ (xₐ, yₐ) of
    /// element `e` at (ξ, η), and its determinant.
    pub(crate) fn jacobian(&self, e: usize, xi: f64, eta: f64) -> (Matrix2<f64>, f64) {
        let s = self.kinds[e].shape(xi, eta);
        let mut j = Matrix2::zeros();
        for (a, &n) in self.elements[e].iter().enumerate() {
            let p = self.nodes[n];
            for c in 0..2 {
                j[(0, c)] += s.dxi[a] * p[c];
                j[(1, c)] += s.deta[a] * p[c];
            }
        }
        (j, j.determinant())
    }

    /// A structured mesh of the rectangle `x × y` of elements of one kind; mid-side nodes
    /// sit at the midpoints (see [`Mesh::rectangle_with`]).
    pub fn rectangle(kind: ElementKind, x: &Spacing, y: &Spacing) -> Result<Self> {
        Self::rectangle_with(x, y, |_, _| kind)
    }

    /// A structured mesh of the rectangle `x × y` whose cell (i, j), the i-th along x and the
    /// j-th along y from 0, is of kind `kind(i, j)`: a Q8 or a Q9 element, or for T6 two
    /// triangles split along the diagonal from the cell's lower-left to its upper-right corner.
    /// The nodes are those of the grid of corners and mid-sides, and of the cell centres that
    /// belong to an element (a Q9's centre, the middle of a T6 cell's diagonal); neighbouring
    /// cells share their face's three nodes whatever their kinds.
    pub fn rectangle_with(
        x: &Spacing,
        y: &Spacing,
        kind: impl Fn(usize, usize) -> ElementKind,
    ) -> Result<Self> {
        let (nx, ny) = (x.len(), y.len());
        memory::require(
            format!("a body of {nx} × {ny} quadratic elements"),
            body_bytes(nx, ny),
            memory::BODY_LIMIT_BYTES,
            "use fewer elements",
        )?;
        let cells: Vec<ElementKind> = (0..ny)
            .flat_map(|j| (0..nx).map(move |i| (i, j)))
            .map(|(i, j)| kind(i, j))
            .collect();
        let (gx, gy) = (2 * nx + 1, 2 * ny + 1);
        let coord = |s: &Spacing, i: usize| {
            let c = s.coords();
            if i.is_multiple_of(2) {
                c[i / 2]
            } else {
                0.5 * (c[i / 2] + c[i / 2 + 1])
            }
        };
        let mut id = vec![usize::MAX; gx * gy];
        let mut nodes = Vec::new();
        for j in 0..gy {
            for i in 0..gx {
                if i % 2 == 1 && j % 2 == 1 && cells[(j / 2) * nx + i / 2] == ElementKind::Q8 {
                    continue;
                }
                id[j * gx + i] = nodes.len();
                nodes.push([coord(x, i), coord(y, j)]);
            }
        }
        let at = |i: usize, j: usize| id[j * gx + i];
        let mut kinds = Vec::with_capacity(nx * ny);
        let mut elements = Vec::with_capacity(nx * ny);
        for (c, &cell) in cells.iter().enumerate() {
            let (i, j) = (2 * (c % nx), 2 * (c / nx));
            let corners = [at(i, j), at(i + 2, j), at(i + 2, j + 2), at(i, j + 2)];
            let sides = [
                at(i + 1, j),
                at(i + 2, j + 1),
                at(i + 1, j + 2),
                at(i, j + 1),
            ];
            let centre = at(i + 1, j + 1);
            let [c0, c1, c2, c3] = corners;
            let [s0, s1, s2, s3] = sides;
            let cell_elements = match cell {
                ElementKind::Q8 => vec![[corners, sides].concat()],
                ElementKind::Q9 => vec![[&corners[..], &sides, &[centre]].concat()],
                ElementKind::T6 => vec![
                    vec![c0, c1, c2, s0, s1, centre],
                    vec![c0, c2, c3, centre, s2, s3],
                ],
            };
            for conn in cell_elements {
                kinds.push(cell);
                elements.push(conn);
            }
        }
        Self::build(kinds, nodes, elements)
    }

    /// Two rectangles stacked as in the paper's Fig. 1: a lower body on `lower_x × lower_y`
    /// and an upper body on `[upper_x.0, upper_x.1] × upper_y`, with `upper_y` starting at
    /// the top of `lower_y`. The upper body uses the lower body's element boundaries over its
    /// width, so the nodes of the two contact faces coincide.
    pub fn stacked(
        kind: ElementKind,
        lower_x: &Spacing,
        lower_y: &Spacing,
        upper_x: (f64, f64),
        upper_y: &Spacing,
    ) -> Result<(Self, Self)> {
        let top = *lower_y.coords().last().unwrap();
        let base = upper_y.coords()[0];
        if (top - base).abs() > GEOMETRY_TOLERANCE * top.abs().max(1.0) {
            return Err(Error::invalid(
                "stacked.upper_y.start",
                base,
                format!("must equal the top of the lower body, {top}"),
            ));
        }
        let lower = Self::rectangle(kind, lower_x, lower_y)?;
        let upper = Self::rectangle(kind, &lower_x.restrict(upper_x.0, upper_x.1)?, upper_y)?;
        Ok((lower, upper))
    }

    /// Moves every node by `f`, e.g. to bend a rectangle in (r, θ) into an annular sector.
    pub fn map(mut self, f: impl Fn([f64; 2]) -> [f64; 2]) -> Result<Self> {
        for p in &mut self.nodes {
            *p = f(*p);
        }
        self.validate()?;
        Ok(self)
    }

    /// The element type of a mesh of one kind; `None` when the mesh mixes kinds (see
    /// [`Mesh::element_kind`]). An `Option` rather than the first element's kind, so that code
    /// written for one kind cannot silently treat a mixed mesh as that kind.
    pub fn kind(&self) -> Option<ElementKind> {
        let first = self.kinds[0];
        self.kinds.iter().all(|&k| k == first).then_some(first)
    }

    /// The type of element `e` (< `elements().len()`).
    pub fn element_kind(&self, e: usize) -> ElementKind {
        self.kinds[e]
    }

    /// Node coordinates.
    pub fn nodes(&self) -> &[[f64; 2]] {
        &self.nodes
    }

    /// Element connectivity, each element's nodes in the local order of its kind.
    pub fn elements(&self) -> &[Vec<usize>] {
        &self.elements
    }

    /// Global nodes (start, middle, end) of a face.
    pub fn face_nodes(&self, f: Face) -> [usize; 3] {
        let conn = &self.elements[f.element];
        self.kinds[f.element].face_nodes(f.local).map(|a| conn[a])
    }

    /// Faces that belong to one element only, in element order.
    pub fn boundary_faces(&self) -> Vec<Face> {
        let mut count = std::collections::HashMap::new();
        let key = |f: Face| {
            let [a, _, b] = self.face_nodes(f);
            (a.min(b), a.max(b))
        };
        let all: Vec<Face> = (0..self.elements.len())
            .flat_map(|element| {
                let faces = self.kinds[element].n_faces();
                (0..faces).map(move |local| Face { element, local })
            })
            .collect();
        for &f in &all {
            *count.entry(key(f)).or_insert(0usize) += 1;
        }
        all.into_iter().filter(|&f| count[&key(f)] == 1).collect()
    }

    /// Length scale for coordinate comparisons: 10⁻⁹ of the bounding-box diagonal.
    fn tolerance(&self) -> f64 {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in &self.nodes {
            for c in 0..2 {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
        }
        GEOMETRY_TOLERANCE * ((hi[0] - lo[0]).hypot(hi[1] - lo[1]))
    }

    /// Nodes whose coordinates satisfy `pred`.
    pub fn nodes_where(&self, pred: impl Fn([f64; 2]) -> bool) -> Vec<usize> {
        (0..self.nodes.len())
            .filter(|&i| pred(self.nodes[i]))
            .collect()
    }

    /// Boundary faces whose three nodes all satisfy `pred`.
    pub fn faces_where(&self, pred: impl Fn([f64; 2]) -> bool) -> Vec<Face> {
        self.boundary_faces()
            .into_iter()
            .filter(|&f| self.face_nodes(f).iter().all(|&n| pred(self.nodes[n])))
            .collect()
    }

    /// Nodes on the line y = `y` with x in `[x0, x1]`.
    pub fn nodes_on_y(&self, y: f64, x0: f64, x1: f64) -> Vec<usize> {
        let t = self.tolerance();
        self.nodes_where(|p| (p[1] - y).abs() <= t && p[0] >= x0 - t && p[0] <= x1 + t)
    }

    /// Nodes on the line x = `x` with y in `[y0, y1]`.
    pub fn nodes_on_x(&self, x: f64, y0: f64, y1: f64) -> Vec<usize> {
        let t = self.tolerance();
        self.nodes_where(|p| (p[0] - x).abs() <= t && p[1] >= y0 - t && p[1] <= y1 + t)
    }

    /// Boundary faces on the line y = `y` with x in `[x0, x1]`, ordered by x.
    pub fn faces_on_y(&self, y: f64, x0: f64, x1: f64) -> Vec<Face> {
        let t = self.tolerance();
        let mut f = self.faces_where(|p| (p[1] - y).abs() <= t && p[0] >= x0 - t && p[0] <= x1 + t);
        f.sort_by(|a, b| {
            self.nodes[self.face_nodes(*a)[1]][0].total_cmp(&self.nodes[self.face_nodes(*b)[1]][0])
        });
        f
    }

    /// Boundary faces on the line x = `x` with y in `[y0, y1]`, ordered by y.
    pub fn faces_on_x(&self, x: f64, y0: f64, y1: f64) -> Vec<Face> {
        let t = self.tolerance();
        let mut f = self.faces_where(|p| (p[0] - x).abs() <= t && p[1] >= y0 - t && p[1] <= y1 + t);
        f.sort_by(|a, b| {
            self.nodes[self.face_nodes(*a)[1]][1].total_cmp(&self.nodes[self.face_nodes(*b)[1]][1])
        });
        f
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every coordinate is checked finite, the first too.
    #[test]
    fn from_coords_refuses_non_finite_coordinates() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let e = Spacing::from_coords(vec![bad, 0.0])
                .unwrap_err()
                .to_string();
            assert!(e.contains("spacing.coords[0]"), "{e}");
            assert!(Spacing::from_coords(vec![0.0, bad]).is_err());
        }
    }

    #[test]
    fn graded_spacing_refines_towards_the_point() {
        let s = Spacing::graded(0.0, 100.0, 40, &[50.0], 10.0).unwrap();
        let c = s.coords();
        assert!(
            c.iter().any(|x| (x - 50.0).abs() < 1e-12),
            "50 is a boundary"
        );
        let i = c.iter().position(|x| (x - 50.0).abs() < 1e-12).unwrap();
        let (near, far) = (c[i] - c[i - 1], c[1] - c[0]);
        assert!((far / near - 10.0).abs() < 1e-9, "ratio {}", far / near);
        assert_eq!(s.len(), 40);
    }

    #[test]
    fn geometric_first_starts_at_the_given_size() {
        let s = Spacing::geometric_first(10.0, 200.0, 40, 0.5).unwrap();
        let c = s.coords();
        assert!((c[1] - c[0] - 0.5).abs() < 1e-9, "{}", c[1] - c[0]);
        assert_eq!((c[0], c[40]), (10.0, 200.0));
        assert!(Spacing::geometric_first(0.0, 1.0, 4, 0.3).is_err());
    }

    #[test]
    fn stacked_meshes_share_contact_nodes() {
        let x = Spacing::graded(0.0, 100.0, 20, &[50.0], 4.0).unwrap();
        let (lower, upper) = Mesh::stacked(
            ElementKind::Q8,
            &x,
            &Spacing::uniform(0.0, 50.0, 5).unwrap(),
            (0.0, 50.0),
            &Spacing::uniform(50.0, 100.0, 5).unwrap(),
        )
        .unwrap();
        let a: Vec<_> = lower
            .nodes_on_y(50.0, 0.0, 50.0)
            .iter()
            .map(|&n| lower.nodes()[n][0])
            .collect();
        let b: Vec<_> = upper
            .nodes_on_y(50.0, 0.0, 50.0)
            .iter()
            .map(|&n| upper.nodes()[n][0])
            .collect();
        assert_eq!(a, b);
        assert_eq!(upper.faces_on_y(50.0, 0.0, 50.0).len(), 10);
    }

    #[test]
    fn rejects_inverted_elements_and_bad_spacings() {
        let err = Mesh::rectangle(
            ElementKind::Q9,
            &Spacing::uniform(0.0, 1.0, 1).unwrap(),
            &Spacing::uniform(0.0, 1.0, 1).unwrap(),
        )
        .unwrap()
        .map(|p| [-p[0], p[1]])
        .unwrap_err();
        assert!(err.to_string().contains("Jacobian"), "{err}");
        let e = Spacing::from_coords(vec![0.0, 1.0, 1.0])
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "invalid spacing.coords[2] = 1: must exceed the previous boundary 1"
        );
        let e = Spacing::from_coords(vec![f64::NAN, 1.0])
            .unwrap_err()
            .to_string();
        assert_eq!(e, "invalid spacing.coords[0] = NaN: must be finite");
        let e = Spacing::uniform(0.0, f64::INFINITY, 2)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "invalid spacing.end = inf: must be finite");
        let e = Spacing::geometric(0.0, 1.0, 2, 0.0)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "invalid spacing.ratio = 0: must be positive and finite");
        assert!(Spacing::graded(0.0, 1.0, 4, &[0.5], f64::INFINITY).is_err());
        assert!(Spacing::geometric_first(0.0, 1.0, 4, f64::NAN).is_err());
        assert!(Spacing::uniform(0.0, 1.0, 4)
            .unwrap()
            .restrict(0.0, 0.3)
            .is_err());
    }

    /// A Q8 cell next to a T6 cell: the two triangles, the quadrilateral and their shared
    /// face; per-element kinds; boundary faces of both kinds, and the shared faces inside.
    #[test]
    fn mixed_rectangles_share_their_faces() {
        let x = Spacing::from_coords(vec![0.0, 2.0, 5.0]).unwrap();
        let y = Spacing::from_coords(vec![0.0, 3.0]).unwrap();
        let mesh =
            Mesh::rectangle_with(&x, &y, |i, _| [ElementKind::Q8, ElementKind::T6][i]).unwrap();
        // A 5 × 3 grid of nodes less the Q8's centre.
        assert_eq!(mesh.nodes().len(), 14);
        assert_eq!(mesh.elements().len(), 3);
        let kinds: Vec<ElementKind> = (0..3).map(|e| mesh.element_kind(e)).collect();
        assert_eq!(kinds, [ElementKind::Q8, ElementKind::T6, ElementKind::T6]);
        assert_eq!(mesh.kind(), None);
        assert_eq!(
            Mesh::rectangle(ElementKind::T6, &x, &y).unwrap().kind(),
            Some(ElementKind::T6)
        );
        // Boundary: Q8 bottom, top, left; T6 0 bottom and right; T6 1 top. The Q8's right
        // face and the triangles' diagonal are shared.
        let boundary = mesh.boundary_faces();
        let face = |element, local| Face { element, local };
        assert_eq!(
            boundary,
            [
                face(0, 0),
                face(0, 2),
                face(0, 3),
                face(1, 0),
                face(1, 1),
                face(2, 1)
            ]
        );
        let top = mesh.faces_on_y(3.0, 0.0, 5.0);
        assert_eq!(top, [face(0, 2), face(2, 1)]);
        // A face is (start, middle, end) counter-clockwise: along the top from right to left.
        let at = |n: usize| mesh.nodes()[n];
        let [a, m, b] = mesh.face_nodes(face(2, 1));
        assert_eq!([at(a), at(m), at(b)], [[5.0, 3.0], [3.5, 3.0], [2.0, 3.0]]);
        assert_eq!(mesh.nodes_on_x(2.0, 0.0, 3.0).len(), 3);
        assert_eq!(mesh.faces_on_x(5.0, 0.0, 3.0), [face(1, 1)]);
    }

    /// A clockwise triangle is refused naming the element and its kind; so is an element
    /// with its kind's wrong node count, and a node no element uses.
    #[test]
    fn bad_mixed_meshes_are_named() {
        let nodes = vec![
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 2.0],
            [0.0, 2.0],
            [1.0, 0.0],
            [2.0, 1.0],
            [1.0, 2.0],
            [0.0, 1.0],
            [4.0, 0.0],
            [3.0, 0.0],
            [3.0, 1.0],
        ];
        let quad = (ElementKind::Q8, (0..8).collect::<Vec<usize>>());
        let triangle = vec![1, 8, 2, 9, 10, 5];
        let ok = Mesh::mixed(
            nodes.clone(),
            vec![quad.clone(), (ElementKind::T6, triangle.clone())],
        )
        .unwrap();
        assert_eq!(ok.boundary_faces().len(), 5);
        let clockwise = vec![1, 2, 8, 5, 10, 9];
        let e = Mesh::mixed(
            nodes.clone(),
            vec![quad.clone(), (ElementKind::T6, clockwise)],
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("element 1 (T6) has Jacobian determinant -") && e.contains("clockwise"),
            "{e}"
        );
        let e = Mesh::mixed(
            nodes.clone(),
            vec![quad.clone(), (ElementKind::T6, vec![1, 8, 2])],
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("element 1 has 3 nodes, a T6 needs 6"), "{e}");
        let e = Mesh::mixed(nodes, vec![quad]).unwrap_err().to_string();
        assert!(
            e.contains("node 8 at [4.0, 0.0] belongs to no element"),
            "{e}"
        );
    }

    /// `body_bytes` is `mesh_bytes` of its grid; an imported mesh of 200 000 nodes with a
    /// contact face of 3000 points is 18 · 384 bytes per node (log₂ rounded up: 18) and four
    /// 3000² matrices, within the limit; sizes past u64 are `None`.
    #[test]
    fn mesh_bytes_is_the_fill_model_of_any_mesh() {
        assert_eq!(body_bytes(40, 25), mesh_bytes(81 * 51, 120));
        let bytes = mesh_bytes(200_000, 3000).unwrap();
        assert_eq!(bytes, 200_000 * 384 * 18 + 4 * 8 * 3000 * 3000);
        assert!(bytes < memory::BODY_LIMIT_BYTES);
        assert_eq!(mesh_bytes(usize::MAX, 0), None);
        assert_eq!(mesh_bytes(1, usize::MAX), None);
    }
}
