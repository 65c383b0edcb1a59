//! The designs a case may run on its contact: none (the contact analysed as it is), the
//! paper's methods for the initial gap (§3: the iteration under a given load or displacement,
//! the linear programme, the load split), and for a roller the robust crown of its envelope and
//! the tuned Fujiwara–Kawase profile. Each is one file implementing [`Design`], registered by
//! its name in [`crate::Registry::standard`]; a design of one's own implements [`Design`] in
//! its own crate and is registered there.

mod analysis;
mod envelope;
mod facing;
mod gap;
pub(crate) mod search;

pub(crate) use analysis::Analysis;
pub use envelope::EnvelopeSplit;
pub use gap::Gap;
pub use search::{
    Circular, CircularSearch, Family, FujiwaraKawase, FujiwaraKawaseSearch, ProfileSearch,
};

use crate::chosen::Chosen;
use crate::gap::GapKind;
use crate::region::OmegaVSpec;
use crate::zone::{Layout, ZoneKind};
use contopt_contact::{ContactSolver, InterfaceProblem};
use contopt_core::observe::{Method, Nested, Observer};
use contopt_core::{ContactState, Error, GapShape, Result, Termination, GEOMETRY_TOLERANCE};
use contopt_optimise::{
    Controller, ControllerSettings, LoadSplitSettings, Optimisation, Pass, Region, SearchSettings,
};
use contopt_results::{CaseReport, CurvePoint, EnvelopeCase, RollerReport, TunedProfile};
use contopt_roller::{
    CaseContact, CrownSettings, Envelope, LoadCase, ProfileFamily, Roller, RollerFigures,
};

/// What a design method does: check a case before anything is built, count its dense
/// matrices, and run. Its name is the one it is registered under
/// ([`crate::Registry::with_design`]).
pub trait Design: Send + Sync {
    /// Refuses a case the method cannot run; fields are named from `[optimisation]`.
    fn check(&self, c: &Check) -> Result<()>;

    /// The n × n matrices the method holds at once on `points` points (with the solver's own
    /// counted by the solver).
    fn dense_copies(&self, points: usize, solver: &dyn ContactSolver) -> u64 {
        solver.dense_copies(points)
    }

    /// Runs the design on the case's contact, timing its stages into `report`.
    fn run(&self, c: &Context, report: &mut CaseReport) -> Result<Designed>;

    /// What a bearing designs its crown by, when the method is one of a bearing's
    /// ([`BearingCrown`]); `None` for the others, which a bearing refuses.
    fn bearing_crown(&self) -> Option<BearingCrown> {
        None
    }
}

/// The crown designs a bearing runs over its rollers' envelope.
#[derive(Clone, Copy, Debug)]
pub enum BearingCrown {
    /// The robust crown by the envelope load split.
    Envelope(LoadSplitSettings),
    /// A family's parameters tuned by a search.
    Search(ProfileFamily, SearchSettings),
}

/// What a design sees of its case: the settings of `[optimisation]` besides the method, the
/// gap, the envelope, and the zone and roller the plan laid out.
#[derive(Clone, Copy)]
pub struct CaseView<'a> {
    /// The method's name, as the scene wrote it (for messages).
    pub method: &'a str,
    /// The controller v(x) of p ≤ v·p_max (§3.1), when the scene gives one.
    pub controller: Option<&'a ControllerSettings>,
    /// Ω_v, when the scene gives it (default: all of the zone; a roller's centre row).
    pub omega_v: Option<&'a OmegaVSpec>,
    /// The surface axis along which the profile changes, when the scene gives one.
    pub profile_axis: Option<usize>,
    /// A roller's envelope of load cases (`[envelope]`).
    pub envelope: Option<&'a Envelope>,
    /// The initial gap's shape.
    pub gap: &'a dyn GapKind,
    /// The zone the gap is read on.
    pub zone: &'a Chosen<dyn ZoneKind>,
    /// The zone with every size known.
    pub layout: &'a Layout,
    /// A roller gap's roller, its crown built.
    pub roller: Option<&'a Roller>,
}

/// What a check sees of a case.
pub struct Check<'a> {
    /// The case.
    pub case: CaseView<'a>,
    /// Whether a body floats.
    pub floating: bool,
}

