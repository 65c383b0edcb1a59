//! Rating lives of a cylindrical roller bearing: ISO 281's basic rating life from the basic
//! dynamic load rating, and ISO/TS 16281's reference rating life from every roller's slice
//! loads (the slice model's, [`SliceLoads::from_distribution`], or a half-space contact's,
//! [`slice_loads_from_pressure`]); per load case and over a duty cycle ([`miner`]).
//!
//! Lives are in millions of revolutions. Sources: ISO 281:2007, *Rolling bearings — Dynamic
//! load ratings and rating life*, clause 6 (radial roller bearings): C_r = b_m·f_c·(i·L_we·cos
//! α)^(7/9)·Z^(3/4)·D_we^(29/27), L_10 = (C_r/P_r)^(10/3); ISO/TR 1281-1:2021 for the formula
//! behind its table of f_c; ISO/TS 16281:2008, *Methods for calculating the modified reference
//! rating life for universally loaded bearings*, clause 5.3 (roller bearings). The standards'
//! texts could not be read here: the table of f_c is checked against ISO/TR 1281-1's formula
//! in the tests, and ISO/TS 16281's equations are those its implementations quote with their
//! numbers (eqs. 47–49, 56–57, 61–64 and the summation of clause 5.4) — see each item.

use contopt_core::{check, Error, Result};
use serde::Serialize;

use crate::{CylindricalRollerBearing, LoadDistribution, Raceway};

/// ISO 281:2007's f_c for radial roller bearings at D_we·cos α/D_pw = 0.01, 0.02, …, 0.30 (its
/// table for radial roller bearings, Table 7); between the rows the standard interpolates
/// linearly. The values are ISO/TR 1281-1's f_c = 207.9·λν·γ^(2/9)·(1 − γ)^(29/27)·(1 + γ)^(−1/4)
/// ·[1 + (1.04·((1 − γ)/(1 + γ))^(143/108))^(9/2)]^(−2/9) with λν = 0.83, rounded to 0.1.
const F_C: [f64; 30] = [
    52.1, 60.8, 66.5, 70.7, 74.1, 76.9, 79.2, 81.2, 82.8, 84.2, 85.4, 86.4, 87.1, 87.7, 88.2, 88.5,
    88.7, 88.8, 88.8, 88.7, 88.5, 88.2, 87.9, 87.5, 87.0, 86.4, 85.8, 85.2, 84.5, 83.8,
];

/// The step of D_we·cos α/D_pw between the rows of [`F_C`].
const F_C_STEP: f64 = 0.01;

/// ISO 281:2007's b_m for cylindrical roller bearings (its Table 1: contemporary bearing steel).
pub const B_M: f64 = 1.1;

/// ISO 281's life exponent of roller bearings.
pub const ROLLER_LIFE_EXPONENT: f64 = 10.0 / 3.0;

/// ISO 281's reduction factor λν of radial roller bearings, 0.83 (in f_c, for edge stresses and
/// the load's uneven spread along the rollers); ISO/TS 16281 divides it out of the rollers'
/// ratings (eq. 49), since it computes that spread itself.
pub const REDUCTION: f64 = 0.83;

/// A loaded cell may reach past the roller's end by this fraction of its half-length (round-off
/// of the grid's positions).
const OUTSIDE: f64 = 1e-9;

/// Time fractions of a duty cycle must sum to 1 within this.
const FRACTIONS: f64 = 1e-9;

/// ISO 281's f_c at γ = D_we·cos α/D_pw, linearly between the rows of its table; an error
/// outside the table (0.01 to 0.30).
pub fn f_c(gamma: f64) -> Result<f64> {
    let last = F_C_STEP * F_C.len() as f64;
    if !(F_C_STEP..=last).contains(&gamma) {
        return Err(Error::invalid(
            "D_we·cos α/D_pw",
            gamma,
            format!("must lie in ISO 281's table of f_c, {F_C_STEP} to {last}"),
        ));
    }
    let position = gamma / F_C_STEP - 1.0;
    let k = (position.floor() as usize).min(F_C.len() - 2);
    let t = position - k as f64;
    Ok(F_C[k] + t * (F_C[k + 1] - F_C[k]))
}

