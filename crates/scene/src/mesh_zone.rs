//! The zone of imported meshes (`contact.zone.kind = "mesh"`): the contact faces of bodies
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

use contopt_core::{check, Error, Result};
use contopt_fem::element::lagrange2;
use contopt_fem::{Analysis, ContactPairing, Face, FaceSample, FeModel, PairingSettings};

use contopt_results::Resolution;

use crate::bodies::BodyKind;
use crate::build::Built;
use crate::error::Locator;
use crate::meshes::MeshFiles;
use crate::registry::Chosen;
use crate::zone::MeshZone;
use crate::{Case, SceneError};

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
    /// Whether it moves the contact faces (a contact can hold it).
    pub fn moves_faces(&self) -> bool {
        self.along.iter().any(|v| v.abs() > MOVES * self.size)
    }
}

impl MeshPart {
    /// The rigid motions its supports leave free, with how each moves the contact faces.
    pub fn free_motions(&self) -> Result<Vec<FreeMotion>> {
        let forces = self.model.forces();
        Ok(self
            .model
            .free_motions()?
            .into_iter()
            .map(|m| FreeMotion {
                along: m.along_normals(&self.model, &self.contact),
                load: m.values.iter().zip(forces).map(|(a, b)| a * b).sum(),
                size: m.values.iter().fold(0.0f64, |s, v| s.max(v.abs())),
                name: m.name,
            })
            .collect())
    }

