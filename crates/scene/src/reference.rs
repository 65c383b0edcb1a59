//! The closed-form pressure beside a validation case: Hertz for a rigid sphere on a
//! half-space (Johnson, *Contact Mechanics*, eqs. 3.39–3.41) and for a rigid cylinder on a
//! half-plane (line contact, eqs. 4.43–4.45); Boussinesq–Sneddon for a rigid flat punch
//! (p = F/(2πa√(a² − r²)), Johnson eq. 3.34; on a half-plane p = q/(π√(a² − x²)), eq. 2.64).
//! A large finite-element block stands in for the half-space. The rigid body's compliance is
//! zero, so the contact modulus is the body's, E* = E/(1 − ν²) (plane stress: E).

use std::f64::consts::PI;

use contopt_fem::Analysis;

use crate::report::{CaseReport, ReferenceCurve};
use crate::spec::{Indenter, MaterialSpec, Problem, RigidLoad, SceneSpec};

/// Points of a reference curve across the computed points' range.
const SAMPLES: usize = 200;

/// Points whose second coordinate is within this of the smallest \[mm\] lie on the plotted
/// row (round-off of the grid's coordinates).
const SAME_ROW: f64 = 1e-9;

/// How the body meets the indenter: a three-dimensional grid (r = √(x² + y²)), an
/// axisymmetric body (r = x) or a plane one (|x|, with its modulus and thickness).
#[derive(Clone, Copy, Debug)]
enum Body {
    Grid,
    Axisymmetric { half_space: bool },
    Plane { modulus: f64, thickness: f64 },
}

/// The closed-form pressure of a converged case without optimisation, where one exists, along
/// the row of interface points the pressure plot draws.
pub(crate) fn curve(spec: &SceneSpec, report: &CaseReport) -> Option<ReferenceCurve> {
    if !report.converged || spec.optimisation.is_some() {
        return None;
    }
    let (material, body, indenter, load) = match &spec.problem {
        Problem::RigidOnHalfSpace {
            material,
            indenter,
            load,
            ..
        } => (material, Body::Grid, indenter, load),
        Problem::RigidOnAxisymmetricHalfSpace {
            material,
            indenter,
            load,
            ..
        } => (
            material,
            Body::Axisymmetric { half_space: true },
            indenter,
            load,
        ),
        Problem::RigidOnBlock {
            material,
            indenter,
            load,
            ..
        } => (
            material,
            Body::Axisymmetric { half_space: false },
            indenter,
            load,
        ),
        Problem::RigidOnHalfPlane {
            material,
            analysis,
            indenter,
            load,
            ..
        } => (material, plane(material, analysis)?, indenter, load),
        _ => return None,
    };
    let form = ClosedForm::new(material, body, indenter, *load)?;
    let row = Row::of(report)?;
    let points = form.sample(&row, body);
    (!points.is_empty()).then(|| ReferenceCurve {
        label: form.label(),
        points,
    })
}

/// A half-plane's modulus E' and thickness.
fn plane(material: &MaterialSpec, analysis: &Analysis) -> Option<Body> {
    let (modulus, thickness) = match *analysis {
        Analysis::PlaneStress { thickness } => (material.e_mpa, thickness),
        Analysis::PlaneStrain { thickness } => (e_star(material), thickness),
        Analysis::Axisymmetric => return None,
    };
    Some(Body::Plane { modulus, thickness })
}

