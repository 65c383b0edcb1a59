//! The results of a contopt run as data: what `result.json` holds and `contopt run --json`
//! prints, and what the tables, CSV files and charts are drawn from.
//!
//! The schema is a contract: [`SCHEMA_VERSION`] says which, every field is always present
//! (`null` or empty when it does not apply), each kind of quantity has one unit, written in the
//! field's name (`_mpa` for pressures and stresses, `_mm` for positions and sizes, `_um` for
//! displacements, gaps and gap changes, `_n` for forces), and a case has one label, used by the
//! table, the files and the charts alike. [`schema`] derives the JSON Schema from these types;
//! `crates/results/result.schema.json` in the repository is that schema, and a test keeps the
//! two equal.
//!
//! This crate knows nothing of bodies or solvers: a chart or a table needs only it.

mod doc;
mod settle;
pub mod shard;
mod validate;
pub mod words;

pub use doc::schema_markdown;
pub use validate::violations;

use std::collections::BTreeMap;

use contopt_core::observe::Method;
use contopt_core::{BodyFields, SectionField, Termination};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The version of this schema. Raised whenever a field changes meaning, unit or name, or goes;
/// a new field raises it too, so that a reader can refuse a file it does not know.
pub const SCHEMA_VERSION: u32 = 10;

/// The JSON Schema of [`Report`] (draft 2020-12), derived from the types.
pub fn schema() -> serde_json::Value {
    serde_json::to_value(schemars::schema_for!(Report)).unwrap_or(serde_json::Value::Null)
}

/// The contract that every field is present, `null` when it does not apply: serde would take
/// a missing `Option` as `None`, so schemars leaves such fields out of `required`.
fn every_field_required(schema: &mut schemars::Schema) {
    let names: Vec<serde_json::Value> = schema
        .get("properties")
        .and_then(|p| p.as_object())
        .map(|p| p.keys().cloned().map(serde_json::Value::String).collect())
        .unwrap_or_default();
    schema.insert("required".into(), names.into());
}

/// All cases of a scene.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct Report {
    /// The schema's version, [`SCHEMA_VERSION`].
    pub schema_version: u32,
    /// The scene's name.
    pub scene: String,
    /// What the scene shows, as its file says.
    pub description: String,
    /// One per case, in the scene's order.
    pub cases: Vec<CaseReport>,
}

/// How a case ended, as a whole.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum CaseStatus {
    /// Every method converged, or met a reduced accuracy only (which `termination` says), and
    /// the answer lies within the model's limits.
    Solved,
    /// A method stopped short; `termination` says why and how far it got.
    NotConverged,
    /// The methods converged, but the answer lies outside what the model can tell: the contact
    /// reaches an edge of its zone (`limit` says which, and the size needed).
    OutsideModel,
}