/// What a design runs on.
pub struct Context<'a> {
    /// The case.
    pub case: CaseView<'a>,
    /// The contact problem of the case's bodies and gap.
    pub problem: &'a InterfaceProblem<'a>,
    /// The case's contact solver.
    pub solver: &'a dyn ContactSolver,
    /// Where the design's iterations report.
    pub observer: &'a dyn Observer,
    /// A roller's load cases, its own first (empty for other gaps).
    pub cases: &'a [LoadCase<'a>],
}

/// What a design found: its last iterate, how it ended, and its figures.
pub struct Designed {
    /// The design method that ran (`None`: the contact analysed as it is).
    pub method: Option<Method>,
    /// The contact solver of its solves.
    pub solver: Option<Method>,
    /// How it ended.
    pub termination: Termination,
    /// The contact pressure of its last iterate \[MPa\], per interface point.
    pub pressure: Vec<f64>,
    /// The gap after deformation \[mm\], per interface point.
    pub gap: Vec<f64>,
    /// The rigid-body displacements of the floating bodies (eq. 2.10).
    pub rigid: Vec<f64>,
    /// The gap change per point \[mm\] (empty without one).
    pub gap_change: Vec<f64>,
    /// What the report shows as Δh instead: a roller's given crown \[mm\].
    pub crown: Option<Vec<f64>>,
    /// The least p_max the method proved (p ≤ v·p_max) \[MPa\].
    pub bound_p_max: Option<f64>,
    /// The largest gap change Δh \[mm\].
    pub dh_max: Option<f64>,
    /// The largest p − v·p̂ over Ω_nv \[MPa\]; `None` without Ω_nv.
    pub omega_nv_excess: Option<f64>,
    /// The method's passes (an iteration's outer steps), for the report's table.
    pub passes: Vec<Pass>,
    /// A roller's figures.
    pub roller: Option<RollerReport>,
    /// The initial gap of the contact the report shows when it is not the case's own (a
    /// bearing's worst roller, tilted and loaded as its load case) \[mm\]; `None`: the case's.
    pub shown_gap: Option<Vec<f64>>,
}

impl Designed {
    /// A contact solve's state, nothing designed.
    pub fn contact(state: ContactState) -> Self {
        Self {
            pressure: state.pressure,
            gap: state.gap,
            rigid: state.rigid,
            ..Self::unsolved(state.termination, state.method)
        }
    }

    /// Nothing solved nor designed: how the run ended, and the solver it had.
    pub fn unsolved(termination: Termination, solver: Method) -> Self {
        Self {
            method: None,
            solver: Some(solver),
            termination,
            pressure: vec![],
            gap: vec![],
            rigid: vec![],
            gap_change: vec![],
            crown: None,
            bound_p_max: None,
            dh_max: None,
            omega_nv_excess: None,
            passes: vec![],
            roller: None,
            shown_gap: None,
        }
    }
}

/// The controller a method needs, checked against the zone's reach, and its regions.
fn check_controller(c: &Check) -> Result<()> {
    let Some(settings) = c.case.controller else {
        return Err(Error::invalid(
            "controller",
            "missing",
            "give the controller v(x) of p ≤ v·p_max: { kind = \"constant\", level = 1.0 }, \
             \"trapezoid\" or \"cubic\" with l1_mm and l2_mm",
        ));
    };
    let within = |e: Error| match e {
        Error::InvalidInput {
            field,
            value,
            reason,
        } => Error::InvalidInput {
            field: format!("controller.{field}"),
            value,
            reason,
        },
        other => other,
    };
    settings.build().map_err(within)?;
    let [hx, hy] = c.case.layout.half_extent();
    let [cx, cy] = c.case.layout.edge_cell();
    settings
        .check_reach([hx, hy, 0.0], [cx, cy, 0.0])
        .map_err(within)?;
    check_regions(&c.case)
}

/// Ω_v and the profile's axis.
fn check_regions(case: &CaseView) -> Result<()> {
    if let Some(omega_v) = case.omega_v {
        omega_v.check().map_err(|e| match e {
            Error::InvalidInput {
                field,
                value,
                reason,
            } => Error::InvalidInput {
                field: format!("omega_v.{field}"),
                value,
                reason,
            },
            other => other,
        })?;
    }
    if let Some(axis) = case.profile_axis {
        contopt_core::check::count("profile_axis", axis, 0, 1)?;
    }
    Ok(())
}

