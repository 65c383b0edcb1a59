//! The model's limits, judged on every converged case: a contact that reaches an edge of its
//! zone (where the zone, not a body, ends it) is outside the model — its pressure is wrong, and
//! the case says where and how large the zone must be; a contact resolved by fewer than
//! [`MIN_CELLS_ACROSS`] cells across its half-width carries a warning with the number, and one
//! whose pressure rises to a sharp edge (a punch's rim) a warning that its peak depends on the
//! cells; and Hertz's nominal contact is reported beside the case where it applies.

use contopt_contact::InterfaceProblem;
use contopt_core::stress::peak_index;
use contopt_core::ElasticBody;
use contopt_greens::CARRIES;
use contopt_results::{CaseReport, CaseStatus, ModelLimit, Resolution};

use super::edge::{line_through, points_per_cell, sharp_edge, SharpEdge};
use crate::mesh_surface::MeshSurface;
use crate::zone::{GridZone, Layout};
use crate::{Case, Hertz};

/// Cells across the contact's half-width below which its peak is not resolved (a Hertz
/// pressure on 8 cells per half-width is within about 1 % of its peak).
pub const MIN_CELLS_ACROSS: f64 = 8.0;

/// Elements of a body's own mesh across the contact's half-width below which the body's
/// deformation under the contact is not resolved, however fine the cells, counted with the
/// largest element under the contact: a sphere on the bundled solid block (20-node hexahedra
/// graded from 0.16 mm at the contact, cells a tenth of Hertz's a; 30 to 2000 N) gave p_max
/// +2.05 %, +5.81 % and +1.18 % against Hertz at 1.0, 1.1 and 1.4 elements across a, and
/// −0.02 %, −0.13 %, −0.46 %, −0.20 % from 1.8 up.
pub const MIN_ELEMENTS_ACROSS: f64 = 1.5;

/// A zone must reach this many Hertz half-widths to hold the contact with a margin.
const HERTZ_MARGIN: f64 = 1.25;

/// Without Hertz, the zone must grow at least by this factor past an edge the contact reaches.
pub(crate) const GROWTH: f64 = 1.5;

/// Hertz's half-width beyond this fraction of the radius across the contact leaves the model's
/// small contact, a ≪ R (Johnson, *Contact Mechanics*, §4.1): there the parabola x²/2R is
/// 0.25 % short of the circle at the contact's edge, and the strains, of order a/R, are no
/// longer small.
pub const SMALL_CONTACT: f64 = 0.1;

/// One edge of a zone: its name, the surface axis it cuts, its position, and its points.
struct Edge {
    name: String,
    axis: usize,
    extent: f64,
    points: Vec<usize>,
    /// A grid's low edge on the bodies' plane of symmetry.
    on_symmetry_plane: bool,
}