/// One case.
#[derive(Clone, Debug, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct CaseReport {
    /// The case's label, the same in tables, files and charts (`L1 = 20 mm`, `ISO/TS 16281`).
    pub label: String,
    /// The numbers the case changed from the scene, by their dotted paths of the scene, with
    /// their values: a sweep's key, or each number a `[[case]]` sets, however it is written
    /// (a table's keys each by its path, `optimisation.method.max_iterations`; an array's
    /// entries by index, `contact.zone.cells.0`). Values that are not numbers (a kind) are
    /// in `input` only.
    pub params: BTreeMap<String, f64>,
    /// The case's inputs as they were resolved: the scene with the case's values put in and
    /// every default written out. It reads back as a scene.
    pub input: serde_json::Value,
    /// How the case ended.
    pub status: CaseStatus,
    /// How its outermost method ended (the optimisation or search, else the contact solve),
    /// with its cause typed: which system stalled, which quantity is not finite, which bound
    /// or constraints conflict and where.
    pub termination: Termination,
    /// `termination` in words, as the table shows it.
    pub message: String,
    /// The optimisation or search that designed the gap; null for a contact analysis.
    pub method: Option<Method>,
    /// The contact solver that solved it (under `auto`, the one chosen).
    pub solver: Option<Method>,
    /// What the user should know about an answer that stands: a penalty solution that
    /// penetrates too far, a contact resolved by too few cells.
    pub warnings: Vec<String>,
    /// Where the answer leaves the model's limits; null within them.
    pub limit: Option<ModelLimit>,
    /// The largest contact pressure at the interface points, maxᵢ pᵢ \[MPa\]; null when the
    /// case did not converge.
    pub p_max_mpa: Option<f64>,
    /// The level p̂ of the bound p ≤ v·p̂ that the optimisation minimised (the paper's p_max of
    /// Tables 1–3) \[MPa\]; null without optimisation. The pressure reaches it where v = 1
    /// only, so `p_max_mpa` may be lower, or higher by the discretisation's error between the
    /// design nodes.
    pub bound_p_max_mpa: Option<f64>,
    /// The largest gap change Δh_max \[µm\]; null without optimisation. Under the iteration
    /// of §3.2 it is the last pass's (the paper's Table 2), within TOLH of the gap change at
    /// the points (`interface[].dh_um`), which is the one the reported pressure was solved
    /// with.
    pub dh_max_um: Option<f64>,
    /// The largest p − v·p̂ over Ω_nv, the points of Ω_opt outside Ω_v where only p ≤ v·p̂ is
    /// asked (−min χ there, eq. 3.1) \[MPa\]: at most round-off when the design keeps its
    /// bound, negative where Ω_nv carries less than it; a design that passes it beyond its
    /// solver's accuracy does not count as solved (`termination` is `infeasible`, naming the
    /// point). Null without optimisation or without Ω_nv.
    pub omega_nv_excess_mpa: Option<f64>,
    /// The floating body's approach δ, positive when the bodies are pressed together \[µm\];
    /// null when nothing floats.
    pub approach_um: Option<f64>,
    /// The largest penetration of the solution, maxᵢ(−dᵢ) \[µm\]: O(1/c) for the penalty
    /// method, round-off for the exact ones.
    pub penetration_um: Option<f64>,
    /// Hertz's nominal contact for the case's shape and load; null where Hertz does not apply.
    pub hertz: Option<Hertz>,
    /// How finely the zone resolves the contact; null without contact.
    pub resolution: Option<Resolution>,
    /// The passes of the optimisation (Table 2's columns); empty without one.
    pub passes: Vec<Pass>,
    /// The steps of a contact analysis's solve, each method's at each level, and Kalker's
    /// counts; null for a design (its passes count their solves) and for a solve that ended
    /// in an error (`termination` says which).
    pub solve: Option<SolveSteps>,
    /// The fields at the interface points.
    pub interface: Vec<Point>,
    /// Wall time of the stages \[ms\]: `build`, then `solve`, `optimise`, `search`,
    /// `envelope`, `subsurface` as the case ran them.
    pub timings_ms: BTreeMap<String, f64>,
    /// What a bearing engineer reads off a roller case; null for other gaps.
    pub roller: Option<RollerReport>,
    /// A bearing case's load distributions, rating lives and heaviest contact (`[bearing]`);
    /// null for other scenes.
    pub bearing: Option<BearingReport>,
    /// Stresses below the surface (`[output.subsurface]`); null when not asked for or when
    /// nothing is in contact.
    pub subsurface: Option<SubsurfaceReport>,
    /// The closed-form pressure of a validation case (Hertz, Sneddon's flat punch), along the
    /// line the pressure chart draws; null where none exists.
    pub reference: Option<ReferenceCurve>,
    /// The fields over the meshes of the case's finite-element bodies under its solution
    /// (`[output] fields`), written as a VTK file for a viewer (not into the JSON report: they
    /// are as large as the meshes); empty when no body has a mesh, when not asked for or when
    /// the case did not converge.
    #[serde(skip)]
    #[schemars(skip)]
    pub fields: Vec<MeshFields>,
}

/// A body's fields over its own mesh under a case's solution, and which body it is.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshFields {
    /// The body's number: 1 below the contact zone (its outward normal is n¹), 2 above it.
    pub body: usize,
    /// Its name (`fe_base`, `fe_punch`).
    pub name: String,
    /// Its mesh, displacements and stresses.
    pub fields: BodyFields,
}

/// Where an answer leaves the model's limits.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct ModelLimit {
    /// The edge the contact reaches (`x = +1.25 mm`, `r = 10 mm`).
    pub edge: String,
    /// How far the zone reaches from its centre across that edge \[mm\].
    pub extent_mm: f64,
    /// How far it must reach to hold the contact, at least \[mm\].
    pub needed_mm: f64,
    /// The whole message.
    pub message: String,
}