/// A design of a roller's crown starts from the straight roller: it designs the whole crown.
fn straight_roller(c: &Check, method: &str) -> Result<()> {
    match c.case.gap.roller_gap() {
        Some(g) if g.profile == CrownSettings::Straight => Ok(()),
        Some(_) => Err(Error::invalid(
            "method",
            method,
            "designs the roller's whole crown: give the straight profile \
             (contact.gap.profile = \"straight\")",
        )),
        None => Ok(()),
    }
}

/// The cell size across a roller's grid \[mm\].
fn cell_across(layout: &Layout) -> f64 {
    layout.edge_cell()[1]
}

/// What an optimisation of a case is set up from.
struct Setup {
    /// The design profile: Δh = shape · design values.
    shape: GapShape,
    /// The pressure control v(x).
    controller: Box<dyn Controller>,
    /// Ω_v as a mask of the points (`None`: everywhere).
    omega_v: Option<Vec<bool>>,
}

/// The case's controller, built from its settings.
fn controller(c: &Context) -> Result<Box<dyn Controller>> {
    c.case
        .controller
        .ok_or_else(|| Error::invalid("controller", "missing", "the method needs one"))?
        .build()
}

/// The gap shape, the controller and Ω_v of an optimisation of `c`: the profile along
/// `profile_axis` (a roller's axis by default), else at the finite-element face nodes (the
/// faces beyond Ω_v following its edge, [`follow_edge`]), else at every point where the bodies
/// face each other, the others following the nearest ([`facing::tied`]); Ω_v from `omega_v`,
/// a roller's centre row by default, else everywhere, within the points that face each other.
fn setup(c: &Context) -> Result<Setup> {
    let case = &c.case;
    let roller = case.roller.is_some();
    let iface = c.problem.interface();
    let axis = case.profile_axis.or(roller.then_some(0));
    let controller = controller(c)?;
    let dy = cell_across(case.layout);
    let omega_v = match (case.omega_v, roller) {
        (Some(region), _) => Some(region.mask(iface)),
        (None, true) => Some(
            iface
                .points()
                .iter()
                .map(|x| x[1].abs() <= 0.5 * dy)
                .collect(),
        ),
        (None, false) => None,
    };
    let facing = facing::facing(case, iface.points());
    let omega_v = match (omega_v, &facing) {
        (Some(mask), Some(facing)) => Some(mask.iter().zip(facing).map(|(m, f)| m & f).collect()),
        (None, Some(facing)) => Some(facing.clone()),
        (mask, None) => mask,
    };
    let shape = match (axis, c.problem.pressure_basis(), &omega_v) {
        (Some(axis), _, _) => GapShape::extruded(iface, axis)?,
        (None, Some(basis), Some(mask)) => follow_edge(basis, mask, iface.points())?,
        (None, Some(basis), None) => basis.clone(),
        (None, None, _) => match &facing {
            Some(facing) => facing::tied(iface, facing)?,
            None => GapShape::pointwise(iface),
        },
    };
    Ok(Setup {
        shape,
        controller,
        omega_v,
    })
}

/// The finite-element faces' gap shape `basis` with every design node that Ω_v (`mask`) does
/// not hold tied to the nearest node that it does: the faces beyond Ω_v (a punch's fillet kept
/// as drawn) move with the designed face's edge, as one piece, rather than being left
/// undetermined. Ω_v holds a node that one of its points reaches, unless the node is itself
/// a point outside Ω_v (one of `points`): where contact is checked at the face nodes (the
/// mortar pairing of [`contopt_fem::ContactPairing`]), the weighted gap of Ω_v's edge node
/// ∫ N¹ₖ h dS / ∫ N¹ₖ dS reaches the nodes of its faces beyond the edge, which check contact
/// of their own outside Ω_v; at Gauss points no node is a point and every node reached is
/// held. Step 6's least-squares fit then has as many Ω_v points as design nodes, at least.
/// Nodes that Ω_v holds keep their rows, so a shape whose nodes it all holds is returned as
/// it is.
fn follow_edge(basis: &GapShape, mask: &[bool], points: &[[f64; 3]]) -> Result<GapShape> {
    let nodes = basis.nodes();
    let distance =
        |a: [f64; 3], b: [f64; 3]| -> f64 { a.iter().zip(&b).map(|(x, y)| (x - y).powi(2)).sum() };
    let size = points
        .iter()
        .flatten()
        .fold(0.0, |m: f64, x| m.max(x.abs()))
        .max(1.0);
    let same = (GEOMETRY_TOLERANCE * size).powi(2);
    let outside: Vec<[f64; 3]> = (0..basis.len())
        .filter(|&i| !mask[i])
        .map(|i| points[i])
        .collect();
    let mut tied = vec![false; nodes.len()];
    for i in (0..basis.len()).filter(|&i| mask[i]) {
        for &(k, w) in basis.row(i) {
            tied[k] |= w != 0.0;
        }
    }
    for (held, node) in tied.iter_mut().zip(nodes) {
        *held = *held && !outside.iter().any(|&x| distance(x, *node) <= same);
    }
    let tied_nodes: Vec<usize> = (0..nodes.len()).filter(|&k| tied[k]).collect();
    if tied_nodes.is_empty() || tied.iter().all(|&t| t) {
        return Ok(basis.clone());
    }
    let nearest = |k: usize| -> usize {
        tied_nodes
            .iter()
            .copied()
            .min_by(|&a, &b| distance(nodes[a], nodes[k]).total_cmp(&distance(nodes[b], nodes[k])))
            .unwrap_or(k)
    };
    let rows = (0..basis.len())
        .map(|i| {
            let mut row: Vec<(usize, f64)> = vec![];
            for &(k, w) in basis.row(i) {
                let k = if tied[k] { k } else { nearest(k) };
                match row.iter_mut().find(|(j, _)| *j == k) {
                    Some((_, sum)) => *sum += w,
                    None => row.push((k, w)),
                }
            }
            row
        })
        .collect();
    GapShape::new(nodes.to_vec(), rows)
}

