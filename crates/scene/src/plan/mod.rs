//! The plan of a case, the first stage of its run and all of its check: every value, every combination of
//! the parts, the memory the case will take — nothing built, nothing solved. What this passes,
//! the run accepts; what the run would refuse, this refuses, at the key that says so.

use std::sync::Arc;

use contopt_core::Material;
use contopt_roller::Roller;

mod budget;
mod pair;
pub(crate) mod survey;

pub use budget::{Memory, DEFAULT_MEMORY_LIMIT_BYTES};

use crate::bodies::{BodyKind, Carried, Placement, Side};
use crate::chosen::Chosen;
use crate::error::Locator;
use crate::load::LoadSpec;
use crate::mesh_surface::MeshSurface;
use crate::meshes::MeshFiles;
use crate::methods::{Check, Design};
use crate::reference::Hertz;
use crate::spec::CaseSpec;
use crate::zone::{Layout, MeshZone, ZoneKind};
use crate::SceneError;
use pair::{check_load, check_pair};

/// A case checked and ready to run: its zone's sizes, Hertz's nominal contact, a roller's
/// geometry, its memory limits and the key of its bodies.
#[derive(Debug)]
pub(crate) struct Plan {
    /// The zone with every size known.
    pub layout: Layout,
    /// The pair's modulus E* \[MPa\], when both bodies' compliances are known.
    pub e_star: Option<f64>,
    /// Hertz's nominal contact for the gap and the load, where it applies.
    pub hertz: Option<Hertz>,
    /// A roller gap's roller, its crown built.
    pub roller: Option<Roller>,
    /// A measured gap on a grid: the distance between the bodies' meshed faces at the zone's
    /// points \[mm\] ([`measured_faces`]).
    pub faces: Option<Vec<f64>>,
    /// The memory limit of dense matrices \[bytes\].
    pub dense_limit: u64,
    /// The case's memory estimate and limit, checked.
    pub memory: budget::Memory,
    /// What the case's bodies are built from: cases with equal keys share one build.
    pub key: BuildKey,
    /// The case's design: its `[optimisation] method`, the contact analysed as it is, or a
    /// bearing's (`[bearing]`: its distributions are its load cases, its lives a report).
    pub design: Chosen<dyn Design>,
    /// Where the design's errors are placed: `optimisation`, or `bearing`.
    pub design_at: &'static str,
}

