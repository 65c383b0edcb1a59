//! Controller functions v(x) of the pressure control p(x) ≤ v(x)·p_max (eq. 3.1).

use contopt_core::{check, Error, Result};
use serde::{Deserialize, Serialize};

/// A controller function v(x) ∈ [0, 1] on Ω_opt (§3.1): the optimised pressure is bounded by
/// (on Ω_v equal to) v(x)·p_max. `x` is an interface point: (r, z) for axisymmetric bodies,
/// (x, y) for plane ones, (x₁, x₂, x₃) on a surface.
///
/// Implement it for any shape of your own; a closure `Fn([f64; 3]) -> f64` is one already.
/// Values are checked where they are used ([`crate::Optimisation::new`]): outside [0, 1] or
/// not finite is an error naming the point.
pub trait Controller {
    /// v at the point `x`.
    fn value(&self, x: [f64; 3]) -> f64;
}

impl<F: Fn([f64; 3]) -> f64> Controller for F {
    fn value(&self, x: [f64; 3]) -> f64 {
        self(x)
    }
}

/// A controller built at run time ([`ControllerSettings::build`]) is one too.
impl Controller for Box<dyn Controller> {
    fn value(&self, x: [f64; 3]) -> f64 {
        self.as_ref().value(x)
    }
}

/// v = `level` everywhere: constant pressure (level 1) or a fixed fraction of p_max.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Constant {
    level: f64,
}

impl Constant {
    /// The constant controller; 0 < `level` ≤ 1.
    pub fn new(level: f64) -> Result<Self> {
        // Open at 0, closed at 1: not `check::between`'s open interval.
        if !(0.0..=1.0).contains(&level) || level == 0.0 {
            return Err(Error::invalid("level", level, "must lie in (0, 1]"));
        }
        Ok(Self { level })
    }
}

impl Controller for Constant {
    fn value(&self, _x: [f64; 3]) -> f64 {
        self.level
    }
}

/// How a one-variable controller falls from 1 at s = 0 to 0 at s = 1.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Fall {
    Linear,
    Cubic,
}

/// A one-variable controller of the distance x = |x_axis| from the axis (or symmetry plane):
/// v = 1 for x ≤ L1, falling to 0 at x = L2, and 0 beyond. With L1 = L2 it is a step: v = 1
/// up to L2 (the constant pressure of Table 1, L1 = 50).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Profile {
    l1: f64,
    l2: f64,
    axis: usize,
    fall: Fall,
}

impl Profile {
    fn new(l1: f64, l2: f64, fall: Fall) -> Result<Self> {
        check::non_negative("l1_mm", l1)?;
        check::finite("l2_mm", l2)?;
        if l2 < l1 {
            return Err(Error::invalid("l2_mm", l2, format!("must be ≥ L1 = {l1}")));
        }
        Ok(Self {
            l1,
            l2,
            axis: 0,
            fall,
        })
    }

    /// Trapezoid (§3.1): v = 1 for x ≤ L1, v = (L2 − x)/(L2 − L1) for L1 ≤ x ≤ L2.
    pub fn trapezoid(l1: f64, l2: f64) -> Result<Self> {
        Self::new(l1, l2, Fall::Linear)
    }

    /// The C¹ controller of Tables 1 and 3: v = 1 for x ≤ L1, v = 1 − 3s² + 2s³ with
    /// s = (x − L1)/(L2 − L1) for L1 ≤ x ≤ L2; dv/dx = 0 at L1 and L2.
    pub fn cubic(l1: f64, l2: f64) -> Result<Self> {
        Self::new(l1, l2, Fall::Cubic)
    }

    /// Measures x along coordinate `axis` (0, the default: r or x; 1: z or y; 2).
    pub fn along(self, axis: usize) -> Result<Self> {
        check::count("axis", axis, 0, 2)?;
        Ok(Self { axis, ..self })
    }
}

impl Controller for Profile {
    fn value(&self, x: [f64; 3]) -> f64 {
        let x = x[self.axis].abs();
        if x <= self.l1 {
            return 1.0;
        }
        if x >= self.l2 {
            return 0.0;
        }
        let s = (x - self.l1) / (self.l2 - self.l1);
        match self.fall {
            Fall::Linear => 1.0 - s,
            // Within [0, 1] in exact arithmetic; round-off near s = 1 gives −2.2e-16, which
            // `Optimisation::new` would refuse.
            Fall::Cubic => (1.0 - 3.0 * s * s + 2.0 * s * s * s).clamp(0.0, 1.0),
        }
    }
}

/// The product v(x₁)·v(x₂) of two controllers: the 2-D control of the bearing roller (§3.1).
pub struct Product<A = Box<dyn Controller>, B = Box<dyn Controller>>(pub A, pub B);

