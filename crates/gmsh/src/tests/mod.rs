//! Tests on the meshes of `meshes/` (made by Gmsh) and on small files written here.

mod errors;
mod hostile;
mod meshes;
mod solids;

use std::collections::HashMap;

use contopt_fem::Face;

use crate::body::Body;
use crate::{GmshMesh, Group};

/// The committed mesh `meshes/NAME`.
fn committed(name: &str) -> GmshMesh {
    let path = format!("{}/../../meshes/{name}", env!("CARGO_MANIFEST_DIR"));
    crate::read(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The group `name` of `groups`.
fn group<'a>(groups: &'a [Group], name: &str) -> &'a Group {
    groups
        .iter()
        .find(|g| g.name == name)
        .unwrap_or_else(|| panic!("no group {name}"))
}

/// Checks a curve group's faces: each a face of exactly one element (counted here, apart
/// from the reader), the body on the chain's left (the element's corner centroid left of
/// start → end), each face starting where the last ended within a chain, and the group's
/// nodes the chain's nodes in order. Returns the number of chains.
fn check_chain(body: &Body, g: &Group) -> usize {
    let mut uses: HashMap<(usize, usize), usize> = HashMap::new();
    for (element, (kind, _)) in body.elements.iter().enumerate() {
        for local in 0..kind.n_faces() {
            let [a, _, b] = body.face_nodes(Face { element, local });
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let mut chains = 0;
    let mut expected_nodes: Vec<usize> = Vec::new();
    for (k, &f) in g.faces.iter().enumerate() {
        let [a, m, b] = body.face_nodes(f);
        assert_eq!(
            uses[&(a.min(b), a.max(b))],
            1,
            "{}: face {f:?} is inside",
            g.name
        );
        let (kind, nodes) = &body.elements[f.element];
        let corners = if *kind == contopt_fem::ElementKind::T6 {
            3
        } else {
            4
        };
        let c = nodes[..corners].iter().fold([0.0, 0.0], |s, &n| {
            [
                s[0] + body.nodes[n][0] / corners as f64,
                s[1] + body.nodes[n][1] / corners as f64,
            ]
        });
        let (pa, pb) = (body.nodes[a], body.nodes[b]);
        let left = (pb[0] - pa[0]) * (c[1] - pa[1]) - (pb[1] - pa[1]) * (c[0] - pa[0]);
        assert!(
            left > 0.0,
            "{}: the body is not on the left of face {f:?}",
            g.name
        );
        let continues = k > 0 && body.face_nodes(g.faces[k - 1])[2] == a;
        if !continues {
            chains += 1;
            if !expected_nodes.contains(&a) {
                expected_nodes.push(a);
            }
        }
        for n in [m, b] {
            if !expected_nodes.contains(&n) {
                expected_nodes.push(n);
            }
        }
    }
    assert_eq!(g.nodes, expected_nodes, "{}: nodes along the chain", g.name);
    chains
}

/// A small mesh file, written here: nodes, element blocks, physical names and entities.
#[derive(Clone)]
struct Msh {
    version: &'static str,
    names: Vec<(usize, i32, &'static str)>,
    /// (dim, tag, physical tags).
    entities: Vec<(usize, i32, Vec<i32>)>,
    nodes: Vec<(u64, [f64; 3])>,
    blocks: Vec<Block>,
}

/// An element block of [`Msh`].
#[derive(Clone)]
struct Block {
    dim: usize,
    entity: i32,
    /// Gmsh's element type.
    kind: i32,
    /// Each element's tag and node tags.
    elements: Vec<(u64, Vec<u64>)>,
}

impl Block {
    fn new(dim: usize, entity: i32, kind: i32, elements: &[(u64, &[u64])]) -> Self {
        let elements = elements.iter().map(|(t, n)| (*t, n.to_vec())).collect();
        Self {
            dim,
            entity,
            kind,
            elements,
        }
    }
}

impl Msh {
    /// Two unit squares side by side, 8-node quadrilaterals (Gmsh tags 1 left, 2 right,
    /// counter-clockwise) on surface 1 ("body"); curve 1 "bottom" (two lines), curve 2 "top"
    /// (two lines), curve 3 "middle" (the shared side, empty of lines here), point 1
    /// "origin".
    fn two_squares() -> Self {
        let nodes = [
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.5, 0.0],
            [1.5, 0.0],
            [2.0, 0.5],
            [1.5, 1.0],
            [1.0, 0.5],
            [0.5, 1.0],
            [0.0, 0.5],
        ];
        Self {
            version: "4.1",
            names: vec![
                (0, 3, "origin"),
                (1, 1, "bottom"),
                (1, 2, "top"),
                (1, 5, "middle"),
                (2, 4, "body"),
            ],
            entities: vec![
                (0, 1, vec![3]),
                (1, 1, vec![1]),
                (1, 2, vec![2]),
                (1, 3, vec![5]),
                (2, 1, vec![4]),
            ],
            nodes: nodes
                .iter()
                .enumerate()
                .map(|(k, p)| (k as u64 + 1, [p[0], p[1], 0.0]))
                .collect(),
            blocks: vec![
                Block::new(0, 1, 15, &[(10, &[1])]),
                Block::new(1, 1, 8, &[(11, &[1, 2, 7]), (12, &[2, 3, 8])]),
                Block::new(1, 2, 8, &[(13, &[4, 5, 10]), (14, &[5, 6, 12])]),
                Block::new(
                    2,
                    1,
                    16,
                    &[
                        (1, &[1, 2, 5, 6, 7, 11, 12, 13]),
                        (2, &[2, 3, 4, 5, 8, 9, 10, 11]),
                    ],
                ),
            ],
        }
    }

    /// The file's text.
    fn text(&self) -> String {
        let mut s = format!("$MeshFormat\n{} 0 8\n$EndMeshFormat\n", self.version);
        s += &format!("$PhysicalNames\n{}\n", self.names.len());
        for (dim, tag, name) in &self.names {
            s += &format!("{dim} {tag} \"{name}\"\n");
        }
        s += "$EndPhysicalNames\n$Entities\n";
        let count = |d| self.entities.iter().filter(|e| e.0 == d).count();
        s += &format!("{} {} {} {}\n", count(0), count(1), count(2), count(3));
        for (dim, tag, physical) in &self.entities {
            let tags: Vec<String> = physical.iter().map(|t| t.to_string()).collect();
            let place = if *dim == 0 { "0 0 0" } else { "0 0 0 1 1 0" };
            let bounds = if *dim == 0 { "" } else { " 0" };
            s += &format!(
                "{tag} {place} {} {}{bounds}\n",
                physical.len(),
                tags.join(" ")
            );
        }
        s += "$EndEntities\n$Nodes\n";
        let (min, max) = self
            .nodes
            .iter()
            .fold((u64::MAX, 0), |(lo, hi), n| (lo.min(n.0), hi.max(n.0)));
        s += &format!(
            "1 {} {min} {max}\n2 1 0 {}\n",
            self.nodes.len(),
            self.nodes.len()
        );
        for (tag, _) in &self.nodes {
            s += &format!("{tag}\n");
        }
        for (_, [x, y, z]) in &self.nodes {
            s += &format!("{x} {y} {z}\n");
        }
        s += "$EndNodes\n$Elements\n";
        let total: usize = self.blocks.iter().map(|b| b.elements.len()).sum();
        s += &format!("{} {total} 1 {total}\n", self.blocks.len());
        for b in &self.blocks {
            s += &format!("{} {} {} {}\n", b.dim, b.entity, b.kind, b.elements.len());
            for (tag, nodes) in &b.elements {
                let nodes: Vec<String> = nodes.iter().map(|n| n.to_string()).collect();
                s += &format!("{tag} {}\n", nodes.join(" "));
            }
        }
        s + "$EndElements\n"
    }

    /// The file read.
    fn parse(&self) -> contopt_core::Result<GmshMesh> {
        crate::parse(self.text().as_bytes(), "t.msh")
    }

    /// The block of `dim` on `entity`.
    fn block(&mut self, dim: usize, entity: i32) -> &mut Block {
        self.blocks
            .iter_mut()
            .find(|b| b.dim == dim && b.entity == entity)
            .expect("a block")
    }

    /// Node `tag`'s coordinates.
    fn node(&mut self, tag: u64) -> &mut [f64; 3] {
        &mut self
            .nodes
            .iter_mut()
            .find(|n| n.0 == tag)
            .expect("a node")
            .1
    }

    /// The error of importing every surface.
    fn import_error(&self) -> String {
        let gmsh = self.parse().expect("the file reads");
        gmsh.import(crate::Surfaces::All).unwrap_err().to_string()
    }
}
