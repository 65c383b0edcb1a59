//! Which of a solid's samples carry a pressure of their own. The samples' influence is
//! C = S K⁻¹ Sᵀ, S the samples' read-out of the face nodes' displacements (each row a
//! sample's cell mean of the faces' shape functions, [`SolidSample`]): C is singular exactly
//! where the rows of S are dependent, as where a grid's cells are finer than the faces under
//! them — anywhere on the face, not only in a count over all of it (a face meshed fine away
//! from the contact and coarse under it has more nodes than cells in all, and a singular C
//! where the pressure is).

use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap, HashMap};

use super::mesh::SolidMesh;
use super::sample::SolidSample;

/// A row is a combination of the rows before it when what is left of it after their
/// elimination is below this fraction of its own largest weight. An exact dependence leaves
/// round-off, 10⁻¹⁵ of the weights and a few times that after elimination; a cell whose mean
/// differs from its neighbours' keeps a fraction of its weights of the order of the cell's
/// share of its faces (10⁻² on a face of 100 cells).
pub const DEPENDENT: f64 = 1e-8;

/// The samples whose read-out rows are combinations of the rows of the samples before them,
/// in order: their count is the rank deficiency of S (and of the influence C), and each lies
/// where its cell's mean adds nothing the cells before it did not read. Sparse Gaussian
/// elimination row by row, each pivot the largest weight left in its row; empty when S has
/// full row rank.
pub fn dependent_samples(mesh: &SolidMesh, samples: &[SolidSample]) -> Vec<usize> {
    let mut echelon = Echelon::default();
    (samples.iter().enumerate())
        .filter(|(_, s)| !echelon.add(s.node_weights(mesh)))
        .map(|(i, _)| i)
        .collect()
}

/// Rows reduced against each other: each holds zeros at the pivot columns of the rows before
/// it, so that eliminating a new row with them in their order leaves it zero at every pivot
/// column.
#[derive(Default)]
struct Echelon {
    /// The rows in the order they came.
    rows: Vec<Pivoted>,
    /// The row whose pivot each column is.
    pivot_of: HashMap<usize, usize>,
}

/// A reduced row: its pivot column and value, and its other entries.
struct Pivoted {
    column: usize,
    value: f64,
    rest: Vec<(usize, f64)>,
}

impl Echelon {
    /// Reduces `row` (column, value) against the rows so far and keeps it; false when nothing
    /// of it is left ([`DEPENDENT`]).
    fn add(&mut self, row: Vec<(usize, f64)>) -> bool {
        let scale = row.iter().fold(0.0f64, |m, &(_, v)| m.max(v.abs()));
        // Ordered, so that ties between weights pick one pivot on every run.
        let mut left: BTreeMap<usize, f64> = row.into_iter().collect();
        let mut queue: BinaryHeap<Reverse<usize>> = (left.keys())
            .filter_map(|c| self.pivot_of.get(c).map(|&r| Reverse(r)))
            .collect();
        while let Some(Reverse(r)) = queue.pop() {
            let pivoted = &self.rows[r];
            let Some(value) = left.remove(&pivoted.column) else {
                continue;
            };
            let factor = value / pivoted.value;
            for &(c, v) in &pivoted.rest {
                let entry = left.entry(c).or_insert_with(|| {
                    if let Some(&q) = self.pivot_of.get(&c) {
                        queue.push(Reverse(q));
                    }
                    0.0
                });
                *entry -= factor * v;
            }
        }
        let largest = left
            .iter()
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
            .map(|(&c, &v)| (c, v));
        match largest {
            Some((column, value)) if value.abs() > DEPENDENT * scale => {
                self.pivot_of.insert(column, self.rows.len());
                left.remove(&column);
                self.rows.push(Pivoted {
                    column,
                    value,
                    rest: left.into_iter().collect(),
                });
                true
            }
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solid::{Cell, SolidKind};

    /// One face of the block's top, its cells `n` × `n` of 1/n mm.
    fn cells(n: usize, z: f64) -> Vec<Cell> {
        let h = 1.0 / n as f64;
        (0..n * n)
            .map(|k| {
                Cell::xy(
                    [((k % n) as f64 + 0.5) * h, ((k / n) as f64 + 0.5) * h, z],
                    [h; 2],
                )
            })
            .collect()
    }

    /// On one hexahedron's top face, the cells' means of its shape functions span at most its
    /// nodes: 9 (biquadratic) or 8 (serendipity); 2 × 2 cells read four independent means,
    /// 3 × 3 cells nine on the 9-node face and one more than the 8-node face has, and 4 × 4
    /// cells leave 16 − 9 and 16 − 8 dependent: each count exactly the cells beyond the
    /// nodes (a rule that found none, or every later cell, would fail).
    #[test]
    fn cells_beyond_the_face_nodes_are_dependent() {
        for (kind, nodes) in [(SolidKind::Hex27, 9), (SolidKind::Hex20, 8)] {
            let mesh = SolidMesh::block(kind, [1.0; 3], [1; 3]).unwrap();
            let top = mesh.faces_where(|x| (x[2] - 1.0).abs() < 1e-9);
            for n in [2usize, 3, 4] {
                let samples =
                    SolidSample::cells(&mesh, &top, &cells(n, 1.0), [0.0, 0.0, 1.0]).unwrap();
                let dependent = dependent_samples(&mesh, &samples);
                assert_eq!(
                    dependent.len(),
                    (n * n).saturating_sub(nodes),
                    "{kind:?}, {n} x {n} cells: {dependent:?}"
                );
            }
        }
    }

    /// A face of 2 × 2 elements against 4 × 4 cells (each element under 2 × 2 of them) has
    /// 25 nodes for 16 cells: none dependent; the 1 × 1 element under the same cells, 9
    /// nodes: 7 dependent.
    #[test]
    fn cells_no_finer_than_their_faces_are_independent() {
        for (elements, dependent) in [(2, 0), (1, 7)] {
            let mesh =
                SolidMesh::block(SolidKind::Hex27, [1.0; 3], [elements, elements, 1]).unwrap();
            let top = mesh.faces_where(|x| (x[2] - 1.0).abs() < 1e-9);
            let samples = SolidSample::cells(&mesh, &top, &cells(4, 1.0), [0.0, 0.0, 1.0]).unwrap();
            assert_eq!(dependent_samples(&mesh, &samples).len(), dependent);
        }
    }
}