impl<A: Controller, B: Controller> Controller for Product<A, B> {
    fn value(&self, x: [f64; 3]) -> f64 {
        self.0.value(x) * self.1.value(x)
    }
}

/// A controller as a scene writes it (`{ kind = "cubic", l1_mm = 20, l2_mm = 50 }`): the
/// controllers of §3.1 and Tables 1–3, built by [`ControllerSettings::build`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ControllerSettings {
    /// v = `level` ([`Constant`]).
    Constant {
        /// The level, in (0, 1].
        level: f64,
    },
    /// 1 up to L1, falling linearly to 0 at L2, in |x_axis| ([`Profile::trapezoid`]).
    Trapezoid {
        /// L1 \[mm\], from the axis or the middle.
        l1_mm: f64,
        /// L2 \[mm\], from the axis or the middle.
        l2_mm: f64,
        /// The coordinate (0, the default: r or x; 1; 2).
        #[serde(default)]
        axis: usize,
    },
    /// 1 up to L1, then 1 − 3s² + 2s³ to 0 at L2 (Tables 1–3, [`Profile::cubic`]).
    Cubic {
        /// L1 \[mm\], from the axis or the middle.
        l1_mm: f64,
        /// L2 \[mm\], from the axis or the middle.
        l2_mm: f64,
        /// The coordinate (0, the default).
        #[serde(default)]
        axis: usize,
    },
    /// The product of two controllers, v(x₁)·v(x₂) ([`Product`]).
    Product {
        /// First factor.
        a: Box<ControllerSettings>,
        /// Second factor.
        b: Box<ControllerSettings>,
    },
}

/// Prefixes the field of an input error with `prefix` (a product's `a.` or `b.`).
fn within(prefix: &str, error: Error) -> Error {
    match error {
        Error::InvalidInput {
            field,
            value,
            reason,
        } => Error::InvalidInput {
            field: format!("{prefix}.{field}"),
            value,
            reason,
        },
        other => other,
    }
}

impl ControllerSettings {
    /// The controller, its values checked; errors name the field as a scene writes it
    /// (`l2_mm`, `a.level`).
    pub fn build(&self) -> Result<Box<dyn Controller>> {
        Ok(match self {
            ControllerSettings::Constant { level } => Box::new(Constant::new(*level)?),
            ControllerSettings::Trapezoid { l1_mm, l2_mm, axis } => {
                Box::new(Profile::trapezoid(*l1_mm, *l2_mm)?.along(*axis)?)
            }
            ControllerSettings::Cubic { l1_mm, l2_mm, axis } => {
                Box::new(Profile::cubic(*l1_mm, *l2_mm)?.along(*axis)?)
            }
            ControllerSettings::Product { a, b } => Box::new(Product(
                a.build().map_err(|e| within("a", e))?,
                b.build().map_err(|e| within("b", e))?,
            )),
        })
    }

