//! The penalty method on the full, uncondensed system of two bodies (eq. 2.22): the bodies'
//! crate builds the joint stiffness system with a penalty spring at each contact point
//! ([`FullSystem`]); [`FullPenalty`] runs Kalker's iteration on it, the same loop as the
//! condensed [`Penalty`](crate::Penalty) runs on the interface problem. The cross-check of
//! the condensation: both must agree to round-off.

use contopt_core::observe::{Method, Observer, Silent};
use contopt_core::{check, ContactState, Error, FullSystem, Residuals, Result, Stall};

use crate::kalker::{self, ContactSet, Infeasible, Sweep};
use crate::watch::{self, Watch};
use crate::PenaltySettings;

/// The penalty method (§2.2, eq. 2.22) on a [`FullSystem`]: Kalker's iteration over the
/// contact set C, with pressure pᵢ = c⟨−dᵢ⟩ at the springs of C. Starts with every point in
/// contact; counts `iterp` and `iterd` as the condensed [`Penalty`](crate::Penalty) does, and
/// gives the same answer (up to round-off) on the same bodies.
///
/// ```
/// use contopt_contact::{FullPenalty, PenaltySettings};
/// use contopt_core::FullSystem;
///
/// /// One point on a spring of compliance a [mm/N] against a rigid flat, initial gap h.
/// struct Spring { a: f64, h: f64, w: [f64; 1], rest: [f64; 1], u: f64 }
///
/// impl FullSystem for Spring {
///     fn points(&self) -> usize { 1 }
///     fn weights(&self) -> &[f64] { &self.w }
///     fn rest_gap(&self) -> &[f64] { &self.rest }
///     fn free_modes(&self) -> usize { 0 }
///     fn solve_springs(&mut self, active: &[bool], c: f64, gap: &mut [f64])
///         -> contopt_core::Result<()> {
///         // (1/a + k) u = −k h with the penalty spring k = c·w when in contact.
///         let k = if active[0] { c * self.w[0] } else { 0.0 };
///         self.u = -k * self.h / (1.0 / self.a + k);
///         gap[0] = self.h + self.u;
///         Ok(())
///     }
///     fn rigid(&self) -> Vec<f64> { vec![] }
///     fn equilibrium(&self, _: &[f64]) -> f64 { 0.0 }
/// }
///
/// // An interference of 1 µm: p = c·(penetration) = h / (a·w + 1/c).
/// let (a, h, c) = (1e-3, -1e-3, 1e6);
/// let mut spring = Spring { a, h, w: [1.0], rest: [h], u: 0.0 };
/// let solver = FullPenalty::new(PenaltySettings { c_mpa_per_mm: c })?;
/// let state = solver.solve(&mut spring)?;
/// assert!((state.pressure[0] - 1e-3 / (1e-3 + 1e-6)).abs() < 1e-12);
/// # Ok::<(), contopt_core::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct FullPenalty {
    c: f64,
}

impl FullPenalty {
    /// The method with `settings`, checked: c positive and finite.
    pub fn new(settings: PenaltySettings) -> Result<Self> {
        Ok(Self {
            c: check::positive("c_mpa_per_mm", settings.c_mpa_per_mm)?,
        })
    }

    /// The method its iterations report as.
    pub fn method(&self) -> Method {
        Method::FullPenalty
    }

    /// Solves the contact of the bodies of `system`.
    pub fn solve(&self, system: &mut dyn FullSystem) -> Result<ContactState> {
        self.solve_observed(system, &Silent)
    }

