//! Named groups of points and curves on a body: a curve group's 3-node lines become the
//! faces of the body's elements, in order along their chain; a point group's points become
//! nodes.

use std::collections::{HashMap, HashSet};

use contopt_core::{Error, Result};
use contopt_fem::Face;

use crate::body::Body;
use crate::msh::GmshMesh;
use crate::types::{self, linear};

/// A named physical group of points (0-D) or curves (1-D) on an imported body.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// The group's name.
    pub name: String,
    /// 0 for points, 1 for curves.
    pub dim: usize,
    /// A curve group's faces on the body, along the chain: each runs counter-clockwise round
    /// its element (with the body on its left), each next one starting where the last ends;
    /// separate chains follow one another, open chains first. Empty for points.
    pub faces: Vec<Face>,
    /// The group's nodes on the body: a curve group's face nodes along the chain (start,
    /// middle, end, middle, end…, each once), a point group's points in file order.
    pub nodes: Vec<usize>,
    /// The group's elements (lines or points) in the whole file, on this body or another.
    pub elements_in_file: usize,
}

/// One element face of a body, by its corner nodes.
#[derive(Clone, Copy, Debug)]
struct Edge {
    /// The face (of the first element that has it).
    face: Face,
    /// Elements that have it: 1 on the boundary.
    count: usize,
    /// The other element's index when two have it.
    other: usize,
}

/// The named 0-D and 1-D groups of `gmsh`, on `body`.
pub(crate) fn collect(gmsh: &GmshMesh, body: &Body) -> Result<Vec<Group>> {
    let edges = edges(body, &line_ends(gmsh, body));
    let mut groups = Vec::new();
    for name in gmsh.physical_names().iter().filter(|p| p.dim <= 1) {
        if let Some(other) = groups.iter().find(|g: &&Group| g.name == name.name) {
            return Err(Error::Mesh(format!(
                "{}: \"{}\" names both a group of {} and a group of {}: rename one",
                gmsh.source(),
                name.name,
                what(other.dim),
                what(name.dim)
            )));
        }
        let group = match name.dim {
            0 => points(gmsh, body, &name.name, name.tag),
            _ => curves(gmsh, body, &edges, &name.name, name.tag)?,
        };
        groups.push(group);
    }
    Ok(groups)
}

/// "points" or "curves".
fn what(dim: usize) -> &'static str {
    if dim == 0 {
        "points"
    } else {
        "curves"
    }
}

/// The body's nodes at an end of a line of a curve group.
fn line_ends(gmsh: &GmshMesh, body: &Body) -> Vec<bool> {
    let mut ends = vec![false; body.nodes.len()];
    for name in gmsh.physical_names().iter().filter(|p| p.dim == 1) {
        for block in gmsh.group_blocks(1, name.tag) {
            for (_, nodes) in block.elements() {
                for &n in nodes.iter().take(2) {
                    if let Some(end) = ends.get_mut(body.of_file_node[n]) {
                        *end = true;
                    }
                }
            }
        }
    }
    ends
}

/// The faces of the body's elements whose corners are both `ends`, by their sorted corner
/// nodes.
fn edges(body: &Body, ends: &[bool]) -> HashMap<(usize, usize), Edge> {
    let mut edges: HashMap<(usize, usize), Edge> = HashMap::new();
    for (element, (kind, _)) in body.elements.iter().enumerate() {
        for local in 0..kind.n_faces() {
            let face = Face { element, local };
            let [a, _, b] = body.face_nodes(face);
            if !(ends[a] && ends[b]) {
                continue;
            }
            edges
                .entry((a.min(b), a.max(b)))
                .and_modify(|e| {
                    e.count += 1;
                    e.other = element;
                })
                .or_insert(Edge {
                    face,
                    count: 1,
                    other: element,
                });
        }
    }
    edges
}

/// The point group `name` (physical tag `tag`): its points on the body.
fn points(gmsh: &GmshMesh, body: &Body, name: &str, tag: i32) -> Group {
    let mut nodes = Vec::new();
    let mut elements_in_file = 0;
    for block in gmsh.group_blocks(0, tag) {
        elements_in_file += block.len();
        for (_, file_nodes) in block.elements() {
            let n = body.of_file_node[file_nodes[0]];
            if n != usize::MAX && !nodes.contains(&n) {
                nodes.push(n);
            }
        }
    }
    Group {
        name: name.to_string(),
        dim: 0,
        faces: Vec::new(),
        nodes,
        elements_in_file,
    }
}