/// ISO 281:2007's basic dynamic radial load rating of `bearing` \[N\] (one row, α = 0):
/// C_r = b_m·f_c·L_we^(7/9)·Z^(3/4)·D_we^(29/27), b_m = [`B_M`], f_c by [`f_c`] at D_we/D_pw.
pub fn dynamic_load_rating(bearing: &CylindricalRollerBearing) -> Result<f64> {
    bearing.check()?;
    let d = bearing.roller_diameter;
    let fc = f_c(d / bearing.pitch_diameter)?;
    Ok(B_M
        * fc
        * bearing.effective_length().powf(7.0 / 9.0)
        * (bearing.rollers as f64).powf(0.75)
        * d.powf(29.0 / 27.0))
}

/// ISO 281's basic rating life L_10 = (C_r/P_r)^(10/3) \[10⁶ revolutions\].
pub fn basic_rating_life(rating: f64, load: f64) -> Result<f64> {
    check::positive("rating_n", rating)?;
    check::positive("load_n", load)?;
    check::derived_positive(
        "load_n",
        load,
        "the basic rating life (C/P)^(10/3)",
        (rating / load).powf(ROLLER_LIFE_EXPONENT),
    )
}

/// ISO/TS 16281's dynamic load ratings of one slice of a roller on each raceway \[N\].
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SliceRatings {
    /// q_ci, on the inner raceway.
    pub inner: f64,
    /// q_ce, on the outer raceway.
    pub outer: f64,
}

/// ISO/TS 16281's slice ratings of `bearing` from its C_r (eqs. 47–49 and 56–57, one row,
/// α = 0, γ = D_we/D_pw, ρ = (1 − γ)/(1 + γ)):
/// Q_ci = C_r/(λν·0.378·Z)·[1 + (1.038·ρ^(143/108))^(9/2)]^(2/9),
/// Q_ce = C_r/(λν·0.364·Z)·[1 + (1.038·ρ^(143/108))^(−9/2)]^(2/9), the roller's ratings on the
/// inner and outer raceway with ISO 281's λν = [`REDUCTION`] taken out, and a slice's
/// q_c = Q_c·(1/n_s)^(7/9). (0.378 and 0.364 are Lundberg–Palmgren's J_r/J_1 and J_r/J_2 of a
/// half-loaded ring, the ratios by which C_r relates to a roller's rating on a rotating and a
/// stationary ring; the exact integrals give 0.3764 and 0.3630.)
pub fn slice_ratings(bearing: &CylindricalRollerBearing, rating: f64) -> Result<SliceRatings> {
    bearing.check()?;
    check::positive("rating_n", rating)?;
    let gamma = bearing.roller_diameter / bearing.pitch_diameter;
    let rho = (1.0 - gamma) / (1.0 + gamma);
    let ratio = 1.038 * rho.powf(143.0 / 108.0);
    let z = bearing.rollers as f64;
    let per_slice = (1.0 / bearing.slices as f64).powf(7.0 / 9.0);
    let roller = |constant: f64, exponent: f64| {
        rating / (REDUCTION * constant * z) * (1.0 + ratio.powf(exponent)).powf(2.0 / 9.0)
    };
    Ok(SliceRatings {
        inner: roller(0.378, 4.5) * per_slice,
        outer: roller(0.364, -4.5) * per_slice,
    })
}

/// Every roller's slice loads on each raceway \[N\]: `rollers` rows of `slices`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SliceLoads {
    rollers: usize,
    slices: usize,
    inner: Vec<f64>,
    outer: Vec<f64>,
}