/// Judges a case's limits into its report. A limit the design left there, judged on contacts
/// the report does not show (a bearing's rollers, each on its own grid), is kept: the case is
/// outside the model, by the shown contact's own limit first (the design's then a warning).
pub(crate) fn judge(report: &mut CaseReport, case: &Case, problem: &InterfaceProblem) {
    let designed = report.limit.take();
    report.hertz = case.plan.hertz.map(|h| contopt_results::Hertz {
        contact: if h.line { "line" } else { "point" }.into(),
        p0_mpa: h.p0,
        half_width_mm: h.half_width,
    });
    report.warnings.extend(locking(case));
    if report.status != CaseStatus::Solved {
        return;
    }
    let points = problem.interface().points();
    let pressure: Vec<f64> = report.interface.iter().map(|q| q.p_mpa).collect();
    let p_max = pressure.iter().fold(0.0f64, |m, &p| m.max(p));
    if p_max <= 0.0 {
        report.warnings.push(untouched(case));
        return;
    }
    let carrying: Vec<bool> = pressure.iter().map(|&p| p > CARRIES * p_max).collect();
    let reached = match &case.plan.layout {
        Layout::Mesh(surface) => end_reached(case, surface, points, &pressure, &carrying),
        _ => edge_reached(case, points, &pressure, &carrying, p_max),
    };
    let reached = match (
        reached.or_else(|| envelope_edge(report, case, points)),
        designed,
    ) {
        (Some(own), Some(other)) => {
            report.warnings.push(other.message);
            Some(own)
        }
        (own, other) => own.or(other),
    };
    if let Some(limit) = reached {
        report.status = CaseStatus::OutsideModel;
        report.limit = Some(limit);
        return;
    }
    report.resolution = resolution(&case.plan.layout, points, &carrying, &pressure);
    if let Some(r) = &report.resolution {
        if r.cells < MIN_CELLS_ACROSS {
            report.warnings.push(format!(
                "the contact's half-width along {} ({:.4} mm) spans {:.1} cells, fewer than \
                 {MIN_CELLS_ACROSS}: its peak is not resolved; refine the zone (cells of at \
                 most {:.4} mm)",
                r.along,
                r.half_width_mm,
                r.cells,
                r.half_width_mm / MIN_CELLS_ACROSS
            ));
        }
    }
    report
        .warnings
        .extend(case.plan.hertz.and_then(large_contact));
    let layout = &case.plan.layout;
    if let Some(edge) = sharp_edge(layout, points, &carrying, &pressure) {
        let beside = case.plan.hertz.and_then(|h| line_contact_beside(h, &edge));
        report
            .warnings
            .push(edge.warning() + &beside.unwrap_or_default());
    }
    report.warnings.extend(light_cases(report));
}

/// What a sharp edge's warning adds where Hertz's nominal line contact is reported beside the
/// case: its p₀ is a cylinder's without ends, the pressure along the middle of a long contact,
/// which the peak at a finite cylinder's end is not (1.5–2 times it on the cells of a usual
/// grid, and more on finer ones).
fn line_contact_beside(hertz: Hertz, edge: &SharpEdge) -> Option<String> {
    (hertz.line && hertz.p0 > 0.0).then(|| {
        format!(
            "; Hertz's p₀ = {:.1} MPa beside the case is the line contact's, a cylinder's \
             without ends: it is the pressure along the middle, and the peak at this edge, \
             {:.2} times it, is no Hertz figure",
            hertz.p0,
            edge.p_mpa / hertz.p0
        )
    })
}

/// A warning for each body whose own elements under the contact
/// ([`ElasticBody::element_sizes`], the largest under a carrying point) are fewer than
/// [`MIN_ELEMENTS_ACROSS`] across the contact's half-width: the cells resolve the contact, the
/// body's mesh does not. Judged on a case within the model's limits (its resolution known),
/// for bodies read point for point on the zone.
pub(crate) fn coarse_elements(report: &mut CaseReport, bodies: [&dyn ElasticBody; 2]) {
    let Some(half_width) = report.resolution.as_ref().map(|r| r.half_width_mm) else {
        return;
    };
    let p_max = report.interface.iter().fold(0.0f64, |m, q| m.max(q.p_mpa));
    for body in bodies {
        let Some(sizes) = body.element_sizes() else {
            continue;
        };
        if sizes.len() != report.interface.len() {
            continue;
        }
        let size = (sizes.iter().zip(&report.interface))
            .filter(|(_, q)| q.p_mpa > CARRIES * p_max)
            .fold(0.0f64, |m, (&s, _)| m.max(s));
        let across = half_width / size;
        if size > 0.0 && across < MIN_ELEMENTS_ACROSS {
            report.warnings.push(format!(
                "`{}`'s own elements under the contact are up to {size:.4} mm, {across:.1} across \
                 the contact's half-width ({half_width:.4} mm), fewer than \
                 {MIN_ELEMENTS_ACROSS}: the cells resolve the contact but the body's mesh does \
                 not, and its deformation there is too stiff or too soft by percents; mesh it \
                 at the contact with elements of at most {:.4} mm",
                body.name(),
                half_width / MIN_ELEMENTS_ACROSS
            ));
        }
    }
}

