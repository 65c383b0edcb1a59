//! The zone of imported meshes (`contact.zone.kind = "mesh"`) as the check surveys it: the
//! contact faces a user meshed (`fe_mesh`), each body's own chain of element edges, and what
//! the pairing of two such bodies says of the surface before either is built
//! ([`MeshSurface`]). The survey itself is the plan's ([`crate::plan`]), the paired build the
//! build stage's ([`crate::build`]).
//!
//! that a user meshed (`fe_mesh`), each body's own chain of element edges, curved or straight.
//!
//! Two imported bodies are paired before either is condensed: the first body's contact faces
//! are cut where the second body's face nodes project and sampled segment to segment along
//! the first body's normal n¹ (eq. 2.1, [`ContactPairing`]), both bodies are built at those
//! points and condensed onto the first body's face nodes, where contact is checked. The zone therefore builds the pair itself from what each kind offers, its
//! model and contact faces ([`crate::bodies::BodyKind::part`]), rather than each kind
//! building its own body. A rigid body or a bed stands on an imported body's faces, sampled
//! at their Gauss points, as on a zone of faces.
//!
//! The check surveys the pair without building it (the pairing's points and nodes without
//! the map between them): the points, the zone's extent for the controller and the limits, and the ends
//! of each contact chain — a contact that reaches the end of a chain where the body's boundary
//! goes on (the contact group was drawn too short) is outside the model, while the end of a
//! chain at a corner of its body (a punch's rim, the axis) is the body's own edge. Points of
//! the first body left out of a pairing (no partner within the search distance) lie beyond
//! the end of the second body's chain, judged at that end, or across a gap wider than the
//! search distance, which no contact of small strain closes.

use std::collections::{HashMap, HashSet};

use contopt_core::Result;
use contopt_fem::element::lagrange2;
use contopt_fem::{Analysis, Face, FeModel, RigidMotion};

use contopt_results::Resolution;

/// A chain's end is a corner of its body when the boundary turns there by more than this
/// angle's cosine (30°): a punch's rim or the axis; less, and the boundary goes on beyond it
/// (a fillet meets the flank tangentially).
const CORNER_COS: f64 = 0.866;

/// A point lies at the end of a chain when it is within this part of the chain's last face
/// of its end: the face's outer and middle Gauss points (as a zone's edge holds the points
/// within half a cell of its outermost).
const AT_END: f64 = 0.6;

/// A motion moves the contact faces when its normal displacement there exceeds this fraction
/// of its largest nodal displacement (round-off of the faces' geometry).
const MOVES: f64 = 1e-9;

/// An imported body offered to a zone of meshes: its model, supported and loaded, and its
/// contact faces along their chain.
pub struct MeshPart {
    /// The body's name in reports.
    pub name: String,
    /// The contact group's name.
    pub group: String,
    /// The model.
    pub model: FeModel,
    /// The contact faces, along the chain.
    pub contact: Vec<Face>,
}

/// A rigid-body motion a body's supports leave free, as a contact sees it.
pub struct FreeMotion {
    /// Its name (`"y translation"`).
    pub name: String,
    /// Its displacement along the outward normal at the contact faces' Gauss points.
    pub along: Vec<f64>,
    /// The work of the body's loads on it \[N·mm per unit motion\].
    pub load: f64,
    /// Its largest nodal displacement.
    pub size: f64,
}

impl FreeMotion {
    /// The free `motion` of a body under the nodal loads `forces`, displaced `along` the
    /// contact faces' normals at their points.
    pub fn new(motion: RigidMotion, along: Vec<f64>, forces: &[f64]) -> Self {
        FreeMotion {
            along,
            load: motion.values.iter().zip(forces).map(|(a, b)| a * b).sum(),
            size: motion.values.iter().fold(0.0f64, |s, v| s.max(v.abs())),
            name: motion.name,
        }
    }

    /// Whether it moves the contact faces (a contact can hold it).
    pub fn moves_faces(&self) -> bool {
        self.along.iter().any(|v| v.abs() > MOVES * self.size)
    }
}

