//! A body's elements chosen from a Gmsh file before they become a mesh: its nodes and
//! elements renumbered, with Gmsh's tags, oriented counter-clockwise and checked for folded,
//! inverted and duplicated pieces. Read by the import and the groups alike (its own module,
//! so that neither imports the other).

use std::collections::BTreeMap;

use contopt_core::{Error, Result};
use contopt_fem::{ElementKind, Face};

use crate::geometry::{self, Orientation};

/// Two nodes closer than this fraction of the shortest element edge (in x and in y) are one
/// point meshed twice.
const DUPLICATE_NODE_FRACTION: f64 = 1e-6;
/// Elements named in one error, at most.
const LISTED: usize = 5;

/// The chosen elements before they become a [`Mesh`].
#[derive(Clone, Debug)]
pub(crate) struct Body {
    /// Node coordinates (x, y).
    pub nodes: Vec<[f64; 2]>,
    /// Gmsh's node tags.
    pub node_tags: Vec<u64>,
    /// Kind and nodes (counter-clockwise once oriented) of each element.
    pub elements: Vec<(ElementKind, Vec<usize>)>,
    /// Gmsh's element tags.
    pub element_tags: Vec<u64>,
    /// The surface entity of each element.
    pub surfaces: Vec<i32>,
    /// The body's node of each node of the file (`usize::MAX` for the others).
    pub of_file_node: Vec<usize>,
}

impl Body {
    /// Global nodes (start, middle, end) of a face.
    pub fn face_nodes(&self, f: Face) -> [usize; 3] {
        let (kind, nodes) = &self.elements[f.element];
        kind.face_nodes(f.local).map(|a| nodes[a])
    }

    /// The area Σ ∫ det J.
    #[cfg(test)]
    pub fn area(&self) -> f64 {
        (self.elements.iter())
            .map(|(kind, element)| {
                let (x, n) = geometry::coords(&self.nodes, element);
                geometry::area(*kind, &x[..n])
            })
            .sum()
    }
}

impl Body {
    /// Every element counter-clockwise: a surface whose elements all run clockwise (Gmsh
    /// orients a surface's elements by its normal, and a surface whose normal is −z runs
    /// clockwise) has each element's local order mirrored; an element that folds, or runs
    /// against the rest of its surface, is refused.
    pub fn orient(&mut self, source: &str) -> Result<()> {
        let orientations: Vec<Orientation> = (self.elements.iter())
            .map(|(kind, element)| {
                let (x, n) = geometry::coords(&self.nodes, element);
                geometry::orientation(*kind, &x[..n])
            })
            .collect();
        if let Some((e, Orientation::Folded { min, max })) = orientations
            .iter()
            .enumerate()
            .find(|(_, o)| matches!(o, Orientation::Folded { .. }))
        {
            return Err(Error::Mesh(format!(
                "{source}: Gmsh element {} is inverted: its Jacobian determinant changes sign \
                 or vanishes (from {min:.3e} to {max:.3e}): a mid-side node lies too far off its \
                 side; refine where the boundary curves, or `Mesh.HighOrderOptimize = 2;`",
                self.element_tags[e]
            )));
        }
        let mut counts: BTreeMap<i32, [usize; 2]> = BTreeMap::new();
        for (e, o) in orientations.iter().enumerate() {
            counts.entry(self.surfaces[e]).or_default()
                [usize::from(*o == Orientation::Clockwise)] += 1;
        }
        let clockwise = |e: usize| {
            let [ccw, cw] = counts[&self.surfaces[e]];
            cw > ccw
        };
        let against: Vec<usize> = (0..self.elements.len())
            .filter(|&e| clockwise(e) != (orientations[e] == Orientation::Clockwise))
            .collect();
        if let Some(&first) = against.first() {
            return Err(self.inverted(
                source,
                &against,
                clockwise(first),
                counts[&self.surfaces[first]],
            ));
        }
        for e in (0..self.elements.len()).filter(|&e| clockwise(e)) {
            let (kind, nodes) = &mut self.elements[e];
            *nodes = geometry::reversed(*kind)
                .iter()
                .map(|&a| nodes[a])
                .collect();
        }
        Ok(())
    }

