//! Axes with ticks at round values, 1, 2 or 5 × 10ᵏ apart, and their labels.

use contopt_results::words::power_of_ten;

/// The fewest and most intervals between ticks on an axis.
const INTERVALS: (usize, usize) = (4, 10);

/// Axes that overhang the data by less than this fraction more than the tightest count as
/// tight; of those, the one with the fewest ticks is taken.
const TIGHT: f64 = 0.02;

/// Data that lie within this fraction of a step of a tick count as on it (round-off of the
/// data, not a feature of them).
const SNAP: f64 = 1e-9;

/// Values whose spread is below this fraction of their magnitude are one value drawn flat:
/// round-off of a constant (an optimum's p = v·p_max with v = 1 spreads by 10⁻¹²), below what
/// a label's six decimals can tell apart.
const FLAT: f64 = 1e-6;

/// Below this step or above this magnitude, tick labels are written as m·10ⁿ.
const PLAIN_SMALLEST_STEP: f64 = 1e-3;
const PLAIN_LARGEST: f64 = 1e6;

/// An axis from one round value to another, with its ticks.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Axis {
    /// The first tick, at or below the smallest value.
    pub lo: f64,
    /// The last tick, at or above the largest value.
    pub hi: f64,
    /// The step between ticks: 1, 2 or 5 × 10ᵏ.
    pub step: f64,
}

impl Axis {
    /// The round axis over the finite `values`: a single value is widened (by a tenth of it,
    /// or by one around zero) and no value at all gives 0 to 1.
    pub fn over(values: impl Iterator<Item = f64>) -> Self {
        let (lo, hi) = span(values);
        Self::between(lo, hi)
    }

    /// The round axis from `lo` to `hi` (`lo` < `hi`, both finite): of the steps 1, 2 or
    /// 5 × 10ᵏ that give 4 to 10 intervals, the one whose axis overhangs the data least, and
    /// of nearly equal ones the one with the fewest ticks (−4.975…4.975 runs from −5 to 5 by
    /// 1, not from −6 to 6 by 2; 0…93.3 from 0 to 100 by 20).
    pub fn between(lo: f64, hi: f64) -> Self {
        let largest = round_step((hi - lo) / INTERVALS.0 as f64);
        let candidates: Vec<Self> = [1.0, 2.0, 2.5, 5.0, 10.0, 20.0]
            .into_iter()
            .map(|divisor| round_step(largest / divisor))
            .map(|step| Self {
                lo: (lo / step + SNAP).floor() * step,
                hi: (hi / step - SNAP).ceil() * step,
                step,
            })
            .filter(|a| (INTERVALS.0..=INTERVALS.1).contains(&a.intervals()))
            .collect();
        let span = |a: &Self| (a.hi - a.lo) / (hi - lo);
        let tightest = candidates.iter().map(span).fold(f64::INFINITY, f64::min);
        candidates
            .into_iter()
            .filter(|a| span(a) <= tightest * (1.0 + TIGHT))
            .min_by_key(Self::intervals)
            .unwrap_or_else(|| {
                let step = round_step((hi - lo) / INTERVALS.0 as f64);
                Self {
                    lo: (lo / step + SNAP).floor() * step,
                    hi: (hi / step - SNAP).ceil() * step,
                    step,
                }
            })
    }

    /// The number of intervals between the ticks.
    fn intervals(&self) -> usize {
        ((self.hi - self.lo) / self.step).round() as usize
    }

    /// The tick values, from `lo` to `hi`.
    pub fn ticks(&self) -> Vec<f64> {
        let first = (self.lo / self.step).round() as i64;
        let last = (self.hi / self.step).round() as i64;
        (first..=last).map(|k| k as f64 * self.step).collect()
    }

    /// The label of tick `v`: as many decimals as the step needs, or m·10ⁿ for very large or
    /// very small values; a minus sign (−), never `-0`.
    pub fn label(&self, v: f64) -> String {
        if v.abs() < self.step * SNAP {
            return "0".into();
        }
        let largest = self.lo.abs().max(self.hi.abs());
        if self.step < PLAIN_SMALLEST_STEP || largest >= PLAIN_LARGEST {
            return scientific(v, self.step);
        }
        let decimals = (-self.step.log10().floor()).max(0.0) as usize;
        format!("{v:.decimals$}").replace('-', "−")
    }
}

/// The smallest of 1, 2, 5 × 10ᵏ at or above `raw` (> 0).
fn round_step(raw: f64) -> f64 {
    let power = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * power)
        .find(|&s| s >= raw * (1.0 - SNAP))
        .unwrap_or(10.0 * power)
}

/// The range of the finite `values`, widened around a single value (or values equal to
/// [`FLAT`] of their size) and (0, 1) without any.
pub(crate) fn span(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if lo > hi {
        (0.0, 1.0)
    } else if hi - lo <= FLAT * lo.abs().max(hi.abs()) {
        let mid = 0.5 * (lo + hi);
        let half = if mid == 0.0 { 1.0 } else { 0.1 * mid.abs() };
        (mid - half, mid + half)
    } else {
        (lo, hi)
    }
}