impl SliceLoads {
    /// No load on `rollers` rollers of `slices` slices.
    pub fn new(rollers: usize, slices: usize) -> Result<Self> {
        check::count("rollers", rollers, 1, usize::MAX)?;
        check::count("slices", slices, 1, usize::MAX)?;
        let n = rollers.checked_mul(slices).ok_or_else(|| {
            Error::invalid(
                "slices",
                slices,
                format!("times {rollers} rollers overflows"),
            )
        })?;
        Ok(Self {
            rollers,
            slices,
            inner: vec![0.0; n],
            outer: vec![0.0; n],
        })
    }

    /// The slice model's loads ([`CylindricalRollerBearing::solve`]).
    pub fn from_distribution(distribution: &LoadDistribution) -> Result<Self> {
        let slices = distribution.slice_x_mm.len();
        let mut loads = Self::new(distribution.rollers.len(), slices)?;
        for (j, r) in distribution.rollers.iter().enumerate() {
            loads.set(Raceway::Inner, j, &r.inner_n)?;
            loads.set(Raceway::Outer, j, &r.outer_n)?;
        }
        Ok(loads)
    }

    /// Roller `roller`'s slice loads on `raceway` replaced by `loads` (from a half-space
    /// contact, [`slice_loads_from_pressure`]): one finite load ≥ 0 per slice.
    pub fn set(&mut self, raceway: Raceway, roller: usize, loads: &[f64]) -> Result<()> {
        check::count("roller", roller, 0, self.rollers - 1)?;
        check::count(
            "slice loads (their number)",
            loads.len(),
            self.slices,
            self.slices,
        )?;
        if let Some(k) = loads.iter().position(|q| !(q.is_finite() && *q >= 0.0)) {
            return Err(Error::invalid(
                format!("slice load {k}"),
                loads[k],
                "must be zero or positive, and finite",
            ));
        }
        let row = roller * self.slices..(roller + 1) * self.slices;
        self.raceway_mut(raceway)[row].copy_from_slice(loads);
        Ok(())
    }

    /// Roller `roller`'s slice loads on `raceway`.
    pub fn roller(&self, raceway: Raceway, roller: usize) -> &[f64] {
        let row = roller * self.slices..(roller + 1) * self.slices;
        &self.raceway(raceway)[row]
    }

    fn raceway(&self, raceway: Raceway) -> &[f64] {
        match raceway {
            Raceway::Inner => &self.inner,
            Raceway::Outer => &self.outer,
        }
    }

    fn raceway_mut(&mut self, raceway: Raceway) -> &mut [f64] {
        match raceway {
            Raceway::Inner => &mut self.inner,
            Raceway::Outer => &mut self.outer,
        }
    }

    /// Slice k's dynamic equivalent load on `raceway` (ISO/TS 16281 eqs. 61–64): the mean over
    /// the rollers of q^p to the power 1/p, p = 4 on a ring that rotates against the load (each
    /// of its points meets every roller), p = 9/2 on one that stands (each point stays under
    /// one roller's load: Lundberg–Palmgren's stationary ring, exponent 4·9/8).
    fn equivalent(&self, raceway: Raceway, rotating: Raceway, k: usize) -> f64 {
        let p = if raceway == rotating { 4.0 } else { 4.5 };
        let loads = self.raceway(raceway);
        let mean = (0..self.rollers)
            .map(|j| loads[j * self.slices + k].powf(p))
            .sum::<f64>()
            / self.rollers as f64;
        mean.powf(1.0 / p)
    }
}

/// ISO/TS 16281's basic reference rating life and its raceways' \[10⁶ revolutions\].
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ReferenceLife {
    /// The inner raceway's, [Σ_k (q_ci/q_ei,k)^(−9/2)]^(−8/9).
    pub inner: f64,
    /// The outer raceway's.
    pub outer: f64,
    /// The bearing's, L_10r = (L_i^(−9/8) + L_e^(−9/8))^(−8/9).
    pub bearing: f64,
}

