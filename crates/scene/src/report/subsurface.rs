//! Stresses below the surface of a case's bodies (`[output.subsurface]`): the request a case
//! makes of its bodies, and their answers for the report.

use contopt_core::stress::peak_index;
use contopt_core::{
    ElasticBody, Geometry, Interface, Result, Section, SectionAxis, SubsurfaceRequest,
};
use contopt_results::{BodyStresses, SubsurfaceReport};

use crate::subsurface::SubsurfaceSpec;

/// Default deepest depth, in contact half-widths: the largest shear of a Hertz contact lies
/// 0.5–0.8 half-widths down.
const DEFAULT_DEPTH_HALF_WIDTHS: f64 = 2.0;

/// Two positions closer than this fraction of a cell are one section.
const SAME_SECTION: f64 = 0.5;
/// Coordinates closer than this \[mm\] are one (round-off).
const DISTINCT_MM: f64 = 1e-12;
/// Depths within this fraction of each other are one (round-off of depths k·d/n).
const SAME_DEPTH: f64 = 1e-9;
/// A von Mises peak this near the surface, in depths sampled, is a surface singularity's (or
/// above the depths asked): a sharp edge's stresses peak at the first depth or the second,
/// depending on where the cells lie about the edge.
const SHALLOW_DEPTHS: usize = 2;

/// The stresses below every body that computes them (a rigid body does not), under the
/// contact pressure `pressure` at the interface points. `shared` says the second body's
/// field is the first's (a roller and raceway of one Poisson's ratio on one grid): it is
/// computed once. `None` when nothing is in contact.
pub(crate) fn compute(
    spec: &SubsurfaceSpec,
    bodies: [&dyn ElasticBody; 2],
    shared: bool,
    pressure: &[f64],
    roller: bool,
) -> Result<Option<SubsurfaceReport>> {
    let interface = bodies[0].interface();
    let Some(request) = request(spec, interface, pressure, roller) else {
        return Ok(None);
    };
    let mut report = SubsurfaceReport {
        depths_mm: request.depths.clone(),
        bodies: vec![],
    };
    let count = if shared { 1 } else { 2 };
    let names = labels(bodies);
    for (k, body) in bodies[..count].iter().enumerate() {
        let own = own_order(bodies, k, pressure)?;
        if let Some(found) = body.subsurface(&own, &request)? {
            let name = if shared {
                format!("{} and {}", bodies[0].name(), bodies[1].name())
            } else {
                names[k].clone()
            };
            report.bodies.push(BodyStresses {
                body: name,
                peaks: found.peaks.into(),
                sections: found.sections,
            });
        }
    }
    Ok(Some(report))
}

/// The bodies' names as their own stresses are labelled: two bodies of one name (two unnamed
/// half-spaces of different Poisson's ratios) are told apart by their side of the zone, the
/// first below it.
fn labels(bodies: [&dyn ElasticBody; 2]) -> [String; 2] {
    let names = bodies.map(|b| b.name().to_string());
    if names[0] != names[1] {
        return names;
    }
    let [below, above] = names;
    [format!("{below} (below)"), format!("{above} (above)")]
}

/// The pressure at body `k`'s points in its own order: the first body's as given (the
/// interface problem lists its points so), the second's paired by position (its faces may list
/// their Gauss points the other way round, as a punch's bottom faces do against a base's top).
pub(crate) fn own_order(
    bodies: [&dyn ElasticBody; 2],
    k: usize,
    pressure: &[f64],
) -> Result<Vec<f64>> {
    if k == 0 {
        return Ok(pressure.to_vec());
    }
    let (first, second) = (bodies[0].interface(), bodies[1].interface());
    let pair = first.partners(second, bodies[0].name(), bodies[1].name())?;
    let mut own = vec![0.0; pressure.len()];
    for (i, &j) in pair.iter().enumerate() {
        own[j] = pressure[i];
    }
    Ok(own)
}

/// A warning for each body whose von Mises peak lies within the [`SHALLOW_DEPTHS`] shallowest
/// depths sampled (or above them: a finite-element body's surface node): there the stresses
/// are either singular (a sharp edge: a punch's rim, a straight roller's end, where the
/// elastic stresses grow without bound) or peak above the depths asked, and the value grows as
/// the cells and depths shrink — a flat punch's rim on 40², 80² and 160² cells gave 511, 620
/// and 1042 MPa, each at its shallowest depth; the bundled straight roller's end peaks at the
/// second. A smooth contact's peak lies well below (Hertz's at 0.48 a; the crowned rollers'
/// at the fifth depth or deeper).
pub(crate) fn shallow_peaks(report: &SubsurfaceReport) -> Vec<String> {
    let Some(&shallow) = report.depths_mm.get(SHALLOW_DEPTHS - 1) else {
        return vec![];
    };
    report
        .bodies
        .iter()
        .filter(|b| b.peaks.von_mises.depth_mm <= shallow * (1.0 + SAME_DEPTH))
        .map(|b| {
            let peak = &b.peaks.von_mises;
            format!(
                "{}'s von Mises stress peaks at the shallowest depths sampled ({:.1} MPa at \
                 {:.4} mm, x, y = {:+.4}, {:+.4} mm): the stresses there are singular (a sharp \
                 edge, where they grow without bound as the cells and depths shrink) or peak \
                 above the depths asked; round the edge, or sample depths nearer the surface, \
                 for a peak that converges",
                b.body, peak.value_mpa, peak.depth_mm, peak.x_mm, peak.y_mm
            )
        })
        .collect()
}