/// Hertz's nominal contact.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct Hertz {
    /// `point` (a sphere: a circle of radius a) or `line` (a cylinder or a roller: a strip of
    /// half-width b).
    pub contact: String,
    /// The peak pressure p₀ \[MPa\].
    pub p0_mpa: f64,
    /// The contact radius a or half-width b \[mm\].
    pub half_width_mm: f64,
}

/// How finely the zone resolves the contact.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct Resolution {
    /// The surface direction in which the contact is resolved by the fewest cells (`x` or
    /// `y` on a grid, `r` on rings and axisymmetric faces, `x` on strips and plane faces).
    pub along: String,
    /// The contact's half-width in that direction, through the largest pressure (its radius
    /// on an axisymmetric body) \[mm\].
    pub half_width_mm: f64,
    /// The cells (rings, strips, faces) across that half-width.
    pub cells: f64,
}

/// One pass of an optimisation (Table 2's columns).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct Pass {
    /// The pass k (for the linear programme: its restrictions).
    pub k: usize,
    /// The level p̂ of the bound p ≤ v·p̂ (Table 2's p_max) \[MPa\].
    pub bound_p_max_mpa: f64,
    /// Δh_max \[µm\].
    pub dh_max_um: f64,
    /// TOLH (4.2), the sum of squared changes of Δh \[mm²\] (the paper's unit).
    pub tolh_mm2: f64,
    /// Kalker's solves of the pass's contact solves (the paper's `iterp`).
    pub iterp: usize,
    /// Kalker's penetration checks of the pass's contact solves (the paper's `iterd`).
    pub iterd: usize,
}

/// The steps of one contact solve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct SolveSteps {
    /// The steps of each method the solve ran, by level: the solver's own at level 0
    /// (Polonsky–Keer's on the zone's grid, the augmented Lagrangian's Uzawa updates, the
    /// QP's interior-point steps), each method it runs one level deeper (Polonsky–Keer's
    /// nested start: each coarser grid one level more; the augmented Lagrangian's Kalker
    /// solves); by level, outermost first, and within a level in the order they first ran.
    pub steps: Vec<MethodSteps>,
    /// Kalker's solves on a contact set (the paper's `iterp`); 0 for a solver without
    /// Kalker's iteration (Polonsky–Keer, the QP).
    pub iterp: usize,
    /// Kalker's penetration checks (the paper's `iterd`); 0 as `iterp`.
    pub iterd: usize,
}

/// The steps one method took at one level of a solve.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct MethodSteps {
    /// The method.
    pub method: Method,
    /// Its level: 0 for the solver, one more for each method that runs it.
    pub level: usize,
    /// Its steps (iterations) at that level, summed over its runs there.
    pub steps: usize,
}

/// The fields at one interface point.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct Point {
    /// Coordinates \[mm\] (axisymmetric: r, z; plane: x, y; grids: x, y, z).
    pub x_mm: [f64; 3],
    /// Contact pressure \[MPa\].
    pub p_mpa: f64,
    /// Gap after deformation \[µm\].
    pub d_um: f64,
    /// Gap change Δh, or a roller's crown drop \[µm\]: the one the pressure `p_mpa` was
    /// solved with.
    pub dh_um: f64,
    /// The initial gap h the contact was solved from \[µm\] (eq. 2.1): the scene's gap less
    /// an approach, or the distance measured between two imported meshes (read as the first
    /// body's field); 4 sizes of the interface where the gap is open for good.
    pub h_um: f64,
}

/// A point of a pressure curve.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct CurvePoint {
    /// Position along the curve \[mm\].
    pub x_mm: f64,
    /// Pressure \[MPa\].
    pub p_mpa: f64,
}

/// A closed-form contact pressure beside a computed one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct ReferenceCurve {
    /// The closed form and its figures (`Hertz: p₀ = 4538 MPa, a = 0.3244 mm`).
    pub label: String,
    /// The curve along the row of interface points nearest the x axis (on an axisymmetric or
    /// plane body: along r or x), within the computed points' range; a flat punch's stops at
    /// the outermost point under the punch (p grows without bound at its rim).
    pub points: Vec<CurvePoint>,
}

