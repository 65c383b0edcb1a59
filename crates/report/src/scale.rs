//! A linear plotters coordinate whose ticks are given: round values ([`Axis`]) or decades of a
//! logarithm with short ticks between them.

use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};

use crate::ticks::Axis;

/// A linear coordinate from `lo` to `hi` with grid lines at `bold` and short ticks at `light`.
#[derive(Clone, Debug)]
pub(crate) struct Scale {
    lo: f64,
    hi: f64,
    bold: Vec<f64>,
    light: Vec<f64>,
}

impl Scale {
    /// The axis's range and its ticks.
    pub fn of(axis: &Axis) -> Self {
        Self::within(axis.lo, axis.hi, axis)
    }

    /// From `lo` to `hi`, with the ticks of `axis` that lie between.
    pub fn within(lo: f64, hi: f64, axis: &Axis) -> Self {
        let margin = 1e-9 * (hi - lo).abs();
        let bold = axis
            .ticks()
            .into_iter()
            .filter(|t| (lo - margin..=hi + margin).contains(t))
            .collect();
        Self {
            lo,
            hi,
            bold,
            light: vec![],
        }
    }

    /// From `lo` to `hi` with grid lines at `ticks`.
    pub fn with_ticks(lo: f64, hi: f64, ticks: Vec<f64>) -> Self {
        Self {
            lo,
            hi,
            bold: ticks,
            light: vec![],
        }
    }

    /// The values with grid lines and labels.
    pub fn ticks(&self) -> &[f64] {
        &self.bold
    }

    /// log₁₀ of values from 10^`lo` to 10^`hi`: the decades bold, 2…9 times each light.
    pub fn decades(lo: i32, hi: i32) -> Self {
        let light = (lo..hi)
            .flat_map(|d| (2..10).map(move |m| f64::from(d) + f64::from(m).log10()))
            .collect();
        Self {
            lo: f64::from(lo),
            hi: f64::from(hi),
            bold: (lo..=hi).map(f64::from).collect(),
            light,
        }
    }
}

impl Ranged for Scale {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let t = (value - self.lo) / (self.hi - self.lo);
        let length = f64::from(limit.1 - limit.0);
        limit.0 + (length * t).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.light.clone()
        } else {
            self.bold.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}