/// The warning of a contact whose Hertz half-width exceeds [`SMALL_CONTACT`] of the radius
/// across it: the answer is the parabola's on a linear body, not the sphere's or the
/// cylinder's.
fn large_contact(hertz: Hertz) -> Option<String> {
    let (a, r) = (hertz.half_width, hertz.radius);
    let ratio = a / r;
    (ratio > SMALL_CONTACT).then(|| {
        // The circle's gap at x = a over the parabola's, less one (the circle ends at x = R).
        let circle = r - (r * r - a * a).max(0.0).sqrt();
        let short = 100.0 * (1.0 - a * a / (2.0 * r) / circle);
        format!(
            "Hertz's {} = {a:.4} mm is {ratio:.2} of the radius across the contact, R = {r:.4} \
             mm, more than {SMALL_CONTACT}: the model holds for a contact small beside R — its \
             gap is the parabola x²/2R ({short:.1} % short of the circle at the contact's edge) \
             on bodies under small strains, of order a/R — so the answer is the parabola's on a \
             linear body; a lighter load or a larger radius keeps within it",
            if hertz.line { "b" } else { "a" },
        )
    })
}

/// A warning for each body of displacement elements whose material is nearly incompressible
/// ([`contopt_fem::locking_warning`]): solved or not, its stiffness is wrong.
fn locking(case: &Case) -> Vec<String> {
    (case.spec.body.iter().enumerate())
        .filter(|(_, b)| b.has_displacement_elements())
        .filter_map(|(i, b)| {
            contopt_fem::locking_warning(&format!("body[{i}] ({})", b.name()), &b.material()?)
        })
        .collect()
}

/// A warning for each of an envelope's load cases past its first (the case's own, judged
/// above) whose contact spans fewer than [`MIN_CELLS_ACROSS`] cells across: a case far lighter
/// than the load the grid was sized for is solved on cells too coarse for it. A bearing's
/// rollers are judged by its design, which names the roller and the load case.
fn light_cases(report: &CaseReport) -> Vec<String> {
    let Some(roller) = report.roller.as_ref().filter(|_| report.bearing.is_none()) else {
        return vec![];
    };
    let Some(own) = roller.envelope.first() else {
        return vec![];
    };
    (roller.envelope.iter().skip(1))
        .filter(|e| e.p_max_mpa > 0.0 && e.cells_across < MIN_CELLS_ACROSS)
        .map(|e| {
            format!(
                "the envelope's case of {:.1} N ({:.3} of the load the grid is sized for) at \
                 {:+.1}′ spans {:.1} cells across its contact's half-width, fewer than \
                 {MIN_CELLS_ACROSS}: its p_max {:.1} MPa is not resolved; give the grid more \
                 cells across (cells[1]) or solve it as a scene of its own",
                e.load_n,
                e.load_n / own.load_n,
                e.tilt_arcmin,
                e.cells_across,
                e.p_max_mpa
            )
        })
        .collect()
}

/// The first of an envelope's load cases past the case's own (judged above) whose contact
/// reaches the grid's outermost rows across, as a limit: a case far heavier than the load the
/// grid was sized for (±`reach_b` Hertz half-widths of the case's own load) is cut by the grid
/// there, so its pressure, the envelope's worst p_max and a crown designed for it are wrong.
/// The reach it needs is Hertz's half-width at its load, b ∝ √Q. A bearing's rollers are
/// judged by its design, each on its own grid.
fn envelope_edge(report: &CaseReport, case: &Case, points: &[[f64; 3]]) -> Option<ModelLimit> {
    let roller = report
        .roller
        .as_ref()
        .filter(|_| report.bearing.is_none())?;
    let own = roller.envelope.first()?;
    let reached = (roller.envelope.iter().skip(1))
        .find(|e| e.p_max_mpa > 0.0 && e.edge_across_mpa > CARRIES * e.p_max_mpa)?;
    let edge = edges(&case.plan.layout, points)
        .into_iter()
        .find(|e| e.axis == 1)?;
    let share = reached.load_n / own.load_n;
    let (needed, why) = match case.plan.hertz {
        Some(h) => {
            let b = h.half_width * share.sqrt();
            let needed = (HERTZ_MARGIN * b).max(GROWTH * edge.extent);
            (needed, format!(" (Hertz's b = {b:.4} mm at its load)"))
        }
        None => (GROWTH * edge.extent, String::new()),
    };
    let name = format!("y = ±{:.4} mm", edge.extent);
    let message = format!(
        "the envelope's case of {:.1} N ({share:.3} times the case's load) at {:+.1}′ \
         reaches the zone's edge {name} (p = {:.4e} MPa there, {:.0} % of its p_max): the zone \
         ends inside its contact, so its pressure, the envelope's worst p_max and all that \
         follows from them are wrong; the zone must reach at least {needed:.4} mm from its \
         centre{why}: {}",
        reached.load_n,
        reached.tilt_arcmin,
        reached.edge_across_mpa,
        100.0 * reached.edge_across_mpa / reached.p_max_mpa,
        widen(case, 1)
    );
    Some(ModelLimit {
        edge: name,
        extent_mm: edge.extent,
        needed_mm: needed,
        message,
    })
}