/// ISO/TS 16281's basic reference rating life of a roller bearing (clause 5.4):
/// L_10r = [Σ_k ((q_ci/q_ei,k)^(−9/2) + (q_ce/q_ee,k)^(−9/2))]^(−8/9), the sum over the slices,
/// q_e the slices' equivalent loads over the rollers on a `rotating` and a standing ring. The
/// modified reference rating life, a_ISO per slice, is [`modified_reference_rating_life`].
/// The standard's stress-riser functions (edge stresses, clause 5.3.3) are not applied: the
/// slice loads are taken as they are. An error when no slice of a raceway carries load (its
/// life is unbounded).
pub fn reference_rating_life(
    ratings: &SliceRatings,
    loads: &SliceLoads,
    rotating: Raceway,
) -> Result<ReferenceLife> {
    modified_reference_rating_life(ratings, loads, rotating, |_, _| Ok(1.0))
}

/// ISO/TS 16281's modified reference rating life with a life modification factor per slice
/// (clause 5.4 with a_ISO in each slice's life):
/// L_nmr = [Σ_k (a_ik^(−9/8)·(q_ci/q_ei,k)^(−9/2) + a_ek^(−9/8)·(q_ce/q_ee,k)^(−9/2))]^(−8/9),
/// each slice's life (q_c/q_e,k)⁴ multiplied by
/// its factor a_k = `factor`(raceway, q_e,k) before the slices' lives are combined (their
/// damages add with the exponent 9/8). A factor of 1 is the basic reference life; a factor
/// the same in every slice multiplies it. Slices without load are not asked for a factor.
pub fn modified_reference_rating_life(
    ratings: &SliceRatings,
    loads: &SliceLoads,
    rotating: Raceway,
    factor: impl Fn(Raceway, f64) -> Result<f64>,
) -> Result<ReferenceLife> {
    check::positive("ratings.inner", ratings.inner)?;
    check::positive("ratings.outer", ratings.outer)?;
    let damage = |raceway: Raceway, rating: f64| -> Result<f64> {
        let mut sum = 0.0;
        for k in 0..loads.slices {
            let q = loads.equivalent(raceway, rotating, k);
            if q > 0.0 {
                let a =
                    check::positive("the slice's life modification factor", factor(raceway, q)?)?;
                sum += a.powf(-9.0 / 8.0) * (q / rating).powf(4.5);
            }
        }
        Ok(sum)
    };
    let life = |raceway: Raceway, rating: f64| -> Result<f64> {
        let d = damage(raceway, rating)?;
        if d <= 0.0 {
            return Err(Error::invalid(
                format!("slice loads on the {raceway:?} raceway"),
                "all zero",
                "some slice must carry load: without load the life is unbounded",
            ));
        }
        check::derived_positive(
            "slice loads",
            "their sum",
            "the reference rating life",
            d.powf(-8.0 / 9.0),
        )
    };
    let (inner, outer) = (
        life(Raceway::Inner, ratings.inner)?,
        life(Raceway::Outer, ratings.outer)?,
    );
    let bearing = (inner.powf(-9.0 / 8.0) + outer.powf(-9.0 / 8.0)).powf(-8.0 / 9.0);
    Ok(ReferenceLife {
        inner,
        outer,
        bearing,
    })
}

/// The slice loads \[N\] of one roller from a contact pressure on a grid over its effective
/// length `length` (|x| ≤ length/2, as [`crate::Roller::bodies`]): each cell's force
/// p·`cell`\[0\]·`cell`\[1\] shared among the `slices` equal slices by the length of the cell
/// (x ± `cell`\[0\]/2) inside each; `points` are the cells' centres (x first).
pub fn slice_loads_from_pressure(
    points: &[[f64; 3]],
    pressure: &[f64],
    cell: [f64; 2],
    length: f64,
    slices: usize,
) -> Result<Vec<f64>> {
    let mut loads = vec![0.0; slices];
    each_overlap(points, pressure, cell, length, slices, |k, inside, p| {
        loads[k] += p * cell[1] * inside;
    })?;
    Ok(loads)
}

