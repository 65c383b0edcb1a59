//! Ω_v as a region of the contact surface (`optimisation.omega_v`): a strip, a disc or a box
//! of surface coordinates.

use contopt_core::{check, Error, Interface, Result};
use serde::{Deserialize, Serialize};

/// Ω_v, the part of the zone where the pressure is prescribed (d = 0, p = v·p_max; §3.1), as
/// a region of the contact surface; the zone's other points are Ω_nv. A point is placed by its
/// surface coordinates: its position less its component along its normal (a grid's (x, y); a
/// finite-element face's or a half-plane's x, or r, with the second coordinate 0).
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum OmegaVSpec {
    /// The points whose surface coordinate `axis` (0 or 1) lies in [from, to].
    Strip {
        /// The coordinate: 0 (x or r) or 1 (y).
        axis: usize,
        /// Lower end \[mm\].
        from_mm: f64,
        /// Upper end \[mm\].
        to_mm: f64,
    },
    /// The points within `radius_mm` of `centre_mm` on the surface.
    Disc {
        /// Centre (x, y) \[mm\].
        centre_mm: [f64; 2],
        /// Radius \[mm\].
        radius_mm: f64,
    },
    /// The points whose surface coordinates lie in [from, to] along both axes.
    Box {
        /// Lower corner (x, y) \[mm\].
        from_mm: [f64; 2],
        /// Upper corner (x, y) \[mm\].
        to_mm: [f64; 2],
    },
}

impl OmegaVSpec {
    /// Refuses a region that is not one: ends out of order, a radius not positive, an axis
    /// off the surface, a coordinate not finite.
    pub fn check(&self) -> Result<()> {
        let finite = |field: &str, v: f64| check::finite(field, v).map(|_| ());
        let ordered = |field: &str, from: f64, to: f64| {
            finite(field, from)?;
            finite(field, to)?;
            if from <= to {
                Ok(())
            } else {
                Err(Error::invalid(
                    field,
                    to,
                    format!("must be at least from_mm = {from}"),
                ))
            }
        };
        match *self {
            OmegaVSpec::Strip {
                axis,
                from_mm,
                to_mm,
            } => {
                if axis > 1 {
                    return Err(Error::invalid(
                        "axis",
                        axis,
                        "a surface coordinate: 0 (x or r) or 1 (y)",
                    ));
                }
                ordered("to_mm", from_mm, to_mm)
            }
            OmegaVSpec::Disc {
                centre_mm,
                radius_mm,
            } => {
                centre_mm.iter().try_for_each(|&c| finite("centre_mm", c))?;
                check::positive("radius_mm", radius_mm).map(|_| ())
            }
            OmegaVSpec::Box { from_mm, to_mm } => {
                (0..2).try_for_each(|k| ordered("to_mm", from_mm[k], to_mm[k]))
            }
        }
    }

    /// Whether a point at `x` with unit normal `normal` lies in the region.
    pub fn contains(&self, x: [f64; 3], normal: [f64; 3]) -> bool {
        let along: f64 = (0..3).map(|k| x[k] * normal[k]).sum();
        let s: [f64; 3] = std::array::from_fn(|k| x[k] - along * normal[k]);
        let within = |v: f64, from: f64, to: f64| from <= v && v <= to;
        match *self {
            OmegaVSpec::Strip {
                axis,
                from_mm,
                to_mm,
            } => within(s[axis.min(1)], from_mm, to_mm),
            OmegaVSpec::Disc {
                centre_mm,
                radius_mm,
            } => (s[0] - centre_mm[0]).hypot(s[1] - centre_mm[1]).hypot(s[2]) <= radius_mm,
            OmegaVSpec::Box { from_mm, to_mm } => {
                (0..2).all(|k| within(s[k], from_mm[k], to_mm[k]))
            }
        }
    }

    /// Each point of `interface` inside the region.
    pub fn mask(&self, interface: &Interface) -> Vec<bool> {
        (interface.points().iter().zip(interface.normals()))
            .map(|(&x, &normal)| self.contains(x, normal))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ω_v's shapes on the contact surface: a finite-element face's points (r, z) with normal y
    /// are placed by r; a grid's (x, y) with normal z by both.
    #[test]
    fn omega_v_regions_contain_their_points() {
        let face = |r: f64| ([r, 50.0, 0.0], [0.0, -1.0, 0.0]);
        let disc = OmegaVSpec::Disc {
            centre_mm: [0.0, 0.0],
            radius_mm: 30.0,
        };
        let strip = OmegaVSpec::Strip {
            axis: 0,
            from_mm: 0.0,
            to_mm: 30.0,
        };
        for r in [0.0, 10.0, 29.9, 30.1, 49.0] {
            let (x, n) = face(r);
            assert_eq!(disc.contains(x, n), r <= 30.0, "{r}");
            assert_eq!(strip.contains(x, n), r <= 30.0, "{r}");
        }
        let grid = |x: f64, y: f64| ([x, y, 0.0], [0.0, 0.0, 1.0]);
        let unit = OmegaVSpec::Box {
            from_mm: [-1.0, -0.5],
            to_mm: [1.0, 0.5],
        };
        let across = OmegaVSpec::Strip {
            axis: 1,
            from_mm: -0.5,
            to_mm: 0.5,
        };
        let round = OmegaVSpec::Disc {
            centre_mm: [1.0, 0.0],
            radius_mm: 1.0,
        };
        for (x, y, in_box, in_strip, in_disc) in [
            (0.0, 0.0, true, true, true),
            (1.5, 0.2, false, true, true),
            (0.5, 0.8, false, false, true),
            (-0.5, 0.4, true, true, false),
        ] {
            let (p, n) = grid(x, y);
            assert_eq!(
                (
                    unit.contains(p, n),
                    across.contains(p, n),
                    round.contains(p, n)
                ),
                (in_box, in_strip, in_disc),
                "({x}, {y})"
            );
        }
        for (region, key) in [
            (
                OmegaVSpec::Disc {
                    centre_mm: [0.0, 0.0],
                    radius_mm: 0.0,
                },
                "radius_mm",
            ),
            (
                OmegaVSpec::Strip {
                    axis: 2,
                    from_mm: 0.0,
                    to_mm: 1.0,
                },
                "axis",
            ),
            (
                OmegaVSpec::Box {
                    from_mm: [0.0, 1.0],
                    to_mm: [1.0, 0.0],
                },
                "to_mm",
            ),
        ] {
            let e = region.check().unwrap_err().to_string();
            assert!(e.contains(key), "{e}");
        }
    }
}