/// The warning of a case whose zone carries no pressure: the bodies do not touch, or touch
/// on less than a cell (Hertz's nominal contact says which, where it applies).
fn untouched(case: &Case) -> String {
    let said = "no point of the zone carries pressure: the bodies do not touch under this load";
    let cell = case.plan.layout.edge_cell();
    let cell = cell[0].max(cell[1]);
    match case.plan.hertz {
        Some(h) if h.half_width > 0.0 => format!(
            "{said}, or touch on less than a cell: Hertz's {} = {:.4e} mm spans {:.2} cells of \
             {cell:.4} mm; refine the zone (cells of at most {:.4e} mm)",
            if h.line { "b" } else { "a" },
            h.half_width,
            h.half_width / cell,
            h.half_width / MIN_CELLS_ACROSS
        ),
        _ => format!("{said}, or touch on less than a cell"),
    }
}

/// The first edge of the zone where the contact carries pressure and the gap goes on beyond
/// it, as a limit with the size the zone needs: on every layout, each edge point's gap asked
/// whether it goes on (a library user's bare grid has
/// [`HalfSpace::edge_reached`](contopt_greens::HalfSpace::edge_reached), its indenter's ends
/// given by axis).
fn edge_reached(
    case: &Case,
    points: &[[f64; 3]],
    pressure: &[f64],
    carrying: &[bool],
    p_max: f64,
) -> Option<ModelLimit> {
    let layout = &case.plan.layout;
    let zone = &case.spec.contact.zone;
    let rim_is_a_body = case.spec.body.iter().any(|b| b.ends_at_rim());
    let cell = layout.edge_cell();
    for edge in edges(layout, points) {
        if rim_is_a_body && edge.axis == 0 {
            continue;
        }
        // A grid's edge on the bodies' plane of symmetry is the middle of the contact.
        if edge.on_symmetry_plane {
            continue;
        }
        let reached = edge.points.iter().copied().find(|&i| {
            carrying[i]
                && case
                    .spec
                    .contact
                    .gap
                    .goes_on(zone, points[i], edge.axis, cell[edge.axis])
        });
        if let Some(i) = reached {
            return Some(limit(case, &edge, pressure[i], p_max));
        }
    }
    None
}

