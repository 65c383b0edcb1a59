//! A cylindrical roller bearing (`[bearing]`): its rollers' loads and tilts by ISO/TS 16281's
//! slice model under each load case of a duty cycle, every loaded roller's contact on one
//! raceway by the half-space grid, and the rating lives per load case and over the cycle.
//!
//! A bearing composes the scene's contact itself: its roller on the solved raceway, both
//! half-spaces on a grid over the effective length ([`compose`]: `[contact]` and `[[body]]`
//! are written from the bearing, the roller with its free ends), so that the solver, the
//! design of the crown (`[optimisation]`) and the outputs are the scene's as for any roller.
//! The envelope of the design is the bearing's own: every loaded roller of every load case,
//! and the crown's tolerance band. The run is in [`run`].

mod run;

pub(crate) use run::run;

use std::ops::Range;

use contopt_core::{check, Error, Material, Result};
use contopt_input::{Node, Value};
use contopt_roller::{
    dynamic_load_rating, slice_ratings, BearingLoad, Crown, CrownSettings,
    CylindricalRollerBearing, Raceway, Roller, SliceRatings, Tilt,
};
use serde::{Deserialize, Serialize};

use crate::error::Locator;
use crate::methods::BearingCrown;
use crate::spec::CaseSpec;
use crate::SceneError;

/// The image pressure's weight at the roller's free ends unless the scene sets one: the
/// weight with which the image alone matches Hetényi's free end face for pressures that reach
/// the end (1.357 under Lundberg's crown, 1.389 under a straight roller's edge, on a roller's
/// grid of 100 × 41 cells; 1.29 where the pressure stops short of the end, and there the
/// weight hardly matters: `examples/free_ends.rs`, the book's chapter "From the bearing to the
/// crown").
pub const FREE_END_WEIGHT: f64 = 1.37;

/// Time fractions of a duty cycle must sum to 1 within this.
const FRACTIONS: f64 = 1e-9;

/// The largest misalignment a load case may hold \[arc-minutes\]: ten degrees, far past any
/// bearing's, and within the slice model's small angles.
const MAX_MISALIGNMENT_ARCMIN: f64 = 600.0;

/// The largest tolerance band \[µm\]: a millimetre.
const MAX_TOLERANCE_UM: f64 = 1000.0;

/// Stribeck's factor of the design load: Q₀ = 5·F_r/Z for the heaviest load case.
const STRIBECK: f64 = 5.0;

/// The eighth root of a time fraction's ratio in [`duty_cycle_levels`]: ISO/TS 16281's slice
/// life goes as q^(−4) (its exponents 9/2 and 8/9 of [`contopt_roller::reference_rating_life`]
/// on one slice), and a slice's Hertzian load as p₀² (Johnson eq. 4.45), so a case's damage
/// t·L⁻¹ goes as t·p₀⁸.
const DAMAGE_EXPONENT: f64 = 8.0;

/// The robust crown's pressure level s_i of each load case for the duty-cycle life, relative
/// to the reference case r, the one of the largest time fraction (the first of those):
///
/// s_i = max(1, (Q_i/Q_r)^(1/2) · (t_r/t_i)^(1/8)),
///
/// `heaviest` = Q_i the load case's heaviest roller load on the solved raceway, `fractions` =
/// t_i. (Q_i/Q_r)^(1/2) is the ratio of the cases' Hertzian line-contact pressures
/// (p₀ ∝ √Q, Johnson eq. 4.45): each case is held to its own load's pressure, not to the
/// heaviest's. (t_r/t_i)^(1/8) lets a case the duty cycle spends less time in carry more by
/// the same damage t·p₀⁸ ([`DAMAGE_EXPONENT`]). No case is held below the reference level: a
/// lighter case held to its own small p₀ would shape the crown for damage it hardly does.
/// With one load case every level is 1 and the crown is the p_max one.
pub fn duty_cycle_levels(heaviest: &[f64], fractions: &[f64]) -> Result<Vec<f64>> {
    check::all_positive("heaviest", heaviest)?;
    check::all_positive("fractions", fractions)?;
    if heaviest.len() != fractions.len() {
        return Err(Error::invalid(
            "heaviest",
            format!("{} loads", heaviest.len()),
            format!("one per load case ({})", fractions.len()),
        ));
    }
    let r = (0..fractions.len())
        .reduce(|a, b| if fractions[b] > fractions[a] { b } else { a })
        .ok_or_else(|| Error::invalid("fractions", "none", "at least one load case"))?;
    Ok(heaviest
        .iter()
        .zip(fractions)
        .map(|(q, t)| {
            let level = (q / heaviest[r]).sqrt() * (fractions[r] / t).powf(1.0 / DAMAGE_EXPONENT);
            level.max(1.0)
        })
        .collect())
}