/// Checks `spec` and plans its run, reading the meshes its bodies name from `meshes`; `at`
/// places the errors.
pub(crate) fn plan(spec: &CaseSpec, at: &Locator, meshes: &MeshFiles) -> Result<Plan, SceneError> {
    let bearing = crate::bearing::plan(spec, at)?;
    let design_at = match bearing {
        Some(_) => "bearing",
        None => "optimisation",
    };
    let design = match bearing {
        Some(b) => {
            let b = Arc::new(b);
            let design: Arc<dyn Design> = b.clone();
            Chosen::new("bearing", serde_json::Value::Null, design, b)
        }
        None => spec.chosen_design(),
    };
    let contact = &spec.contact;
    check_pair(&spec.body, &contact.zone).map_err(|e| at.library("", e))?;
    contact
        .gap
        .check(&contact.zone)
        .map_err(|e| at.library("contact.gap", e))?;
    let surveyed = survey::survey(&spec.body, &contact.zone, meshes, at)?;
    check_measured(spec, surveyed.as_ref(), at)?;
    let e_star = pair_modulus(&spec.body, &contact.zone);
    let (force, approach) = load_figures(contact.load);
    let rough = e_star.and_then(|e| contact.gap.hertz(&contact.zone, e, force, approach, None));
    let roller = roller(spec, force, at)?;
    let layout = contact
        .zone
        .layout(
            &|cells| contact.gap.natural_cell(cells, rough, roller.as_ref()),
            surveyed,
        )
        .map_err(|e| at.library("contact.zone", e))?;
    let length = layout.line_length();
    let hertz = e_star.and_then(|e| contact.gap.hertz(&contact.zone, e, force, approach, length));
    if layout.symmetric().contains(&true) && !contact.gap.measured() {
        return Err(at.at(
            "contact.zone.symmetry",
            "a grid with symmetry holds a half or a quarter of bodies that model the symmetry \
             with their own meshes, the gap measured between them (contact.gap = { kind = \
             \"measured\" }): a gap's shape, its Hertz figures and the contact's force are the \
             whole contact's",
        ));
    }
    for (k, body) in spec.body.iter().enumerate() {
        let place = placement(spec, &layout, k, at, meshes);
        body.check(&place)
            .map_err(|e| at.library(&format!("body[{k}]"), e))?;
    }
    let faces = measured_faces(spec, &layout, at, meshes)?;
    check_determined(spec, &layout, at, meshes)?;
    // Two meshes paired on a zone of meshes may be pressed by their interference alone.
    let interference = contact.gap.measured() && matches!(layout, Layout::Mesh(_));
    check_load(
        [&spec.body[0], &spec.body[1]],
        &contact.zone,
        contact.load,
        interference,
    )
    .map_err(|e| at.library("", e))?;
    let floating = floats(spec, &layout);
    let check = Check {
        case: spec.view(&layout, roller.as_ref()),
        floating,
    };
    design.check(&check).map_err(|e| at.library(design_at, e))?;
    if let Some(envelope) = &spec.envelope {
        if roller.is_none() {
            return Err(at.at(
                "envelope",
                "only a roller gap has an envelope of load cases",
            ));
        }
        envelope.check().map_err(|e| at.library("envelope", e))?;
    }
    if let Some(sub) = &spec.output.subsurface {
        sub.check()
            .map_err(|e| at.library("output.subsurface", e))?;
    }
    let solver = spec.solver.build().map_err(|e| at.library("solver", e))?;
    let dense_limit = budget::dense_limit(spec).map_err(|e| at.library("", e))?;
    let memory = budget::check(spec, &layout, solver.as_ref(), at, meshes)?;
    Ok(Plan {
        key: BuildKey {
            zone: contact.zone.clone(),
            layout: layout.clone(),
            bodies: spec.body.clone(),
            load: contact.load,
            memory_limit_bytes: memory.limit_bytes,
            measured: contact.gap.measured(),
        },
        memory,
        layout,
        e_star,
        hertz,
        roller,
        faces,
        dense_limit,
        design,
        design_at,
    })
}

/// What a case's bodies are built from — everything [`placement`] hands a body: the zone, its
/// layout with every size resolved (a grid without `cell_mm` takes its cells from the case's
/// gap and load), the bodies' kinds with their settings, the contact's load, the memory limit
/// and whether the gap is measured between the bodies' faces — compared as values: cases with
/// equal keys share one build.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct BuildKey {
    zone: Chosen<dyn ZoneKind>,
    layout: Layout,
    bodies: Vec<Chosen<dyn BodyKind>>,
    load: LoadSpec,
    memory_limit_bytes: u64,
    measured: bool,
}

/// Where body `k` stands.
pub(crate) fn placement<'a>(
    spec: &'a CaseSpec,
    layout: &'a Layout,
    k: usize,
    at: &'a Locator,
    meshes: &'a MeshFiles,
) -> Placement<'a> {
    Placement {
        kind: spec.body[k].name(),
        zone: &spec.contact.zone,
        layout,
        side: if k == 0 { Side::Below } else { Side::Above },
        load: spec.contact.load,
        dir: at.dir(),
        meshes,
        // Checked positive with the case's budget, before any body is built.
        memory_limit_bytes: budget::limit(spec).unwrap_or(DEFAULT_MEMORY_LIMIT_BYTES),
        measured: spec.contact.gap.measured(),
    }
}