    /// Solves the contact of the bodies of `system`, reporting each of Kalker's solves
    /// (`iterp`) to `observer` with the number of points that break a sign condition as the
    /// measure (tolerance 0). On [`Flow::Stop`](contopt_core::observe::Flow::Stop) it returns
    /// the last solve with [`Termination::Stopped`](contopt_core::Termination).
    pub fn solve_observed(
        &self,
        system: &mut dyn FullSystem,
        observer: &dyn Observer,
    ) -> Result<ContactState> {
        check(system)?;
        let mut springs = Springs::new(system, self.c);
        let mut active = vec![true; springs.points()];
        let watch = Watch::new(observer, self.method());
        let mut lists = Infeasible::new(springs.points());
        let sweep = kalker::iterate(&mut springs, &mut active, watch, &mut lists)?;
        let state = springs.state(active, sweep);
        watch::announce(observer, &state);
        Ok(state)
    }
}

/// A full system has points, and one weight and one rest gap per point, all finite.
fn check(system: &dyn FullSystem) -> Result<()> {
    let n = system.points();
    if n == 0 {
        return Err(Error::invalid(
            "full system",
            "no points",
            "at least one contact point",
        ));
    }
    for (what, values) in [
        ("weights", system.weights()),
        ("rest_gap", system.rest_gap()),
    ] {
        if values.len() != n {
            return Err(Error::invalid(
                format!("full system {what}"),
                values.len(),
                format!("one value per contact point ({n})"),
            ));
        }
        check::all_finite(&format!("full system {what}"), values)?;
    }
    Ok(())
}

/// A [`FullSystem`] with its springs' stiffness c, as Kalker's iteration solves it: the
/// pressure pᵢ = −c dᵢ on C (negative where the spring is in tension).
struct Springs<'s> {
    system: &'s mut dyn FullSystem,
    c: f64,
    gap: Vec<f64>,
    pressure: Vec<f64>,
    /// The largest |hᵢ|.
    rest_scale: f64,
}

impl<'s> Springs<'s> {
    fn new(system: &'s mut dyn FullSystem, c: f64) -> Self {
        let n = system.points();
        let rest_scale = system.rest_gap().iter().fold(0.0f64, |s, h| s.max(h.abs()));
        Self {
            system,
            c,
            gap: vec![0.0; n],
            pressure: vec![0.0; n],
            rest_scale,
        }
    }

    /// The contact state of the last solve: p = c⟨−d⟩ on C when solved.
    fn state(self, active: Vec<bool>, sweep: Sweep) -> ContactState {
        let mut pressure = self.pressure;
        if sweep.halt.is_none() {
            pressure.iter_mut().for_each(|p| *p = p.max(0.0));
        }
        let residuals = Residuals::new(self.system.equilibrium(&pressure), &pressure, &self.gap);
        let mut state = ContactState {
            rigid: self.system.rigid(),
            pressure,
            gap: self.gap,
            active,
            iterations: 1,
            iterp: sweep.iterp,
            iterd: sweep.iterd,
            residuals,
            method: Method::FullPenalty,
            termination: contopt_core::Termination::Converged,
        };
        state.stop_if_not_finite();
        if let Some(halt) = sweep.halt {
            watch::end(&mut state, halt);
        }
        state
    }
}

impl ContactSet for Springs<'_> {
    fn points(&self) -> usize {
        self.gap.len()
    }

    fn anchor(&self) -> Option<usize> {
        let h = self.system.rest_gap();
        (self.system.free_modes() > 0)
            .then(|| (0..h.len()).min_by(|&i, &j| h[i].total_cmp(&h[j])))?
    }

    fn solve_on(&mut self, active: &[bool]) -> Result<std::result::Result<(), Stall>> {
        self.system.solve_springs(active, self.c, &mut self.gap)?;
        for ((p, d), &on) in self.pressure.iter_mut().zip(&self.gap).zip(active) {
            *p = if on { -self.c * d } else { 0.0 };
        }
        Ok(Ok(()))
    }

    fn pressure(&self) -> &[f64] {
        &self.pressure
    }

    fn clearance(&self, i: usize) -> f64 {
        self.gap[i]
    }

    fn gap_scale(&self) -> f64 {
        self.gap.iter().fold(self.rest_scale, |s, d| s.max(d.abs()))
    }
}