/// A raceway, as a scene names it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RacewaySpec {
    /// The inner ring's raceway (convex; the default).
    #[default]
    Inner,
    /// The outer ring's raceway (concave).
    Outer,
}

impl RacewaySpec {
    fn raceway(self) -> Raceway {
        match self {
            RacewaySpec::Inner => Raceway::Inner,
            RacewaySpec::Outer => Raceway::Outer,
        }
    }

    fn name(self) -> &'static str {
        match self {
            RacewaySpec::Inner => "inner",
            RacewaySpec::Outer => "outer",
        }
    }
}

/// What a design of a bearing's crown minimises.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BearingObjective {
    /// The worst contact's p_max over every loaded roller, load case and the tolerance band
    /// (the default).
    #[default]
    PMax,
    /// The duty cycle's life: ISO/TS 16281's L10r from the half-space contacts' slice loads,
    /// by Palmgren–Miner over the load cases, the band's worst. A profile search maximises it
    /// over its family; the robust crown (`envelope_split`) is designed for it without a
    /// search, by holding each load case i to its duty-cycle pressure level
    /// s_i = max(1, (Q_i/Q_r)^(1/2)·(t_r/t_i)^(1/8)) times p̂ instead of one level for all
    /// (Q_i its heaviest roller load, t_i its time fraction, r the case of the largest).
    Life,
}

