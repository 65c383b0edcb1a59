//! The designs a case may run on its contact: none (the contact analysed as it is), the
//! paper's methods for the initial gap (§3: the iteration under a given load or displacement,
//! the linear programme, the load split), and for a roller the robust crown of its envelope and
//! the tuned Fujiwara–Kawase profile. Each is one file implementing [`Design`]; one line of
//! [`MethodSpec`] and of [`design`] registers it.

mod analysis;
mod envelope;
mod gap;
pub(crate) mod search;

use contopt_contact::{ContactSolver, InterfaceProblem};
use contopt_core::observe::{Method, Nested, Observer};
use contopt_core::{ContactState, Error, GapShape, Result, Termination, GEOMETRY_TOLERANCE};
use contopt_optimise::{
    Controller, IterationSettings, LinearProgrammeSettings, LoadSplitSettings, Optimisation,
    OptimisationMethod, Pass, Region, SearchSettings,
};
use contopt_results::{CaseReport, CurvePoint, EnvelopeCase, RollerReport, TunedProfile};
use contopt_roller::{CaseContact, CrownSettings, LoadCase, ProfileFamily, RollerFigures};
use serde::{Deserialize, Serialize};

use crate::prepare::Plan;
use crate::spec::{CaseSpec, OptimisationSpec};
use crate::zone::Layout;
use crate::Case;

/// A design method and its settings, as `[optimisation] method` names it: the library's
/// settings with the library's defaults.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MethodSpec {
    /// The iteration of §3.2 under a given load: p_max from the floating body's equilibrium
    /// (Tables 1 and 3).
    GivenLoad(IterationSettings),
    /// The iteration of §3.2 under a given displacement: p_max from the contact pressure
    /// (Table 2).
    GivenDisplacement(IterationSettings),
    /// The restricted linear programme (3.5) on the dense influence matrix (small problems).
    LinearProgramme(LinearProgrammeSettings),
    /// The optimum of (3.5) from the loads carried by the design columns, without a dense
    /// matrix (a floating body; pointwise or extruded profiles).
    LoadSplit(LoadSplitSettings),
    /// A roller's symmetric crown with the least worst-case p_max over its `[envelope]`:
    /// max over the cases of p ≤ v·p_max.
    EnvelopeSplit(LoadSplitSettings),
    /// A roller's Fujiwara–Kawase profile with K1, K2 and z_m tuned by a Nelder–Mead search to
    /// the least worst-case p_max over its `[envelope]` (or its own load), edge-loaded crowns
    /// penalised.
    ProfileSearch(SearchSettings),
    /// A roller's circular crown, its crowned fraction and end drop tuned as the profile
    /// search tunes Fujiwara–Kawase's.
    CircularSearch(SearchSettings),
}

/// The design of a case: the registration of every method.
pub(crate) fn design(spec: &CaseSpec) -> Box<dyn Design> {
    let Some(opt) = &spec.optimisation else {
        return Box::new(analysis::Analysis);
    };
    match &opt.method {
        MethodSpec::GivenLoad(s) => Box::new(gap::Gap(OptimisationMethod::GivenLoad(*s))),
        MethodSpec::GivenDisplacement(s) => {
            Box::new(gap::Gap(OptimisationMethod::GivenDisplacement(*s)))
        }
        MethodSpec::LinearProgramme(s) => {
            Box::new(gap::Gap(OptimisationMethod::LinearProgramme(*s)))
        }
        MethodSpec::LoadSplit(s) => Box::new(gap::Gap(OptimisationMethod::LoadSplit(*s))),
        MethodSpec::EnvelopeSplit(s) => Box::new(envelope::EnvelopeSplit(*s)),
        MethodSpec::ProfileSearch(s) => {
            Box::new(search::ProfileSearch(*s, ProfileFamily::FujiwaraKawase))
        }
        MethodSpec::CircularSearch(s) => {
            Box::new(search::ProfileSearch(*s, ProfileFamily::Circular))
        }
    }
}

/// What a design method does: check a case before anything is built, count its dense
/// matrices, and run.
pub(crate) trait Design {
    /// Refuses a case the method cannot run; fields are named from `[optimisation]`.
    fn check(&self, c: &Check) -> Result<()>;

    /// The n × n matrices the method holds at once on `points` points (with the solver's own
    /// counted by the solver).
    fn dense_copies(&self, points: usize, solver: &dyn ContactSolver) -> u64 {
        solver.dense_copies(points)
    }

    /// Runs the design on the case's contact, timing its stages into `report`.
    fn run(&self, c: &Context, report: &mut CaseReport) -> Result<Designed>;
}

/// What a check sees of a case.
pub(crate) struct Check<'a> {
    pub spec: &'a CaseSpec,
    pub layout: &'a Layout,
    /// Whether a body floats.
    pub floating: bool,
    /// Whether the gap is a roller's.
    pub roller: bool,
}

