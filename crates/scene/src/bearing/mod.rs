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

mod grids;
mod run;

use std::ops::Range;

use contopt_core::{check, Error, Result};
use contopt_input::{Node, Value};
use contopt_results::LubricationReport;
use contopt_roller::{
    dynamic_load_rating, fatigue_load_limit, hertz_slice_load, life_modification_factor,
    rated_viscosity, slice_ratings, static_load_rating, BearingLoad, CrownSettings,
    CrownTolerances, CylindricalRollerBearing, Raceway, Roller, SliceRatings, FATIGUE_STRESS_MPA,
};

pub(crate) use crate::bearing_spec::duty_cycle_levels;
use crate::bearing_spec::{
    BearingObjective, BearingSpec, RacewaySpec, FRACTIONS, MAX_TOLERANCE_UM,
};
use crate::error::Locator;
use crate::lives::Lubrication;
use crate::methods::BearingCrown;
use crate::spec::CaseSpec;
use crate::SceneError;

/// A bearing as its case's check planned it — the bearing with its crowns, the load cases,
/// the ratings — and the design of its case: every loaded roller's contact under each load
/// case's distribution, the crown designed over them when the scene asks, the lives
/// ([`run`]).
#[derive(Debug)]
pub(crate) struct BearingPlan {
    /// How the crown is designed over the rollers' envelope (`[optimisation]`), if it is.
    pub crown: Option<BearingCrown>,
    /// The grid's cells along and across the roller.
    pub cells: [usize; 2],
    /// How far the grid reaches across, in Hertz half-widths of its load.
    pub reach: f64,
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
    /// The roller crown's tolerance box and its grid, when the scene gives one.
    pub crown_tolerance: Option<(CrownTolerances, usize)>,
    pub objective: BearingObjective,
    /// The rotating ring's speed \[min⁻¹\], for lives in hours.
    pub speed_rpm: Option<f64>,
    /// The lubrication's figures for ISO 281's a_ISO.
    pub lubrication: Option<Lubricated>,
}

/// A bearing's lubrication as the lives take it and the report shows it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lubricated {
    pub figures: Lubrication,
    pub report: LubricationReport,
}

/// The lubrication of `b` turning at `speed` \[min⁻¹\]: ν₁ and κ = ν/ν₁, C_0r and C_u (the
/// scene's or ISO 281's), e_C·C_u; fields named from the bearing.
fn lubricated(
    b: &BearingSpec,
    bearing: &CylindricalRollerBearing,
    speed: Option<f64>,
) -> Result<Option<Lubricated>> {
    let Some(lub) = &b.lubrication else {
        return Ok(None);
    };
    lub.check()?;
    let speed = speed.ok_or_else(|| {
        Error::invalid(
            "speed_rpm",
            "missing",
            "ISO 281's rated viscosity ν₁ of [bearing.lubrication] needs the speed: give \
             bearing.speed_rpm",
        )
    })?;
    let rated = rated_viscosity(speed, bearing.pitch_diameter)?;
    let viscosity = lub.viscosity()?;
    let kappa = viscosity / rated;
    let static_rating = static_load_rating(bearing)?;
    let limit = match lub.fatigue_load_limit_n {
        Some(c) => c,
        None => fatigue_load_limit(bearing)?,
    };
    // Refuses a κ below the formula's range here, before anything is solved.
    life_modification_factor(kappa, 0.0)
        .map_err(|e| Error::invalid("lubrication.viscosity_mm2_s", viscosity, e.to_string()))?;
    let slice_limit = slice_fatigue_limits(b, bearing, limit)?;
    Ok(Some(Lubricated {
        figures: Lubrication {
            kappa,
            contaminated_limit_n: lub.contamination * limit,
            contaminated_slice_limits_n: slice_limit.map(|q| lub.contamination * q),
        },
        report: LubricationReport {
            viscosity_mm2_s: viscosity,
            rated_viscosity_mm2_s: rated,
            kappa,
            contamination: lub.contamination,
            static_load_rating_n: static_rating,
            fatigue_load_limit_n: limit,
        },
    }))
}

/// Each raceway's slice fatigue load limit \[N\] (inner, outer): the load of a Hertzian slice
/// of `bearing` ([`hertz_slice_load`], L_we/n_s wide, on the pair's radius and modulus) at
/// ISO 281's fatigue stress ([`FATIGUE_STRESS_MPA`]) times √(C_u/C_u,ISO), `limit` = C_u.
fn slice_fatigue_limits(
    b: &BearingSpec,
    bearing: &CylindricalRollerBearing,
    limit: f64,
) -> Result<[f64; 2]> {
    let stress = FATIGUE_STRESS_MPA * (limit / fatigue_load_limit(bearing)?).sqrt();
    let width = bearing.effective_length() / bearing.slices as f64;
    let (d, pitch) = (b.roller_diameter_mm, b.pitch_diameter_mm);
    let pair = |raceway_diameter: f64| -> Result<f64> {
        let roller = Roller {
            raceway_diameter: Some(raceway_diameter),
            ..b.roller()
        };
        Ok(hertz_slice_load(
            stress,
            width,
            roller.radius()?,
            roller.e_star(),
        ))
    };
    Ok([pair(pitch - d)?, pair(-(pitch + d))?])
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
    if let Some(n) = b.speed_rpm {
        check::positive("speed_rpm", n).map_err(within("bearing".into()))?;
    }
    let lubrication = lubricated(b, &bearing, b.speed_rpm).map_err(within("bearing".into()))?;
    let crown_tolerance = (b.crown_tolerance.as_ref())
        .map(|t| Ok((t.tolerances(0.5 * bearing.effective_length())?, t.grid)))
        .transpose()
        .map_err(within("bearing".into()))?;
    Ok(Some(BearingPlan {
        crown_tolerance,
        crown: (spec.optimisation.as_ref()).and_then(|o| o.method.bearing_crown()),
        cells: b.cells,
        reach: b.reach_b,
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
        speed_rpm: b.speed_rpm,
        lubrication,
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