/// The regions of a mask: Ω_v inside, Ω_nv outside.
fn regions(mask: &[bool]) -> Vec<Region> {
    mask.iter()
        .map(|&inside| {
            if inside {
                Region::OmegaV
            } else {
                Region::OmegaNv
            }
        })
        .collect()
}

/// An optimisation of `c` on `shape` with `controller` and Ω_v from `mask`, reporting to the
/// case's observer.
fn optimisation_of<'a>(c: &'a Context, setup: &'a Setup) -> Result<Optimisation<'a>> {
    let optimisation = Optimisation::new(c.problem, &setup.shape, setup.controller.as_ref())?
        .with_observer(c.observer);
    match setup.omega_v.as_deref() {
        Some(mask) => optimisation.with_regions(regions(mask)),
        None => Ok(optimisation),
    }
}

/// A roller case's figures under the crown `drop` (per point \[mm\]) from the contacts of its
/// load cases (its own first), with the envelope's cases when the scene has one and the tuned
/// parameters of a search.
fn roller_figures(
    c: &Context,
    contacts: &[CaseContact],
    drop: &[f64],
    tuned: Option<TunedProfile>,
) -> Option<RollerReport> {
    c.case.roller?;
    let points = c.problem.interface().points();
    let figures = RollerFigures::new(contacts, points, drop, cell_across(c.case.layout));
    roller_report(&figures, c.case.envelope.is_some(), tuned)
}

/// The report of a roller's figures: its first case's, and every case's as an envelope when
/// `envelope` (with the worst p_max over them); `None` without cases.
pub(crate) fn roller_report(
    figures: &RollerFigures,
    envelope: bool,
    tuned: Option<TunedProfile>,
) -> Option<RollerReport> {
    let own = figures.cases.first()?;
    let cases: Vec<EnvelopeCase> = match envelope {
        true => figures
            .cases
            .iter()
            .map(|f| EnvelopeCase {
                load_n: f.load_n,
                tilt_arcmin: f.tilt_arcmin,
                p_max_mpa: f.p_max,
                p_max_at_mm: f.p_max_at_mm,
                edge_loading: f.edge_loading,
                approach_um: f.approach_um,
                cells_across: f.cells_across,
                edge_across_mpa: f.edge_across_mpa,
                centre_line: f
                    .centre_line
                    .iter()
                    .map(|&[x_mm, p_mpa]| CurvePoint { x_mm, p_mpa })
                    .collect(),
            })
            .collect(),
        false => vec![],
    };
    Some(RollerReport {
        p_max_at_mm: own.p_max_at_mm,
        edge_loading: own.edge_loading,
        half_width_mm: own.half_width_mm,
        crown_drop_end_um: own.crown_drop_end_um,
        worst_p_max_mpa: envelope.then_some(figures.worst_p_max),
        envelope: cases,
        tuned,
    })
}

