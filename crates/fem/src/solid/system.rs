//! The assembled and factorised stiffness system ([`System`]) of a solid, with its free rigid
//! motions, and the solve of a supported model through it ([`SolidModel::solve`]).

use std::time::Instant;

use contopt_core::{check, memory, Error, Result};

use super::fill::factor_values;
use super::model::SolidModel;
use crate::dissection::{nested_dissection, unknowns_of, Adjacency};
use crate::factor::{Factor, Ordering};
use crate::system::{free_rigid_modes, pins, Dof, RigidMotion, System, Triplets};

/// What to do with rigid motions the supports leave free.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Pinning {
    /// Refuse them: the model must be supported.
    Refuse,
    /// Hold one unknown per free motion and carry the motions separately (a body in contact).
    Pin,
}

/// Bytes per assembled entry of the stiffness's upper triangle: a (row, column) pair and a
/// value, and their sorted copy in the sparse matrix.
const BYTES_PER_ENTRY: u64 = 2 * (16 + 8);

impl System {
    /// Numbers, assembles and factorises a solid `model`'s stiffness with the unknowns of
    /// `tail_nodes` last, the others ordered by `ordering`. The memory is checked against
    /// `limit` \[bytes\] before anything large is allocated: the factor's first, counted on
    /// the nodes' graph (module `solid::fill`) for the orderings made on the nodes (nested
    /// dissection, natural); then the assembly's, from the elements; and the factor's again,
    /// exactly, after its symbolic analysis, whatever the ordering.
    pub fn solid(
        model: &SolidModel,
        name: &str,
        tail_nodes: &[usize],
        pinning: Pinning,
        ordering: Ordering,
        limit: u64,
    ) -> Result<Self> {
        let (dofs, modes) = numbering(model, tail_nodes, pinning)?;
        let n_free = dofs.iter().filter(|d| matches!(d, Dof::Free(_))).count();
        let tail: std::collections::HashSet<usize> = tail_nodes.iter().copied().collect();
        let n_tail = (0..dofs.len())
            .filter(|&g| tail.contains(&(g / 3)) && matches!(dofs[g], Dof::Free(_)))
            .count();
        let start = Instant::now();
        let nodes = match elimination_nodes(model, &dofs, &tail, ordering) {
            Some((graph, free, nodes)) => {
                let values = factor_values(&graph, &free, &nodes, name)?;
                memory::require(
                    format!(
                        "{name}: the Cholesky factor of {n_free} unknowns (at least \
                         {values} values, counted on the nodes' graph before assembly)"
                    ),
                    memory::bytes(&[values as usize], 8),
                    limit,
                    "use fewer elements (coarser away from the contact)",
                )?;
                Some(nodes)
            }
            None => None,
        };
        let ordering_time = start.elapsed();
        let entries = assembly_entries(model, name, limit)?;
        let start = Instant::now();
        let triplets = assemble(model, &dofs, entries)?;
        let matrix = triplets.matrix(n_free)?;
        drop(triplets.idx);
        let assembly_time = start.elapsed();
        let start = Instant::now();
        let factor = match (ordering, nodes) {
            (Ordering::Dissection, Some(nodes)) => {
                let order = unknowns_of(&nodes, &dofs);
                Factor::permuted(matrix.as_ref(), n_tail, name, order, limit)?
            }
            _ => Factor::ordered(matrix.as_ref(), n_tail, name, ordering, limit)?,
        };
        Ok(Self {
            dofs,
            n_free,
            n_tail,
            modes,
            prescribed_load: triplets.prescribed_load,
            factor,
            assembly_time,
            factorisation_time: ordering_time + start.elapsed(),
        })
    }
}

impl SolidModel {
    /// Solves the supported model under its given loads: nodal displacements (3 per node).
    /// Errors when the supports leave a rigid motion free.
    pub fn solve(&self) -> Result<Vec<f64>> {
        let system = System::solid(
            self,
            "model",
            &[],
            Pinning::Refuse,
            Ordering::Amd,
            memory::BODY_LIMIT_BYTES,
        )?;
        let u = system.solve(&self.forces, None);
        self.check_displacement(&u)?;
        Ok(u)
    }

    /// The rigid motions its supports leave free (what [`crate::solid::SolidBody`] pins and
    /// reports as its rigid modes), without assembling anything: the 3-D counterpart of
    /// [`crate::FeModel::free_motions`].
    pub fn free_motions(&self) -> Result<Vec<RigidMotion>> {
        Ok(numbering(self, &[], Pinning::Pin)?.1)
    }