/// E* = E/(1 − ν²) of a body pressed by a rigid one.
fn e_star(m: &MaterialSpec) -> f64 {
    m.e_mpa / (1.0 - m.nu * m.nu)
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
    /// The closed form of `indenter` pressed on `body` by `load`; none for a roller along a
    /// grid (no closed form on a finite length), an approach on a plane or a finite block
    /// (their approach depends on a datum or the block's size), or values out of range.
    fn new(m: &MaterialSpec, body: Body, indenter: &Indenter, load: RigidLoad) -> Option<Self> {
        let e = e_star(m);
        let form = match (*indenter, body, load) {
            (
                Indenter::Sphere { radius_mm: r },
                Body::Plane { modulus, thickness },
                RigidLoad::ForceN(f),
            ) => {
                let q = f / thickness;
                let b = (4.0 * q * r / (PI * modulus)).sqrt();
                Self::Hertz {
                    p0: 2.0 * q / (PI * b),
                    a: b,
                    line: true,
                }
            }
            (
                Indenter::FlatPunch { radius_mm: a },
                Body::Plane { thickness, .. },
                RigidLoad::ForceN(f),
            ) => Self::Punch {
                p_centre: f / thickness / (PI * a),
                a,
                plane: true,
            },
            (_, Body::Plane { .. }, _) | (Indenter::Cylinder { .. }, _, _) => return None,
            (_, Body::Axisymmetric { half_space: false }, RigidLoad::ApproachMm(_)) => return None,
            (Indenter::Sphere { radius_mm: r }, _, RigidLoad::ForceN(f)) => {
                let a = (3.0 * f * r / (4.0 * e)).cbrt();
                Self::Hertz {
                    p0: 3.0 * f / (2.0 * PI * a * a),
                    a,
                    line: false,
                }
            }
            (Indenter::Sphere { radius_mm: r }, _, RigidLoad::ApproachMm(delta)) => {
                let a = (r * delta).sqrt();
                Self::Hertz {
                    p0: 2.0 * a * e / (PI * r),
                    a,
                    line: false,
                }
            }
            (Indenter::FlatPunch { radius_mm: a }, _, load) => {
                let f = match load {
                    RigidLoad::ForceN(f) => f,
                    RigidLoad::ApproachMm(delta) => 2.0 * a * e * delta,
                };
                Self::Punch {
                    p_centre: f / (2.0 * PI * a * a),
                    a,
                    plane: false,
                }
            }
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
    fn sample(&self, row: &Row, body: Body) -> Vec<[f64; 2]> {
        let r = |x: f64| match body {
            Body::Grid => x.hypot(row.y),
            _ => x.abs(),
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
            .map(|x| [x, self.at(r(x))])
            .filter(|p| p[1].is_finite())
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
            .map(|q| q.x[1].abs())
            .fold(f64::INFINITY, f64::min);
        let xs: Vec<f64> = report
            .interface
            .iter()
            .filter(|q| q.x[1].abs() <= y + SAME_ROW)
            .map(|q| q.x[0])
            .collect();
        let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (lo < hi).then_some(Self { y, xs, lo, hi })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Format, Scene, BUNDLED};

    fn steel() -> MaterialSpec {
        MaterialSpec {
            e_mpa: 2e5,
            nu: 0.3,
        }
    }

    /// ∫ p over the contact, by the midpoint rule on `n` rings or strips out to `a`.
    fn load(form: &ClosedForm, a: f64, n: usize, ring: bool) -> f64 {
        (0..n)
            .map(|k| {
                let (r0, r1) = (a * k as f64 / n as f64, a * (k + 1) as f64 / n as f64);
                let r = 0.5 * (r0 + r1);
                let width = if ring {
                    PI * (r1 * r1 - r0 * r0)
                } else {
                    2.0 * (r1 - r0)
                };
                form.at(r) * width
            })
            .sum()
    }

    /// Hertz: p₀ = 3F/(2πa²) with a = (3FR/4E*)^⅓, the pressure carries F, and an approach
    /// δ = a²/R gives the same contact; line contact carries q = F/b.
    #[test]
    fn hertz_carries_the_load() {
        let sphere = Indenter::Sphere { radius_mm: 10.0 };
        let form = ClosedForm::new(&steel(), Body::Grid, &sphere, RigidLoad::ForceN(1000.0));
        let Some(ClosedForm::Hertz { p0, a, line: false }) = form else {
            panic!("{form:?}");
        };
        let expected_a = (3.0f64 * 1000.0 * 10.0 / (4.0 * 2e5 / 0.91)).cbrt();
        assert!((a - expected_a).abs() < 1e-12 && (a - 0.3244).abs() < 1e-4);
        assert!((p0 - 3.0 * 1000.0 / (2.0 * PI * a * a)).abs() < 1e-9);
        let carried = load(&form.unwrap(), a, 20_000, true);
        assert!((carried / 1000.0 - 1.0).abs() < 1e-4, "{carried}");
        let pushed = ClosedForm::new(
            &steel(),
            Body::Axisymmetric { half_space: true },
            &sphere,
            RigidLoad::ApproachMm(a * a / 10.0),
        );
        let Some(ClosedForm::Hertz { p0: p, a: b, .. }) = pushed else {
            panic!("{pushed:?}");
        };
        assert!((p / p0 - 1.0).abs() < 1e-12 && (b / a - 1.0).abs() < 1e-12);
        let plane = Body::Plane {
            modulus: 2e5 / 0.91,
            thickness: 2.0,
        };
        let line = ClosedForm::new(&steel(), plane, &sphere, RigidLoad::ForceN(1000.0)).unwrap();
        let ClosedForm::Hertz {
            a: b, line: true, ..
        } = line
        else {
            panic!("{line:?}");
        };
        assert!((load(&line, b, 20_000, false) / 500.0 - 1.0).abs() < 1e-4);
    }

    /// Sneddon: p(0) = F/(2πa²), the pressure carries F (its rim singularity integrable:
    /// finer rings converge), and an approach δ carries F = 2aE*δ.
    #[test]
    fn the_flat_punch_carries_the_load() {
        let punch = Indenter::FlatPunch { radius_mm: 10.0 };
        let f = 31415.93;
        let body = Body::Axisymmetric { half_space: true };
        let form = ClosedForm::new(&steel(), body, &punch, RigidLoad::ForceN(f)).unwrap();
        assert!((form.at(0.0) - f / (2.0 * PI * 100.0)).abs() < 1e-9);
        assert!((form.at(0.0) - 50.0).abs() < 1e-4);
        assert_eq!(form.at(10.0), 0.0);
        let carried = load(&form, 10.0, 400_000, true);
        assert!((carried / f - 1.0).abs() < 2e-3, "{carried}");
        let delta = f / (2.0 * 10.0 * 2e5 / 0.91);
        let pushed = ClosedForm::new(&steel(), body, &punch, RigidLoad::ApproachMm(delta));
        assert_eq!(pushed, Some(form));
        let block = Body::Axisymmetric { half_space: false };
        assert_eq!(
            ClosedForm::new(&steel(), block, &punch, RigidLoad::ApproachMm(delta)),
            None
        );
    }

    fn bundled(name: &str) -> CaseReport {
        let text = BUNDLED.iter().find(|(n, _)| *n == name).unwrap().1;
        let scene = Scene::parse(text, Format::Toml, std::path::Path::new(name)).unwrap();
        scene.cases().unwrap()[0].run().unwrap()
    }

    /// The bundled validation scenes carry their closed form, and their pressure along the
    /// plotted row is within a few per cent of it: Hertz on the grid (except at the rim, where
    /// a cell straddles it) and Sneddon on the rings away from the rim.
    #[test]
    fn validation_scenes_match_their_closed_forms() {
        let hertz = bundled("hertz");
        let curve = hertz.reference.as_ref().unwrap();
        assert!(
            curve
                .label
                .starts_with("Hertz: p₀ = 4538 MPa, a = 0.3244 mm"),
            "{}",
            curve.label
        );
        let form = ClosedForm::new(
            &steel(),
            Body::Grid,
            &Indenter::Sphere { radius_mm: 10.0 },
            RigidLoad::ForceN(1000.0),
        )
        .unwrap();
        let ClosedForm::Hertz { p0, a, .. } = form else {
            panic!()
        };
        let row = Row::of(&hertz).unwrap();
        assert!((row.y - 0.00625).abs() < 1e-12, "{}", row.y);
        for q in hertz
            .interface
            .iter()
            .filter(|q| q.x[1].abs() <= row.y + SAME_ROW)
        {
            let r = q.x[0].hypot(q.x[1]);
            if r < 0.8 * a {
                assert!((q.p - form.at(r)).abs() < 0.02 * p0, "{q:?} {}", form.at(r));
            }
        }
        let peak = curve.points.iter().map(|p| p[1]).fold(0.0, f64::max);
        assert!(peak <= p0 && peak > 0.99 * p0);
        let punch = bundled("flat-punch");
        let curve = punch.reference.as_ref().unwrap();
        assert!(curve.label.contains("p(0) = 50.0 MPa"), "{}", curve.label);
        for q in punch.interface.iter().filter(|q| q.x[0] < 8.0) {
            let exact = 50.0 / (1.0 - (q.x[0] / 10.0).powi(2)).sqrt();
            assert!((q.p / exact - 1.0).abs() < 0.03, "{q:?} {exact}");
        }
        let last = curve.points.last().unwrap();
        assert!(last[0] < 10.0 && last[1].is_finite());
        assert!(bundled("paper-table1").reference.is_none());
    }
}
