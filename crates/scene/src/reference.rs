//! The closed-form pressure beside a validation case: Hertz for a sphere on a half-space
//! (Johnson, *Contact Mechanics*, eqs. 3.39–3.41) and for a cylinder on a half-plane (line
//! contact, eqs. 4.43–4.45); Boussinesq–Sneddon for a flat punch (p = F/(2πa√(a² − r²)),
//! Johnson eq. 3.34; on a half-plane p = q/(π√(a² − x²)), eq. 2.64). Two elastic bodies meet
//! with the pair's modulus 1/E* = Σ(1 − ν²)/E (plane stress: 1/E); a rigid body adds nothing,
//! and a large finite-element block stands in for the half-space. Which closed form a case has
//! is its gap kind's answer ([`crate::GapKind::reference`]).

use std::f64::consts::PI;

use contopt_results::{CaseReport, CurvePoint, ReferenceCurve};

use crate::load::LoadSpec;
use crate::zone::Surface;
use crate::Case;

/// Points of a reference curve across the computed points' range.
const SAMPLES: usize = 200;

/// Points whose second coordinate is within this of the smallest \[mm\] lie on the plotted
/// row (round-off of the grid's coordinates).
const SAME_ROW: f64 = 1e-9;

/// Hertz's nominal contact: a circle of radius a (point) or a strip of half-width b (line).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hertz {
    /// A line contact (a cylinder, a roller).
    pub line: bool,
    /// The peak pressure p₀ \[MPa\].
    pub p0: f64,
    /// a or b \[mm\].
    pub half_width: f64,
    /// R, the radius of curvature across the contact whose parabola x²/2R is the gap \[mm\].
    pub radius: f64,
}

impl Hertz {
    /// A sphere of radius `r` pressed by `force` with the pair's modulus `e_star`
    /// (Johnson, *Contact Mechanics*, eqs. 3.39–3.41).
    pub fn sphere(r: f64, force: f64, e_star: f64) -> Self {
        let a = (3.0 * force * r / (4.0 * e_star)).cbrt();
        Self {
            line: false,
            p0: 3.0 * force / (2.0 * PI * a * a),
            half_width: a,
            radius: r,
        }
    }

    /// A sphere of radius `r` pushed in by the approach `delta`.
    pub fn sphere_approach(r: f64, delta: f64, e_star: f64) -> Self {
        let a = (r * delta).sqrt();
        Self {
            line: false,
            p0: 2.0 * a * e_star / (PI * r),
            half_width: a,
            radius: r,
        }
    }

    /// A cylinder of radius `r` under the line load `q` \[N/mm\] (Johnson, eqs. 4.43–4.45).
    pub fn line(r: f64, q: f64, e_star: f64) -> Self {
        let b = (4.0 * q * r / (PI * e_star)).sqrt();
        Self {
            line: true,
            p0: 2.0 * q / (PI * b),
            half_width: b,
            radius: r,
        }
    }

    /// Whether its numbers are usable.
    pub(crate) fn usable(self) -> Option<Self> {
        (self.p0 > 0.0 && self.p0.is_finite() && self.half_width > 0.0).then_some(self)
    }
}

/// The closed-form pressure of a converged contact analysis, where one exists, along the row
/// of interface points the pressure chart draws.
pub(crate) fn curve(case: &Case, report: &CaseReport) -> Option<ReferenceCurve> {
    if !report.is_solved() || case.spec.optimisation.is_some() {
        return None;
    }
    let on = ReferenceCase::of(case)?;
    let form = ClosedForm::usable(case.spec.contact.gap.reference(&on)?)?;
    let row = Row::of(report)?;
    let points = form.sample(&row, on.surface);
    (!points.is_empty()).then(|| ReferenceCurve {
        label: form.label(),
        points,
    })
}

/// What a gap's closed form may draw on: a converged contact analysis of its case.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceCase {
    /// How the zone meets the indenter: a three-dimensional grid (r = √(x² + y²)), an
    /// axisymmetric surface (r = x) or a plane one (|x|).
    pub surface: Surface,
    /// The pair's modulus E* \[MPa\].
    pub e_star: f64,
    /// Hertz's nominal contact, as the case's plan found it.
    pub hertz: Option<Hertz>,
    /// The contact's load.
    pub load: LoadSpec,
    /// The zone's grid length or plane thickness \[mm\].
    pub line_length: Option<f64>,
    /// Whether an elastic body is a half-space itself (not a block standing in for one).
    pub on_half_space: bool,
}

impl ReferenceCase {
    /// The case's, when the pair's modulus is known.
    fn of(case: &Case) -> Option<Self> {
        Some(Self {
            surface: case.spec.contact.zone.surface(),
            e_star: case.plan.e_star?,
            hertz: case.plan.hertz,
            load: case.spec.contact.load,
            line_length: case.plan.layout.line_length(),
            on_half_space: case.spec.body.iter().any(|b| b.is_half_space()),
        })
    }
}