/// The first end of an imported body's contact faces that the contact reaches where the
/// body's boundary goes on beyond it (and the gap with it), as a limit: the group was drawn
/// too short. The end of a chain at a corner of its body, or at one of its partner's, is a
/// body's own edge.
fn end_reached(
    case: &Case,
    surface: &MeshSurface,
    points: &[[f64; 3]],
    pressure: &[f64],
    carrying: &[bool],
) -> Option<ModelLimit> {
    let contact = &case.spec.contact;
    let p_max = pressure.iter().fold(0.0f64, |m, &p| m.max(p));
    for end in surface.open_ends() {
        let beyond = [0, 1].map(|c| end.at[c] + end.face * end.outward[c]);
        if !contact
            .gap
            .finite_at(&contact.zone, [beyond[0], beyond[1], 0.0])
        {
            continue;
        }
        let Some(i) = (0..points.len()).find(|&i| carrying[i] && end.holds(points[i])) else {
            continue;
        };
        // The contact's span along the group up to this end: to its farthest carrying point.
        let span = (0..points.len())
            .filter(|&k| carrying[k])
            .map(|k| (end.at[0] - points[k][0]).hypot(end.at[1] - points[k][1]))
            .fold(0.0f64, f64::max);
        let needed = GROWTH * span;
        let edge = format!(
            "the end of \"{}\" at ({:.4}, {:.4}) mm",
            end.group, end.at[0], end.at[1]
        );
        let message = format!(
            "the contact reaches {edge}, the contact group of `{}` (p = {:.4e} MPa there, {:.0} \
             % of p_max), where the body's boundary goes on: the contact faces end inside the \
             contact, so the pressure and all that follows from it are wrong; name more of the \
             boundary in the group: the contact spans {span:.4} mm up to this end, so let the \
             group reach at least {needed:.4} mm from the contact's far side",
            end.body,
            pressure[i],
            100.0 * pressure[i] / p_max
        );
        return Some(ModelLimit {
            edge,
            extent_mm: span,
            needed_mm: needed,
            message,
        });
    }
    None
}

/// The limit of a contact that reached `edge`, with the size the zone needs.
fn limit(case: &Case, edge: &Edge, p: f64, p_max: f64) -> ModelLimit {
    let (needed, why) = match case.plan.hertz {
        Some(h) => (
            (HERTZ_MARGIN * h.half_width).max(GROWTH * edge.extent),
            format!(
                " (Hertz's {} = {:.4} mm)",
                if h.line { "b" } else { "a" },
                h.half_width
            ),
        ),
        None => (GROWTH * edge.extent, String::new()),
    };
    let message = format!(
        "the contact reaches the zone's edge {} (p = {p:.4e} MPa there, {:.0} % of p_max): the \
         zone ends inside the contact, so the pressure and all that follows from it are wrong; \
         the zone must reach at least {needed:.4} mm from its centre{why}: {}",
        edge.name,
        100.0 * p / p_max,
        widen(case, edge.axis)
    );
    ModelLimit {
        edge: edge.name.clone(),
        extent_mm: edge.extent,
        needed_mm: needed,
        message,
    }
}

/// What widens a zone along `axis`: a roller's grid across is ±`reach_b`·b (the bearing's
/// key for a bearing's) unless the scene gives its `cell_mm`, any other zone's cells.
fn widen(case: &Case, axis: usize) -> String {
    let roller = case.spec.contact.gap.roller_gap().is_some();
    let zone = case.spec.contact.zone.downcast::<GridZone>();
    let sized = zone.is_some_and(|g| g.cell_mm.is_some());
    match (roller && axis == 1 && !sized, case.spec.bearing.is_some()) {
        (true, true) => "raise bearing.reach_b (the grid's reach across, in Hertz half-widths \
                         of the design load)"
            .into(),
        (true, false) => "raise contact.gap.reach_b (the grid's reach across, in Hertz \
                          half-widths)"
            .into(),
        _ => "give it more or larger cells".into(),
    }
}

/// The edges of a zone and the points along each: a grid's four sides; the rim of rings or
/// of axisymmetric faces; both ends of strips; the outer end of plane faces (x = 0 is their
/// plane of symmetry).
fn edges(layout: &Layout, points: &[[f64; 3]]) -> Vec<Edge> {
    let cell = layout.edge_cell();
    let along = |axis: usize, high: bool| {
        let pick = |m: f64, v: f64| if high { m.max(v) } else { m.min(v) };
        let start = if high {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        };
        let end = points.iter().fold(start, |m, x| pick(m, x[axis]));
        let near: Vec<usize> = (0..points.len())
            .filter(|&i| (points[i][axis] - end).abs() < 0.5 * cell[axis].max(f64::MIN_POSITIVE))
            .collect();
        (end, near)
    };
    let named = |axis: usize, high: bool, symbol: &str| {
        let (end, near) = along(axis, high);
        let outer = if high {
            end + 0.5 * cell[axis]
        } else {
            end - 0.5 * cell[axis]
        };
        Edge {
            name: format!("{symbol} = {outer:+.4} mm"),
            axis,
            extent: outer.abs(),
            points: near,
            on_symmetry_plane: !high && layout.symmetric()[axis],
        }
    };
    match layout {
        Layout::Grid { .. } => vec![
            named(0, false, "x"),
            named(0, true, "x"),
            named(1, false, "y"),
            named(1, true, "y"),
        ],
        Layout::Rings(_) => vec![named(0, true, "r")],
        Layout::Strips { .. } => vec![named(0, false, "x"), named(0, true, "x")],
        Layout::Faces(f) if f.analysis == contopt_fem::Analysis::Axisymmetric => {
            vec![named(0, true, "r")]
        }
        Layout::Faces(_) => vec![named(0, true, "x")],
        // The ends of imported contact faces are judged by `end_reached`.
        Layout::Mesh(_) => vec![],
    }
}