    /// Every nodal displacement is finite, else the loads or the material are beyond f64.
    pub(crate) fn check_displacement(&self, u: &[f64]) -> Result<()> {
        check::all_derived("loads", "the given loads", "the displacements", u)
    }
}

/// The entries the assembly of `model`'s element stiffnesses holds (each element's upper
/// triangle), when their memory is within `limit` \[bytes\].
fn assembly_entries(model: &SolidModel, name: &str, limit: u64) -> Result<usize> {
    let mesh = &model.mesh;
    let entries: usize = (0..mesh.n_elements())
        .map(|e| {
            let m = 3 * mesh.kind(e).n_nodes();
            m * (m + 1) / 2
        })
        .sum();
    memory::require(
        format!(
            "{name}: assembling a solid of {} nodes and {} elements",
            mesh.nodes().len(),
            mesh.n_elements()
        ),
        memory::bytes(&[entries], BYTES_PER_ENTRY),
        limit,
        "use fewer elements",
    )?;
    Ok(entries)
}

/// The nodes' graph, each node's free unknowns, and the nodes with a free unknown in the
/// order their unknowns are eliminated (those of `tail` last, in index order, as
/// [`numbering`] numbers them), for the orderings made on the nodes: nested dissection of
/// their coordinates, or their numbering; none for AMD, which orders the assembled matrix.
fn elimination_nodes(
    model: &SolidModel,
    dofs: &[Dof],
    tail: &std::collections::HashSet<usize>,
    ordering: Ordering,
) -> Option<(Adjacency, Vec<usize>, Vec<usize>)> {
    let mesh = &model.mesh;
    let n_nodes = mesh.nodes().len();
    let graph = || Adjacency::of_elements(n_nodes, (0..mesh.n_elements()).map(|e| mesh.element(e)));
    let (graph, order) = match ordering {
        Ordering::Amd => return None,
        Ordering::Natural => (graph(), (0..n_nodes).collect()),
        Ordering::Dissection => {
            let graph = graph();
            let order = nested_dissection(mesh.nodes(), &graph);
            (graph, order)
        }
    };
    let free: Vec<usize> = (0..n_nodes)
        .map(|k| {
            (dofs[3 * k..3 * k + 3].iter())
                .filter(|d| matches!(d, Dof::Free(_)))
                .count()
        })
        .collect();
    let leading = order.into_iter().filter(|k| !tail.contains(k));
    let trailing = (0..n_nodes).filter(|k| tail.contains(k));
    let nodes = leading.chain(trailing).filter(|&k| free[k] > 0).collect();
    Some((graph, free, nodes))
}

/// Status of every DOF (3·node + axis) with the free unknowns numbered, those of
/// `tail_nodes` last, and the free rigid motions (pinned, or refused).
fn numbering(
    model: &SolidModel,
    tail_nodes: &[usize],
    pinning: Pinning,
) -> Result<(Vec<Dof>, Vec<RigidMotion>)> {
    let n_nodes = model.mesh.nodes().len();
    let mut dofs = vec![Dof::Free(usize::MAX); 3 * n_nodes];
    for (&(node, c), &v) in &model.prescribed {
        dofs[3 * node + c] = Dof::Prescribed(v);
    }
    let mut on_tail = vec![false; 3 * n_nodes];
    for &n in tail_nodes {
        on_tail[3 * n..3 * n + 3].fill(true);
    }
    let modes = free_rigid_modes(candidate_modes(model), &dofs)?;
    match pinning {
        Pinning::Refuse if !modes.is_empty() => {
            let names: Vec<&str> = modes.iter().map(|m| m.name.as_str()).collect();
            return Err(Error::invalid(
                "supports",
                names.join(", "),
                "leave these rigid motions free: hold the solid (or use it as a contact body)",
            ));
        }
        Pinning::Refuse => {}
        Pinning::Pin => {
            for g in pins(&modes, &dofs, &on_tail) {
                dofs[g] = Dof::Pinned;
            }
        }
    }
    let mut n_free = 0;
    for tail in [false, true] {
        for (g, d) in dofs.iter_mut().enumerate() {
            if on_tail[g] == tail && matches!(d, Dof::Free(_)) {
                *d = Dof::Free(n_free);
                n_free += 1;
            }
        }
    }
    if n_free == 0 {
        return Err(Error::invalid(
            "supports",
            "every degree of freedom",
            "leave at least one unknown",
        ));
    }
    Ok((dofs, modes))
}

