//! The results of a scene: the schema of `result.json` and of `contopt run --json`.

use std::collections::BTreeMap;
use std::time::Instant;

use serde::{Deserialize, Serialize};

/// The penetration, as a fraction of the largest elastic displacement, above which a solution
/// carries a warning: the paper's c = E·10⁴ penetrates by about 10⁻⁶ of it.
pub const PENETRATION_WARNING: f64 = 1e-3;

/// All cases of a scene.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Report {
    /// The scene's name.
    pub scene: String,
    /// One per case, in sweep order.
    pub cases: Vec<CaseReport>,
}

/// One case.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct CaseReport {
    /// `key = value` of the sweep, or the scene's name.
    pub label: String,
    /// The swept parameter and its value.
    pub params: BTreeMap<String, f64>,
    /// The largest contact pressure at the interface points, maxᵢ pᵢ \[MPa\], in every case
    /// (for a roller's envelope, under the scene's own load); null when it did not converge.
    pub p_max: Option<f64>,
    /// The level p̂ of the bound p ≤ v·p̂ that the optimisation minimised, the paper's p_max in
    /// Tables 1–3 \[MPa\]; null without optimisation. The pressure at a point reaches it only
    /// where v = 1, so `p_max` may be lower (C1 with L1 = 0 has v = 1 at r = 0 alone) or, by
    /// the discretisation's error between the design nodes, marginally higher.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bound_p_max: Option<f64>,
    /// The largest penetration of the solution, maxᵢ(−dᵢ) \[µm\]: O(1/c) for the penalty
    /// method, round-off for the others; null when it did not converge.
    #[serde(default)]
    pub penetration_um: Option<f64>,
    /// What the user should know about an answer that stands: a penalty solution that
    /// penetrates by more than [`PENETRATION_WARNING`] of its elastic displacement.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
    /// Largest gap change \[µm\]; null without optimisation.
    pub dh_max_um: Option<f64>,
    /// The floating body's approach, −λ of its rigid mode \[µm\] (with an optimisation, at the
    /// reference node); null when nothing floats.
    #[serde(default)]
    pub approach_um: Option<f64>,
    /// Whether the solver (and the optimisation) converged.
    pub converged: bool,
    /// Why not, when it did not.
    pub error: Option<String>,
    /// The optimisation's rows (Table 2's columns); empty without optimisation.
    pub iterations: Vec<IterationRow>,
    /// The fields at the interface points.
    pub interface: Vec<PointReport>,
    /// Wall time of the stages \[ms\]: `build`, then `solve` or `optimise`.
    pub timings_ms: BTreeMap<String, f64>,
    /// What a bearing engineer reads off a roller case (the `roller` kind only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roller: Option<RollerReport>,
    /// Stresses below the surface (`[output.subsurface]`); null when not asked for or when
    /// nothing is in contact.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub subsurface: Option<SubsurfaceReport>,
    /// The closed-form pressure of a validation case (a rigid sphere, cylinder or flat punch
    /// on a half-space, a half-plane or a large block, without optimisation), along the line
    /// the pressure plot draws; absent where none exists.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference: Option<ReferenceCurve>,
}

/// A closed-form contact pressure beside a computed one.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct ReferenceCurve {
    /// The closed form and its figures (`Hertz: p₀ = 4539 MPa, a = 0.3244 mm`).
    pub label: String,
    /// (x \[mm\], p \[MPa\]) along the row of interface points nearest the x axis (on an
    /// axisymmetric or plane body: along r or x), within the computed points' range; a flat
    /// punch's curve stops at the outermost point under the punch (p grows without bound at
    /// its rim).
    pub points: Vec<[f64; 2]>,
}

/// Stresses below the surface under a case's contact pressure.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct SubsurfaceReport {
    /// The depths evaluated \[mm\].
    pub depths_mm: Vec<f64>,
    /// Each body that computes stresses (a rigid body does not).
    pub bodies: Vec<BodyStresses>,
}

/// The stresses below one body's surface.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct BodyStresses {
    /// The body (two names when they share one field: a roller and raceway of one Poisson's
    /// ratio).
    pub body: String,
    /// The largest von Mises and Tresca stresses, the largest tension σ₁ and compression σ₃,
    /// each with its position (x, y) and depth \[MPa, mm\]. A finite-element body reports
    /// its nodes, (x, y) in its own coordinates and the depth as the distance to the nearest
    /// contact point; a peak at a singular edge grows as the mesh is refined.
    pub peaks: contopt_core::StressPeaks,
    /// The sections' fields, written as CSV and heat maps (not into the JSON report).
    #[serde(skip)]
    pub sections: Vec<contopt_core::SectionField>,
}

/// A roller case's figures. Columns are the grid's cells along the axis; the ends are the
/// outermost columns, at the cell nearest each end of the effective length.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct RollerReport {
    /// Where the largest pressure sits: x along the axis, y across \[mm\].
    pub p_max_at_mm: [f64; 2],
    /// Whether the ends carry more than 10 % above the pressure at mid-length.
    pub edge_loading: bool,
    /// Contact half-width at mid-length and at the ends (the mean of both) \[mm\], counted in
    /// cells.
    pub half_width_mm: [f64; 2],
    /// The crown's drop at the ends \[µm\].
    pub crown_drop_end_um: f64,
    /// The cases of the scene's `[envelope]` under this crown, the scene's own load and tilt
    /// first; empty without an envelope.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub envelope: Vec<EnvelopeCaseReport>,
    /// The largest p_max over the envelope \[MPa\]; null without an envelope.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub worst_p_max: Option<f64>,
    /// The parameters a `fujiwara_kawase_tuned` profile found.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tuned: Option<TunedProfile>,
}