/// What a design runs on.
pub(crate) struct Context<'a> {
    pub spec: &'a CaseSpec,
    pub plan: &'a Plan,
    pub problem: &'a InterfaceProblem<'a>,
    pub solver: &'a dyn ContactSolver,
    pub observer: &'a dyn Observer,
    /// A roller's load cases, its own first (empty for other gaps).
    pub cases: &'a [LoadCase<'a>],
}

/// What a design found: its last iterate, how it ended, and its figures.
pub(crate) struct Designed {
    pub method: Option<Method>,
    pub solver: Option<Method>,
    pub termination: Termination,
    pub pressure: Vec<f64>,
    pub gap: Vec<f64>,
    pub rigid: Vec<f64>,
    /// The gap change per point \[mm\] (empty without one).
    pub gap_change: Vec<f64>,
    /// What the report shows as Δh instead: a roller's given crown \[mm\].
    pub crown: Option<Vec<f64>>,
    pub bound_p_max: Option<f64>,
    pub dh_max: Option<f64>,
    /// The largest p − v·p̂ over Ω_nv \[MPa\]; `None` without Ω_nv.
    pub omega_nv_excess: Option<f64>,
    pub passes: Vec<Pass>,
    pub roller: Option<RollerReport>,
}

impl Designed {
    /// A contact solve's state, nothing designed.
    fn contact(state: ContactState) -> Self {
        Self {
            pressure: state.pressure,
            gap: state.gap,
            rigid: state.rigid,
            ..Self::unsolved(state.termination, state.method)
        }
    }

    /// Nothing solved nor designed: how the run ended, and the solver it had.
    pub(crate) fn unsolved(termination: Termination, solver: Method) -> Self {
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
        }
    }
}

/// A roller's load cases for `problem`, its own first; none for other gaps.
pub(crate) fn load_cases<'a>(
    case: &Case,
    problem: &InterfaceProblem<'a>,
) -> Result<Vec<LoadCase<'a>>> {
    match &case.plan.roller {
        Some(roller) => contopt_roller::load_cases(problem, roller, case.spec.envelope.as_ref()),
        None => Ok(vec![]),
    }
}

/// The optimisation settings of a design method's case.
fn optimisation(spec: &CaseSpec) -> Result<&OptimisationSpec> {
    spec.optimisation
        .as_ref()
        .ok_or_else(|| Error::invalid("method", "none", "a design needs [optimisation]"))
}

/// The controller a method needs, checked against the zone's reach, and its regions.
fn check_controller(c: &Check) -> Result<()> {
    let opt = optimisation(c.spec)?;
    let Some(settings) = &opt.controller else {
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
    let [hx, hy] = c.layout.half_extent();
    let [cx, cy] = c.layout.edge_cell();
    settings
        .check_reach([hx, hy, 0.0], [cx, cy, 0.0])
        .map_err(within)?;
    check_regions(opt)
}

/// Ω_v and the profile's axis.
fn check_regions(opt: &OptimisationSpec) -> Result<()> {
    if let Some(omega_v) = &opt.omega_v {
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
    if let Some(axis) = opt.profile_axis {
        contopt_core::check::count("profile_axis", axis, 0, 1)?;
    }
    Ok(())
}

/// A design of a roller's crown starts from the straight roller: it designs the whole crown.
fn straight_roller(c: &Check, method: &str) -> Result<()> {
    match c.spec.contact.gap.roller_gap() {
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
fn cell_across(plan: &Plan) -> f64 {
    plan.layout.edge_cell()[1]
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
    optimisation(c.spec)?
        .controller
        .as_ref()
        .ok_or_else(|| Error::invalid("controller", "missing", "the method needs one"))?
        .build()
}

/// The gap shape, the controller and Ω_v of an optimisation of `c`: the profile along
/// `profile_axis` (a roller's axis by default), else at the finite-element face nodes (the
/// faces beyond Ω_v following its edge, [`follow_edge`]), else at every point; Ω_v from
/// `omega_v`, a roller's centre row by default, else everywhere.
fn setup(c: &Context) -> Result<Setup> {
    let opt = optimisation(c.spec)?;
    let roller = c.plan.roller.is_some();
    let iface = c.problem.interface();
    let axis = opt.profile_axis.or(roller.then_some(0));
    let controller = controller(c)?;
    let dy = cell_across(c.plan);
    let omega_v = match (&opt.omega_v, roller) {
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
    let shape = match (axis, c.problem.pressure_basis(), &omega_v) {
        (Some(axis), _, _) => GapShape::extruded(iface, axis)?,
        (None, Some(basis), Some(mask)) => follow_edge(basis, mask, iface.points())?,
        (None, Some(basis), None) => basis.clone(),
        (None, None, _) => GapShape::pointwise(iface),
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
    c.plan.roller.as_ref()?;
    let points = c.problem.interface().points();
    let figures = RollerFigures::new(contacts, points, drop, cell_across(c.plan));
    roller_report(&figures, c.spec.envelope.is_some(), tuned)
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
    if c.spec.envelope.is_none() || c.cases.len() < 2 {
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