/// A roller case's figures. Columns are the grid's cells along the axis; the ends are the
/// outermost columns.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct RollerReport {
    /// Where the largest pressure sits: x along the axis, y across \[mm\].
    pub p_max_at_mm: [f64; 2],
    /// Whether the ends carry more than 10 % above the pressure at mid-length.
    pub edge_loading: bool,
    /// The contact half-width at mid-length and at the ends (their mean) \[mm\], counted in
    /// cells.
    pub half_width_mm: [f64; 2],
    /// The crown's drop at the ends \[µm\].
    pub crown_drop_end_um: f64,
    /// The load cases of the scene's `[envelope]` under this crown, the scene's own first;
    /// empty without an envelope.
    pub envelope: Vec<EnvelopeCase>,
    /// The largest p_max over the envelope \[MPa\]; null without an envelope.
    pub worst_p_max_mpa: Option<f64>,
    /// The parameters a profile search found; null for other crowns.
    pub tuned: Option<TunedProfile>,
}

/// One load case of a roller's envelope.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct EnvelopeCase {
    /// Load Q \[N\].
    pub load_n: f64,
    /// Misalignment γ \[arc-minutes\].
    pub tilt_arcmin: f64,
    /// Largest contact pressure \[MPa\].
    pub p_max_mpa: f64,
    /// Where it sits: x along the axis, y across \[mm\].
    pub p_max_at_mm: [f64; 2],
    /// Whether an end carries more than 10 % above the pressure at mid-length.
    pub edge_loading: bool,
    /// The roller's approach \[µm\].
    pub approach_um: f64,
    /// Cells across the contact's half-width through its peak: below the report's least
    /// (`MIN_CELLS_ACROSS` of the scene crate, 8) the case carries a warning.
    pub cells_across: f64,
    /// The largest pressure on the grid's outermost rows across \[MPa\]: above 10⁻⁶ of the
    /// case's p_max its contact reaches the grid's edge across, and the case is outside the
    /// model.
    pub edge_across_mpa: f64,
    /// The pressure along the centre row.
    pub centre_line: Vec<CurvePoint>,
}

/// A crown tuned by a profile search: Fujiwara–Kawase's or a circular one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct TunedProfile {
    /// The family: `fujiwara_kawase` or `circular`.
    pub family: String,
    /// Fujiwara–Kawase's load coefficient K1; null for a circular crown.
    pub k1: Option<f64>,
    /// The crowned fraction of each half-length (Fujiwara–Kawase's K2).
    pub k2: f64,
    /// End drop z_m \[µm\].
    pub z_m_um: f64,
    /// A circular crown's radius \[mm\]; null for Fujiwara–Kawase's.
    pub radius_mm: Option<f64>,
    /// How many crowns the search solved (each under every case).
    pub evaluations: usize,
}

/// A bearing case's figures (`[bearing]`): each load case's distribution over the rollers and
/// rating lives, the lives over the duty cycle, and the heaviest contact of the roller on the
/// solved raceway.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct BearingReport {
    /// ISO 281's basic dynamic radial load rating C_r \[N\].
    pub dynamic_load_rating_n: f64,
    /// ISO/TS 16281's slice ratings on the inner and the outer raceway, q_ci and q_ce \[N\].
    pub slice_ratings_n: [f64; 2],
    /// The raceway whose contacts the case's fields and `p_max_mpa` show (both raceways'
    /// contacts are solved): `inner` or `outer`.
    pub raceway: String,
    /// The ring that rotates against the load: `inner` or `outer`.
    pub rotating: String,
    /// The roller load the grid and the load-dependent profiles are built for \[N\].
    pub design_load_n: f64,
    /// The weight of the image pressure at the roller's free ends; null: a half-space roller.
    pub free_ends_weight: Option<f64>,
    /// The crown's tolerance band ±t on its end drop \[µm\] (0: none); lives and pressures are
    /// the worst over the band.
    pub tolerance_um: f64,
    /// The robust crown's pressure level per load case, relative to the reference case's,
    /// when it is designed for the life (`objective = "life"`); null otherwise.
    pub pressure_levels: Option<Vec<f64>>,
    /// The solved contacts on both raceways: loaded rollers of every load case, duplicates
    /// (a roller and its mirror across the load line) solved once, times the band's three
    /// crowns.
    pub contacts_solved: usize,
    /// The load cases, in the scene's order.
    pub load_cases: Vec<BearingLoadCase>,
    /// Palmgren–Miner's lives over the load cases' time fractions.
    pub duty_cycle: Lives,
    /// The contact with the largest pressure over every load case and the band.
    pub worst: WorstContact,
    /// The rotating ring's speed against the other \[min⁻¹\]; null when the scene gives none
    /// (lives then in revolutions only).
    pub speed_rpm: Option<f64>,
    /// The duty cycle's lives in hours at that speed; null without one.
    pub duty_cycle_hours: Option<LifeHours>,
    /// ISO 281's lubrication and fatigue limit figures behind the modified lives; null
    /// without `[bearing.lubrication]`.
    pub lubrication: Option<LubricationReport>,
    /// The worst roller crown over its tolerance box; null without `crown_tolerance`.
    pub crown_tolerance: Option<CrownToleranceReport>,
}