/// A cylindrical roller bearing (`[bearing]`): one row, contact angle 0, rings and rollers of
/// one material.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BearingSpec {
    /// Number of rollers Z.
    pub rollers: usize,
    /// Roller diameter D_we \[mm\].
    pub roller_diameter_mm: f64,
    /// Roller length between its sharp corners \[mm\].
    pub roller_length_mm: f64,
    /// Axial width of each end's chamfer \[mm\] (default 0): the effective length L_we is the
    /// length less two chamfers, and the roller's free end faces lie a chamfer beyond it.
    #[serde(default)]
    pub chamfer_mm: f64,
    /// Pitch diameter D_pw \[mm\].
    pub pitch_diameter_mm: f64,
    /// Diametral operating clearance \[mm\] (default 0; negative: a preload).
    #[serde(default)]
    pub clearance_mm: f64,
    /// Slices per roller of ISO/TS 16281's model (default 30, the standard's least).
    #[serde(default = "BearingSpec::default_slices")]
    pub slices: usize,
    /// The roller's crown (default straight; a design of the crown starts straight).
    #[serde(default)]
    pub roller_profile: CrownSettings,
    /// The inner raceway's crown (default straight).
    #[serde(default)]
    pub inner_profile: CrownSettings,
    /// The outer raceway's crown (default straight).
    #[serde(default)]
    pub outer_profile: CrownSettings,
    /// The rings' and rollers' material (ISO/TS 16281's load–deflection constant is steel's).
    pub material: Material,
    /// The raceway whose contacts are solved on the half-space grid (default inner, the
    /// convex one, where the pressure is highest).
    #[serde(default)]
    pub raceway: RacewaySpec,
    /// The ring that rotates against the load (default inner), for the lives.
    #[serde(default)]
    pub rotating: RacewaySpec,
    /// The roller–raceway grid: cells along the effective length, and across (odd, at
    /// least 3).
    pub cells: [usize; 2],
    /// How far the grid's outer cell centres reach across, in Hertz half-widths of the design
    /// load (default 3).
    #[serde(default = "BearingSpec::default_reach")]
    pub reach_b: f64,
    /// The roller load the grid and the load-dependent profiles are built for \[N\]; default
    /// Stribeck's 5·F_r/Z of the heaviest load case.
    #[serde(default)]
    pub design_load_n: Option<f64>,
    /// The roller's end faces as free faces, by the image pressure of weight
    /// `free_end_weight` (default on); off: a half-space roller.
    #[serde(default = "BearingSpec::default_free_ends")]
    pub free_ends: bool,
    /// The image pressure's weight at the free ends (default [`FREE_END_WEIGHT`]).
    #[serde(default = "BearingSpec::default_free_end_weight")]
    pub free_end_weight: f64,
    /// The crown's tolerance band: its end drop may be off by ±t \[µm\] (default 0); every
    /// contact is solved at both ends of the band too, and the worst is taken.
    #[serde(default)]
    pub tolerance_um: f64,
    /// What a design of the crown minimises (default the worst p_max).
    #[serde(default)]
    pub objective: BearingObjective,
    /// The angle of roller 0 from the load's direction \[°\] (default 0: a roller on the load
    /// line).
    #[serde(default)]
    pub first_roller_deg: f64,
    /// The load cases of the duty cycle (`[[bearing.load]]`).
    pub load: Vec<BearingLoadSpec>,
}

/// One load case of a bearing's duty cycle (`[[bearing.load]]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BearingLoadSpec {
    /// Its name in tables (default `F_r = … N`).
    #[serde(default)]
    pub label: Option<String>,
    /// The radial load F_r \[N\].
    pub radial_n: f64,
    /// The inner ring held misaligned against the outer, in the load's plane
    /// \[arc-minutes\] (default 0).
    #[serde(default)]
    pub misalignment_arcmin: f64,
    /// A moment on the inner ring in the load's plane \[N·mm\]: the ring is then free to tilt
    /// under it (instead of a held misalignment).
    #[serde(default)]
    pub moment_nmm: Option<f64>,
    /// Its time fraction of the duty cycle (default 1; the fractions sum to 1).
    #[serde(default = "BearingLoadSpec::default_fraction")]
    pub fraction: f64,
}

impl BearingSpec {
    fn default_slices() -> usize {
        30
    }

    fn default_reach() -> f64 {
        3.0
    }

    fn default_free_ends() -> bool {
        true
    }

    fn default_free_end_weight() -> f64 {
        FREE_END_WEIGHT
    }

    /// The effective length L_we \[mm\].
    fn effective_length(&self) -> f64 {
        self.roller_length_mm - 2.0 * self.chamfer_mm
    }

    /// The roller load the grid and profiles are built for \[N\].
    fn design_load(&self) -> f64 {
        self.design_load_n.unwrap_or_else(|| {
            let heaviest = self.load.iter().map(|l| l.radial_n).fold(0.0, f64::max);
            STRIBECK * heaviest / self.rollers.max(1) as f64
        })
    }

    /// The solved raceway's diameter, positive for the inner ring, negative for the outer.
    fn raceway_diameter(&self) -> f64 {
        match self.raceway {
            RacewaySpec::Inner => self.pitch_diameter_mm - self.roller_diameter_mm,
            RacewaySpec::Outer => -(self.pitch_diameter_mm + self.roller_diameter_mm),
        }
    }