/// The contacts of a roller's load cases under the gap change `change` (per point \[mm\]):
/// its own `own` state, and when the scene has an envelope every further case solved from
/// scratch, nested under the case's observer. `Ok(Err)` when a case's answer does not stand,
/// with its termination.
fn envelope_contacts(
    c: &Context,
    own: &ContactState,
    change: &[f64],
    report: &mut CaseReport,
) -> Result<std::result::Result<Vec<ContactState>, Termination>> {
    if c.case.envelope.is_none() || c.cases.len() < 2 {
        return Ok(Ok(vec![own.clone()]));
    }
    let started = std::time::Instant::now();
    let zeros;
    let change = if change.is_empty() {
        zeros = vec![0.0; c.problem.len()];
        &zeros
    } else {
        change
    };
    let solved =
        contopt_roller::solve_cases(&c.cases[1..], change, c.solver, None, &Nested(c.observer));
    report.time("envelope", started);
    let states = solved?;
    if let Some(s) = states.iter().find(|s| !s.termination.is_solved()) {
        return Ok(Err(s.termination.clone().inside(s.method)));
    }
    Ok(Ok(std::iter::once(own.clone()).chain(states).collect()))
}

/// The contacts of states, for the figures.
fn contacts<'s>(c: &Context, states: &'s [ContactState]) -> Vec<CaseContact<'s>> {
    states
        .iter()
        .zip(c.cases)
        .map(|(s, case)| CaseContact {
            load_n: case.load_n,
            tilt_arcmin: case.tilt_arcmin,
            pressure: &s.pressure,
            approach_mm: s.approach().unwrap_or(0.0),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::{Format, Registry};

    /// A sphere on a bed on 20 rings out to 5 mm, with `optimisation` as its `[optimisation]`.
    fn scene(optimisation: &str) -> crate::Scene {
        let text = format!(
            "name = \"design\"\n[contact]\nzone = {{ kind = \"rings\", rings = 20, radius_mm = \
             5.0 }}\ngap = {{ kind = \"sphere\", radius_mm = 20.0 }}\nload = {{ force_n = \
             1000.0 }}\n[[body]]\nkind = \"winkler\"\nmodulus_mpa_per_mm = 50.0\n[[body]]\n\
             kind = \"rigid\"\n[optimisation]\n{optimisation}\n"
        );
        Registry::standard()
            .parse(&text, Format::Toml, Path::new("design.toml"))
            .unwrap()
    }

    /// A method's check sees the case through its view: the controller's reach is checked
    /// against the zone's, and a missing controller is named.
    #[test]
    fn a_controller_is_checked_against_the_zone() {
        let scene = scene(
            "method = \"given_load\"\ncontroller = { kind = \"cubic\", l1_mm = 1.0, l2_mm = 4.0 }",
        );
        let case = &scene.cases()[0];
        let mut view = case.spec.view(case.layout(), None);
        let check = |view: CaseView| {
            check_controller(&Check {
                case: view,
                floating: true,
            })
        };
        assert!(check(view).is_ok());
        view.controller = None;
        let missing = check(view).unwrap_err().to_string();
        assert!(missing.contains("controller"), "{missing}");
        let far: ControllerSettings =
            contopt_input::Node::parse_toml("c = { kind = \"cubic\", l1_mm = 1.0, l2_mm = 50.0 }")
                .unwrap()
                .deserialize_at("c")
                .unwrap();
        view.controller = Some(&far);
        let beyond = check(view).unwrap_err().to_string();
        assert!(beyond.contains("controller.l2_mm"), "{beyond}");
    }

    /// Ω_v inside, Ω_nv outside.
    #[test]
    fn a_mask_splits_the_regions() {
        assert_eq!(
            regions(&[true, false, true]),
            [Region::OmegaV, Region::OmegaNv, Region::OmegaV]
        );
    }

    /// The given load designs the gap on the bed: the pressure is uniform at the controller's
    /// level v = 1 where it is prescribed, p_max = F / (π a²) over the whole zone.
    #[test]
    fn the_given_load_designs_a_uniform_pressure() {
        let scene =
            scene("method = \"given_load\"\ncontroller = { kind = \"constant\", level = 1.0 }");
        let report = scene.cases()[0].run().unwrap();
        let p_max = 1000.0 / (std::f64::consts::PI * 25.0);
        let bound = report.bound_p_max_mpa.unwrap();
        assert!(
            (bound / p_max - 1.0).abs() < 1e-6,
            "{bound} MPa against {p_max}"
        );
    }
}