/// ISO 281's figures of a bearing's lubrication and fatigue limit.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct LubricationReport {
    /// The lubricant's kinematic viscosity at the operating temperature ν \[mm²/s\].
    pub viscosity_mm2_s: f64,
    /// ISO 281's rated viscosity ν₁ at the speed and pitch diameter \[mm²/s\].
    pub rated_viscosity_mm2_s: f64,
    /// The viscosity ratio κ = ν/ν₁ (a_ISO takes κ > 4 as 4).
    pub kappa: f64,
    /// The contamination factor e_C.
    pub contamination: f64,
    /// ISO 76's basic static radial load rating C_0r \[N\].
    pub static_load_rating_n: f64,
    /// The fatigue load limit C_u \[N\]: the scene's, or ISO 281's C_0r/8.2 (smaller past
    /// D_pw = 100 mm).
    pub fatigue_load_limit_n: f64,
}

/// The worst roller crown over the box of its manufacturing tolerances, found by a grid over
/// the box (its corners among its points) and a simplex search from the grid's worst, on the
/// solved raceway's contacts under the final load distributions (design grid).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct CrownToleranceReport {
    /// The tolerances, each ±: the end drop \[µm\], the crowned length at each end \[mm\],
    /// the log constant (relative).
    pub tolerances: [f64; 3],
    /// Which of them the crown has (a circular crown has no log constant, ISO's no finite
    /// end drop).
    pub active: [bool; 3],
    /// The worst crown's deviation from the nominal, each in −1 … 1 of its tolerance.
    pub deviation: [f64; 3],
    /// The worst crown's p_max over the contacts \[MPa\].
    pub p_max_mpa: f64,
    /// The worst crown's duty-cycle life from the solved raceway's slice peaks
    /// \[10⁶ revolutions\].
    pub life_mrev: f64,
    /// The nominal crown's p_max on the same contacts \[MPa\].
    pub nominal_p_max_mpa: f64,
    /// The nominal crown's life on the same contacts \[10⁶ revolutions\].
    pub nominal_life_mrev: f64,
    /// The objective at the worst corner of the box (the worst p_max \[MPa\], or −1000·ln of
    /// the life for `objective = "life"`).
    pub worst_corner: f64,
    /// The objective at the worst crown found, at least `worst_corner`.
    pub worst: f64,
    /// The crowns evaluated.
    pub evaluations: usize,
}

/// Lives in hours at the bearing's speed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct LifeHours {
    /// ISO 281's basic rating life L₁₀h \[h\].
    pub iso_281_h: f64,
    /// ISO/TS 16281's reference rating life from the half-space contacts, L₁₀rh \[h\].
    pub half_space_h: f64,
    /// ISO 281's modified rating life L_nmh \[h\]; null without lubrication.
    pub modified_h: Option<f64>,
    /// ISO/TS 16281's modified reference rating life L_nmrh \[h\]; null without lubrication.
    pub modified_reference_h: Option<f64>,
}

/// Modified lives (ISO 281's a_ISO applied).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct ModifiedLives {
    /// a_ISO at P = F_r (over a duty cycle: L_nm/L₁₀).
    pub a_iso: f64,
    /// ISO 281's modified rating life L_nm = a_ISO·L₁₀ \[10⁶ revolutions\].
    pub modified_mrev: f64,
    /// L_nmr/L₁₀r: the slices' a_ISO in effect over the bearing.
    pub a_iso_reference: f64,
    /// ISO/TS 16281's modified reference rating life L_nmr from the half-space contacts'
    /// slices, a_ISO per slice (each slice's life a_ISO,k·(q_c/q_e,k)⁴) \[10⁶ revolutions\].
    pub modified_reference_mrev: f64,
}