    /// The bearing without crowns, checked (its dimensions).
    fn bearing(&self) -> Result<CylindricalRollerBearing> {
        check::finite("bearing.first_roller_deg", self.first_roller_deg)?;
        let b = CylindricalRollerBearing {
            rollers: self.rollers,
            roller_diameter: self.roller_diameter_mm,
            roller_length: self.roller_length_mm,
            chamfer: self.chamfer_mm,
            pitch_diameter: self.pitch_diameter_mm,
            clearance: self.clearance_mm,
            roller_crown: Crown::Straight,
            inner_crown: Crown::Straight,
            outer_crown: Crown::Straight,
            slices: self.slices,
            first_roller: self.first_roller_deg.to_radians(),
        };
        b.check()?;
        Ok(b)
    }

    /// The roller on the solved raceway under the design load, its crown straight.
    fn roller(&self) -> Roller {
        Roller {
            diameter: self.roller_diameter_mm,
            length: self.effective_length(),
            raceway_diameter: Some(self.raceway_diameter()),
            roller: self.material,
            raceway: self.material,
            load: self.design_load(),
            tilt: 0.0,
            crown: Crown::Straight,
        }
    }
}

impl BearingLoadSpec {
    fn default_fraction() -> f64 {
        1.0
    }

    /// Its label: the scene's, or `F_r = … N`.
    fn label(&self) -> String {
        self.label
            .clone()
            .unwrap_or_else(|| format!("F_r = {} N", self.radial_n))
    }

    /// The library's load: a held misalignment, or a moment the ring tilts under.
    fn load(&self) -> BearingLoad {
        let tilt = match self.moment_nmm {
            Some(m) => Tilt::Moment(m),
            None => Tilt::Held((self.misalignment_arcmin / 60.0).to_radians()),
        };
        BearingLoad {
            radial_n: self.radial_n,
            tilt,
        }
    }

    /// Checks the case's numbers; fields are named from the case.
    fn check(&self) -> Result<()> {
        check::positive("radial_n", self.radial_n)?;
        check::between(
            "misalignment_arcmin",
            self.misalignment_arcmin,
            -MAX_MISALIGNMENT_ARCMIN,
            MAX_MISALIGNMENT_ARCMIN,
        )?;
        if let Some(m) = self.moment_nmm {
            check::finite("moment_nmm", m)?;
            if self.misalignment_arcmin != 0.0 {
                return Err(Error::invalid(
                    "moment_nmm",
                    m,
                    "a load case holds the ring misaligned or lets it tilt under a moment, \
                     not both: leave misalignment_arcmin out",
                ));
            }
        }
        check::positive("fraction", self.fraction).map(|_| ())
    }
}

/// A bearing as its case's check planned it: the bearing with its crowns, the load cases,
/// the ratings.
#[derive(Debug)]
pub(crate) struct BearingPlan {
    /// The bearing, the scene's crowns built.
    pub bearing: CylindricalRollerBearing,
    /// The load cases: label, load, time fraction.
    pub loads: Vec<(String, BearingLoad, f64)>,
    /// The solved raceway and the rotating ring.
    pub raceway: Raceway,
    pub rotating: Raceway,
    /// ISO 281's C_r \[N\] and ISO/TS 16281's slice ratings.
    pub rating: f64,
    pub ratings: SliceRatings,
    /// The design load \[N\].
    pub design_load: f64,
    /// The image's weight at the free ends, when they are free.
    pub free_ends: Option<f64>,
    /// The tolerance band \[mm\].
    pub tolerance: f64,
    pub objective: BearingObjective,
}

/// The span of the key at `path` of `tree`.
fn span(tree: &Node, path: &str) -> Option<Range<usize>> {
    tree.get(path).and_then(Node::span)
}

/// A number placed at the key `path` of `tree`.
fn number(value: f64, tree: &Node, path: &str) -> Node {
    Node::new(Value::Float(value)).with_span(span(tree, path))
}

