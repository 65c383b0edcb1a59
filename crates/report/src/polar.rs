//! A bearing case's load zone drawn around the ring, as the trade draws it: each roller at
//! its place on the pitch circle (the load pointing down), its load an arrow inward of length
//! proportional to Q, and each load case's zone the curve through its loaded rollers' tips.

use std::io;

use contopt_results::CaseReport;
use plotters::element::{Circle, PathElement, Text};
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::figure::{Area, Drawn, Figure};
use crate::style::{self, GAP, LABEL_SIZE, TITLE_SIZE};

/// The figure's side \[SVG units\].
const SIDE: f64 = 560.0;
/// The pitch circle's radius \[SVG units\].
const RING: f64 = 190.0;
/// The heaviest roller's arrow, as a fraction of the ring's radius.
const LONGEST: f64 = 0.85;

/// The load zone of `case`'s load cases; `None` for a case that is not a bearing's or whose
/// rollers carry nothing.
pub(crate) fn load_zone(case: &CaseReport) -> Option<io::Result<Figure>> {
    let b = case.bearing.as_ref()?;
    let top = (b.load_cases.iter())
        .flat_map(|c| c.rollers.iter().map(|r| r.load_n))
        .fold(0.0, f64::max);
    if top <= 0.0 {
        return None;
    }
    let legend = 30.0 * b.load_cases.len() as f64;
    let height = SIDE + legend;
    let title = format!("{}: load zone (Q_max = {top:.0} N)", case.label);
    Some(Figure::draw(SIDE, height, |area| {
        paint(area, &title, top, b)
    }))
}

/// Paints the ring, every load case's arrows and zone, and the legend.
fn paint(area: &Area, title: &str, top: f64, b: &contopt_results::BearingReport) -> Drawn {
    let centre = (0.5 * SIDE, 0.5 * SIDE + 10.0);
    let at = |psi_deg: f64, r: f64| {
        // ψ from the load's direction, which points down the page.
        let psi = psi_deg.to_radians();
        (
            (centre.0 + r * psi.sin()).round() as i32,
            (centre.1 + r * psi.cos()).round() as i32,
        )
    };
    let head = Pos::new(HPos::Center, VPos::Top);
    area.draw(&Text::new(
        title.to_string(),
        ((0.5 * SIDE) as i32, GAP as i32),
        style::text(TITLE_SIZE).pos(head),
    ))?;
    let ring: Vec<(i32, i32)> = (0..=360).map(|d| at(d as f64, RING)).collect();
    area.draw(&PathElement::new(ring, style::stroke(style::GRID, 2)))?;
    let arrow = |q: f64| RING * (1.0 - LONGEST * q / top);
    for (k, case) in b.load_cases.iter().enumerate() {
        let colour = style::colour(k);
        let mut zone = vec![];
        for r in &case.rollers {
            area.draw(&Circle::new(
                at(r.angle_deg, RING),
                4,
                style::stroke(style::GRID, 1),
            ))?;
            if r.load_n <= 0.0 {
                continue;
            }
            let tip = at(r.angle_deg, arrow(r.load_n));
            area.draw(&PathElement::new(
                vec![at(r.angle_deg, RING), tip],
                style::stroke(colour, 2),
            ))?;
            zone.push((r.angle_deg, tip));
        }
        zone.sort_by(|a, b| {
            let wrap = |d: f64| (d + 180.0).rem_euclid(360.0);
            wrap(a.0).total_cmp(&wrap(b.0))
        });
        let tips: Vec<(i32, i32)> = zone.iter().map(|z| z.1).collect();
        area.draw(&PathElement::new(tips, style::stroke(colour, 1)))?;
        let y = (SIDE + 30.0 * k as f64) as i32;
        area.draw(&PathElement::new(
            vec![(40, y), (80, y)],
            style::stroke(colour, 3),
        ))?;
        area.draw(&Text::new(
            case.label.clone(),
            (90, y),
            style::text(LABEL_SIZE).pos(Pos::new(HPos::Left, VPos::Center)),
        ))?;
    }
    let foot = at(0.0, RING + 28.0);
    area.draw(&Text::new(
        "F_r ↓".to_string(),
        foot,
        style::text(LABEL_SIZE).pos(head),
    ))
}
