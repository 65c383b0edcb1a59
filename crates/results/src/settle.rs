//! No NaN or infinity leaves a case: a report that holds one becomes a case that did not
//! converge, naming the field, with its numbers dropped.

use contopt_core::{Quantity, Termination};

use crate::{CaseReport, CaseStatus};

impl CaseReport {
    /// Sets `p_max_mpa` to the largest pressure of the interface points when the case has
    /// points, then turns a report that holds a NaN or an infinity (in its figures, its
    /// points, its passes, its roller figures or its termination's numbers) into one that did
    /// not converge, [`Termination::NonFinite`] naming the field, its numbers dropped: no
    /// non-finite value reaches `result.json`, the CSV or the charts. Last, writes
    /// `message`, the termination in words.
    pub fn settle(&mut self) {
        if self.status != CaseStatus::NotConverged && !self.interface.is_empty() {
            let top = self.interface.iter().fold(0.0f64, |m, q| m.max(q.p_mpa));
            self.p_max_mpa = Some(top);
        }
        if let Some(field) = self.first_non_finite() {
            *self = Self {
                status: CaseStatus::NotConverged,
                termination: Termination::NonFinite {
                    quantity: Quantity::Figure {
                        name: field.to_string(),
                    },
                },
                method: self.method,
                solver: self.solver,
                timings_ms: std::mem::take(&mut self.timings_ms),
                ..Self::new(&self.label, &self.params, self.input.take())
            };
        }
        self.message = self.termination.to_string();
    }

    /// The first field holding a NaN or an infinity.
    fn first_non_finite(&self) -> Option<&'static str> {
        let scalars = [
            ("p_max", self.p_max_mpa),
            ("bound_p_max", self.bound_p_max_mpa),
            ("dh_max", self.dh_max_um),
            ("omega_nv_excess", self.omega_nv_excess_mpa),
            ("approach", self.approach_um),
            ("penetration", self.penetration_um),
        ];
        let scalars = scalars
            .into_iter()
            .filter_map(|(name, v)| v.map(|v| (name, v)));
        let points = self.interface.iter().flat_map(|q| {
            let [x, y, z] = q.x_mm;
            [
                ("point", x),
                ("point", y),
                ("point", z),
                ("pressure", q.p_mpa),
                ("gap", q.d_um),
                ("gap change", q.dh_um),
                ("initial gap", q.h_um),
            ]
        });
        let passes = self.passes.iter().flat_map(|r| {
            [
                ("pass p_max", r.bound_p_max_mpa),
                ("pass Δh_max", r.dh_max_um),
                ("TOLH", r.tolh_mm2),
            ]
        });
        scalars
            .chain(termination_values(&self.termination))
            .chain(points)
            .chain(passes)
            .chain(self.roller_values())
            .chain(self.bearing_values())
            .find(|(_, v)| !v.is_finite())
            .map(|(name, _)| name)
    }

    /// The numbers of a bearing's figures: its ratings, lives, loads and pressures.
    fn bearing_values(&self) -> Vec<(&'static str, f64)> {
        let Some(b) = &self.bearing else {
            return vec![];
        };
        let lives = |l: &crate::Lives| {
            [
                ("ISO 281 life", l.iso_281_mrev),
                ("slice model life", l.slice_model_mrev),
                ("half-space life", l.half_space_mrev),
                ("peak-pressure life", l.peak_pressure_mrev),
            ]
        };
        let mut values = vec![
            ("load rating", b.dynamic_load_rating_n),
            ("worst p_max", b.worst.p_max_mpa),
        ];
        values.extend(lives(&b.duty_cycle));
        for c in &b.load_cases {
            values.extend(lives(&c.lives));
            values.push(("load case p_max", c.p_max_mpa));
            values.extend(c.displacement_um.map(|d| ("ring displacement", d)));
            for r in &c.rollers {
                values.push(("roller load", r.load_n));
                values.extend(r.tilt_arcmin.map(|t| ("roller tilt", t)));
            }
        }
        values
    }

    /// The numbers of the roller's figures.
    fn roller_values(&self) -> impl Iterator<Item = (&'static str, f64)> + '_ {
        self.roller.iter().flat_map(|r| {
            let envelope = r.envelope.iter().flat_map(|e| {
                [
                    ("envelope p_max", e.p_max_mpa),
                    ("envelope approach", e.approach_um),
                ]
                .into_iter()
                .chain(e.centre_line.iter().map(|c| ("envelope pressure", c.p_mpa)))
            });
            [
                ("roller half-width", r.half_width_mm[0]),
                ("roller half-width", r.half_width_mm[1]),
                ("crown drop", r.crown_drop_end_um),
                ("worst p_max", r.worst_p_max_mpa.unwrap_or(0.0)),
            ]
            .into_iter()
            .chain(envelope)
        })
    }
}

/// The numbers a termination holds (a step limit's measure and tolerance, a large
/// displacement's figures), inside an inner method's too.
fn termination_values(t: &Termination) -> Vec<(&'static str, f64)> {
    match t {
        Termination::StepLimit {
            measure, tolerance, ..
        } => vec![
            ("termination measure", *measure),
            ("termination tolerance", *tolerance),
        ],
        Termination::LargeDisplacement {
            displacement_mm,
            size_mm,
        } => vec![
            ("termination displacement", *displacement_mm),
            ("termination size", *size_mm),
        ],
        Termination::Inner { termination, .. } => termination_values(termination),
        _ => vec![],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Point;

    /// A NaN anywhere turns a solved case into one that did not converge, naming the field,
    /// with nothing non-finite left; a finite case keeps its figures.
    #[test]
    fn non_finite_values_end_the_case() {
        let mut case = CaseReport::new("c", &Default::default(), serde_json::Value::Null);
        case.status = CaseStatus::Solved;
        case.termination = Termination::Converged;
        case.interface = vec![Point {
            x_mm: [0.0; 3],
            p_mpa: 5.0,
            d_um: 0.0,
            dh_um: 0.0,
            h_um: 0.0,
        }];
        let mut good = case.clone();
        good.settle();
        assert_eq!(good.p_max_mpa, Some(5.0));
        assert!(good.is_solved());
        case.interface[0].d_um = f64::NAN;
        case.settle();
        assert_eq!(case.status, CaseStatus::NotConverged);
        let gap = Quantity::Figure { name: "gap".into() };
        assert_eq!(case.termination, Termination::NonFinite { quantity: gap });
        assert!(
            case.message.starts_with("the gap is not finite"),
            "{}",
            case.message
        );
        assert!(case.interface.is_empty() && case.p_max_mpa.is_none());
    }

    /// A termination's measure that is not finite (a step limit's NaN, inside an inner
    /// method's) ends the case as not finite too.
    #[test]
    fn a_non_finite_termination_measure_ends_the_case() {
        let mut case = CaseReport::new("c", &Default::default(), serde_json::Value::Null);
        case.status = CaseStatus::NotConverged;
        let limit = |measure| Termination::StepLimit {
            steps: 3,
            measure,
            tolerance: 1e-3,
        };
        case.termination = limit(0.5).inside(contopt_core::observe::Method::LoadSplit);
        let mut good = case.clone();
        good.settle();
        assert_eq!(good.termination, case.termination);
        case.termination = limit(f64::NAN).inside(contopt_core::observe::Method::LoadSplit);
        case.settle();
        let name = "termination measure".to_string();
        let quantity = Quantity::Figure { name };
        assert_eq!(case.termination, Termination::NonFinite { quantity });
    }
}