/// A copy of the node at `path` of `tree`, or `default` placed at the bearing.
fn copy(tree: &Node, path: &str, default: Value) -> Node {
    tree.get(path)
        .cloned()
        .unwrap_or_else(|| Node::new(default).with_span(span(tree, "bearing")))
}

/// Writes the contact a bearing composes into a case's `tree`: the roller on the solved
/// raceway (`[contact]`: a grid of `bearing.cells`, the roller gap with the roller's and the
/// raceway's crowns, the design load) and the two half-spaces (`[[body]]`: the raceway, then
/// the roller with its free ends), each value placed at the bearing key it comes from; and
/// `[output.subsurface]` when the scene does not set it (a bearing reports the stresses below
/// its worst contact). A scene without `[bearing]` is left alone; one that also writes
/// `[contact]` or `[[body]]` is refused.
pub(crate) fn compose(tree: &mut Node, at: &Locator) -> Result<(), SceneError> {
    if tree.get("bearing").is_none() {
        return Ok(());
    }
    for key in ["contact", "body", "envelope"] {
        // A resolved input writes an absent envelope as null.
        if tree
            .get(key)
            .is_some_and(|n| !matches!(n.value(), Value::Null))
        {
            return Err(at.at(
                key,
                "a bearing composes its roller's contact, bodies and envelope itself: give the \
                 grid as bearing.cells and leave [contact], [[body]] and [envelope] out",
            ));
        }
    }
    let spec: BearingSpec = tree.deserialize_at("bearing").map_err(|e| at.input(e))?;
    spec.bearing().map_err(|e| at.library("", e))?;
    check_cells(&spec).map_err(|e| at.library("bearing", e))?;
    let contact = contact_node(&spec, tree);
    let bodies = body_nodes(&spec, tree);
    tree.insert("contact", contact).map_err(|e| at.input(e))?;
    tree.insert("body", bodies).map_err(|e| at.input(e))?;
    if tree.get("output").is_none() {
        let output = Node::table([("subsurface", Node::table::<&str>([]))]);
        tree.insert("output", output).map_err(|e| at.input(e))?;
    } else if tree.get("output.subsurface").is_none() {
        let empty = Node::table::<&str>([]);
        tree.insert("output.subsurface", empty)
            .map_err(|e| at.input(e))?;
    }
    Ok(())
}

/// The grid's cells: at least one along, an odd number across, at least 3.
fn check_cells(spec: &BearingSpec) -> Result<()> {
    check::count("cells[0]", spec.cells[0], 1, usize::MAX)?;
    if spec.cells[1] < 3 || spec.cells[1].is_multiple_of(2) {
        return Err(Error::invalid(
            "cells[1]",
            spec.cells[1],
            "an odd number, at least 3: the centre row lies on y = 0",
        ));
    }
    check::positive("reach_b", spec.reach_b).map(|_| ())
}

/// `[contact]` of a bearing.
fn contact_node(spec: &BearingSpec, tree: &Node) -> Node {
    let cells = Node::new(Value::Array(
        spec.cells
            .iter()
            .map(|&n| Node::new(Value::Integer(n as i64)).with_span(span(tree, "bearing.cells")))
            .collect(),
    ))
    .with_span(span(tree, "bearing.cells"));
    let zone = Node::table([
        ("kind", Node::new(Value::String("grid".into()))),
        ("cells", cells),
    ]);
    let raceway_profile = match spec.raceway {
        RacewaySpec::Inner => "bearing.inner_profile",
        RacewaySpec::Outer => "bearing.outer_profile",
    };
    let straight = || Value::String("straight".into());
    let gap = Node::table([
        ("kind", Node::new(Value::String("roller".into()))),
        (
            "diameter_mm",
            number(spec.roller_diameter_mm, tree, "bearing.roller_diameter_mm"),
        ),
        (
            "length_mm",
            number(spec.effective_length(), tree, "bearing.roller_length_mm"),
        ),
        (
            "raceway_diameter_mm",
            number(spec.raceway_diameter(), tree, "bearing.pitch_diameter_mm"),
        ),
        ("reach_b", number(spec.reach_b, tree, "bearing.reach_b")),
        ("profile", copy(tree, "bearing.roller_profile", straight())),
        ("raceway_profile", copy(tree, raceway_profile, straight())),
    ]);
    let load = Node::table([(
        "force_n",
        number(spec.design_load(), tree, "bearing.design_load_n"),
    )]);
    Node::table([("zone", zone), ("gap", gap), ("load", load)])
}