impl MeshPart {
    /// The rigid motions its supports leave free, with how each moves the contact faces.
    pub fn free_motions(&self) -> Result<Vec<FreeMotion>> {
        Ok((self.model.free_motions()?.into_iter())
            .map(|m| {
                let along = m.along_normals(&self.model, &self.contact);
                FreeMotion::new(m, along, self.model.forces())
            })
            .collect())
    }

    /// Whether it floats: a free motion moves its contact faces.
    pub(crate) fn floats(&self) -> Result<bool> {
        Ok(self.free_motions()?.iter().any(FreeMotion::moves_faces))
    }

    /// The position and tangent dx/ds of a face at parameter `s`.
    fn face_at(&self, f: Face, s: f64) -> ([f64; 2], [f64; 2]) {
        let nodes = self.model.mesh().face_nodes(f);
        let mut x = [0.0; 2];
        let mut t = [0.0; 2];
        for (k, at) in [-1.0, 0.0, 1.0].into_iter().enumerate() {
            let (l, dl) = lagrange2(at, s);
            let p = self.model.mesh().nodes()[nodes[k]];
            for c in 0..2 {
                x[c] += l * p[c];
                t[c] += dl * p[c];
            }
        }
        (x, t)
    }

    /// The length of the chord of face `f` \[mm\].
    pub(crate) fn chord(&self, f: Face) -> f64 {
        let (a, _) = self.face_at(f, -1.0);
        let (b, _) = self.face_at(f, 1.0);
        (b[0] - a[0]).hypot(b[1] - a[1])
    }

    /// The ends of its contact chain(s), each a corner of the body or not.
    pub(crate) fn ends(&self) -> Vec<ChainEnd> {
        let mesh = self.model.mesh();
        let corners = |f: Face| {
            let [a, _, b] = mesh.face_nodes(f);
            (a, b)
        };
        let in_group: HashSet<Face> = self.contact.iter().copied().collect();
        // The boundary faces outside the group, by the node they start and end at.
        let (mut starting, mut ending) = (HashMap::new(), HashMap::new());
        for f in mesh.boundary_faces() {
            if !in_group.contains(&f) {
                starting.insert(corners(f).0, f);
                ending.insert(corners(f).1, f);
            }
        }
        let starts: HashSet<usize> = self.contact.iter().map(|&f| corners(f).0).collect();
        let finishes: HashSet<usize> = self.contact.iter().map(|&f| corners(f).1).collect();
        let mut ends = vec![];
        for &f in &self.contact {
            let (a, b) = corners(f);
            if !finishes.contains(&a) {
                // The chain starts here: beyond it lies the boundary face that ends at `a`.
                let (x, t) = self.face_at(f, -1.0);
                let next = ending.get(&a).map(|&g| self.face_at(g, 1.0).1);
                ends.push(self.end(f, x, [-t[0], -t[1]], next.map(|n| [-n[0], -n[1]])));
            }
            if !starts.contains(&b) {
                let (x, t) = self.face_at(f, 1.0);
                let next = starting.get(&b).map(|&g| self.face_at(g, -1.0).1);
                ends.push(self.end(f, x, t, next));
            }
        }
        ends
    }

    /// The end of the chain at `x` on face `f`, leaving along `outward`, the boundary going on
    /// along `next` (pointing away from the end), if the body's boundary goes on at all.
    fn end(&self, f: Face, x: [f64; 2], outward: [f64; 2], next: Option<[f64; 2]>) -> ChainEnd {
        let unit = |v: [f64; 2]| {
            let l = v[0].hypot(v[1]);
            [v[0] / l, v[1] / l]
        };
        let outward = unit(outward);
        // A boundary that turns by a NaN (a degenerate face) counts as a corner.
        let corner = next.map(unit).is_none_or(|n| {
            let cos = outward[0] * n[0] + outward[1] * n[1];
            cos.is_nan() || cos <= CORNER_COS
        });
        ChainEnd {
            body: self.name.clone(),
            group: self.group.clone(),
            at: x,
            outward,
            face: self.chord(f),
            corner,
        }
    }
}