/// The depths and sections of the scene, with their defaults from the contact area.
fn request(
    spec: &SubsurfaceSpec,
    interface: &Interface,
    pressure: &[f64],
    roller: bool,
) -> Option<SubsurfaceRequest> {
    let contact: Vec<[f64; 3]> = interface
        .points()
        .iter()
        .zip(pressure)
        .filter(|(_, p)| **p > 0.0)
        .map(|(x, _)| *x)
        .collect();
    let max_depth = match spec.max_depth_mm {
        Some(d) => d,
        None => DEFAULT_DEPTH_HALF_WIDTHS * half_width(interface, &contact)?,
    };
    let n = spec.depths;
    let depths = (1..=n).map(|k| max_depth * k as f64 / n as f64).collect();
    let sections = if interface.geometry() != Geometry::Surface {
        // A plane or axisymmetric body has one section, its own plane.
        vec![Section {
            axis: SectionAxis::X,
            at: 0.0,
        }]
    } else if spec.sections.is_empty() {
        default_sections(interface, pressure, roller)
    } else {
        spec.sections
            .iter()
            .map(|s| Section {
                axis: s.along,
                at: s.at_mm,
            })
            .collect()
    };
    Some(SubsurfaceRequest { depths, sections })
}

/// The contact's half-width: its radius on an axisymmetric body, else the smaller half-extent
/// over the axes along which it extends; `None` without contact.
fn half_width(interface: &Interface, contact: &[[f64; 3]]) -> Option<f64> {
    let first = contact.first()?;
    if interface.geometry() == Geometry::Axisymmetric {
        return contact.iter().map(|x| x[0]).reduce(f64::max);
    }
    // One point in contact still spans its own weight's width (a cell or a strip).
    let extent = |axis: usize, cell: f64| {
        let (lo, hi) = contact
            .iter()
            .fold((first[axis], first[axis]), |(l, h), x| {
                (l.min(x[axis]), h.max(x[axis]))
            });
        0.5 * (hi - lo + cell)
    };
    [0, 1]
        .into_iter()
        .map(|axis| (axis, spacing(interface, axis)))
        .filter(|&(_, cell)| cell > 0.0)
        .map(|(axis, cell)| extent(axis, cell))
        .reduce(f64::min)
}

/// The smallest spacing between distinct point coordinates along `axis` (0 when they all
/// agree).
fn spacing(interface: &Interface, axis: usize) -> f64 {
    let mut v: Vec<f64> = interface.points().iter().map(|x| x[axis]).collect();
    v.sort_by(f64::total_cmp);
    v.windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| *d > DISTINCT_MM)
        .fold(0.0, |m: f64, d| if m == 0.0 { d } else { m.min(d) })
}

/// A grid's default sections: along x and along y through the largest pressure; a roller's
/// (x along its axis): across the contact at mid-length, at the end cell on the side of the
/// largest pressure, and at the largest pressure where that is neither. The order is fixed, so
/// a section's number says which it is.
fn default_sections(interface: &Interface, pressure: &[f64], roller: bool) -> Vec<Section> {
    let peak = peak_index(pressure).unwrap_or(0);
    let at = interface.points().get(peak).copied().unwrap_or_default();
    if !roller {
        return vec![
            Section {
                axis: SectionAxis::X,
                at: at[1],
            },
            Section {
                axis: SectionAxis::Y,
                at: at[0],
            },
        ];
    }
    let along = interface.points().iter().map(|x| x[0]);
    let end = if at[0] < 0.0 {
        along.fold(f64::INFINITY, f64::min)
    } else {
        along.fold(f64::NEG_INFINITY, f64::max)
    };
    let cell = spacing(interface, 0);
    let mut positions: Vec<f64> = vec![0.0];
    for x in [end, at[0]] {
        if positions
            .iter()
            .all(|p| (p - x).abs() > SAME_SECTION * cell)
        {
            positions.push(x);
        }
    }
    positions
        .into_iter()
        .map(|x| Section {
            axis: SectionAxis::Y,
            at: x,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use contopt_results::{BodyStresses, Peak, Peaks, SubsurfaceReport};

    use super::shallow_peaks;

    /// A body's peaks with von Mises `value` at `depth` mm (the other criteria alike).
    fn body(name: &str, value: f64, depth: f64) -> BodyStresses {
        let peak = Peak {
            value_mpa: value,
            x_mm: 0.5,
            y_mm: -0.25,
            depth_mm: depth,
        };
        BodyStresses {
            body: name.into(),
            peaks: Peaks {
                von_mises: peak,
                tresca: peak,
                max_principal: peak,
                min_principal: peak,
                shear_xz: peak,
                shear_yz: None,
            },
            sections: vec![],
        }
    }

    /// A von Mises peak at the shallowest depths sampled (a punch's rim) is named with its
    /// value and place; one below them (Hertz's, at 0.48 a) is not; depths k·d/n that round
    /// off count as their own; a single depth sampled judges nothing.
    #[test]
    fn a_peak_at_the_shallowest_depth_is_named() {
        let depths_mm: Vec<f64> = (1..=50).map(|k| 1.0 * k as f64 / 50.0).collect();
        let report = SubsurfaceReport {
            depths_mm: depths_mm.clone(),
            bodies: vec![
                body("block", 1042.3, 0.04 * (1.0 + 1e-15)),
                body("sphere", 1400.0, 0.06),
            ],
        };
        let said = shallow_peaks(&report);
        assert_eq!(said.len(), 1, "{said:?}");
        assert!(said[0].starts_with("block's von Mises"), "{said:?}");
        assert!(said[0].contains("1042.3 MPa at 0.0400 mm"), "{said:?}");
        assert!(said[0].contains("x, y = +0.5000, -0.2500 mm"), "{said:?}");
        let none = SubsurfaceReport {
            depths_mm: vec![0.5],
            bodies: vec![body("block", 1.0, 0.0)],
        };
        assert!(shallow_peaks(&none).is_empty());
    }
}