/// `[[body]]` of a bearing: the solved raceway, then the roller.
fn body_nodes(spec: &BearingSpec, tree: &Node) -> Node {
    let material = || copy(tree, "bearing.material", Value::Null);
    let name = |n: String| Node::new(Value::String(n));
    let half_space = || Node::new(Value::String("half_space".into()));
    let raceway = Node::table([
        ("name", name(format!("{} raceway", spec.raceway.name()))),
        ("kind", half_space()),
        ("material", material()),
    ]);
    let mut roller = vec![
        ("name", name("roller".into())),
        ("kind", half_space()),
        ("material", material()),
    ];
    if spec.free_ends {
        let face = 0.5 * spec.effective_length() + spec.chamfer_mm;
        let faces = Node::new(Value::Array(vec![
            number(-face, tree, "bearing.chamfer_mm"),
            number(face, tree, "bearing.chamfer_mm"),
        ]));
        let ends = Node::table([
            ("faces_mm", faces),
            (
                "weight",
                number(spec.free_end_weight, tree, "bearing.free_end_weight"),
            ),
        ])
        .with_span(span(tree, "bearing.free_ends"));
        roller.push(("free_ends", ends));
    }
    Node::new(Value::Array(vec![raceway, Node::table(roller)]))
}

/// Checks a bearing case beyond its composed contact: the load cases and their fractions,
/// the crowns, the ratings, the tolerance band and the design method; fields are named from
/// `bearing` (or `optimisation`).
pub(crate) fn plan(spec: &CaseSpec, at: &Locator) -> Result<Option<BearingPlan>, SceneError> {
    let Some(b) = &spec.bearing else {
        return Ok(None);
    };
    let within = |path: String| move |e: Error| at.library(&path, e);
    check::count("load (its cases)", b.load.len(), 1, crate::MAX_CASES)
        .map_err(within("bearing".into()))?;
    for (k, load) in b.load.iter().enumerate() {
        load.check().map_err(within(format!("bearing.load[{k}]")))?;
    }
    let total: f64 = b.load.iter().map(|l| l.fraction).sum();
    if (total - 1.0).abs() > FRACTIONS {
        return Err(at.at(
            "bearing.load",
            format!("the load cases' fractions sum to {total}: they must sum to 1"),
        ));
    }
    let bearing = crowned(b, at)?;
    let rating =
        dynamic_load_rating(&bearing).map_err(within("bearing.roller_diameter_mm".into()))?;
    let ratings = slice_ratings(&bearing, rating).map_err(within("bearing".into()))?;
    let weight = b.free_ends.then_some(b.free_end_weight);
    if let Some(w) = weight {
        check::between("free_end_weight", w, -f64::EPSILON, 2.0 + f64::EPSILON)
            .map_err(within("bearing".into()))?;
    }
    check::between(
        "tolerance_um",
        b.tolerance_um,
        -f64::EPSILON,
        MAX_TOLERANCE_UM,
    )
    .map_err(within("bearing".into()))?;
    if let Some(q) = b.design_load_n {
        check::positive("design_load_n", q).map_err(within("bearing".into()))?;
    }
    check_method(spec, b).map_err(within("optimisation".into()))?;
    Ok(Some(BearingPlan {
        bearing,
        loads: b
            .load
            .iter()
            .map(|l| (l.label(), l.load(), l.fraction))
            .collect(),
        raceway: b.raceway.raceway(),
        rotating: b.rotating.raceway(),
        rating,
        ratings,
        design_load: b.design_load(),
        free_ends: weight,
        tolerance: 1e-3 * b.tolerance_um,
        objective: b.objective,
    }))
}