/// The measured gap on a zone of imported meshes is the distance between two of them: it needs
/// both. (On a grid, [`measured_faces`].)
fn check_measured(
    spec: &CaseSpec,
    surveyed: Option<&MeshSurface>,
    at: &Locator,
) -> Result<(), SceneError> {
    let paired = surveyed.is_some_and(|s| s.paired);
    let meshes = spec.contact.zone.downcast::<MeshZone>().is_some();
    if spec.contact.gap.measured() && meshes && !paired {
        return Err(at.at(
            "contact.gap",
            "the measured gap is the distance between two imported meshes: both bodies of \
             kind \"fe_mesh\" on a zone of kind \"mesh\" (give another gap's shape)",
        ));
    }
    Ok(())
}

/// A body whose influence is singular among some of the zone's points
/// ([`BodyKind::carried_pressures`]: a solid read on cells finer than the faces under them,
/// anywhere on its face) against a rigid partner, which adds no compliance of its own, leaves
/// the pressure there undetermined: any answer the solver stops at is one of many (a rigid
/// sphere on the bundled solid block on 24 × 24 cells of 0.07 mm over faces of 0.16 mm: p_max
/// 10 105 MPa against Hertz's 3 104). Refused with the dependent points, where they lie and
/// the face nodes there: a count over the whole face passed a face meshed fine around the
/// contact and coarse under it (p_max 22 250 MPa against Hertz's 1 955). Exact for any
/// contact set, so dependent points outside the contact are refused too (12 × 12 cells of
/// 0.14 mm on the bundled block, within 1 % when solved, 7 points dependent where its faces
/// widen). A compliant partner (a half-space) makes the pair's influence definite, and is not
/// refused.
fn check_determined(
    spec: &CaseSpec,
    layout: &Layout,
    at: &Locator,
    meshes: &MeshFiles,
) -> Result<(), SceneError> {
    let Some(points) = layout.points() else {
        return Ok(());
    };
    for (k, body) in spec.body.iter().enumerate() {
        if spec.body[1 - k].compliance(&spec.contact.zone) != Some(0.0) {
            continue;
        }
        let place = placement(spec, layout, k, at, meshes);
        let Some(carried) = body.carried_pressures(&place) else {
            continue;
        };
        let key = format!("body[{k}]");
        let carried = carried.map_err(|e| at.library(&key, e))?;
        if !carried.dependent.is_empty() {
            return Err(at.at(&key, undetermined(points, &carried)));
        }
    }
    Ok(())
}

/// Why the pressure on `points` points, of which `carried` says some are dependent, is not
/// determined against a rigid body.
fn undetermined(points: usize, carried: &Carried) -> String {
    let [lo, hi] = carried.region_mm;
    format!(
        "read as each cell's mean over its contact faces, {} of the zone's {points} points \
         repeat what the others read (its influence among them has rank {}): the {} points \
         centred in x {:.4} … {:.4} mm, y {:.4} … {:.4} mm are read from {} face nodes, so \
         against a rigid body, which adds no compliance of its own, the pressure there is not \
         determined; give the zone cells no finer than the faces under them, or mesh the \
         contact finer there",
        carried.dependent.len(),
        points - carried.dependent.len(),
        carried.region_points,
        lo[0],
        hi[0],
        lo[1],
        hi[1],
        carried.region_nodes
    )
}

/// The meshed faces may overlap by this fraction of the zone's size (the round-off of the
/// meshes' coordinates); more is refused.
const OVERLAP: f64 = 1e-6;

