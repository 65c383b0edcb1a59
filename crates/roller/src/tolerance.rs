//! The crown's manufacturing tolerances as a box of its parameters, and the worst crown in
//! the box.
//!
//! A crown is ground to a drawing that tolerances each of its parameters: the drop at the
//! ends, the crowned length (where the crown starts), and for a logarithmic crown its constant
//! (Fujiwara–Kawase's A = K1·Q/(π l E*), the coefficient of Lundberg's, ISO's and Johns–Gohar's
//! logarithm). Every crown whose parameters lie within their tolerances may be delivered, so
//! a design is only as good as the worst of them. Neither p_max nor the life is monotone in
//! every parameter (a crown too short leaves edge peaks, one too long a centre peak; the
//! worst of a ridge in between may lie inside the box), so the worst is searched, not taken
//! at the box's corners: the corners and a grid over the box first, then Nelder and Mead's
//! simplex from the worst of them, held in the box ([`worst_in_box`]).

use std::ops::ControlFlow;

use contopt_core::{check, Error, Result};
use contopt_optimise::{nelder_mead, SearchSettings};
use serde::{Deserialize, Serialize};

use crate::Crown;

/// The parameters a crown's tolerances span, in the order of a deviation's components.
pub const PARAMETERS: [&str; 3] = ["drop", "crowned length", "log constant"];

/// The least points along each of the box's axes of [`worst_in_box`]'s grid: its two ends.
pub const MIN_GRID: usize = 2;

/// The most points along an axis: 3 axes of 9 points are 729 crowns, more than a search of
/// the simplex after them needs.
pub const MAX_GRID: usize = 9;

/// A crown's manufacturing tolerances, each ± about the nominal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CrownTolerances {
    /// The end drop's \[mm\]: z_m of Fujiwara–Kawase's, the drop at the ends of a circular
    /// crown's and of Johns–Gohar's (Lundberg's and ISO's are infinite at the ends: none).
    pub drop: f64,
    /// The crowned length's at each end \[mm\]: where a crown with a flat centre starts
    /// (Fujiwara–Kawase's K2·l/2, a circular crown's l/2 − flat).
    pub crowned_length: f64,
    /// The logarithm's constant's, relative (0.1: ±10 %): Fujiwara–Kawase's A, Lundberg's,
    /// ISO's and Johns–Gohar's coefficient.
    pub log_constant: f64,
}

impl CrownTolerances {
    /// Checks each tolerance ≥ 0 and finite, the relative one below 1.
    pub fn check(&self) -> Result<()> {
        check::non_negative("tolerance.drop_mm", self.drop)?;
        check::non_negative("tolerance.crowned_length_mm", self.crowned_length)?;
        check::non_negative("tolerance.log_constant", self.log_constant)?;
        if self.log_constant >= 1.0 {
            return Err(Error::invalid(
                "tolerance.log_constant",
                self.log_constant,
                "is relative and must be below 1 (a constant off by all of itself)",
            ));
        }
        Ok(())
    }

    /// Which of the [`PARAMETERS`] `crown` has and these tolerances move.
    pub fn active(&self, crown: &Crown) -> [bool; 3] {
        let has = match crown {
            Crown::FujiwaraKawase { .. } => [true, true, true],
            Crown::Circular { .. } => [true, true, false],
            Crown::JohnsGohar { .. } => [true, false, true],
            Crown::Iso { .. } | Crown::Lundberg { .. } => [false, false, true],
            _ => [false; 3],
        };
        let tolerance = [self.drop, self.crowned_length, self.log_constant];
        std::array::from_fn(|k| has[k] && tolerance[k] > 0.0)
    }

    /// The crown as made: `nominal` with each parameter off by `deviation`\[k\] ∈ \[−1, 1\]
    /// times its tolerance, on a roller of effective length `length` \[mm\]. An error when a
    /// tolerance takes a parameter out of its range (a drop or constant to zero or below, a
    /// crowned length to nothing or past the roller's end), and for a crown none of whose
    /// parameters the box spans (a table, a sum: its drawing's own tolerances apply).
    pub fn as_made(&self, nominal: &Crown, deviation: [f64; 3], length: f64) -> Result<Crown> {
        let [d_drop, d_length, d_log] = deviation;
        let half = 0.5 * check::positive("length", length)?;
        let scale = 1.0 + d_log * self.log_constant;
        let drop = |z: f64| positive("drop", z + d_drop * self.drop);
        match *nominal {
            Crown::FujiwaraKawase { a, k2, z_m } => {
                let crowned = k2 * half + d_length * self.crowned_length;
                let k2 = within_length(crowned, half)? / half;
                Ok(Crown::FujiwaraKawase {
                    a: a * scale,
                    k2,
                    z_m: drop(z_m)?,
                })
            }
            Crown::Circular { radius, flat } => {
                let s = half - flat;
                let end = s * s / (radius + (radius * radius - s * s).max(0.0).sqrt());
                let crowned = within_length(s + d_length * self.crowned_length, half)?;
                Crown::circular_with_drop(drop(end)?, half - crowned, half)
            }
            Crown::JohnsGohar { scale: c, end } => {
                // The end drop c·ln(1/end) moved by the tolerance, at the new coefficient.
                let z = drop(-c * end.ln())?;
                Ok(Crown::JohnsGohar {
                    scale: c * scale,
                    end: (-z / (c * scale)).exp(),
                })
            }
            Crown::Iso { diameter } => Ok(Crown::Lundberg {
                scale: 0.00035 * diameter * scale,
            }),
            Crown::Lundberg { scale: c } => Ok(Crown::Lundberg { scale: c * scale }),
            Crown::Straight => Ok(Crown::Straight),
            _ => Err(Error::invalid(
                "crown",
                "a table or a sum of crowns",
                "has no drop, crowned length or log constant for a tolerance box: give a \
                 parametric crown",
            )),
        }
    }
}