/// The solid's six rigid motions: translations along x, y, z and rotations about the axes
/// through the nodes' centroid.
fn candidate_modes(model: &SolidModel) -> Vec<RigidMotion> {
    let nodes = model.mesh.nodes();
    let n = nodes.len() as f64;
    let c = nodes.iter().fold([0.0; 3], |s, p| {
        [s[0] + p[0] / n, s[1] + p[1] / n, s[2] + p[2] / n]
    });
    let field = |f: &dyn Fn([f64; 3]) -> [f64; 3]| -> Vec<f64> {
        nodes
            .iter()
            .flat_map(|p| f([p[0] - c[0], p[1] - c[1], p[2] - c[2]]))
            .collect()
    };
    let motion = |name: &str, f: &dyn Fn([f64; 3]) -> [f64; 3]| RigidMotion {
        name: name.into(),
        values: field(f),
    };
    vec![
        motion("x translation", &|_| [1.0, 0.0, 0.0]),
        motion("y translation", &|_| [0.0, 1.0, 0.0]),
        motion("z translation", &|_| [0.0, 0.0, 1.0]),
        motion("rotation about x", &|p| [0.0, -p[2], p[1]]),
        motion("rotation about y", &|p| [p[2], 0.0, -p[0]]),
        motion("rotation about z", &|p| [-p[1], p[0], 0.0]),
    ]
}

/// The element stiffnesses over the free unknowns of `dofs` (upper triangle), with K_fp u_p;
/// `entries` is the count reserved.
fn assemble(model: &SolidModel, dofs: &[Dof], entries: usize) -> Result<Triplets> {
    let n_free = dofs.iter().filter(|d| matches!(d, Dof::Free(_))).count();
    let mut t = Triplets {
        idx: Vec::with_capacity(entries),
        val: Vec::with_capacity(entries),
        prescribed_load: vec![0.0; n_free],
    };
    for e in 0..model.mesh.n_elements() {
        let ke = model.element_stiffness(e)?;
        let conn = model.mesh.element(e);
        let m = 3 * conn.len();
        let g = |k: usize| 3 * conn[k / 3] + k % 3;
        for kb in 0..m {
            let Dof::Free(j) = dofs[g(kb)] else { continue };
            for ka in 0..m {
                match dofs[g(ka)] {
                    Dof::Free(i) if i <= j => {
                        t.idx.push(faer::sparse::Pair::new(i, j));
                        t.val.push(ke[ka * m + kb]);
                    }
                    Dof::Prescribed(v) if v != 0.0 => t.prescribed_load[j] += ke[kb * m + ka] * v,
                    _ => {}
                }
            }
        }
    }
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::factor::factorisations;
    use crate::solid::{Axis, SolidKind, SolidMesh};
    use contopt_core::Material;

    /// A factor past the limit is refused before the assembly, its size counted on the nodes'
    /// graph: the error names that size and the limit, and no factorisation is made. The count
    /// leaves out the relaxed supernodes' zeros, so it is at most what the factor then stores,
    /// and not far below it.
    #[test]
    fn a_factor_past_the_limit_is_refused_before_assembly() {
        let mesh = SolidMesh::block(SolidKind::Hex20, [1.0, 1.0, 1.0], [5, 5, 5]).unwrap();
        let mut model = SolidModel::new(mesh, Material::new(2e5, 0.3).unwrap());
        let bottom = model.mesh().nodes_where(|x| x[2].abs() < 1e-9);
        for axis in Axis::ALL {
            model.fix(&bottom, axis).unwrap();
        }
        let top = model.mesh().faces_where(|x| (x[2] - 1.0).abs() < 1e-9);
        let face = model.mesh().nodes_of(&top);
        let build = |limit| {
            System::solid(
                &model,
                "block",
                &face,
                Pinning::Pin,
                Ordering::Dissection,
                limit,
            )
        };
        let stored = 8 * build(memory::BODY_LIMIT_BYTES).unwrap().factor.factor_nnz() as u64;
        let limit = 1_000_000;
        let before = factorisations();
        let Err(refused) = build(limit) else {
            panic!("not refused")
        };
        assert_eq!(factorisations(), before);
        let Error::TooLarge { bytes, .. } = refused else {
            panic!("{refused}")
        };
        let message = refused.to_string();
        assert!(message.contains("counted on the nodes' graph"), "{message}");
        let megabytes = format!(
            "would take {} MB, over the limit of 1 MB",
            bytes / 1_000_000
        );
        assert!(message.contains(&megabytes), "{message}");
        assert!(bytes <= stored, "{bytes} > {stored}");
        assert!(
            bytes as f64 > COUNTED_SHARE * stored as f64,
            "{bytes} of {stored}"
        );
    }

    /// The least share of the factor's storage the count on the nodes' graph gives on the
    /// test's block (measured: 0.976; L's lower triangle alone would be 0.750).
    const COUNTED_SHARE: f64 = 0.9;
}