    /// Whether it floats: a free motion moves its contact faces.
    fn floats(&self) -> Result<bool> {
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
    fn chord(&self, f: Face) -> f64 {
        let (a, _) = self.face_at(f, -1.0);
        let (b, _) = self.face_at(f, 1.0);
        (b[0] - a[0]).hypot(b[1] - a[1])
    }

    /// The ends of its contact chain(s), each a corner of the body or not.
    fn ends(&self) -> Vec<ChainEnd> {
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

/// The mesh zone of `spec`, surveyed from its bodies' meshes (`None` for other zones);
/// errors placed at the body or the zone's key.
pub(crate) fn survey(
    bodies: &[Chosen<dyn BodyKind>],
    zone: &crate::zone::ZoneSpec,
    meshes: &MeshFiles,
    at: &Locator,
) -> Result<Option<MeshSurface>, SceneError> {
    let crate::zone::ZoneSpec::Mesh(zone) = zone else {
        return Ok(None);
    };
    let settings = settings(zone).map_err(|e| at.library("contact.zone", e))?;
    let parts = parts(bodies, zone, meshes, at)?;
    let floats = parts
        .iter()
        .flatten()
        .map(MeshPart::floats)
        .collect::<Result<Vec<bool>>>()
        .map_err(|e| at.library("body", e))?;
    if floats == [true, true] {
        return Err(at.at(
            "body[1].supports",
            "both imported bodies float along the contact normal, each pressed only by the \
             other: hold one of them (a support that stops its motion along the normal), as \
             the run would refuse two free motions that move the contact alike",
        ));
    }
    let floating = floats.contains(&true);
    let nodes = [0, 1].map(|k| parts[k].as_ref().map(|p| p.model.mesh().nodes().len()));
    let (owner, paired) = match &parts {
        [Some(a), Some(b)] => {
            let survey =
                ContactPairing::survey((&a.model, &a.contact), (&b.model, &b.contact), &settings)
                    .map_err(|e| pairing_error(e, at))?;
            (a, Some(survey))
        }
        [Some(a), None] | [None, Some(a)] => (a, None),
        [None, None] => {
            return Err(at.at(
                "contact.zone.kind",
                "a zone of kind \"mesh\" is the contact faces of an imported body: give one \
                 body (or both) of kind \"fe_mesh\"",
            ))
        }
    };
    let index: HashMap<Face, usize> = owner
        .contact
        .iter()
        .enumerate()
        .map(|(k, &f)| (f, k))
        .collect();
    let (points, faces_of, samples): (Vec<[f64; 2]>, Vec<Vec<usize>>, usize) = match &paired {
        Some(survey) => (
            survey.nodes.clone(),
            (survey.node_faces.iter())
                .map(|faces| faces.iter().map(|f| index[f]).collect())
                .collect(),
            survey.first.len(),
        ),
        None => {
            let gauss: Vec<FaceSample> = (owner.contact.iter())
                .flat_map(|&f| FaceSample::gauss(&owner.model, f))
                .collect();
            (
                gauss.iter().map(|s| s.point).collect(),
                gauss.iter().map(|s| vec![index[&s.face]]).collect(),
                gauss.len(),
            )
        }
    };
    let face_lengths: Vec<f64> = owner.contact.iter().map(|&f| owner.chord(f)).collect();
    let half_extent = points.iter().fold([0.0f64; 2], |m, p| {
        [m[0].max(p[0].abs()), m[1].max(p[1].abs())]
    });
    let mut ends = vec![];
    for part in parts.iter().flatten() {
        ends.extend(part.ends());
    }
    Ok(Some(MeshSurface {
        analysis: zone.analysis,
        samples,
        cell: face_lengths.iter().fold(0.0, |m: f64, &l| m.max(l)),
        points,
        faces_of,
        face_lengths,
        paired: paired.is_some(),
        nodes,
        half_extent,
        ends,
        floating,
    }))
}

/// The pairing's settings of a zone: its search distance, positive and finite when given.
fn settings(zone: &MeshZone) -> Result<PairingSettings> {
    if let Some(d) = zone.search_mm {
        check::positive("search_mm", d)?;
    }
    Ok(PairingSettings {
        search_distance: zone.search_mm,
    })
}

/// The parts the bodies offer, each error at its body.
fn parts(
    bodies: &[Chosen<dyn BodyKind>],
    zone: &MeshZone,
    meshes: &MeshFiles,
    at: &Locator,
) -> Result<[Option<MeshPart>; 2], SceneError> {
    let part = |k: usize| {
        bodies[k]
            .part(meshes, zone.analysis)
            .transpose()
            .map_err(|e| at.library(&format!("body[{k}]"), e))
    };
    Ok([part(0)?, part(1)?])
}

/// A pairing's error at the key it concerns: a chain that breaks at its body's `contact`,
/// faces that do not pair at the zone.
fn pairing_error(e: Error, at: &Locator) -> SceneError {
    let Error::InvalidInput {
        field,
        value,
        reason,
    } = e
    else {
        return at.library("contact.zone", e);
    };
    let key = match field.as_str() {
        f if f.starts_with("pairing.first") => "body[0].contact",
        f if f.starts_with("pairing.second") => "body[1].contact",
        _ => "contact.zone",
    };
    at.at(
        key,
        format!("the contact faces ({value}) do not pair: {reason}"),
    )
}

impl Case {
    /// The two imported bodies of a mesh zone, paired and built together (`None` unless both
    /// bodies are imported), with the pairing that measured the gap between them.
    pub(crate) fn build_pair(&self) -> Result<Option<Built>, SceneError> {
        let start = std::time::Instant::now();
        let (spec, at) = (&self.spec, &self.locator);
        let crate::zone::ZoneSpec::Mesh(zone) = &spec.contact.zone else {
            return Ok(None);
        };
        let [Some(first), Some(second)] = parts(&spec.body, zone, &self.meshes, at)? else {
            return Ok(None);
        };
        let settings = settings(zone).map_err(|e| at.library("contact.zone", e))?;
        let pairing = ContactPairing::new(
            (&first.model, &first.contact),
            (&second.model, &second.contact),
            &settings,
        )
        .map_err(|e| pairing_error(e, at))?;
        let (a, b) = pairing
            .bodies((first.name, first.model), (second.name, second.model))
            .map_err(|e| at.library("body", e))?;
        let stats = [*a.stats(), *b.stats()];
        let bodies: [Box<dyn contopt_core::ElasticBody>; 2] = [Box::new(a), Box::new(b)];
        Ok(Some(Built::paired(bodies, pairing, stats, start.elapsed())))
    }
}
