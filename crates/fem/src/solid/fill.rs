//! The size of a solid's Cholesky factor before its stiffness is assembled, counted on the
//! graph of its nodes (two nodes are neighbours when an element holds both), eliminated node
//! by node in the order their unknowns will be. A node's free unknowns share its neighbours,
//! so the unknowns fill in as their nodes do, each entry of the nodes' factor an fᵢ × fⱼ block
//! of the unknowns' (fᵢ the free unknowns of node i; George and Liu's quotient graphs), and a
//! fundamental supernode of the nodes is one of the unknowns. The count is the values a
//! supernodal factor of the unknowns stores without relaxation (each supernode's whole
//! diagonal block and its rows below), exactly; the factor made stores more (relaxed
//! supernodes keep zeros), never less, so a refusal on the count never refuses a factor that
//! would fit.

use contopt_core::{Error, Result};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::{SupernodalThreshold, SymbolicSupernodalParams};
use faer::sparse::{FaerError, SymbolicSparseColMatRef};
use faer::Side;

use crate::dissection::Adjacency;

/// The supernodal symbolic Cholesky analysis of the upper triangle `pattern` in its own order,
/// without relaxed supernodes: the factor whose values [`factor_values`] counts.
fn unrelaxed(
    pattern: SymbolicSparseColMatRef<'_, usize>,
) -> Result<SymbolicCholesky<usize>, FaerError> {
    factorize_symbolic_cholesky(
        pattern,
        Side::Upper,
        SymmetricOrdering::Identity,
        CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            supernodal_params: SymbolicSupernodalParams { relax: None },
            ..Default::default()
        },
    )
}

/// The values of the supernodal Cholesky factor, without relaxation, of the unknowns of
/// `nodes` eliminated in that order (position → node; each node's `free[node]` unknowns in
/// turn), from the symbolic analysis of the nodes' graph `graph`: Σ over its fundamental
/// supernodes of F (F + B), F the supernode's unknowns, B those of its rows below.
pub(super) fn factor_values(
    graph: &Adjacency,
    free: &[usize],
    nodes: &[usize],
    body: &str,
) -> Result<u64> {
    let n = nodes.len();
    let mut position = vec![usize::MAX; free.len()];
    for (p, &node) in nodes.iter().enumerate() {
        position[node] = p;
    }
    // The upper triangle of the nodes' graph in elimination order.
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0);
    for (q, &node) in nodes.iter().enumerate() {
        let start = row_idx.len();
        row_idx.extend(
            graph
                .of(node)
                .iter()
                .map(|&m| position[m])
                .filter(|&p| p < q),
        );
        row_idx.push(q);
        row_idx[start..].sort_unstable();
        col_ptr.push(row_idx.len());
    }
    let pattern = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
    let symbolic = unrelaxed(pattern).map_err(|e| Error::Singular {
        body: body.into(),
        detail: format!("symbolic analysis of the nodes' graph failed: {e:?}"),
    })?;
    let SymbolicCholeskyRaw::Supernodal(sn) = symbolic.raw() else {
        unreachable!("the analysis is forced supernodal")
    };
    let f = |p: usize| free[nodes[p]] as u64;
    let count = (0..sn.n_supernodes())
        .map(|s| {
            let rows = &sn.row_idx()[sn.col_ptr_for_row_idx()[s]..sn.col_ptr_for_row_idx()[s + 1]];
            let below: u64 = rows.iter().map(|&r| f(r)).sum();
            let columns: u64 = (sn.supernode_begin()[s]..sn.supernode_end()[s])
                .map(f)
                .sum();
            columns * (columns + below)
        })
        .sum();
    Ok(count)
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::SymbolicSparseColMat;

    /// A row of `n` 8-node cubes, one unit apart, as node lists.
    fn bar(n: usize) -> Vec<Vec<usize>> {
        (0..n)
            .map(|i| (0..8).map(|c| 4 * (i + c / 4) + c % 4).collect())
            .collect()
    }

    /// The count on the nodes' graph is the supernodal symbolic analysis, without relaxation,
    /// of the unknowns' graph (every pair of free unknowns of two neighbouring nodes, or of
    /// one node), for nodes with 0 to 3 free unknowns in a scrambled elimination order.
    #[test]
    fn the_nodes_count_is_the_unknowns_factor() {
        let cubes = bar(6);
        let n_nodes = 4 * 7;
        let graph = Adjacency::of_elements(n_nodes, cubes.iter().map(Vec::as_slice));
        let free: Vec<usize> = (0..n_nodes).map(|k| [3, 2, 3, 1, 3, 0][k % 6]).collect();
        let nodes: Vec<usize> = (0..n_nodes)
            .map(|k| (11 * k + 5) % n_nodes)
            .filter(|&k| free[k] > 0)
            .collect();
        let counted = factor_values(&graph, &free, &nodes, "bar").unwrap();
        // The unknowns, node after node in elimination order.
        let first: Vec<usize> = (nodes.iter())
            .scan(0, |next, &k| {
                let at = *next;
                *next += free[k];
                Some(at)
            })
            .collect();
        let mut at = vec![usize::MAX; n_nodes];
        for (p, &k) in nodes.iter().enumerate() {
            at[k] = first[p];
        }
        let n: usize = free.iter().sum();
        let mut pairs = Vec::new();
        for &k in &nodes {
            for &m in graph.of(k).iter().chain([k].iter()) {
                if free[m] == 0 {
                    continue;
                }
                for i in at[m]..at[m] + free[m] {
                    for j in at[k]..at[k] + free[k] {
                        if i <= j {
                            pairs.push(faer::sparse::Pair::new(i, j));
                        }
                    }
                }
            }
        }
        let (pattern, _) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs).unwrap();
        let symbolic = unrelaxed(pattern.as_ref()).unwrap();
        assert_eq!(counted, symbolic.len_val() as u64);
        // Fill happened: the count is more than the graph's own upper triangle.
        assert!(counted > pairs.len() as u64, "{counted} {}", pairs.len());
    }
}