/// The bearing with its roller's and raceways' crowns, built for the design load.
fn crowned(b: &BearingSpec, at: &Locator) -> Result<CylindricalRollerBearing, SceneError> {
    let mut bearing = b.bearing().map_err(|e| at.library("", e))?;
    let roller = b.roller();
    let dir = at.dir();
    let build = |settings: &CrownSettings, key: &str| {
        settings
            .build(&roller, dir)
            .map_err(|e| at.library(&format!("bearing.{key}"), e))
    };
    bearing.roller_crown = build(&b.roller_profile, "roller_profile")?;
    bearing.inner_crown = build(&b.inner_profile, "inner_profile")?;
    bearing.outer_crown = build(&b.outer_profile, "outer_profile")?;
    Ok(bearing)
}

/// The design methods a bearing takes: none, the robust crown over its envelope (with a
/// controller), or a profile search (without); a design starts from the straight roller.
fn check_method(spec: &CaseSpec, b: &BearingSpec) -> Result<()> {
    let Some(opt) = &spec.optimisation else {
        return Ok(());
    };
    let Some(crown) = opt.method.bearing_crown() else {
        return Err(Error::invalid(
            "method",
            opt.method.name(),
            "a bearing's crown is designed by envelope_split (the robust crown over its \
             rollers), profile_search or circular_search",
        ));
    };
    match crown {
        BearingCrown::Envelope(s) => s.check()?,
        BearingCrown::Search(_, s) => s.check()?,
    }
    if b.roller_profile != CrownSettings::Straight {
        return Err(Error::invalid(
            "method",
            "a design",
            "designs the roller's whole crown: give the straight roller \
             (bearing.roller_profile = \"straight\")",
        ));
    }
    match (crown, &opt.controller) {
        (BearingCrown::Envelope(_), None) => Err(Error::invalid(
            "controller",
            "missing",
            "the robust crown needs the controller v(x): { kind = \"cubic\", l1_mm, l2_mm }",
        )),
        (BearingCrown::Envelope(_), Some(c)) => c.build().map(|_| ()),
        (_, Some(_)) => Err(Error::invalid(
            "controller",
            "given",
            "a profile search tunes its family's parameters and takes no controller",
        )),
        (_, None) => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The levels of the bundled duty cycle (its heaviest rollers under the straight roller,
    /// rounded): the aligned case of half the time is the reference, the 2′ case's small p₀
    /// is lifted to it, the 4′ case's is √(4824/3440)·(0.5/0.2)^(1/8) = 1.3279; one load case
    /// is held to 1, and so are cases of one load and time; mismatched lists are refused.
    #[test]
    fn duty_cycle_levels_weigh_load_and_time() {
        let levels = duty_cycle_levels(&[3440.0, 1950.0, 4824.0], &[0.5, 0.3, 0.2]).unwrap();
        let want = (4824.0f64 / 3440.0).sqrt() * 2.5f64.powf(0.125);
        assert_eq!(levels[..2], [1.0, 1.0]);
        assert!((levels[2] - want).abs() < 1e-12 && (want - 1.3279).abs() < 1e-4);
        assert_eq!(duty_cycle_levels(&[5.0], &[1.0]).unwrap(), [1.0]);
        assert_eq!(
            duty_cycle_levels(&[2.0, 2.0], &[0.5, 0.5]).unwrap(),
            [1.0, 1.0]
        );
        let e = duty_cycle_levels(&[1.0], &[0.5, 0.5])
            .unwrap_err()
            .to_string();
        assert!(e.contains("heaviest"), "{e}");
    }
}