/// One load case of a bearing.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct BearingLoadCase {
    /// Its label (`F_r = 8900 N`, or the scene's).
    pub label: String,
    /// Its time fraction of the duty cycle.
    pub fraction: f64,
    /// The radial load F_r \[N\].
    pub radial_n: f64,
    /// The rings' relative tilt in the load's plane \[arc-minutes\]: held, or solved under
    /// the moment.
    pub misalignment_arcmin: f64,
    /// The moment the rollers carry in the load's plane \[N·mm\].
    pub moment_nmm: f64,
    /// The inner ring's displacement against the outer, along the load and across it \[µm\].
    pub displacement_um: [f64; 2],
    /// The loaded zone's half-angle \[°\] (180 when the clearance closes all round).
    pub loaded_zone_deg: f64,
    /// Harris's load distribution factor ε.
    pub load_factor: f64,
    /// The rings' Newton steps.
    pub iterations: usize,
    /// Every roller, roller 0 first.
    pub rollers: Vec<BearingRoller>,
    /// The largest contact pressure over its loaded rollers on the solved raceway \[MPa\].
    pub p_max_mpa: f64,
    /// The largest contact pressure over its loaded rollers on the inner and on the outer
    /// raceway \[MPa\].
    pub p_max_rings_mpa: [f64; 2],
    /// Its rating lives.
    pub lives: Lives,
    /// Its lives in hours at the bearing's speed; null without one.
    pub hours: Option<LifeHours>,
}

/// One roller of a load case.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct BearingRoller {
    /// Its angle from the load's direction \[°\].
    pub angle_deg: f64,
    /// Its load Q_j \[N\].
    pub load_n: f64,
    /// Its tilt against the inner and the outer raceway \[arc-minutes\].
    pub tilt_arcmin: [f64; 2],
    /// Its largest contact pressure on the solved raceway \[MPa\] (the band's worst); null
    /// when unloaded.
    pub p_max_mpa: Option<f64>,
    /// Its largest contact pressure on the inner and on the outer raceway \[MPa\] (the
    /// band's worst); null when unloaded.
    pub p_max_rings_mpa: [Option<f64>; 2],
}

/// Rating lives \[10⁶ revolutions\].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct Lives {
    /// ISO 281's basic rating life L10 = (C_r/P_r)^(10/3), P_r = F_r.
    pub iso_281_mrev: f64,
    /// ISO/TS 16281's basic reference rating life L10r from the slice model's slice loads.
    pub slice_model_mrev: f64,
    /// L10r with the solved raceway's slice loads from the half-space contacts (the band's
    /// worst).
    pub half_space_mrev: f64,
    /// L10r with each of those slices' loads raised to the Hertzian line load of its peak
    /// pressure, π·R·w·p²/E* (the edge stresses of the contact, which a slice load alone
    /// does not see; the band's worst).
    pub peak_pressure_mrev: f64,
    /// The half-space life's rings alone, inner and outer: each raceway's L₁₀r, which
    /// `half_space_mrev` combines as (L_i^(−9/8) + L_e^(−9/8))^(−8/9) (ISO/TS 16281).
    pub rings_mrev: [f64; 2],
    /// The modified lives; null without `[bearing.lubrication]`.
    pub modified: Option<ModifiedLives>,
}

/// The contact with the largest pressure of a bearing case.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct WorstContact {
    /// Its load case (from 0).
    pub load_case: usize,
    /// Its roller (from 0).
    pub roller: usize,
    /// The roller's load \[N\].
    pub load_n: f64,
    /// Its tilt against the solved raceway \[arc-minutes\].
    pub tilt_arcmin: f64,
    /// The crown's deviation within the tolerance band \[µm\] (−t, 0 or +t at the ends).
    pub deviation_um: f64,
    /// The largest pressure \[MPa\].
    pub p_max_mpa: f64,
    /// Where it sits: x along the axis, y across \[mm\].
    pub p_max_at_mm: [f64; 2],
    /// Whether an end carries more than 10 % above the pressure at mid-length.
    pub edge_loading: bool,
}