    /// The error of elements `against` their surface (of the first's surface, with `counts`
    /// counter-clockwise and clockwise elements).
    fn inverted(
        &self,
        source: &str,
        against: &[usize],
        clockwise: bool,
        counts: [usize; 2],
    ) -> Error {
        let tags: Vec<String> = against
            .iter()
            .take(LISTED)
            .map(|&e| self.element_tags[e].to_string())
            .collect();
        let elements = match against.len() {
            1 => format!("element {} is", tags[0]),
            n if n <= LISTED => format!("elements {} are", tags.join(", ")),
            n => format!("elements {}, … ({n} in all) are", tags.join(", ")),
        };
        let (theirs, rest) = if clockwise {
            ("counter-clockwise", "clockwise")
        } else {
            ("clockwise", "counter-clockwise")
        };
        Error::Mesh(format!(
            "{source}: Gmsh {elements} inverted (negative Jacobian determinant): {theirs}, \
             while {} of the {} elements of surface {} run {rest}",
            counts[usize::from(clockwise)],
            counts[0] + counts[1],
            self.surfaces[against[0]],
        ))
    }

    /// Two nodes at one point (closer than [`DUPLICATE_NODE_FRACTION`] of the shortest element
    /// edge in x and in y) are refused: surfaces meshed separately along a shared curve.
    /// The nodes are sorted by the cell of that size they fall in: a pair lies in one cell or
    /// in neighbouring ones, found by searching the sorted cells.
    pub fn refuse_duplicate_nodes(&self, source: &str) -> Result<()> {
        let tol = DUPLICATE_NODE_FRACTION * self.shortest_edge();
        let mut cells: Vec<(i64, i64, usize)> = (self.nodes.iter().enumerate())
            .map(|(n, p)| ((p[0] / tol).floor() as i64, (p[1] / tol).floor() as i64, n))
            .collect();
        cells.sort_unstable();
        let near = |n: usize, m: usize| {
            let (p, q) = (self.nodes[n], self.nodes[m]);
            (p[0] - q[0]).abs() <= tol && (p[1] - q[1]).abs() <= tol
        };
        for (k, &(i, j, n)) in cells.iter().enumerate() {
            // Cells (i, j) and (i, j + 1) follow in order; (i + 1, j − 1 ..= j + 1) are found.
            let column = cells[k + 1..]
                .iter()
                .take_while(|c| c.0 == i && c.1 <= j.saturating_add(1));
            let next = (i.saturating_add(1), j.saturating_sub(1));
            let from = cells.partition_point(|c| (c.0, c.1) < next);
            let beside = cells[from..]
                .iter()
                .take_while(|c| c.0 == next.0 && c.1 <= j.saturating_add(1));
            if let Some(&(_, _, m)) = column.chain(beside).find(|c| near(n, c.2)) {
                let p = self.nodes[n];
                return Err(Error::Mesh(format!(
                    "{source}: nodes {} and {} lie at one point ({}, {}): two surfaces are meshed \
                     separately along a curve they share; join them with `Coherence Mesh;` after \
                     meshing (`gmsh.model.mesh.removeDuplicateNodes()`), or fragment the \
                     geometry before (`BooleanFragments`); if they are two bodies in contact, \
                     import each by its physical group",
                    self.node_tags[n.min(m)],
                    self.node_tags[n.max(m)],
                    p[0],
                    p[1]
                )));
            }
        }
        Ok(())
    }

    /// The shortest distance between the corners of an element face.
    fn shortest_edge(&self) -> f64 {
        (0..self.elements.len())
            .flat_map(|element| {
                (0..self.elements[element].0.n_faces()).map(move |local| Face { element, local })
            })
            .map(|f| {
                let [a, _, b] = self.face_nodes(f);
                let (p, q) = (self.nodes[a], self.nodes[b]);
                (p[0] - q[0]).hypot(p[1] - q[1])
            })
            .fold(f64::INFINITY, f64::min)
    }
}