/// One load case of a roller's envelope.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
pub struct EnvelopeCaseReport {
    /// Load Q \[N\].
    pub load_n: f64,
    /// Misalignment γ \[arc-minutes\].
    pub tilt_arcmin: f64,
    /// Largest contact pressure \[MPa\].
    pub p_max: f64,
    /// Where it sits: x along the axis, y across \[mm\].
    pub p_max_at_mm: [f64; 2],
    /// Whether an end carries more than 10 % above the pressure at mid-length.
    pub edge_loading: bool,
    /// The roller's approach \[µm\].
    pub approach_um: f64,
    /// The pressure along the centre row: (x \[mm\], p \[MPa\]).
    pub centre_line: Vec<[f64; 2]>,
}

/// A Fujiwara–Kawase profile tuned by the Nelder–Mead search.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
pub struct TunedProfile {
    /// Load coefficient K1.
    pub k1: f64,
    /// Crowned fraction K2 of each half-length.
    pub k2: f64,
    /// End drop z_m \[mm\].
    pub z_m_mm: f64,
    /// How many crowns the search solved (each under every case).
    pub evaluations: usize,
}

impl CaseReport {
    pub(crate) fn new(label: &str, params: &BTreeMap<String, f64>) -> Self {
        Self {
            label: label.to_string(),
            params: params.clone(),
            p_max: None,
            bound_p_max: None,
            penetration_um: None,
            warnings: vec![],
            dh_max_um: None,
            approach_um: None,
            converged: false,
            error: None,
            iterations: vec![],
            interface: vec![],
            timings_ms: BTreeMap::new(),
            roller: None,
            subsurface: None,
            reference: None,
        }
    }

    /// Sets `p_max` to the largest pressure of the interface points (when converged), then
    /// turns a report that holds a NaN or an infinity into an unconverged one that names the
    /// field, with its numbers dropped: no non-finite value reaches `result.json`, the CSV or
    /// the plots.
    pub(crate) fn settle(&mut self) {
        if self.converged {
            self.p_max = Some(self.interface.iter().fold(0.0f64, |m, q| m.max(q.p)));
        }
        if let Some((field, value)) = self.first_non_finite() {
            let error = format!(
                "the result's {field} is not finite ({value}): the data overflow f64 \
                 (check the load, the moduli and the units)"
            );
            *self = Self {
                error: Some(error),
                timings_ms: std::mem::take(&mut self.timings_ms),
                ..Self::new(&self.label, &self.params)
            };
        }
    }

    /// The first field holding a NaN or an infinity, with its value.
    fn first_non_finite(&self) -> Option<(&'static str, f64)> {
        let scalars = [
            ("p_max", self.p_max),
            ("bound_p_max", self.bound_p_max),
            ("dh_max_um", self.dh_max_um),
            ("approach_um", self.approach_um),
            ("penetration_um", self.penetration_um),
        ];
        let points = self.interface.iter().flat_map(|q| {
            let [x, y, z] = q.x;
            [("point", x), ("point", y), ("point", z), ("pressure", q.p)]
                .into_iter()
                .chain([("gap", q.d), ("gap change", q.dh)])
        });
        let rows = self.iterations.iter().flat_map(|r| {
            [
                ("iteration p_max", r.bound_p_max),
                ("iteration Δh_max", r.dh_max_um),
                ("TOLH", r.tolh),
            ]
        });
        let roller = self.roller.iter().flat_map(|r| {
            let envelope = r.envelope.iter().flat_map(|e| {
                [
                    ("envelope p_max", e.p_max),
                    ("envelope approach", e.approach_um),
                ]
                .into_iter()
                .chain(e.centre_line.iter().map(|c| ("envelope pressure", c[1])))
            });
            [
                ("roller half-width", r.half_width_mm[0]),
                ("roller half-width", r.half_width_mm[1]),
                ("crown drop", r.crown_drop_end_um),
                ("worst p_max", r.worst_p_max.unwrap_or(0.0)),
            ]
            .into_iter()
            .chain(envelope)
        });
        scalars
            .into_iter()
            .filter_map(|(name, v)| v.map(|v| (name, v)))
            .chain(points)
            .chain(rows)
            .chain(roller)
            .find(|(_, v)| !v.is_finite())
    }

    pub(crate) fn time(&mut self, stage: &str, since: Instant) {
        self.timings_ms
            .insert(stage.to_string(), 1e3 * since.elapsed().as_secs_f64());
    }
}

/// One row of the optimisation.
#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
pub struct IterationRow {
    /// Outer iteration k (for the LP: its passes).
    pub k: usize,
    /// The level p̂ of the bound p ≤ v·p̂ (Table 2's p_max) \[MPa\].
    pub bound_p_max: f64,
    /// Δh_max \[µm\].
    pub dh_max_um: f64,
    /// TOLH (4.2) \[mm²\].
    pub tolh: f64,
    /// Kalker's solves.
    pub iterp: usize,
    /// Kalker's penetration checks.
    pub iterd: usize,
}

/// The fields at one interface point.
#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
pub struct PointReport {
    /// Coordinates \[mm\] (axisymmetric: r, z; grids: x, y).
    pub x: [f64; 3],
    /// Contact pressure \[MPa\].
    pub p: f64,
    /// Gap after deformation \[mm\].
    pub d: f64,
    /// Gap change Δh \[mm\].
    pub dh: f64,
}
