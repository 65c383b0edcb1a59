//! Nested dissection of a mesh's nodes by their coordinates (George 1973; the geometric
//! variant of Miller, Teng, Thurston and Vavasis 1998): the nodes are cut by the smallest of a
//! few planes near the median across each axis, the nodes on one side touching the
//! other (the separator) are numbered last, and each half is cut again. A separator's unknowns
//! fill in among themselves only, so a 3-D mesh's factor grows as n^(4/3) rather than the
//! faster growth minimum-degree orderings show on quadratic solids.

use crate::system::Dof;

/// Node sets this small are not cut further; their nodes keep their order.
const LEAF_NODES: usize = 64;

/// Where a set may be cut, as fractions of its nodes sorted along the longest side: the plane
/// with the fewest separator nodes wins (so that a cut lands between element layers), the
/// most even of those on a tie.
const CUTS: [f64; 5] = [0.4, 0.45, 0.5, 0.55, 0.6];

/// Which nodes share an element with which (compressed rows, each node's neighbours).
pub(crate) struct Adjacency {
    start: Vec<usize>,
    neighbours: Vec<usize>,
}

impl Adjacency {
    /// The graph of `n_nodes` nodes in which two nodes are neighbours when an element holds
    /// both.
    pub fn of_elements<'a>(n_nodes: usize, elements: impl Iterator<Item = &'a [usize]>) -> Self {
        let mut lists: Vec<Vec<usize>> = vec![Vec::new(); n_nodes];
        for conn in elements {
            for &a in conn {
                lists[a].extend(conn.iter().filter(|&&b| b != a));
            }
        }
        let mut start = Vec::with_capacity(n_nodes + 1);
        let mut neighbours = Vec::new();
        start.push(0);
        for mut list in lists {
            list.sort_unstable();
            list.dedup();
            neighbours.extend(list);
            start.push(neighbours.len());
        }
        Self { start, neighbours }
    }

    /// The neighbours of `node`, ascending.
    pub fn of(&self, node: usize) -> &[usize] {
        &self.neighbours[self.start[node]..self.start[node + 1]]
    }
}

/// The nodes in elimination order (position → node): every separator after the two halves it
/// separates.
pub(crate) fn nested_dissection(points: &[[f64; 3]], graph: &Adjacency) -> Vec<usize> {
    let mut order = Vec::with_capacity(points.len());
    let mut side = vec![Side::Out; points.len()];
    let mut stack = vec![Task::Cut((0..points.len()).collect())];
    while let Some(task) = stack.pop() {
        match task {
            Task::Number(nodes) => order.extend(nodes),
            Task::Cut(nodes) if nodes.len() <= LEAF_NODES => order.extend(nodes),
            Task::Cut(nodes) => {
                let [a, b, separator] = bisect(nodes, points, graph, &mut side);
                // Popped in reverse: the first half, the second, then the separator.
                stack.push(Task::Number(separator));
                stack.push(Task::Cut(b));
                stack.push(Task::Cut(a));
            }
        }
    }
    order
}

enum Task {
    Cut(Vec<usize>),
    Number(Vec<usize>),
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    Out,
    Below,
    Above,
}

/// The two halves of `nodes` and their separator, by the best of [`CUTS`] across each of the
/// three axes: the fewest separator nodes, the most even split on a tie. Every axis is tried,
/// not only the longest side: on a mesh graded towards its contact the longest side may have
/// the most nodes on a plane across it. `side` is all [`Side::Out`] on entry and on return.
fn bisect(
    nodes: Vec<usize>,
    points: &[[f64; 3]],
    graph: &Adjacency,
    side: &mut [Side],
) -> [Vec<usize>; 3] {
    let mut best: Option<(Vec<usize>, usize, Vec<usize>)> = None;
    for axis in [0, 1, 2] {
        let mut sorted = nodes.clone();
        sorted.sort_by(|&a, &b| points[a][axis].total_cmp(&points[b][axis]));
        let split_at = |fraction: f64| {
            let value = points[sorted[(fraction * sorted.len() as f64) as usize]][axis];
            sorted.partition_point(|&k| points[k][axis] < value)
        };
        let mut splits: Vec<usize> = CUTS.iter().map(|&f| split_at(f)).collect();
        splits.retain(|&k| k > 0 && k < sorted.len());
        for k in splits {
            let cut = separator(&sorted, k, graph, side);
            let key = |cut: &[usize], k: usize| (cut.len(), (2 * k).abs_diff(sorted.len()));
            if best
                .as_ref()
                .is_none_or(|(c, b, _)| key(&cut, k) < key(c, *b))
            {
                best = Some((cut, k, sorted.clone()));
            }
        }
    }
    match best {
        Some((cut, k, sorted)) => halves(sorted, k, cut, side),
        // Every node on one point: split the list in the middle instead.
        None => {
            let k = nodes.len() / 2;
            let cut = separator(&nodes, k, graph, side);
            halves(nodes, k, cut, side)
        }
    }
}