/// The largest pressure \[MPa\] in each of `slices` equal slices of a roller's grid (the
/// cells that reach into the slice), as [`slice_loads_from_pressure`] takes the grid.
pub fn slice_peaks_from_pressure(
    points: &[[f64; 3]],
    pressure: &[f64],
    cell: [f64; 2],
    length: f64,
    slices: usize,
) -> Result<Vec<f64>> {
    let mut peaks = vec![0.0f64; slices];
    each_overlap(points, pressure, cell, length, slices, |k, _, p| {
        peaks[k] = peaks[k].max(p);
    })?;
    Ok(peaks)
}

/// The load \[N\] of a slice `width` \[mm\] wide under Hertz's line contact of peak `p0`
/// \[MPa\] between surfaces of effective radius `radius` \[mm\] and modulus `e_star` \[MPa\]:
/// π·R·w·p₀²/E* (Johnson, *Contact Mechanics*, eq. 4.45, p₀ = (q·E*/(πR))^½, solved for the
/// line load q). A slice whose pressure is Hertz's carries it; at an edge peak it is the load
/// a Hertzian slice would need to reach that peak.
pub fn hertz_slice_load(p0: f64, width: f64, radius: f64, e_star: f64) -> f64 {
    std::f64::consts::PI * radius * width * p0 * p0 / e_star
}

/// Calls `f(k, inside, p)` for every loaded cell and every slice k its x-range reaches into
/// (`inside` \[mm\] of it, p its pressure), after the checks of
/// [`slice_loads_from_pressure`].
fn each_overlap(
    points: &[[f64; 3]],
    pressure: &[f64],
    cell: [f64; 2],
    length: f64,
    slices: usize,
    mut f: impl FnMut(usize, f64, f64),
) -> Result<()> {
    check::count(
        "pressure (its length)",
        pressure.len(),
        points.len(),
        points.len(),
    )?;
    check::count("slices", slices, 1, usize::MAX)?;
    check::positive("cell[0]", cell[0])?;
    check::positive("cell[1]", cell[1])?;
    check::positive("length", length)?;
    if let Some(i) = pressure.iter().position(|p| !(p.is_finite() && *p >= 0.0)) {
        return Err(Error::invalid(
            format!("pressure[{i}]"),
            pressure[i],
            "must be zero or positive, and finite",
        ));
    }
    let width = length / slices as f64;
    for (x, p) in points.iter().zip(pressure).filter(|(_, p)| **p > 0.0) {
        let (from, to) = (x[0] - 0.5 * cell[0], x[0] + 0.5 * cell[0]);
        if to.max(-from) > 0.5 * length * (1.0 + OUTSIDE) {
            return Err(Error::invalid(
                "pressure",
                format!("{p} MPa at x = {} mm", x[0]),
                format!("lies outside the roller's length ±{} mm", 0.5 * length),
            ));
        }
        let first = (((from + 0.5 * length) / width).floor().max(0.0)) as usize;
        for k in first..slices {
            let (lo, hi) = (
                -0.5 * length + k as f64 * width,
                -0.5 * length + (k + 1) as f64 * width,
            );
            if lo >= to {
                break;
            }
            let inside = (to.min(hi) - from.max(lo)).max(0.0);
            if inside > 0.0 {
                f(k, inside, *p);
            }
        }
    }
    Ok(())
}