/// Stresses below the surface under a case's contact pressure.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct SubsurfaceReport {
    /// The depths evaluated \[mm\].
    pub depths_mm: Vec<f64>,
    /// Each body that computes stresses (a rigid body does not).
    pub bodies: Vec<BodyStresses>,
}

/// The stresses below one body's surface.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct BodyStresses {
    /// The body (two names when they share one field: a roller and raceway of one Poisson's
    /// ratio).
    pub body: String,
    /// The largest von Mises and Tresca stresses, the largest tension σ₁ and compression σ₃,
    /// each with where it is. A finite-element body reports its nodes, (x, y) in its own
    /// coordinates and the depth as the distance to the nearest contact point; a peak at a
    /// singular edge grows as the mesh is refined.
    pub peaks: Peaks,
    /// The sections' fields, written as CSV and heat maps (not into the JSON report).
    #[serde(skip)]
    #[schemars(skip)]
    pub sections: Vec<SectionField>,
}

/// The largest value of each criterion below a surface.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct Peaks {
    /// Largest von Mises stress.
    pub von_mises: Peak,
    /// Largest shear stress (σ₁ − σ₃)/2 (Tresca).
    pub tresca: Peak,
    /// Largest principal stress σ₁ (the largest tension when positive).
    pub max_principal: Peak,
    /// Smallest principal stress σ₃ (the largest compression), its value negative.
    pub min_principal: Peak,
    /// Largest orthogonal shear |τ_xz| (it reverses as a contact rolls along x; a plane or
    /// axisymmetric body's in-plane shear).
    pub shear_xz: Peak,
    /// Largest orthogonal shear |τ_yz| (rolling along y: a roller on a grid along x); null
    /// where τ_yz is zero at every point evaluated (a plane or axisymmetric body has none), a
    /// peak that is nowhere.
    pub shear_yz: Option<Peak>,
}

/// Where a criterion is largest, and its value.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(transform = every_field_required)]
pub struct Peak {
    /// The value \[MPa\].
    pub value_mpa: f64,
    /// First surface coordinate \[mm\].
    pub x_mm: f64,
    /// Second surface coordinate \[mm\] (0 on a plane or axisymmetric body).
    pub y_mm: f64,
    /// Depth below the surface \[mm\].
    pub depth_mm: f64,
}

impl From<contopt_core::Peak> for Peak {
    fn from(p: contopt_core::Peak) -> Self {
        Self {
            value_mpa: p.value,
            x_mm: p.x,
            y_mm: p.y,
            depth_mm: p.depth,
        }
    }
}

impl From<contopt_core::StressPeaks> for Peaks {
    fn from(p: contopt_core::StressPeaks) -> Self {
        Self {
            von_mises: p.von_mises.into(),
            tresca: p.tresca.into(),
            max_principal: p.max_principal.into(),
            min_principal: p.min_principal.into(),
            shear_xz: p.shear_xz.into(),
            shear_yz: (p.shear_yz.value != 0.0).then(|| p.shear_yz.into()),
        }
    }
}

impl CaseReport {
    /// A case that has not run yet: every figure null, `status` not converged.
    pub fn new(label: &str, params: &BTreeMap<String, f64>, input: serde_json::Value) -> Self {
        let termination = Termination::Stopped { after: 0 };
        Self {
            label: label.to_string(),
            params: params.clone(),
            input,
            status: CaseStatus::NotConverged,
            message: termination.to_string(),
            termination,
            method: None,
            solver: None,
            warnings: vec![],
            limit: None,
            p_max_mpa: None,
            bound_p_max_mpa: None,
            dh_max_um: None,
            omega_nv_excess_mpa: None,
            approach_um: None,
            penetration_um: None,
            hertz: None,
            resolution: None,
            passes: vec![],
            solve: None,
            interface: vec![],
            timings_ms: BTreeMap::new(),
            roller: None,
            bearing: None,
            subsurface: None,
            reference: None,
            fields: vec![],
        }
    }

    /// Whether the case converged within the model's limits.
    pub fn is_solved(&self) -> bool {
        self.status == CaseStatus::Solved
    }

    /// Records the wall time of a stage that began at `since`.
    pub fn time(&mut self, stage: &str, since: std::time::Instant) {
        self.timings_ms
            .insert(stage.to_string(), 1e3 * since.elapsed().as_secs_f64());
    }
}
