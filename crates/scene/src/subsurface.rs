//! What a case asks of the stresses below the surface (`[output.subsurface]`): the depths and
//! sections; the report stage computes them ([`crate::report`]).

use contopt_core::{Result, SectionAxis};
use serde::{Deserialize, Serialize};

/// The most depths a case may ask for: each costs a pass over the whole grid.
const MAX_DEPTHS: usize = 1000;

/// Stresses below the surface of every elastic body that computes them (half-spaces,
/// half-planes, finite-element bodies), under each case's contact pressure
/// (`[output.subsurface]`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SubsurfaceSpec {
    /// Deepest depth \[mm\]; default twice the contact's half-width (the smaller half-extent
    /// of the contact area; its radius on an axisymmetric body), where the largest shear of a
    /// Hertz contact (0.5–0.8 half-widths down) lies well inside.
    #[serde(default)]
    pub max_depth_mm: Option<f64>,
    /// Number of depths, evenly spaced from max_depth/depths down to max_depth (default 40).
    #[serde(default = "SubsurfaceSpec::default_depths")]
    pub depths: usize,
    /// Vertical sections of a grid; default: along x and along y through the largest
    /// pressure (a roller: across the contact at mid-length, at the end cell on the side of
    /// the largest pressure, and at the largest pressure where that is neither). A plane or
    /// axisymmetric body has one section, its own plane.
    #[serde(default)]
    pub sections: Vec<SectionSpec>,
}

/// A vertical section through a grid.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionSpec {
    /// `"x"` or `"y"`: the direction of the section along the surface.
    pub along: SectionAxis,
    /// The other surface coordinate \[mm\] (the nearest row or column of cells is taken).
    pub at_mm: f64,
}

impl SubsurfaceSpec {
    fn default_depths() -> usize {
        40
    }

    /// Checks the values before anything is solved.
    pub(crate) fn check(&self) -> Result<()> {
        contopt_core::check::count("depths", self.depths, 1, MAX_DEPTHS)?;
        if let Some(d) = self.max_depth_mm {
            contopt_core::check::positive("max_depth_mm", d)?;
        }
        for (k, s) in self.sections.iter().enumerate() {
            contopt_core::check::finite(&format!("sections[{k}].at_mm"), s.at_mm)?;
        }
        Ok(())
    }
}