/// `value` of the parameter `what` when positive.
fn positive(what: &str, value: f64) -> Result<f64> {
    match value > 0.0 && value.is_finite() {
        true => Ok(value),
        false => Err(Error::invalid(
            format!("tolerance of the {what}"),
            value,
            "takes the parameter to zero or below: a tolerance smaller than the parameter",
        )),
    }
}

/// A crowned length at each end within (0, `half`] \[mm\].
fn within_length(crowned: f64, half: f64) -> Result<f64> {
    match crowned > 0.0 && crowned <= half * (1.0 + 1e-12) {
        true => Ok(crowned.min(half)),
        false => Err(Error::invalid(
            "tolerance of the crowned length",
            crowned,
            format!("takes the crowned length out of (0, {half}] mm, the roller's half-length"),
        )),
    }
}

/// The worst crown [`worst_in_box`] found.
#[derive(Clone, Debug, PartialEq)]
pub struct WorstCrown {
    /// Its deviation, each component in \[−1, 1\] of its tolerance ([`PARAMETERS`]' order).
    pub deviation: [f64; 3],
    /// The crown.
    pub crown: Crown,
    /// The objective there (larger is worse).
    pub value: f64,
    /// The worst of the box's corners' objectives.
    pub worst_corner: f64,
    /// The crowns evaluated.
    pub evaluations: usize,
}