/// Palmgren–Miner's life of a duty cycle: L = 1/Σ_i (t_i/L_i) over `cases` of (time fraction
/// t_i, life L_i), the fractions positive and summing to 1.
pub fn miner(cases: &[(f64, f64)]) -> Result<f64> {
    check::count("duty cycle (its cases)", cases.len(), 1, usize::MAX)?;
    for (i, &(fraction, life)) in cases.iter().enumerate() {
        check::positive(&format!("duty cycle[{i}].fraction"), fraction)?;
        check::positive(&format!("duty cycle[{i}].life"), life)?;
    }
    let total: f64 = cases.iter().map(|c| c.0).sum();
    if (total - 1.0).abs() > FRACTIONS {
        return Err(Error::invalid(
            "duty cycle fractions (their sum)",
            total,
            "must sum to 1",
        ));
    }
    let damage: f64 = cases.iter().map(|(t, l)| t / l).sum();
    check::derived_positive("duty cycle", "its lives", "the damage Σ t/L", damage).map(|d| 1.0 / d)
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::bearing::bearing_209 as bearing;

    /// The table of f_c is ISO/TR 1281-1's formula rounded to 0.1 (λν = 0.83): every row within
    /// 0.05; between rows, linear; outside, an error.
    #[test]
    fn f_c_is_iso_tr_1281s_formula() {
        let formula = |g: f64| {
            let r = (1.0 - g) / (1.0 + g);
            207.9 * 0.83 * g.powf(2.0 / 9.0) * (1.0 - g).powf(29.0 / 27.0) / (1.0 + g).powf(0.25)
                * (1.0 + (1.04 * r.powf(143.0 / 108.0)).powf(4.5)).powf(-2.0 / 9.0)
        };
        for k in 0..F_C.len() {
            let g = 0.01 * (k + 1) as f64;
            assert!(
                (f_c(g).unwrap() - formula(g)).abs() <= 0.05 + 1e-9,
                "{g}: {} vs {}",
                f_c(g).unwrap(),
                formula(g)
            );
        }
        assert!((f_c(0.155).unwrap() - 88.35).abs() < 1e-12);
        for g in [0.005, 0.31, f64::NAN] {
            assert!(f_c(g).unwrap_err().to_string().contains("f_c"));
        }
    }

    /// The 209 bearing's C_r, worked by hand: f_c(10/65) = 88.2 + 0.3846·0.3 = 88.315,
    /// C_r = 1.1·88.315·9.6^(7/9)·14^(3/4)·10^(29/27) = 48 427 N; its life at 8900 N.
    #[test]
    fn dynamic_load_rating_of_a_209_bearing() {
        let c = dynamic_load_rating(&bearing(30)).unwrap();
        assert!((c - 48_427.036).abs() < 0.01, "{c}");
        let l = basic_rating_life(c, 8900.0).unwrap();
        assert!((l - (c / 8900.0).powf(10.0 / 3.0)).abs() < 1e-12 * l);
        assert!(basic_rating_life(c, 0.0).is_err());
    }

    /// Rollers loaded evenly along their length: the reference life is Lundberg–Palmgren's
    /// [(Q_ci/Q_ei)^(−9/2) + (Q_ce/Q_ee)^(−9/2)]^(−8/9) of the whole rollers (Q_c = q_c·n_s^(7/9),
    /// Q_ei the rollers' loads' 4-mean, Q_ee their 9/2-mean), whatever the number of slices;
    /// with the outer ring rotating the means swap.
    #[test]
    fn even_slices_give_the_rollers_lives() {
        let rating = dynamic_load_rating(&bearing(1)).unwrap();
        let q: Vec<f64> = (0..14)
            .map(|j| {
                3000.0
                    * (2.0 * std::f64::consts::PI * j as f64 / 14.0)
                        .cos()
                        .max(0.0)
                        .powf(10.0 / 9.0)
            })
            .collect();
        let mean = |p: f64| (q.iter().map(|q| q.powf(p)).sum::<f64>() / 14.0).powf(1.0 / p);
        let mut lives = vec![];
        for slices in [1, 7, 30] {
            let b = bearing(slices);
            let r = slice_ratings(&b, rating).unwrap();
            let mut loads = SliceLoads::new(14, slices).unwrap();
            for (j, qj) in q.iter().enumerate() {
                let even = vec![qj / slices as f64; slices];
                loads.set(Raceway::Inner, j, &even).unwrap();
                loads.set(Raceway::Outer, j, &even).unwrap();
            }
            let n79 = (slices as f64).powf(7.0 / 9.0);
            let (qci, qce) = (r.inner * n79, r.outer * n79);
            for (rotating, (pi, pe)) in [(Raceway::Inner, (4.0, 4.5)), (Raceway::Outer, (4.5, 4.0))]
            {
                let life = reference_rating_life(&r, &loads, rotating).unwrap();
                let want =
                    ((qci / mean(pi)).powf(-4.5) + (qce / mean(pe)).powf(-4.5)).powf(-8.0 / 9.0);
                assert!(
                    (life.bearing / want - 1.0).abs() < 1e-12,
                    "{slices}: {} vs {want}",
                    life.bearing
                );
                assert!((life.inner / (qci / mean(pi)).powi(4) - 1.0).abs() < 1e-12);
            }
            lives.push(
                reference_rating_life(&r, &loads, Raceway::Inner)
                    .unwrap()
                    .bearing,
            );
        }
        assert!(
            lives.iter().all(|l| (l / lives[0] - 1.0).abs() < 1e-12),
            "{lives:?}"
        );
        let unloaded = SliceLoads::new(14, 7).unwrap();
        let r = slice_ratings(&bearing(7), rating).unwrap();
        assert!(reference_rating_life(&r, &unloaded, Raceway::Inner).is_err());
    }

    /// The modified reference life: a factor the same in every slice multiplies each ring's
    /// life by itself (a = 2: ×2 exactly); a factor per slice weights each slice's damage by
    /// a^(−9/8) before they add: one roller, 2 slices on each ring carrying q and 2q, factors
    /// 4 and 1, give [4^(−9/8)·q^(9/2) + (2q)^(9/2)]/q_c^(9/2) per ring, to the −8/9, written
    /// out here; a factor taken where a slice carries nothing would be a defect.
    #[test]
    fn a_factor_per_slice_weights_each_slices_damage() {
        let b = bearing(2);
        let r = slice_ratings(&b, dynamic_load_rating(&b).unwrap()).unwrap();
        let mut loads = SliceLoads::new(14, 2).unwrap();
        loads.set(Raceway::Inner, 0, &[1000.0, 2000.0]).unwrap();
        loads.set(Raceway::Outer, 0, &[1000.0, 2000.0]).unwrap();
        let basic = reference_rating_life(&r, &loads, Raceway::Inner).unwrap();
        let twice =
            modified_reference_rating_life(&r, &loads, Raceway::Inner, |_, _| Ok(2.0)).unwrap();
        assert!((twice.bearing / basic.bearing - 2.0).abs() < 1e-12);
        assert!((twice.outer / basic.outer - 2.0).abs() < 1e-12);
        let per_slice = |_: Raceway, q: f64| {
            assert!(q > 0.0);
            Ok(if q < 800.0 { 4.0 } else { 1.0 })
        };
        let life = modified_reference_rating_life(&r, &loads, Raceway::Inner, per_slice).unwrap();
        // The inner ring rotates: slice k's equivalent load is the 4-mean over 14 rollers.
        let qe = |q: f64| q * (1.0f64 / 14.0).powf(0.25);
        let inner = |a: [f64; 2]| {
            (a[0].powf(-9.0 / 8.0) * (qe(1000.0) / r.inner).powf(4.5)
                + a[1].powf(-9.0 / 8.0) * (qe(2000.0) / r.inner).powf(4.5))
            .powf(-8.0 / 9.0)
        };
        let factors = [1000.0, 2000.0].map(|q| if qe(q) < 800.0 { 4.0 } else { 1.0 });
        assert_eq!(factors, [4.0, 1.0]);
        assert!(
            (life.inner / inner(factors) - 1.0).abs() < 1e-12,
            "{factors:?}"
        );
        assert!((basic.inner / inner([1.0, 1.0]) - 1.0).abs() < 1e-12);
    }

    /// A pressure map's slice loads: every cell's force lands in the slices its width covers,
    /// they sum to the map's force, and a load outside the roller is refused.
    #[test]
    fn slice_loads_of_a_pressure_map() {
        // 7 columns of 0.5 mm over a 3.5 mm roller, 2 rows of 0.1 mm, cut into 3 slices.
        let points: Vec<[f64; 3]> = (0..14)
            .map(|i| [-1.5 + 0.5 * (i % 7) as f64, 0.1 * (i / 7) as f64, 0.0])
            .collect();
        let pressure: Vec<f64> = (0..14).map(|i| 100.0 * (1 + i % 7) as f64).collect();
        let loads = slice_loads_from_pressure(&points, &pressure, [0.5, 0.1], 3.5, 3).unwrap();
        // Per column (both rows): 10·(1..7) N over [−1.75 + 0.5i, −1.25 + 0.5i]; slices 7/6 mm.
        let w = 3.5 / 3.0;
        let column = |i: usize, lo: f64, hi: f64| {
            let (a, b) = (-1.75 + 0.5 * i as f64, -1.25 + 0.5 * i as f64);
            20.0 * (i + 1) as f64 * (hi.min(b) - lo.max(a)).max(0.0)
        };
        for (k, got) in loads.iter().enumerate() {
            let (lo, hi) = (-1.75 + k as f64 * w, -1.75 + (k + 1) as f64 * w);
            let want: f64 = (0..7).map(|i| column(i, lo, hi)).sum();
            assert!((got - want).abs() < 1e-9, "{k}: {got} vs {want}");
        }
        assert!((loads.iter().sum::<f64>() - 2.0 * 0.05 * 2800.0).abs() < 1e-9);
        let e = slice_loads_from_pressure(&points, &pressure, [0.5, 0.1], 3.0, 3)
            .unwrap_err()
            .to_string();
        assert!(e.contains("outside the roller"), "{e}");
    }

    /// A slice's peak is the largest pressure of the cells reaching into it; Hertz's slice load
    /// of a Hertzian strip's peak is the strip's own load: a line load q over width w between
    /// radii R gives p₀ = (q·E*/(πR))^½ and back π·R·w·p₀²/E* = q·w.
    #[test]
    fn slice_peaks_and_their_hertzian_loads() {
        let points: Vec<[f64; 3]> = (0..14)
            .map(|i| [-1.5 + 0.5 * (i % 7) as f64, 0.1 * (i / 7) as f64, 0.0])
            .collect();
        let pressure: Vec<f64> = (0..14)
            .map(|i| 100.0 * (1 + i % 7) as f64 + (i / 7) as f64)
            .collect();
        let peaks = slice_peaks_from_pressure(&points, &pressure, [0.5, 0.1], 3.5, 3).unwrap();
        // Slices of 7/6 mm from −1.75: the first reaches columns 0–2, the second 2–4, the last 4–6.
        assert_eq!(peaks, vec![301.0, 501.0, 701.0]);
        let (q, w, r, e) = (544.6, 0.32, 4.3, 1.1538e5);
        let p0 = (q * e / (std::f64::consts::PI * r)).sqrt();
        assert!((hertz_slice_load(p0, w, r, e) - q * w).abs() < 1e-9 * q * w);
    }

    /// Palmgren–Miner by hand; fractions that do not sum to 1 are named.
    #[test]
    fn miner_sums_the_damage() {
        let l = miner(&[(0.25, 100.0), (0.75, 10.0)]).unwrap();
        assert!((l - 1.0 / (0.0025 + 0.075)).abs() < 1e-12);
        let e = miner(&[(0.5, 1.0), (0.4, 2.0)]).unwrap_err().to_string();
        assert!(e.contains("fractions") && e.contains("0.9"), "{e}");
        assert!(miner(&[(1.0, 0.0)])
            .unwrap_err()
            .to_string()
            .contains("life"));
    }
}