/// A closed form: the pressure at distance r from the axis (or x from the plane's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ClosedForm {
    /// p₀√(1 − r²/a²) for r < a (sphere: contact radius a; cylinder: half-width b).
    Hertz {
        /// The peak pressure p₀ \[MPa\].
        p0: f64,
        /// a or b \[mm\].
        a: f64,
        /// A line contact.
        line: bool,
    },
    /// p(0)/√(1 − r²/a²) for r < a (a half-plane's punch: the same with its own p(0)).
    Punch {
        /// The pressure at the centre \[MPa\].
        p_centre: f64,
        /// The punch's radius (half-width) \[mm\].
        a: f64,
        /// On a half-plane.
        plane: bool,
    },
}

impl From<Hertz> for ClosedForm {
    fn from(h: Hertz) -> Self {
        Self::Hertz {
            p0: h.p0,
            a: h.half_width,
            line: h.line,
        }
    }
}

impl ClosedForm {
    /// The form, when its pressure and its radius are positive and finite.
    fn usable(self) -> Option<Self> {
        let (p, a) = match self {
            Self::Hertz { p0, a, .. } => (p0, a),
            Self::Punch { p_centre, a, .. } => (p_centre, a),
        };
        (p > 0.0 && p.is_finite() && a > 0.0 && a.is_finite()).then_some(self)
    }

    /// The pressure at distance `r` from the axis \[MPa\].
    fn at(&self, r: f64) -> f64 {
        match *self {
            Self::Hertz { p0, a, .. } => p0 * (1.0 - (r / a).powi(2)).max(0.0).sqrt(),
            Self::Punch { p_centre, a, .. } if r < a => p_centre / (1.0 - (r / a).powi(2)).sqrt(),
            Self::Punch { .. } => 0.0,
        }
    }

    fn label(&self) -> String {
        let n = |v: f64| format!("{v:.4}");
        match *self {
            Self::Hertz { p0, a, line: false } => {
                format!("Hertz: p₀ = {p0:.0} MPa, a = {} mm", n(a))
            }
            Self::Hertz { p0, a, line: true } => {
                format!("Hertz line contact: p₀ = {p0:.0} MPa, b = {} mm", n(a))
            }
            Self::Punch {
                p_centre, plane, ..
            } => {
                let kind = if plane {
                    "flat punch (plane)"
                } else {
                    "Sneddon flat punch"
                };
                format!("{kind}: p(0) = {p_centre:.1} MPa")
            }
        }
    }

    /// The curve along `row`: [`SAMPLES`] points across its x range, with the contact edge
    /// itself; a punch's stops at the outermost row point under it.
    fn sample(&self, row: &Row, surface: Surface) -> Vec<CurvePoint> {
        let r = |x: f64| surface.radius([x, row.y, 0.0]);
        let (lo, hi) = match *self {
            Self::Punch { a, .. } => {
                let inside = |x: &&f64| r(**x) < a;
                let reach = row
                    .xs
                    .iter()
                    .filter(inside)
                    .map(|x| x.abs())
                    .fold(0.0, f64::max);
                (row.lo.max(-reach), row.hi.min(reach))
            }
            Self::Hertz { .. } => (row.lo, row.hi),
        };
        let mut xs: Vec<f64> = (0..=SAMPLES)
            .map(|k| lo + (hi - lo) * k as f64 / SAMPLES as f64)
            .collect();
        if let Self::Hertz { a, .. } = *self {
            let edge = (a * a - row.y * row.y).max(0.0).sqrt();
            xs.extend([-edge, edge].into_iter().filter(|x| (lo..=hi).contains(x)));
        }
        xs.sort_by(f64::total_cmp);
        xs.into_iter()
            .map(|x| CurvePoint {
                x_mm: x,
                p_mpa: self.at(r(x)),
            })
            .filter(|p| p.p_mpa.is_finite())
            .collect()
    }
}

/// The row of interface points the pressure plot draws: those nearest the x axis.
struct Row {
    y: f64,
    xs: Vec<f64>,
    lo: f64,
    hi: f64,
}

impl Row {
    fn of(report: &CaseReport) -> Option<Self> {
        let y = report
            .interface
            .iter()
            .map(|q| q.x_mm[1].abs())
            .fold(f64::INFINITY, f64::min);
        let xs: Vec<f64> = report
            .interface
            .iter()
            .filter(|q| q.x_mm[1].abs() <= y + SAME_ROW)
            .map(|q| q.x_mm[0])
            .collect();
        let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (lo < hi).then_some(Self { y, xs, lo, hi })
    }
}