/// The crown of the box `tolerances` about `nominal` (effective length `length`) where
/// `objective` is largest (a worst p_max, or a negative life): the objective at the `grid`ⁿ
/// points of a grid over the n active axes ([`CrownTolerances::active`]), its ends included,
/// so every corner; then Nelder–Mead from the worst of them, its first steps a grid spacing,
/// each trial point held in the box (clamped to \[−1, 1\]), within `settings`. With no active
/// axis, the nominal crown alone.
pub fn worst_in_box(
    tolerances: &CrownTolerances,
    nominal: &Crown,
    length: f64,
    grid: usize,
    settings: &SearchSettings,
    mut objective: impl FnMut(&Crown) -> Result<f64>,
) -> Result<WorstCrown> {
    tolerances.check()?;
    check::count("grid", grid, MIN_GRID, MAX_GRID)?;
    let axes: Vec<usize> = (0..3).filter(|&k| tolerances.active(nominal)[k]).collect();
    let full = |u: &[f64]| {
        let mut d = [0.0; 3];
        for (&k, &v) in axes.iter().zip(u) {
            d[k] = v.clamp(-1.0, 1.0);
        }
        d
    };
    let mut evaluations = 0;
    let mut value_at = |d: [f64; 3]| -> Result<f64> {
        evaluations += 1;
        let value = objective(&tolerances.as_made(nominal, d, length)?)?;
        check::finite("the objective under a crown of the tolerance box", value)
    };
    let spacing = 2.0 / (grid - 1) as f64;
    let (mut worst, mut worst_corner) = (([0.0; 3], f64::NEG_INFINITY), f64::NEG_INFINITY);
    for index in 0..grid.pow(axes.len() as u32) {
        let u: Vec<f64> = (0..axes.len())
            .map(|a| -1.0 + spacing * ((index / grid.pow(a as u32)) % grid) as f64)
            .collect();
        let d = full(&u);
        let value = value_at(d)?;
        if u.iter().all(|v| v.abs() == 1.0) {
            worst_corner = worst_corner.max(value);
        }
        if value > worst.1 {
            worst = (d, value);
        }
    }
    if !axes.is_empty() {
        let start: Vec<f64> = axes.iter().map(|&k| worst.0[k]).collect();
        let step: Vec<f64> = start.iter().map(|&v| -v.signum() * spacing).collect();
        let step: Vec<f64> = step
            .iter()
            .map(|&s| if s == 0.0 { spacing } else { s })
            .collect();
        let search = nelder_mead(
            |u: &[f64]| value_at(full(u)).map(|v| ControlFlow::Continue(-v)),
            &start,
            &step,
            settings,
        )?;
        if -search.value > worst.1 {
            worst = (full(&search.x), -search.value);
        }
    }
    Ok(WorstCrown {
        deviation: worst.0,
        crown: tolerances.as_made(nominal, worst.0, length)?,
        value: worst.1,
        worst_corner: match axes.is_empty() {
            true => worst.1,
            false => worst_corner,
        },
        evaluations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A Fujiwara–Kawase crown of a 10 mm roller: A = 1.3 µm, crowned 2 mm at each end,
    /// z_m = 10 µm.
    fn nominal() -> Crown {
        Crown::FujiwaraKawase {
            a: 0.0013,
            k2: 0.4,
            z_m: 0.010,
        }
    }

    const BOX: CrownTolerances = CrownTolerances {
        drop: 0.002,
        crowned_length: 0.5,
        log_constant: 0.2,
    };

    /// Each parameter moves by its tolerance: z_m by ±2 µm, the crowned length K2·l/2 by
    /// ±0.5 mm, A by ±20 %; out of range is named.
    #[test]
    fn the_crown_as_made_moves_each_parameter() {
        let made = BOX.as_made(&nominal(), [1.0, -1.0, 0.5], 10.0).unwrap();
        let Crown::FujiwaraKawase { a, k2, z_m } = made else {
            panic!("{made:?}")
        };
        assert!((z_m - 0.012).abs() < 1e-15 && (k2 - 0.3).abs() < 1e-15);
        assert!((a - 0.0013 * 1.1).abs() < 1e-15);
        let circular = Crown::circular_with_drop(0.01, 3.0, 5.0).unwrap();
        let made = BOX.as_made(&circular, [-1.0, 1.0, 1.0], 10.0).unwrap();
        assert!((made.drop(4.999_999, 10.0).unwrap() - 0.008).abs() < 1e-8);
        assert_eq!(made.drop(2.49, 10.0).unwrap(), 0.0);
        assert!(made.drop(2.51, 10.0).unwrap() > 0.0);
        let wide = CrownTolerances {
            crowned_length: 4.0,
            ..BOX
        };
        let e = wide
            .as_made(&nominal(), [0.0, 1.0, 0.0], 10.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("crowned length"), "{e}");
        assert_eq!(BOX.active(&Crown::iso(10.0).unwrap()), [false, false, true]);
    }

    /// The drop of the crown as made at |x| = 4.2 mm: it falls with the crowned length
    /// shortened, rises with z_m and A.
    fn drop_at(crown: &Crown) -> Result<f64> {
        crown.drop(4.2, 10.0)
    }

    /// A worst inside the box: the objective −(z(4.2) − z*)² (in units of 0.1 µm), z* the
    /// drop of the crown at the deviation (0.3, 0.3, 0.3), off the 3-point grid: largest
    /// (zero) on a surface through the box's inside, and below at every corner. The search
    /// finds it within 10⁻³ of a brute-force scan of 41³ crowns.
    #[test]
    fn a_worst_inside_the_box_is_found() {
        let target = drop_at(&BOX.as_made(&nominal(), [0.3; 3], 10.0).unwrap()).unwrap();
        let objective = |c: &Crown| drop_at(c).map(|z| -((z - target) * 1e4).powi(2));
        let settings = SearchSettings {
            tolerance: 1e-9,
            max_evaluations: 200,
        };
        let found = worst_in_box(&BOX, &nominal(), 10.0, 3, &settings, objective).unwrap();
        let n = 41;
        let mut brute = f64::NEG_INFINITY;
        for i in 0..n * n * n {
            let t = |k: usize| -1.0 + 2.0 * (k % n) as f64 / (n - 1) as f64;
            let d = [t(i), t(i / n), t(i / (n * n))];
            brute = brute.max(objective(&BOX.as_made(&nominal(), d, 10.0).unwrap()).unwrap());
        }
        assert!(found.worst_corner < -0.1, "{found:?}");
        assert!(found.value >= brute - 1e-3, "{} vs {brute}", found.value);
        assert!(found.deviation.iter().any(|d| d.abs() < 1.0), "{found:?}");
        assert!(found.evaluations <= 27 + 200);
        let z = drop_at(&found.crown).unwrap();
        assert!((z - target).abs() < 5e-6, "{z} vs {target}");
    }

    /// The worst found is never better than a corner: here the drop itself, monotone in
    /// each parameter, is worst at the corner of the longest crown, deepest drop and largest
    /// constant; a crown of no parametric form is refused.
    #[test]
    fn the_worst_is_at_least_every_corner() {
        let settings = SearchSettings::default();
        let found = worst_in_box(&BOX, &nominal(), 10.0, 2, &settings, drop_at).unwrap();
        for i in 0..8 {
            let d = std::array::from_fn(|k| if i >> k & 1 == 1 { 1.0 } else { -1.0 });
            let corner = drop_at(&BOX.as_made(&nominal(), d, 10.0).unwrap()).unwrap();
            assert!(found.value >= corner, "{d:?}: {corner} > {}", found.value);
        }
        assert_eq!(found.deviation, [1.0, 1.0, 1.0]);
        assert_eq!(found.value, found.worst_corner);
        let table = Crown::table(vec![0.0, 5.0], vec![0.0, 0.01]).unwrap();
        assert!(worst_in_box(&BOX, &table, 10.0, 3, &settings, drop_at).is_err());
    }
}