    /// Refuses a controller whose L1 or L2 lies beyond the region along its axis by more
    /// than a cell: `half_extent` is the largest |x| of the region's points along each
    /// coordinate, `cell` the cell size there \[mm\]. Such a controller never falls inside
    /// the region (L2 written as a roller's whole length, say, where it is measured from the
    /// middle).
    pub fn check_reach(&self, half_extent: [f64; 3], cell: [f64; 3]) -> Result<()> {
        match self {
            ControllerSettings::Constant { .. } => Ok(()),
            ControllerSettings::Trapezoid { l1_mm, l2_mm, axis }
            | ControllerSettings::Cubic { l1_mm, l2_mm, axis } => {
                let axis = check::count("axis", *axis, 0, 2)?;
                let reach = half_extent[axis] + cell[axis];
                for (field, value) in [("l1_mm", *l1_mm), ("l2_mm", *l2_mm)] {
                    if value > reach {
                        return Err(Error::invalid(
                            field,
                            value,
                            format!(
                                "lies beyond the region, whose points reach |x{axis}| = {} mm \
                                 (a cell {} mm): L1 and L2 are measured from the axis or the \
                                 middle (a roller's half length)",
                                half_extent[axis], cell[axis]
                            ),
                        ));
                    }
                }
                Ok(())
            }
            ControllerSettings::Product { a, b } => {
                a.check_reach(half_extent, cell)
                    .map_err(|e| within("a", e))?;
                b.check_reach(half_extent, cell).map_err(|e| within("b", e))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profiles() {
        let cubic = Profile::cubic(20.0, 50.0).unwrap();
        assert_eq!(cubic.value([10.0, 0.0, 0.0]), 1.0);
        assert!((cubic.value([35.0, 0.0, 0.0]) - 0.5).abs() < 1e-15);
        assert_eq!(cubic.value([50.0, 0.0, 0.0]), 0.0);
        // C¹: the slope vanishes at both ends.
        let h = 1e-6;
        for x in [20.0, 50.0] {
            let slope = (cubic.value([x + h, 0.0, 0.0]) - cubic.value([x - h, 0.0, 0.0])) / h;
            assert!(slope.abs() < 1e-5, "{x}: {slope}");
        }
        let trapezoid = Profile::trapezoid(0.0, 4.0).unwrap().along(1).unwrap();
        assert_eq!(trapezoid.value([9.0, -1.0, 0.0]), 0.75);
        let step = Profile::cubic(50.0, 50.0).unwrap();
        assert_eq!(step.value([49.9, 0.0, 0.0]), 1.0);
        let roller = Product(Constant::new(1.0).unwrap(), trapezoid);
        assert_eq!(roller.value([0.0, 2.0, 0.0]), 0.5);
        let closure = |x: [f64; 3]| 1.0 - x[0];
        assert_eq!(closure.value([0.25, 0.0, 0.0]), 0.75);
    }

    #[test]
    fn invalid_controllers_are_named() {
        let e = Profile::cubic(30.0, 20.0).unwrap_err().to_string();
        assert!(e.contains("invalid l2_mm = 20"), "{e}");
        assert!(Profile::trapezoid(-1.0, 2.0).is_err());
        assert!(Constant::new(1.5).is_err());
        assert!(Constant::new(f64::NAN).is_err());
        assert!(Profile::cubic(0.0, 1.0).unwrap().along(3).is_err());
    }
}

#[cfg(test)]
mod settings_tests {
    use super::*;

    fn product() -> ControllerSettings {
        ControllerSettings::Product {
            a: Box::new(ControllerSettings::Constant { level: 1.0 }),
            b: Box::new(ControllerSettings::Cubic {
                l1_mm: 2.0,
                l2_mm: 5.0,
                axis: 0,
            }),
        }
    }

    /// Built controllers have the values of the types they name; a scene's spelling reads.
    #[test]
    fn settings_build_the_controllers() {
        let v = product().build().unwrap();
        assert_eq!(v.value([1.0, 9.0, 0.0]), 1.0);
        assert!((v.value([3.5, 0.0, 0.0]) - 0.5).abs() < 1e-15);
        let read: ControllerSettings =
            serde_json::from_str(r#"{"trapezoid": {"l1_mm": 0, "l2_mm": 4}}"#).unwrap();
        let built = read.build().unwrap();
        assert_eq!(built.value([-1.0, 0.0, 0.0]), 0.75);
        let e = serde_json::from_str::<ControllerSettings>(r#"{"cubic": {"l1": 0, "l2_mm": 4}}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("unknown field `l1`"), "{e}");
    }

    /// Errors name the field as a scene writes it, inside a product too.
    #[test]
    fn settings_errors_name_the_fields() {
        let bad = ControllerSettings::Product {
            a: Box::new(ControllerSettings::Constant { level: 1.5 }),
            b: Box::new(ControllerSettings::Constant { level: 1.0 }),
        };
        let e = bad.build().err().unwrap().to_string();
        assert!(e.starts_with("invalid a.level = 1.5"), "{e}");
        let bad = ControllerSettings::Trapezoid {
            l1_mm: 1.0,
            l2_mm: 2.0,
            axis: 3,
        };
        assert!(bad
            .build()
            .err()
            .unwrap()
            .to_string()
            .contains("invalid axis = 3"));
    }

    /// A roller of length 10 mm on cells of 0.25 mm: L2 = 5 (its half length) passes, L2 = 10
    /// (its whole length) is refused naming l2_mm, the value, the extent and the half length.
    #[test]
    fn controllers_beyond_the_region_are_refused() {
        let (extent, cell) = ([4.875, 0.2, 0.0], [0.25, 0.04, 0.0]);
        product().check_reach(extent, cell).unwrap();
        let whole = ControllerSettings::Product {
            a: Box::new(ControllerSettings::Constant { level: 1.0 }),
            b: Box::new(ControllerSettings::Cubic {
                l1_mm: 2.0,
                l2_mm: 10.0,
                axis: 0,
            }),
        };
        let e = whole.check_reach(extent, cell).unwrap_err().to_string();
        assert!(
            e.starts_with("invalid b.l2_mm = 10") && e.contains("4.875") && e.contains("half"),
            "{e}"
        );
        let across = ControllerSettings::Trapezoid {
            l1_mm: 0.5,
            l2_mm: 0.5,
            axis: 1,
        };
        let e = across.check_reach(extent, cell).unwrap_err().to_string();
        assert!(e.starts_with("invalid l1_mm = 0.5"), "{e}");
    }
}