/// `v` as m·10ⁿ, m with the digits the step needs (`2·10⁵`, `1.5·10⁻³`).
fn scientific(v: f64, step: f64) -> String {
    let n = v.abs().log10().floor() as i32;
    let mantissa = v / 10f64.powi(n);
    let decimals = (n as f64 - step.log10().floor()).clamp(0.0, 6.0) as usize;
    let m = format!("{mantissa:.decimals$}");
    if m == "1" {
        power_of_ten(n)
    } else if m == "-1" {
        format!("−{}", power_of_ten(n))
    } else {
        format!("{}·{}", m.replace('-', "−"), power_of_ten(n))
    }
}

/// The decades that hold the positive finite `values`: (⌊log₁₀ min⌋, ⌈log₁₀ max⌉), at least
/// one apart; (0, 1) without any.
pub(crate) fn decades(values: impl Iterator<Item = f64>) -> (i32, i32) {
    let (lo, hi) = values
        .filter(|v| *v > 0.0 && v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if lo > hi {
        return (0, 1);
    }
    let (lo, hi) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    (lo, hi.max(lo + 1))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(axis: &Axis) -> Vec<String> {
        axis.ticks().iter().map(|&v| axis.label(v)).collect()
    }

    /// The data's extremes (Gauss points at 0.313 and 49.687, a peak of 93.317) are not
    /// ticks: the axis runs between round values around them.
    #[test]
    fn ticks_are_round() {
        let x = Axis::over([0.313, 12.0, 49.687].into_iter());
        assert_eq!(labels(&x), ["0", "10", "20", "30", "40", "50"]);
        let y = Axis::over([0.0, 93.317].into_iter());
        assert_eq!(labels(&y), ["0", "20", "40", "60", "80", "100"]);
        // A roller's cell centres: −5 to 5 by 1 overhangs them less than −6 to 6 by 2.
        let roller = Axis::over([-4.975, 4.975].into_iter());
        assert_eq!((roller.lo, roller.hi, roller.step), (-5.0, 5.0, 1.0));
        let small = Axis::over([-0.0123, 0.0871].into_iter());
        assert_eq!(small.step, 0.02);
        assert_eq!(labels(&small)[0], "−0.02");
        assert!(labels(&small).contains(&"0".to_string()));
        assert_eq!(labels(&small).last().unwrap(), "0.10");
        for (lo, hi) in [(3.7, 3.9), (1e-7, 9e-7), (-5e3, 2.2e5), (0.0, 4538.9)] {
            let axis = Axis::between(lo, hi);
            let ticks = axis.ticks();
            assert!(axis.lo <= lo && axis.hi >= hi, "{axis:?}");
            assert!((4..=11).contains(&ticks.len()), "{axis:?}");
            let m = axis.step / 10f64.powf(axis.step.log10().floor());
            assert!([1.0, 2.0, 5.0].iter().any(|r| (m - r).abs() < 1e-9), "{m}");
        }
    }

    /// Large and small ticks read as m·10ⁿ.
    #[test]
    fn large_and_small_labels() {
        let e = Axis::between(0.0, 4e6);
        assert_eq!(e.label(2e6), "2·10⁶");
        assert_eq!(e.label(1e6), "10⁶");
        let halves = Axis::between(1e6, 3e6);
        assert_eq!(halves.label(1.5e6), "1.5·10⁶");
        assert_eq!(halves.label(2e6), "2.0·10⁶");
        assert_eq!(Axis::between(0.0, 4e5).label(2e5), "200000");
        let tiny = Axis::between(1e-7, 9e-7);
        assert_eq!(tiny.label(4e-7), "4·10⁻⁷");
        assert_eq!(Axis::between(-4e6, 0.0).label(-1e6), "−10⁶");
    }

    /// A single value is widened to a range around it; none gives (0, 1); non-finite values
    /// are skipped.
    #[test]
    fn one_value_is_widened_and_non_finite_skipped() {
        assert_eq!(span([5.0, f64::NAN].into_iter()), (4.5, 5.5));
        assert_eq!(span([0.0, 0.0].into_iter()), (-1.0, 1.0));
        let flat = span([1864.2, 1864.2 * (1.0 + 1e-12)].into_iter());
        assert!(
            (flat.0 - 1677.78).abs() < 1e-6 && (flat.1 - 2050.62).abs() < 1e-6,
            "{flat:?}"
        );
        assert_eq!(span([1.0, 1.001].into_iter()), (1.0, 1.001));
        assert_eq!(span([f64::INFINITY].into_iter()), (0.0, 1.0));
        assert_eq!(span(std::iter::empty()), (0.0, 1.0));
        let axis = Axis::over([0.0, f64::NAN, f64::NEG_INFINITY].into_iter());
        assert!(axis.ticks().iter().all(|t| t.is_finite()));
        assert!(axis.lo < 0.0 && axis.hi > 0.0);
    }

    /// Decades over the positive values; zero and negatives left out.
    #[test]
    fn decades_hold_the_positive_values() {
        assert_eq!(decades([1e-3, 0.2, 3.0, 0.0, -1.0].into_iter()), (-3, 1));
        assert_eq!(decades([5.0].into_iter()), (0, 1));
        assert_eq!(decades([0.0].into_iter()), (0, 1));
    }
}