/// A measured gap on a zone of its own surface (a grid): the distance between the bodies'
/// faces as meshed at the zone's points, the sum of their face shapes
/// ([`BodyKind::face_shape`]; a body without one has its face on the zone's surface). One
/// body at least brings its face, and the faces do not overlap. `None` for other gaps and for
/// a zone of imported meshes, whose pairing measures the gap.
fn measured_faces(
    spec: &CaseSpec,
    layout: &Layout,
    at: &Locator,
    meshes: &MeshFiles,
) -> Result<Option<Vec<f64>>, SceneError> {
    let Some(Ok(surface)) = layout.surface() else {
        return Ok(None);
    };
    if !spec.contact.gap.measured() {
        return Ok(None);
    }
    let mut total = vec![0.0; surface.len()];
    let mut brought = false;
    for (k, body) in spec.body.iter().enumerate() {
        let place = placement(spec, layout, k, at, meshes);
        let Some(shape) = body.face_shape(&place) else {
            continue;
        };
        let key = format!("body[{k}]");
        let shape = shape.map_err(|e| at.library(&key, e))?;
        if shape.len() != total.len() {
            return Err(at.at(
                &key,
                format!(
                    "its face's shape has {} values for the zone's {} points",
                    shape.len(),
                    total.len()
                ),
            ));
        }
        total.iter_mut().zip(&shape).for_each(|(t, h)| *t += h);
        brought = true;
    }
    if !brought {
        return Err(at.at(
            "contact.gap",
            "the measured gap is the distance between the bodies' meshed faces: on a grid, a \
             body that brings its face (kind \"solid\"), or two imported meshes on a zone of \
             kind \"mesh\" (give another gap's shape)",
        ));
    }
    let [wx, wy] = layout.half_extent();
    let tolerance = OVERLAP * 2.0 * wx.hypot(wy);
    let overlaps = (total.iter().enumerate()).filter(|(_, &h)| h < -tolerance || h.is_nan());
    if let Some((i, &h)) = overlaps.min_by(|a, b| a.1.total_cmp(b.1)) {
        let x = surface.points()[i];
        return Err(at.at(
            "contact.gap",
            format!(
                "the bodies' meshed faces overlap by {:.4e} mm in the cell centred at ({}, {}) \
                 mm (more than the {tolerance:.1e} mm of round-off): place the parts in Gmsh \
                 so that they touch, not overlap; an interference between solids on a grid is \
                 not read",
                -h, x[0], x[1]
            ),
        ));
    }
    Ok(Some(total))
}

/// The pair's modulus 1/E* = Σ compliance, when both bodies give theirs and it is positive.
fn pair_modulus(bodies: &[Chosen<dyn BodyKind>], zone: &Chosen<dyn ZoneKind>) -> Option<f64> {
    let total: f64 = bodies
        .iter()
        .map(|b| b.compliance(zone))
        .sum::<Option<f64>>()?;
    (total > 0.0 && total.is_finite()).then(|| 1.0 / total)
}

/// The contact's force and approach.
fn load_figures(load: LoadSpec) -> (Option<f64>, Option<f64>) {
    match load {
        LoadSpec::ForceN(f) => (Some(f), None),
        LoadSpec::ApproachMm(a) => (None, Some(a)),
        LoadSpec::None => (None, None),
    }
}

/// Whether a body floats: pressed by a contact force, a punch under a pressure, or an
/// imported body whose supports leave a motion free that its contact faces hold.
fn floats(spec: &CaseSpec, layout: &Layout) -> bool {
    matches!(spec.contact.load, LoadSpec::ForceN(_))
        || matches!(layout, Layout::Mesh(m) if m.floating)
        || spec.body.iter().any(|b| b.floats())
}

/// A roller gap's roller: two half-spaces on the grid, the raceway first, pressed by a force.
fn roller(spec: &CaseSpec, force: Option<f64>, at: &Locator) -> Result<Option<Roller>, SceneError> {
    let Some(gap) = spec.contact.gap.roller_gap() else {
        return Ok(None);
    };
    let materials: Vec<Material> = spec
        .body
        .iter()
        .filter(|b| b.is_half_space())
        .filter_map(|b| b.material())
        .collect();
    let (Some(force), [raceway, roller]) = (force, materials.as_slice()) else {
        return Err(at.at(
            "contact.gap",
            "a roller gap is the contact of two half_space bodies (the raceway first, the \
             roller second) pressed by contact.load = { force_n }",
        ));
    };
    gap.roller([*raceway, *roller], force, at.dir())
        .map(Some)
        .map_err(|e| at.library("contact.gap", e))
}