/// How many cells span the contact's half-width through the largest pressure, in the
/// direction where they are fewest (on a grid, the smaller of the two counts: a roller's
/// contact may be long across and short along its axis; from the plane of a grid's
/// `symmetry`, all of the run). A grid's run across the whole zone, which a body ends there (a
/// cylinder as long as the zone), is not counted: `None` when both are.
fn resolution(
    layout: &Layout,
    points: &[[f64; 3]],
    carrying: &[bool],
    pressure: &[f64],
) -> Option<Resolution> {
    let peak = peak_index(pressure)?;
    if let Layout::Mesh(surface) = layout {
        return Some(surface.resolution(points, carrying));
    }
    // The carrying points on the line through the peak along the other axis.
    let count = |other: usize| {
        let line = line_through(points, peak, 1 - other);
        line.iter().filter(|&&i| carrying[i]).count() as f64
    };
    match layout {
        Layout::Grid {
            nx,
            ny,
            dx,
            dy,
            symmetric,
            ..
        } => {
            // From the plane of symmetry, the carrying run is the half-width itself.
            let half = |axis: usize, n: f64| if symmetric[axis] { n } else { 0.5 * n };
            let counts = [count(1), count(0)];
            let cells = [half(0, counts[0]), half(1, counts[1])];
            // A run across the whole zone ends where a body ends (a cylinder as long as the
            // zone, which the zone's edges did not cut): no edge of the contact to resolve.
            let within = |axis: usize| counts[axis] < [*nx, *ny][axis] as f64;
            let axis = (0..2)
                .filter(|&axis| within(axis))
                .min_by(|&a, &b| cells[a].total_cmp(&cells[b]))?;
            Some(Resolution {
                along: ["x", "y"][axis].into(),
                half_width_mm: cells[axis] * [*dx, *dy][axis],
                cells: cells[axis],
            })
        }
        _ => {
            let inside: Vec<f64> = points
                .iter()
                .zip(carrying)
                .filter(|(_, c)| **c)
                .map(|(x, _)| x[0])
                .collect();
            let lo = inside.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = inside.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let symmetric = matches!(layout, Layout::Strips { .. });
            let half = if symmetric { 0.5 * (hi - lo) } else { hi };
            let per_cell = points_per_cell(layout) as f64;
            let cells = inside.len() as f64 / per_cell / if symmetric { 2.0 } else { 1.0 };
            let radial = match layout {
                Layout::Rings(_) => true,
                Layout::Faces(f) => f.analysis == contopt_fem::Analysis::Axisymmetric,
                _ => false,
            };
            Some(Resolution {
                along: if radial { "r" } else { "x" }.into(),
                half_width_mm: half,
                cells,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use contopt_contact::InterfaceProblem;
    use contopt_results::{CaseReport, CaseStatus, EnvelopeCase, Point, RollerReport};

    use super::{judge, large_contact, light_cases, MIN_CELLS_ACROSS};
    use crate::{Case, Format, Registry, Scene};

    /// A sphere (R = 20 mm) on a Winkler bed, on `rings` rings over r < 5 mm.
    fn scene(rings: usize) -> Scene {
        let text = format!(
            "name = \"bed\"\n[contact]\nzone = {{ kind = \"rings\", rings = {rings}, radius_mm = \
             5.0 }}\ngap = {{ kind = \"sphere\", radius_mm = 20.0 }}\nload = {{ force_n = \
             1000.0 }}\n[[body]]\nkind = \"winkler\"\nmodulus_mpa_per_mm = 50.0\n[[body]]\nkind \
             = \"rigid\"\n"
        );
        Registry::standard()
            .parse(&text, Format::Toml, Path::new("bed.toml"))
            .unwrap()
    }

    /// A report of `case` in `status` whose first `carrying` points carry 100 MPa, the rest
    /// nothing, with the case's contact problem.
    fn report(
        case: &Case,
        carrying: usize,
        status: CaseStatus,
    ) -> (CaseReport, InterfaceProblem<'static>) {
        let problem = case.problem().unwrap();
        let mut report = CaseReport::new("bed", &Default::default(), serde_json::Value::Null);
        report.status = status;
        report.interface = (problem.interface().points().iter().enumerate())
            .map(|(i, &x_mm)| Point {
                x_mm,
                p_mpa: if i < carrying { 100.0 } else { 0.0 },
                d_um: 0.0,
                dh_um: 0.0,
                h_um: 0.0,
            })
            .collect();
        (report, problem)
    }

    /// A steel sphere of R = 10 mm on steel (E* = 115 GPa) under 1 MN touches over
    /// a = 4.02 mm = 0.40 R: warned, with the parabola 4.2 % short of the circle at r = a
    /// (R − √(R² − a²) = 0.844 mm against a²/2R = 0.808 mm); a rigid one (E* = 231 GPa),
    /// a = 3.19 mm, 2.6 %; under 1 kN, a/R = 0.04 is not warned.
    #[test]
    fn a_contact_large_beside_its_radius_is_named() {
        let e_star = 2.1e5 / (2.0 * (1.0 - 0.09));
        let steel = large_contact(crate::Hertz::sphere(10.0, 1.0e6, e_star)).unwrap();
        assert!(
            steel.contains("a = 4.0207 mm is 0.40 of the radius") && steel.contains("(4.2 % short"),
            "{steel}"
        );
        assert!(large_contact(crate::Hertz::sphere(10.0, 1.0e3, e_star)).is_none());
        let rigid = large_contact(crate::Hertz::sphere(10.0, 1.0e6, 2.0 * e_star)).unwrap();
        assert!(
            rigid.contains("0.32 of the radius") && rigid.contains("(2.6 % short"),
            "{rigid}"
        );
    }

    /// A contact that carries pressure at the zone's rim, where the sphere's gap goes on, is
    /// outside the model: the case says which edge, and that the zone must grow past it.
    #[test]
    fn a_contact_at_the_rim_is_outside_the_model() {
        let scene = scene(20);
        let case = &scene.cases()[0];
        let (mut r, problem) = report(case, 20, CaseStatus::Solved);
        judge(&mut r, case, &problem);
        assert_eq!(r.status, CaseStatus::OutsideModel);
        let limit = r.limit.expect("the rim is reached");
        assert!((limit.extent_mm - 5.0).abs() < 0.2, "{limit:?}");
        assert!(limit.needed_mm > limit.extent_mm, "{limit:?}");
        assert!(r.resolution.is_none());
    }

    /// A contact on fewer than [`MIN_CELLS_ACROSS`] rings carries a warning with its count; one
    /// on more carries none; both stay solved.
    #[test]
    fn a_contact_on_few_cells_is_named_with_their_count() {
        let scene = scene(40);
        let case = &scene.cases()[0];
        let (mut few, problem) = report(case, 3, CaseStatus::Solved);
        judge(&mut few, case, &problem);
        assert_eq!(few.status, CaseStatus::Solved);
        let cells = few.resolution.as_ref().unwrap().cells;
        assert!((cells - 3.0).abs() < 1e-12, "{cells}");
        assert!(cells < MIN_CELLS_ACROSS);
        assert_eq!(few.warnings.len(), 1, "{:?}", few.warnings);
        assert!(few.warnings[0].contains("3.0 cells"), "{:?}", few.warnings);
        let (mut many, _) = report(case, 12, CaseStatus::Solved);
        judge(&mut many, case, &problem);
        assert_eq!(many.resolution.as_ref().unwrap().cells, 12.0);
        assert!(many.warnings.is_empty(), "{:?}", many.warnings);
    }

    /// A pressure that rises to the contact's edge (Sneddon's punch, p ∝ 1/√(a² − r²), on
    /// the first 20 of 40 rings) is named as a sharp edge with its peak and the pressure a ring
    /// inward; Hertz's, falling to zero, and an even pressure (an optimised punch) are not.
    #[test]
    fn a_peak_at_a_sharp_edge_is_named() {
        let scene = scene(40);
        let case = &scene.cases()[0];
        let judged = |shape: &dyn Fn(f64) -> f64| {
            let (mut r, problem) = report(case, 20, CaseStatus::Solved);
            let rim = 1.01 * r.interface[19].x_mm[0];
            for q in &mut r.interface[..20] {
                q.p_mpa = 100.0 * shape(q.x_mm[0] / rim);
            }
            judge(&mut r, case, &problem);
            r.warnings
        };
        let sneddon = judged(&|s| 1.0 / (1.0 - s * s).sqrt());
        assert_eq!(sneddon.len(), 1, "{sneddon:?}");
        assert!(sneddon[0].contains("sharp edge"), "{sneddon:?}");
        assert!(sneddon[0].contains("r = +"), "{sneddon:?}");
        let hertz = judged(&|s| (1.0 - s * s).sqrt());
        assert!(hertz.is_empty(), "{hertz:?}");
        let even = judged(&|s| 1.0 + 1e-9 * s);
        assert!(even.is_empty(), "{even:?}");
    }

    /// A zone that carries nothing says the bodies do not touch; a case that did not converge
    /// is not judged (its pressure is not an answer), though Hertz's nominal contact is shown.
    #[test]
    fn nothing_carried_is_said_and_an_unconverged_case_is_not_judged() {
        let scene = scene(20);
        let case = &scene.cases()[0];
        let (mut none, problem) = report(case, 0, CaseStatus::Solved);
        judge(&mut none, case, &problem);
        assert!(
            none.warnings[0].contains("do not touch"),
            "{:?}",
            none.warnings
        );
        let (mut short, _) = report(case, 20, CaseStatus::NotConverged);
        judge(&mut short, case, &problem);
        assert_eq!(short.status, CaseStatus::NotConverged);
        assert!(short.limit.is_none() && short.resolution.is_none());
        assert!(short.warnings.is_empty(), "{:?}", short.warnings);
    }

    /// An envelope's case past the first that spans fewer than [`MIN_CELLS_ACROSS`] cells
    /// across is named with its load, share of the nominal and tilt; the first (the case's own,
    /// judged by its resolution) and one that carries nothing are not.
    #[test]
    fn a_light_envelope_case_is_named() {
        let case = |load_n: f64, cells_across: f64, p_max_mpa: f64| EnvelopeCase {
            load_n,
            tilt_arcmin: 2.0,
            p_max_mpa,
            p_max_at_mm: [0.0, 0.0],
            edge_loading: false,
            approach_um: 1.0,
            cells_across,
            edge_across_mpa: 0.0,
            centre_line: vec![],
        };
        let mut report = CaseReport::new("roller", &Default::default(), serde_json::Value::Null);
        report.roller = Some(RollerReport {
            p_max_at_mm: [0.0, 0.0],
            edge_loading: false,
            half_width_mm: [0.1, 0.1],
            crown_drop_end_um: 10.0,
            envelope: vec![
                case(5000.0, 3.0, 2000.0),
                case(50.0, 4.5, 400.0),
                case(2500.0, 14.0, 1400.0),
                case(10.0, 0.0, 0.0),
            ],
            worst_p_max_mpa: Some(2000.0),
            tuned: None,
        });
        let said = light_cases(&report);
        assert_eq!(said.len(), 1, "{said:?}");
        assert!(said[0].contains("50.0 N (0.010 of"), "{said:?}");
        assert!(said[0].contains("+2.0′ spans 4.5 cells"), "{said:?}");
    }
}