/// The curve group `name` (physical tag `tag`): its 3-node lines whose ends are nodes of the
/// body, each a boundary face of the body, chained. Lines of another body are left out.
fn curves(
    gmsh: &GmshMesh,
    body: &Body,
    edges: &HashMap<(usize, usize), Edge>,
    name: &str,
    tag: i32,
) -> Result<Group> {
    let source = gmsh.source();
    let mut faces = Vec::new();
    let mut seen = HashSet::new();
    let mut elements_in_file = 0;
    for block in gmsh.group_blocks(1, tag) {
        elements_in_file += block.len();
        let t = block.element_type();
        for (line, file_nodes) in block.elements() {
            match t.number {
                types::LINE3 => {}
                types::LINE2 => return Err(linear(source, line, t)),
                _ => {
                    return Err(Error::Mesh(format!(
                        "{source}: line {line} of the group \"{name}\" is of {t}: faces are \
                         3-node lines (type 8); set `Mesh.ElementOrder = 2;`"
                    )))
                }
            }
            // Gmsh's 3-node line: start, end, middle.
            let [a, b, m] = [0, 1, 2].map(|k| body.of_file_node[file_nodes[k]]);
            if a == usize::MAX || b == usize::MAX {
                continue;
            }
            let face = boundary_face(body, edges, [a, m, b]).map_err(|why| {
                Error::Mesh(format!(
                    "{source}: line {line} of the group \"{name}\" {why}: a group's lines must \
                     be boundary faces of the body"
                ))
            })?;
            if seen.insert(face) {
                faces.push(face);
            }
        }
    }
    let (faces, nodes) = chain(body, faces);
    Ok(Group {
        name: name.to_string(),
        dim: 1,
        faces,
        nodes,
        elements_in_file,
    })
}

/// The boundary face with corners `a`, `b` and middle `m`, or why there is none.
fn boundary_face(
    body: &Body,
    edges: &HashMap<(usize, usize), Edge>,
    [a, m, b]: [usize; 3],
) -> std::result::Result<Face, String> {
    let tag = |n: usize| body.node_tags[n];
    let edge = edges.get(&(a.min(b), a.max(b))).ok_or_else(|| {
        format!(
            "joins nodes {} and {}, which no element face joins",
            tag(a),
            tag(b)
        )
    })?;
    if edge.count > 1 {
        return Err(format!(
            "lies inside the body, between elements {} and {}",
            body.element_tags[edge.face.element], body.element_tags[edge.other]
        ));
    }
    let middle = body.face_nodes(edge.face)[1];
    if middle != m {
        return Err(format!(
            "has middle node {}, the face of element {} node {}",
            tag(m),
            body.element_tags[edge.face.element],
            tag(middle)
        ));
    }
    Ok(edge.face)
}

/// `faces` in chains: each chain starts at a face whose start no face ends at (or, for
/// closed loops, the first face left in file order) and follows the face that starts where
/// the last ends. Returns the faces and their nodes along the chains, each node once.
fn chain(body: &Body, faces: Vec<Face>) -> (Vec<Face>, Vec<usize>) {
    let ends: Vec<[usize; 3]> = faces.iter().map(|&f| body.face_nodes(f)).collect();
    let mut starting: HashMap<usize, Vec<usize>> = HashMap::new();
    for (k, [s, _, _]) in ends.iter().enumerate() {
        starting.entry(*s).or_default().push(k);
    }
    let ending: HashSet<usize> = ends.iter().map(|[_, _, e]| *e).collect();
    let heads = (0..faces.len()).filter(|&k| !ending.contains(&ends[k][0]));
    let starts: Vec<usize> = heads.chain(0..faces.len()).collect();
    let mut used = vec![false; faces.len()];
    let mut order = Vec::with_capacity(faces.len());
    let mut nodes = Vec::new();
    let mut on = HashSet::new();
    let mut visit = |n: usize, nodes: &mut Vec<usize>| {
        if on.insert(n) {
            nodes.push(n);
        }
    };
    for start in starts {
        let mut next = Some(start).filter(|&k| !used[k]);
        if let Some(k) = next {
            visit(ends[k][0], &mut nodes);
        }
        while let Some(k) = next {
            used[k] = true;
            order.push(faces[k]);
            visit(ends[k][1], &mut nodes);
            visit(ends[k][2], &mut nodes);
            next = starting
                .get(&ends[k][2])
                .and_then(|ks| ks.iter().copied().find(|&j| !used[j]));
        }
    }
    (order, nodes)
}
