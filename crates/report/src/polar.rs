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
    let zones: Vec<Zone> = (b.load_cases.iter())
        .map(|c| Zone {
            label: &c.label,
            rollers: c.rollers.iter().map(|r| (r.angle_deg, r.load_n)).collect(),
        })
        .collect();
    Some(Figure::draw(SIDE, height, |area| {
        paint(area, &title, top, &zones)
    }))
}

/// One load case as the figure draws it: its label and its rollers' (ψ \[°\], Q \[N\]).
struct Zone<'a> {
    label: &'a str,
    rollers: Vec<(f64, f64)>,
}

/// The ring's centre in the figure \[SVG units\].
const CENTRE: (f64, f64) = (0.5 * SIDE, 0.5 * SIDE + 10.0);

/// The point at angle ψ from the load's direction (which points down the page) and radius
/// `r` from the ring's centre \[SVG units\].
fn at(psi_deg: f64, r: f64) -> (i32, i32) {
    let psi = psi_deg.to_radians();
    (
        (CENTRE.0 + r * psi.sin()).round() as i32,
        (CENTRE.1 + r * psi.cos()).round() as i32,
    )
}

/// Paints the ring, every load case's arrows and zone, and the legend.
fn paint(area: &Area, title: &str, top: f64, zones: &[Zone]) -> Drawn {
    let head = Pos::new(HPos::Center, VPos::Top);
    area.draw(&Text::new(
        title.to_string(),
        ((0.5 * SIDE) as i32, GAP as i32),
        style::text(TITLE_SIZE).pos(head),
    ))?;
    let ring: Vec<(i32, i32)> = (0..=360).map(|d| at(d as f64, RING)).collect();
    area.draw(&PathElement::new(ring, style::stroke(style::GRID, 2)))?;
    let arrow = |q: f64| RING * (1.0 - LONGEST * q / top);
    for (k, case) in zones.iter().enumerate() {
        let colour = style::colour(k);
        let mut zone = vec![];
        for &(psi, q) in &case.rollers {
            area.draw(&Circle::new(
                at(psi, RING),
                4,
                style::stroke(style::GRID, 1),
            ))?;
            if q <= 0.0 {
                continue;
            }
            let tip = at(psi, arrow(q));
            area.draw(&PathElement::new(
                vec![at(psi, RING), tip],
                style::stroke(colour, 2),
            ))?;
            zone.push((psi, tip));
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
            case.label.to_string(),
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The `<polyline>`s of `svg` as their points.
    fn polylines(svg: &str) -> Vec<Vec<(i32, i32)>> {
        (svg.split("<polyline ").skip(1))
            .map(|piece| {
                let points = piece.split("points=\"").nth(1).unwrap();
                let points = &points[..points.find('"').unwrap()];
                (points.split_whitespace())
                    .map(|p| {
                        let (x, y) = p.split_once(',').unwrap();
                        (x.parse().unwrap(), y.parse().unwrap())
                    })
                    .collect()
            })
            .collect()
    }

    /// Each loaded roller's spoke runs from the pitch circle at its angle ψ inward, its length
    /// Q/Q_max of the longest (the heaviest roller's 0.85 of the ring's radius, pointing along
    /// the load: down the page at ψ = 0, to the right at ψ = 90°); an unloaded roller has
    /// none. A spoke drawn at −ψ, outward, or scaled by another load fails.
    #[test]
    fn spokes_stand_at_their_rollers_angles_and_loads() {
        let rollers = vec![(0.0, 5000.0), (90.0, 2500.0), (30.0, 4000.0), (180.0, 0.0)];
        let zones = [Zone {
            label: "case",
            rollers: rollers.clone(),
        }];
        let figure =
            Figure::draw(SIDE, SIDE + 30.0, |area| paint(area, "t", 5000.0, &zones)).unwrap();
        let spokes: Vec<Vec<(i32, i32)>> = (polylines(figure.svg()).into_iter())
            .filter(|l| l.len() == 2)
            .collect();
        let (cx, cy) = (CENTRE.0 as i32, CENTRE.1 as i32);
        let ring = RING as i32;
        // The heaviest, ψ = 0: from the ring's bottom straight up by 0.85·RING.
        let heaviest = vec![(cx, cy + ring), (cx, cy + ring - (LONGEST * RING) as i32)];
        // ψ = 90°: from the ring's right-hand side inward by half that.
        let half = vec![
            (cx + ring, cy),
            (cx + ring - (0.5 * LONGEST * RING) as i32, cy),
        ];
        for want in [&heaviest, &half] {
            let near =
                |a: (i32, i32), b: (i32, i32)| (a.0 - b.0).abs() <= 1 && (a.1 - b.1).abs() <= 1;
            assert!(
                spokes
                    .iter()
                    .any(|s| near(s[0], want[0]) && near(s[1], want[1])),
                "{want:?} not among {spokes:?}"
            );
        }
        // The roller at ψ = 30°: its spoke's direction is its angle, its length 0.8 of the
        // longest.
        let (dx, dy) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
        let foot = (
            cx + (RING * dx).round() as i32,
            cy + (RING * dy).round() as i32,
        );
        let spoke = spokes.iter().find(|s| s[0] == foot).expect("the 30° spoke");
        let (sx, sy) = (
            (spoke[0].0 - spoke[1].0) as f64,
            (spoke[0].1 - spoke[1].1) as f64,
        );
        let length = sx.hypot(sy);
        assert!(
            (length / (0.8 * LONGEST * RING) - 1.0).abs() < 0.01,
            "{length}"
        );
        assert!((sx / length - dx).abs() < 0.01 && (sy / length - dy).abs() < 0.01);
        // No spoke from the unloaded roller at the top.
        assert!(!spokes.iter().any(|s| s[0] == (cx, cy - ring)));
    }
}
