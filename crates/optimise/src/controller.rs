//! Controller functions v(x) of the pressure control p(x) ≤ v(x)·p_max (eq. 3.1).

use contopt_core::{Error, Result};

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

/// v = `level` everywhere: constant pressure (level 1) or a fixed fraction of p_max.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Constant {
    level: f64,
}

impl Constant {
    /// The constant controller; 0 < `level` ≤ 1.
    pub fn new(level: f64) -> Result<Self> {
        if !(level > 0.0 && level <= 1.0) {
            return Err(Error::invalid(
                "controller.level",
                level,
                "must lie in (0, 1]",
            ));
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
        if !(l1 >= 0.0 && l1.is_finite()) {
            return Err(Error::invalid(
                "controller.l1",
                l1,
                "must be finite and ≥ 0",
            ));
        }
        if !(l2 >= l1 && l2.is_finite()) {
            return Err(Error::invalid(
                "controller.l2",
                l2,
                format!("must be finite and ≥ L1 = {l1}"),
            ));
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
        if axis > 2 {
            return Err(Error::invalid("controller.axis", axis, "0, 1 or 2"));
        }
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
            Fall::Cubic => 1.0 - 3.0 * s * s + 2.0 * s * s * s,
        }
    }
}

/// The product v(x₁)·v(x₂) of two controllers: the 2-D control of the bearing roller (§3.1).
pub struct Product<A, B>(pub A, pub B);

impl<A: Controller, B: Controller> Controller for Product<A, B> {
    fn value(&self, x: [f64; 3]) -> f64 {
        self.0.value(x) * self.1.value(x)
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
        assert!(e.contains("controller.l2") && e.contains("20"), "{e}");
        assert!(Profile::trapezoid(-1.0, 2.0).is_err());
        assert!(Constant::new(1.5).is_err());
        assert!(Constant::new(f64::NAN).is_err());
        assert!(Profile::cubic(0.0, 1.0).unwrap().along(3).is_err());
    }
}