/// The end of a contact chain.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainEnd {
    /// The body's name.
    pub body: String,
    /// Its contact group.
    pub group: String,
    /// Where the chain ends \[mm\].
    pub at: [f64; 2],
    /// The unit tangent leaving the chain there.
    pub outward: [f64; 2],
    /// The length of the chain's last face \[mm\].
    pub face: f64,
    /// Whether the body's boundary turns there (its own edge), or ends.
    pub corner: bool,
}

impl ChainEnd {
    /// Whether the point `x` lies at this end (within 0.6 of the last face's length of it).
    pub fn holds(&self, x: [f64; 3]) -> bool {
        (x[0] - self.at[0]).hypot(x[1] - self.at[1]) < AT_END * self.face
    }

    /// Whether `other` ends at the same place (within 0.6 of either's last face).
    fn meets(&self, other: &ChainEnd) -> bool {
        let d = (self.at[0] - other.at[0]).hypot(self.at[1] - other.at[1]);
        d < AT_END * self.face.max(other.face)
    }
}

/// A zone of imported meshes surveyed from its bodies: its points in the order the built
/// interface will have them, where they lie, and the ends of the contact chains.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshSurface {
    /// The analysis of both bodies.
    pub analysis: Analysis,
    /// The interface points \[mm\] (x = r in axisymmetry).
    pub points: Vec<[f64; 2]>,
    /// The faces of the first imported body's chain that hold each point (their indices: one,
    /// or two at a node where faces meet).
    pub faces_of: Vec<Vec<usize>>,
    /// The length of each face of that chain \[mm\].
    pub face_lengths: Vec<f64>,
    /// Whether two imported bodies are paired (else a partner stands on one).
    pub paired: bool,
    /// Each imported body's node count, by side.
    pub nodes: [Option<usize>; 2],
    /// The points where a pairing integrates, at which both bodies are condensed before their
    /// compliance is mapped onto the nodes (the points themselves when not paired).
    pub samples: usize,
    /// How far the points reach from the origin along x and y \[mm\].
    pub half_extent: [f64; 2],
    /// The longest face of the first imported body's chain \[mm\].
    pub cell: f64,
    /// The ends of the contact chains.
    pub ends: Vec<ChainEnd>,
    /// Whether an imported body floats (a free motion moves its contact faces).
    pub floating: bool,
}

impl MeshSurface {
    /// The ends of the contact chains where the contact could go on: the body's boundary goes
    /// on beyond them, and no corner of a body (its own edge, or its partner's) lies there.
    pub fn open_ends(&self) -> impl Iterator<Item = &ChainEnd> {
        self.ends
            .iter()
            .filter(|end| !end.corner && !self.ends.iter().any(|e| e.corner && e.meets(end)))
    }

    /// How many faces of the first imported body's chain span the contact's half-width: the
    /// faces that hold a carrying point (a node carries on both its faces), their length the contact's; all of it when the
    /// contact reaches a corner on the axis or a symmetry line x = 0 (a half model), else
    /// half of it.
    pub fn resolution(&self, points: &[[f64; 3]], carrying: &[bool]) -> Resolution {
        let mut faces: Vec<usize> = (0..points.len().min(self.faces_of.len()))
            .filter(|&i| carrying[i])
            .flat_map(|i| self.faces_of[i].iter().copied())
            .collect();
        faces.sort_unstable();
        faces.dedup();
        let length: f64 = faces.iter().map(|&f| self.face_lengths[f]).sum();
        let tolerance =
            contopt_core::GEOMETRY_TOLERANCE * self.half_extent[0].max(self.half_extent[1]);
        let halved = !self.ends.iter().any(|e| {
            e.corner
                && e.at[0].abs() <= tolerance
                && (0..points.len()).any(|i| carrying[i] && e.holds(points[i]))
        });
        let share = if halved { 0.5 } else { 1.0 };
        Resolution {
            along: if self.analysis == Analysis::Axisymmetric {
                "r"
            } else {
                "x"
            }
            .into(),
            half_width_mm: share * length,
            cells: share * faces.len() as f64,
        }
    }
}