/// The smaller of the two one-sided separators of the split of `nodes` at `k`: the nodes
/// below that touch a node above, or those above that touch one below.
fn separator(nodes: &[usize], k: usize, graph: &Adjacency, side: &mut [Side]) -> Vec<usize> {
    for (i, &n) in nodes.iter().enumerate() {
        side[n] = if i < k { Side::Below } else { Side::Above };
    }
    let touching = |range: &[usize], other: Side| -> Vec<usize> {
        range
            .iter()
            .copied()
            .filter(|&n| graph.of(n).iter().any(|&m| side[m] == other))
            .collect()
    };
    let below = touching(&nodes[..k], Side::Above);
    let above = touching(&nodes[k..], Side::Below);
    for &n in nodes {
        side[n] = Side::Out;
    }
    if below.len() <= above.len() {
        below
    } else {
        above
    }
}

/// The nodes below and above `k` outside the separator `cut`, and `cut`.
fn halves(nodes: Vec<usize>, k: usize, cut: Vec<usize>, side: &mut [Side]) -> [Vec<usize>; 3] {
    for &n in &cut {
        side[n] = Side::Below;
    }
    let keep = |list: &[usize], side: &[Side]| -> Vec<usize> {
        list.iter()
            .copied()
            .filter(|&n| side[n] == Side::Out)
            .collect()
    };
    let a = keep(&nodes[..k], side);
    let b = keep(&nodes[k..], side);
    for &n in &cut {
        side[n] = Side::Out;
    }
    [a, b, cut]
}

/// The free unknowns of `dofs` (3 per node) node after node in the order `nodes`, each
/// node's in turn: position → unknown, what [`crate::factor::Factor::permuted`] takes.
pub(crate) fn unknowns_of(nodes: &[usize], dofs: &[Dof]) -> Vec<usize> {
    (nodes.iter())
        .flat_map(|&node| 3 * node..3 * node + 3)
        .filter_map(|g| match dofs[g] {
            Dof::Free(i) => Some(i),
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 9 × 9 × 9 lattice of nodes, each element a unit cube of 8 corners.
    fn lattice(n: usize) -> (Vec<[f64; 3]>, Adjacency) {
        let id = |i: usize, j: usize, k: usize| (k * n + j) * n + i;
        let points = (0..n * n * n)
            .map(|m| [(m % n) as f64, ((m / n) % n) as f64, (m / (n * n)) as f64])
            .collect();
        let mut cubes = Vec::new();
        for k in 0..n - 1 {
            for j in 0..n - 1 {
                for i in 0..n - 1 {
                    let c: Vec<usize> = (0..8)
                        .map(|b| id(i + (b & 1), j + ((b >> 1) & 1), k + (b >> 2)))
                        .collect();
                    cubes.push(c);
                }
            }
        }
        let graph = Adjacency::of_elements(n * n * n, cubes.iter().map(Vec::as_slice));
        (points, graph)
    }

    /// Every node is numbered once, and the last nodes are the first cut: one plane of the
    /// lattice (n² nodes), all at one coordinate, which no element crosses.
    #[test]
    fn the_first_separator_is_a_plane_numbered_last() {
        let n = 9;
        let (points, graph) = lattice(n);
        let order = nested_dissection(&points, &graph);
        let mut seen = order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..n * n * n).collect::<Vec<_>>());
        let last = &order[order.len() - n * n..];
        let plane = (0..3).find(|&a| last.iter().all(|&m| points[m][a] == points[last[0]][a]));
        assert!(plane.is_some(), "{:?}", &last[..5]);
        let axis = plane.unwrap_or(0);
        let before = &order[..order.len() - n * n];
        assert!(before
            .iter()
            .all(|&m| points[m][axis] != points[last[0]][axis]));
    }
}
