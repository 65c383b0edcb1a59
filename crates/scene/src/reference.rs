//! The closed-form pressure beside a validation case: Hertz for a sphere on a half-space
//! (Johnson, *Contact Mechanics*, eqs. 3.39–3.41) and for a cylinder on a half-plane (line
//! contact, eqs. 4.43–4.45); Boussinesq–Sneddon for a flat punch (p = F/(2πa√(a² − r²)),
//! Johnson eq. 3.34; on a half-plane p = q/(π√(a² − x²)), eq. 2.64). Two elastic bodies meet
//! with the pair's modulus 1/E* = Σ(1 − ν²)/E (plane stress: 1/E); a rigid body adds nothing,
//! and a large finite-element block stands in for the half-space.

use std::f64::consts::PI;

use contopt_results::{CaseReport, CurvePoint, ReferenceCurve};

use crate::gap::{GapSpec, Hertz};
use crate::spec::LoadSpec;
use crate::zone::Layout;
use crate::Case;

/// Points of a reference curve across the computed points' range.
const SAMPLES: usize = 200;

/// Points whose second coordinate is within this of the smallest \[mm\] lie on the plotted
/// row (round-off of the grid's coordinates).
const SAME_ROW: f64 = 1e-9;

/// How the zone meets the indenter: a three-dimensional grid (r = √(x² + y²)), an
/// axisymmetric surface (r = x) or a plane one (|x|).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Body {
    Grid,
    Axisymmetric,
    Plane,
}

/// The closed-form pressure of a converged contact analysis, where one exists, along the row
/// of interface points the pressure chart draws.
pub(crate) fn curve(case: &Case, report: &CaseReport) -> Option<ReferenceCurve> {
    if !report.is_solved() || case.spec.optimisation.is_some() {
        return None;
    }
    let body = match &case.plan.layout {
        Layout::Grid { .. } => Body::Grid,
        Layout::Rings(_) => Body::Axisymmetric,
        Layout::Strips { .. } => Body::Plane,
        Layout::Faces(f) if f.analysis == contopt_fem::Analysis::Axisymmetric => Body::Axisymmetric,
        Layout::Mesh(m) if m.analysis == contopt_fem::Analysis::Axisymmetric => Body::Axisymmetric,
        Layout::Faces(_) | Layout::Mesh(_) => Body::Plane,
    };
    let form = ClosedForm::new(case, body)?;
    let row = Row::of(report)?;
    let points = form.sample(&row, body);
    (!points.is_empty()).then(|| ReferenceCurve {
        label: form.label(),
        points,
    })
}

/// A closed form: the pressure at distance r from the axis (or x from the plane's).
#[derive(Clone, Copy, Debug, PartialEq)]
enum ClosedForm {
    /// p₀√(1 − r²/a²) for r < a (sphere: contact radius a; cylinder: half-width b).
    Hertz { p0: f64, a: f64, line: bool },
    /// p(0)/√(1 − r²/a²) for r < a (a half-plane's punch: the same with its own p(0)).
    Punch { p_centre: f64, a: f64, plane: bool },
}

impl ClosedForm {
    /// The closed form of the case's gap, bodies and load: Hertz where the plan found it (not
    /// for a cylinder along a grid or a roller, which have no closed form on a finite length);
    /// Sneddon for a flat punch pressed by a force, or pushed in on a half-space (a block's or a
    /// plane's approach depends on its size or datum).
    fn new(case: &Case, body: Body) -> Option<Self> {
        let spec = &case.spec;
        let e_star = case.plan.e_star?;
        let form = match (&spec.contact.gap, body, spec.contact.load) {
            (GapSpec::Sphere(_), _, _) | (GapSpec::Cylinder(_), Body::Plane, _) => {
                let Hertz {
                    line,
                    p0,
                    half_width,
                } = case.plan.hertz?;
                Self::Hertz {
                    p0,
                    a: half_width,
                    line,
                }
            }
            (GapSpec::FlatPunch(p), Body::Plane, LoadSpec::ForceN(f)) => Self::Punch {
                p_centre: f / case.plan.layout.line_length()? / (PI * p.radius_mm),
                a: p.radius_mm,
                plane: true,
            },
            (GapSpec::FlatPunch(p), Body::Grid | Body::Axisymmetric, load) => {
                let a = p.radius_mm;
                let f = match load {
                    LoadSpec::ForceN(f) => f,
                    LoadSpec::ApproachMm(delta) if on_half_space(case) => 2.0 * a * e_star * delta,
                    _ => return None,
                };
                Self::Punch {
                    p_centre: f / (2.0 * PI * a * a),
                    a,
                    plane: false,
                }
            }
            _ => return None,
        };
        let (p, a) = match form {
            Self::Hertz { p0, a, .. } => (p0, a),
            Self::Punch { p_centre, a, .. } => (p_centre, a),
        };
        (p > 0.0 && p.is_finite() && a > 0.0 && a.is_finite()).then_some(form)
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
    fn sample(&self, row: &Row, body: Body) -> Vec<CurvePoint> {
        let r = |x: f64| match body {
            Body::Grid => x.hypot(row.y),
            Body::Axisymmetric | Body::Plane => x.abs(),
        };
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

/// Whether the elastic body is a half-space itself (not a block standing in for one).
fn on_half_space(case: &Case) -> bool {
    case.spec.body.iter().any(|b| b.is_half_space())
}
