//! A cylindrical roller bearing around the roller: the load distribution over its rollers by
//! ISO/TS 16281's slice model, the rings' equilibrium found by Newton's method.
//!
//! Each roller is cut into n_s slices along its effective length L_we. A slice k of roller j
//! carries q = c·e^(10/9) where e > 0 is the slice's elastic approach, the load–deflection law
//! of line contact with ISO/TS 16281's constant c_L = 35948·L_we^(8/9) N/mm^(10/9) for the
//! roller's total approach between the two raceways and c_s = c_L/n_s per slice (ISO/TS
//! 16281:2008 eqs. 35–37, steel; quoted by implementations of the standard, which could not be
//! read here). It agrees with Palmgren's δ = 3.84·10⁻⁵·Q^0.9/l^0.8 for one contact (Harris &
//! Kotzalas, *Essential Concepts of Bearing Technology*, 5th ed., §6) to 4 %: two such contacts
//! in series give c = 37 313·l^(8/9). Here the two contacts of a roller are kept apart, each
//! with 2^(10/9)·c_s per slice, so that two equal contacts in series are the standard's c_s
//! exactly and a roller can tilt against each ring by its own angle (raceways with different
//! crowns).
//!
//! The kinematics are the standard's (its eqs. 38–41): the inner ring moves by δ and tilts by
//! the slope t against the outer ring; a roller at the angle φ_j from the load sees the rings
//! approach by δ_j = δ_y cos φ_j + δ_z sin φ_j − s/2 (s the diametral clearance) and tilt by
//! T_j = t_y cos φ_j + t_z sin φ_j. The roller itself sits at the approach a_j from the inner
//! raceway and tilts by τ_j against it, so that its slices' approaches are
//! e_i = a_j − x_k·τ_j − z_i(x_k) on the inner raceway and
//! e_o = δ_j − a_j − x_k·(T_j − τ_j) − z_o(x_k) on the outer, z the crowns' drops (the roller's
//! and the raceway's). Equilibrium is the minimum of the elastic energy less the work of the
//! load, a convex function: each roller's (a_j, τ_j) minimise its own energy (a 2 × 2 Newton
//! solve), and the rings' displacement minimises what remains, by Newton's method on the
//! condensed (Schur complement) stiffness with a backtracking line search. ISO/TS 16281's own
//! equilibrium (its eqs. 45–46): F_r = Σ_j cos φ_j·Q_j, M = Σ_j cos φ_j·Σ_k x_k·q_jk.

use std::f64::consts::PI;

use contopt_core::drive::{Driver, Step};
use contopt_core::faer::linalg::solvers::{Llt, Solve};
use contopt_core::faer::{Mat, Side};
use contopt_core::observe::{Method, Observer, Silent};
use contopt_core::{check, Error, Quantity, Result, Stall, Termination};
use serde::Serialize;

use crate::Crown;

/// ISO/TS 16281's constant of line contact \[N/mm^(10/9)\]: c_L = 35948·L_we^(8/9) for the
/// roller's total approach between the raceways, steel on steel (eq. 35).
pub const LINE_CONTACT: f64 = 35_948.0;

/// The load–deflection exponent of line contact, q ∝ e^(10/9).
pub const LINE_EXPONENT: f64 = 10.0 / 9.0;

/// The most rollers a bearing may have.
const MAX_ROLLERS: usize = 10_000;

/// The most slices a roller may be cut into.
const MAX_SLICES: usize = 10_000;

/// A roller's guidance: springs this fraction of the contact stiffness at a 1 µm approach hold
/// a roller midway between the rings (its approach and tilt) where no slice decides them (an
/// unloaded roller; a tilt that one loaded slice leaves free). They move a loaded roller's
/// loads by about this fraction.
const GUIDANCE: f64 = 1e-12;

/// The approach \[mm\] at which [`GUIDANCE`] is measured.
const GUIDANCE_APPROACH: f64 = 1e-3;

/// Armijo's sufficient decrease of the line searches.
const SUFFICIENT_DECREASE: f64 = 1e-4;

/// An energy may rise by this fraction of itself in a line search: its round-off, below which
/// the last Newton steps' decrease cannot be told (they are taken on the gradient's word).
const ENERGY_ROUNDOFF: f64 = 1e-13;

/// Armijo's condition with the energy's round-off: `trial` is below `current` by at least the
/// fraction [`SUFFICIENT_DECREASE`] of the `expected` decrease (negative), give or take
/// [`ENERGY_ROUNDOFF`].
fn decreased(trial: f64, current: f64, expected: f64) -> bool {
    trial <= current + SUFFICIENT_DECREASE * expected + ENERGY_ROUNDOFF * current.abs()
}

/// The most halvings of a line search's step before it stalls.
const MAX_HALVINGS: usize = 60;

/// A singular Hessian of the rings is shifted by this fraction of its largest diagonal term
/// ([`Model::factor`]).
const SINGULAR: f64 = 1e-12;

/// The most Newton steps of one roller's equilibrium.
const ROLLER_STEPS: usize = 100;

/// A slice's interference within this fraction of the rings' motion (|u| + s/2) is round-off
/// and carries nothing: without clearance a roller at the loaded zone's edge sees
/// δ_r·cos 90° ≈ 6·10⁻¹⁷·δ_r, which would otherwise be reported as a load of 10⁻¹⁵ N and
/// solved as a contact on a grid sized for it.
const ROUND_OFF: f64 = 1e-12;

/// A roller's equilibrium is met when its force and moment imbalance are this fraction of the
/// bearing's tolerance.
const ROLLER_TOLERANCE: f64 = 1e-3;

/// Which ring: the roller's tilt against it ([`LoadDistribution::roller_cases`]), or which
/// ring rotates against the load ([`crate::reference_rating_life`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Raceway {
    /// The inner ring.
    Inner,
    /// The outer ring.
    Outer,
}

/// A cylindrical roller bearing's inside (ISO 281's symbols), one row, contact angle 0.
#[derive(Clone, Debug)]
pub struct CylindricalRollerBearing {
    /// Number of rollers Z (at least 3).
    pub rollers: usize,
    /// Roller diameter D_we \[mm\].
    pub roller_diameter: f64,
    /// Roller length between its theoretically sharp corners \[mm\].
    pub roller_length: f64,
    /// Axial width of each end's chamfer \[mm\]: the effective length is
    /// L_we = `roller_length` − 2·`chamfer` (ISO 281's definition, the raceways assumed wider).
    pub chamfer: f64,
    /// Pitch diameter D_pw \[mm\].
    pub pitch_diameter: f64,
    /// Diametral operating clearance s \[mm\]; negative for a preload.
    pub clearance: f64,
    /// The roller's crown along L_we ([`Crown::drop`] with the length L_we).
    pub roller_crown: Crown,
    /// The inner raceway's crown along the roller.
    pub inner_crown: Crown,
    /// The outer raceway's crown along the roller.
    pub outer_crown: Crown,
    /// Slices per roller n_s (implementations of ISO/TS 16281 quote its minimum of 30).
    pub slices: usize,
    /// The angle of roller 0 from the load's direction \[rad\]; the others follow at 2π/Z.
    pub first_roller: f64,
}

/// How the rings' relative tilt is set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tilt {
    /// The inner ring held misaligned against the outer by this angle in the load's plane
    /// \[rad\] (0: aligned); the moment the rollers then carry is reported.
    Held(f64),
    /// The inner ring free to tilt under this moment in the load's plane \[N·mm\],
    /// M = Σ_j cos φ_j·Σ_k x_k·q_jk; its tilt is solved.
    Moment(f64),
}

/// What the inner ring carries against the outer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BearingLoad {
    /// The radial load F_r \[N\], positive, along φ = 0.
    pub radial_n: f64,
    /// The rings' tilt: held at a misalignment, or free under a moment.
    pub tilt: Tilt,
}

/// The equilibrium's tolerance and budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BearingSettings {
    /// The rings' force imbalance over F_r, and their moment imbalance over F_r·L_we, at
    /// convergence.
    pub tolerance: f64,
    /// The most Newton steps of the rings.
    pub max_iterations: usize,
}

impl Default for BearingSettings {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 100,
        }
    }
}

/// One roller's share of the load.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RollerLoad {
    /// Its angle φ_j from the load's direction \[rad\].
    pub angle: f64,
    /// Its load Q_j \[N\] (the outer contact's slices summed; the inner's agree to the
    /// tolerance).
    pub load_n: f64,
    /// Its tilt against the inner raceway \[rad\], as [`crate::Roller::tilt`]: an extra gap
    /// γ·x along the axis.
    pub tilt_inner: f64,
    /// Its tilt against the outer raceway \[rad\], likewise.
    pub tilt_outer: f64,
    /// The moment of its inner contact's slice loads about mid-length, Σ_k x_k·q_k \[N·mm\].
    pub moment_nmm: f64,
    /// The slice loads of its inner contact \[N\], slice by slice along x.
    pub inner_n: Vec<f64>,
    /// The slice loads of its outer contact \[N\].
    pub outer_n: Vec<f64>,
}

/// A roller's load and tilt against one raceway: a load case of the roller on that raceway
/// ([`crate::bearing_cases`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RollerCase {
    /// The roller's index.
    pub roller: usize,
    /// Its load \[N\].
    pub load_n: f64,
    /// Its tilt against the raceway \[arc-minutes\].
    pub tilt_arcmin: f64,
}

/// The bearing's equilibrium: the rings' displacement and every roller's load.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LoadDistribution {
    /// The inner ring's displacement against the outer \[mm\]: along the load, across it.
    pub displacement_mm: [f64; 2],
    /// The rings' relative tilt \[rad\]: in the load's plane, across it.
    pub tilt: [f64; 2],
    /// The moment the rollers carry \[N·mm\], in the load's plane (Σ_j cos φ_j·Σ_k x_k·q_jk)
    /// and across it (sin φ_j).
    pub moment_nmm: [f64; 2],
    /// Half the diametral clearance \[mm\].
    pub half_clearance_mm: f64,
    /// The slices' mid-points along the roller \[mm\].
    pub slice_x_mm: Vec<f64>,
    /// Every roller's load, roller 0 first.
    pub rollers: Vec<RollerLoad>,
    /// Newton steps of the rings.
    pub iterations: usize,
    /// The rings' imbalance at the end: force over F_r, moment over F_r·L_we.
    pub residual: f64,
    /// How the equilibrium ended.
    pub termination: Termination,
}

impl LoadDistribution {
    /// The heaviest roller's load Q_max \[N\].
    pub fn max_load(&self) -> f64 {
        self.rollers.iter().map(|r| r.load_n).fold(0.0, f64::max)
    }

    /// The half-angle of the loaded zone the rings' displacement δ_r gives \[rad\]: where the
    /// approach δ_r·cos ψ meets half the clearance, cos ψ_l = s/(2δ_r) (Harris & Kotzalas
    /// §7; straight rollers, aligned rings); π when the clearance is closed all round.
    pub fn load_zone(&self) -> f64 {
        let radial = self.displacement_mm[0].hypot(self.displacement_mm[1]);
        (self.half_clearance_mm / radial).clamp(-1.0, 1.0).acos()
    }

    /// Harris's load distribution factor ε = ½·(1 − s/(2δ_r)): 0.5 without clearance.
    pub fn load_factor(&self) -> f64 {
        let radial = self.displacement_mm[0].hypot(self.displacement_mm[1]);
        0.5 * (1.0 - self.half_clearance_mm / radial)
    }

    /// Every loaded roller as a load case of the roller on `raceway`: its load and its tilt
    /// against that raceway, heaviest first.
    pub fn roller_cases(&self, raceway: Raceway) -> Vec<RollerCase> {
        let mut cases: Vec<RollerCase> = (0..self.rollers.len())
            .filter(|&j| self.rollers[j].load_n > 0.0)
            .map(|j| {
                let r = &self.rollers[j];
                let tilt = match raceway {
                    Raceway::Inner => r.tilt_inner,
                    Raceway::Outer => r.tilt_outer,
                };
                RollerCase {
                    roller: j,
                    load_n: r.load_n,
                    tilt_arcmin: 60.0 * tilt.to_degrees(),
                }
            })
            .collect();
        cases.sort_by(|a, b| b.load_n.total_cmp(&a.load_n));
        cases
    }
}

impl CylindricalRollerBearing {
    /// The effective length L_we = length − 2·chamfer \[mm\].
    pub fn effective_length(&self) -> f64 {
        self.roller_length - 2.0 * self.chamfer
    }

    /// ISO/TS 16281's c_L = 35948·L_we^(8/9) \[N/mm^(10/9)\]: a straight roller's load
    /// Q = c_L·δ^(10/9) at the total approach δ between its raceways.
    pub fn line_constant(&self) -> f64 {
        LINE_CONTACT * self.effective_length().powf(8.0 / 9.0)
    }

    /// The slices' mid-points x_k along L_we \[mm\].
    pub fn slice_positions(&self) -> Vec<f64> {
        let (l, n) = (self.effective_length(), self.slices as f64);
        (0..self.slices)
            .map(|k| -0.5 * l + (k as f64 + 0.5) * l / n)
            .collect()
    }

    /// The rollers' angles φ_j from the load \[rad\].
    pub fn roller_angles(&self) -> Vec<f64> {
        (0..self.rollers)
            .map(|j| self.first_roller + 2.0 * PI * j as f64 / self.rollers as f64)
            .collect()
    }

    /// The bearing, checked: dimensions positive, the chamfers shorter than half the roller,
    /// the rollers inside the pitch circle and not overlapping, the clearance finite.
    pub fn check(&self) -> Result<()> {
        check::count("bearing.rollers", self.rollers, 3, MAX_ROLLERS)?;
        check::count("bearing.slices", self.slices, 1, MAX_SLICES)?;
        let d = check::positive("bearing.roller_diameter_mm", self.roller_diameter)?;
        check::positive("bearing.roller_length_mm", self.roller_length)?;
        check::non_negative("bearing.chamfer_mm", self.chamfer)?;
        check::positive("bearing.pitch_diameter_mm", self.pitch_diameter)?;
        check::finite("bearing.clearance_mm", self.clearance)?;
        check::finite("bearing.first_roller_rad", self.first_roller)?;
        if self.effective_length() <= 0.0 {
            return Err(Error::invalid(
                "bearing.chamfer_mm",
                self.chamfer,
                format!(
                    "must leave an effective length (the roller is {} mm long)",
                    self.roller_length
                ),
            ));
        }
        if d >= self.pitch_diameter || self.rollers as f64 * d >= PI * self.pitch_diameter {
            return Err(Error::invalid(
                "bearing.roller_diameter_mm",
                d,
                format!(
                    "{} rollers must fit on the pitch circle of {} mm",
                    self.rollers, self.pitch_diameter
                ),
            ));
        }
        Ok(())
    }

    /// The equilibrium under `load`: every roller's load, tilt and slice loads. Bad input is an
    /// error; an equilibrium that is not met within `settings` returns its last iterate with a
    /// [`Termination`] that says how far it got.
    pub fn solve(
        &self,
        load: &BearingLoad,
        settings: &BearingSettings,
    ) -> Result<LoadDistribution> {
        self.solve_observed(load, settings, &Silent)
    }

    /// [`CylindricalRollerBearing::solve`], each Newton step of the rings reported to
    /// `observer` as an event of [`Method::RingEquilibrium`] with the rings' imbalance (force
    /// over F_r, moment over F_r·L_we) against [`BearingSettings::tolerance`].
    pub fn solve_observed(
        &self,
        load: &BearingLoad,
        settings: &BearingSettings,
        observer: &dyn Observer,
    ) -> Result<LoadDistribution> {
        let model = Model::new(self, load)?;
        check::positive("settings.tolerance", settings.tolerance)?;
        check::count(
            "settings.max_iterations",
            settings.max_iterations,
            1,
            usize::MAX,
        )?;
        model.solve(settings, observer)
    }
}

/// The sums over one contact's slices: Σq, Σx·q, Σh, Σx·h, Σx²·h (h = dq/de) and the energy.
#[derive(Clone, Copy, Debug, Default)]
struct Sums {
    force: f64,
    moment: f64,
    h0: f64,
    h1: f64,
    h2: f64,
    energy: f64,
}

/// A roller's own unknowns: its approach from the inner raceway and its tilt against it.
#[derive(Clone, Copy, Debug)]
struct RollerState {
    approach: f64,
    tilt: f64,
}

/// One roller's condensed contribution to the rings.
struct Condensed {
    energy: f64,
    /// ∂E/∂δ_j, ∂E/∂T_j at the roller's equilibrium.
    gradient: [f64; 2],
    /// The Schur complement of the roller's unknowns: d²E/d(δ_j, T_j)².
    stiffness: [[f64; 2]; 2],
    converged: bool,
}

/// The rings' potential, its gradient and condensed Hessian at one displacement.
struct Rings {
    potential: f64,
    gradient: Vec<f64>,
    hessian: Mat<f64>,
    converged: bool,
    loaded: usize,
}

/// The bearing prepared for its equilibrium.
struct Model {
    x: Vec<f64>,
    /// Crown drops on the inner and outer contact at each slice.
    drop_inner: Vec<f64>,
    drop_outer: Vec<f64>,
    /// Each contact's slice constant 2^(10/9)·c_L/n_s.
    kappa: f64,
    cos: Vec<f64>,
    sin: Vec<f64>,
    half_clearance: f64,
    /// The guidance springs on a roller's approach and tilt.
    spring: [f64; 2],
    radial: f64,
    tilt: Tilt,
    length: f64,
    line_constant: f64,
}

impl Model {
    fn new(bearing: &CylindricalRollerBearing, load: &BearingLoad) -> Result<Self> {
        bearing.check()?;
        check::positive("load.radial_n", load.radial_n)?;
        match load.tilt {
            Tilt::Held(angle) => {
                check::between("load.tilt.misalignment_rad", angle, -0.5 * PI, 0.5 * PI)?;
            }
            Tilt::Moment(m) => {
                check::finite("load.tilt.moment_nmm", m)?;
            }
        }
        let length = bearing.effective_length();
        let x = bearing.slice_positions();
        let drops = |raceway: &Crown| -> Result<Vec<f64>> {
            x.iter()
                .map(|&xk| Ok(bearing.roller_crown.drop(xk, length)? + raceway.drop(xk, length)?))
                .collect()
        };
        let (drop_inner, drop_outer) = (drops(&bearing.inner_crown)?, drops(&bearing.outer_crown)?);
        let line_constant = bearing.line_constant();
        let kappa = 2f64.powf(LINE_EXPONENT) * line_constant / bearing.slices as f64;
        let reference = GUIDANCE
            * LINE_EXPONENT
            * 2f64.powf(LINE_EXPONENT)
            * line_constant
            * GUIDANCE_APPROACH.powf(LINE_EXPONENT - 1.0);
        let angles = bearing.roller_angles();
        Ok(Self {
            x,
            drop_inner,
            drop_outer,
            kappa,
            cos: angles.iter().map(|a| a.cos()).collect(),
            sin: angles.iter().map(|a| a.sin()).collect(),
            half_clearance: 0.5 * bearing.clearance,
            spring: [reference, reference * 0.25 * length * length],
            radial: load.radial_n,
            tilt: load.tilt,
            length,
            line_constant,
        })
    }

    /// The rings' unknowns: the displacement (along, across), and the tilt slopes when a
    /// moment is given.
    fn unknowns(&self) -> usize {
        match self.tilt {
            Tilt::Held(_) => 2,
            Tilt::Moment(_) => 4,
        }
    }

    /// The approach and tilt slope roller `j` sees from the rings at `u`.
    fn ring_motion(&self, u: &[f64], j: usize) -> (f64, f64) {
        let (c, s) = (self.cos[j], self.sin[j]);
        let approach = c * u[0] + s * u[1] - self.half_clearance;
        let slope = match self.tilt {
            Tilt::Held(angle) => c * angle.tan(),
            Tilt::Moment(_) => c * u[2] + s * u[3],
        };
        (approach, slope)
    }

    /// One contact's slice sums at the approaches `e(k)`.
    fn sums(&self, e: impl Fn(usize) -> f64) -> Sums {
        let mut s = Sums::default();
        for (k, &x) in self.x.iter().enumerate() {
            let e = e(k);
            if e <= 0.0 {
                continue;
            }
            let root = e.cbrt().cbrt();
            let (q, h) = (self.kappa * e * root, LINE_EXPONENT * self.kappa * root);
            s.force += q;
            s.moment += x * q;
            s.h0 += h;
            s.h1 += x * h;
            s.h2 += x * x * h;
            s.energy += 9.0 / 19.0 * q * e;
        }
        s
    }

    /// The inner and outer contacts' sums of a roller at `state` between rings that approach
    /// by `delta` and tilt by `slope`.
    fn contacts(&self, state: RollerState, delta: f64, slope: f64) -> (Sums, Sums) {
        let RollerState { approach: a, tilt } = state;
        let inner = self.sums(|k| a - self.x[k] * tilt - self.drop_inner[k]);
        let outer = self.sums(|k| delta - a - self.x[k] * (slope - tilt) - self.drop_outer[k]);
        (inner, outer)
    }

    /// A roller's energy and its gradient and Hessian in its own unknowns.
    fn roller_energy(
        &self,
        state: RollerState,
        delta: f64,
        slope: f64,
    ) -> (f64, [f64; 2], [[f64; 2]; 2]) {
        let (i, o) = self.contacts(state, delta, slope);
        let [ka, kt] = self.spring;
        let (da, dt) = (state.approach - 0.5 * delta, state.tilt - 0.5 * slope);
        let energy = i.energy + o.energy + 0.5 * (ka * da * da + kt * dt * dt);
        let gradient = [i.force - o.force + ka * da, -i.moment + o.moment + kt * dt];
        let off = -(i.h1 + o.h1);
        let hessian = [[i.h0 + o.h0 + ka, off], [off, i.h2 + o.h2 + kt]];
        (energy, gradient, hessian)
    }

    /// Roller `j`'s equilibrium between rings that approach by `delta` and tilt by `slope`,
    /// from `state`: Newton's method on its energy, with backtracking.
    fn settle(&self, state: &mut RollerState, delta: f64, slope: f64, tolerance: [f64; 2]) -> bool {
        for _ in 0..ROLLER_STEPS {
            let (energy, g, h) = self.roller_energy(*state, delta, slope);
            if g[0].abs() <= tolerance[0] && g[1].abs() <= tolerance[1] {
                return true;
            }
            let det = h[0][0] * h[1][1] - h[0][1] * h[1][0];
            let step = [
                -(h[1][1] * g[0] - h[0][1] * g[1]) / det,
                -(h[0][0] * g[1] - h[1][0] * g[0]) / det,
            ];
            let slope_along = g[0] * step[0] + g[1] * step[1];
            let mut alpha = 1.0;
            let accepted = (0..MAX_HALVINGS).any(|_| {
                let trial = RollerState {
                    approach: state.approach + alpha * step[0],
                    tilt: state.tilt + alpha * step[1],
                };
                let ok = decreased(
                    self.roller_energy(trial, delta, slope).0,
                    energy,
                    alpha * slope_along,
                );
                if ok {
                    *state = trial;
                } else {
                    alpha *= 0.5;
                }
                ok
            });
            if !accepted || !step.iter().all(|s| s.is_finite()) {
                return false;
            }
        }
        false
    }

    /// Roller `j`'s condensed contribution at the rings' `u`, its state settled from `state`.
    fn condense(
        &self,
        u: &[f64],
        j: usize,
        state: &mut RollerState,
        tolerance: [f64; 2],
    ) -> Condensed {
        let (delta, slope) = self.ring_motion(u, j);
        let converged = self.settle(state, delta, slope, tolerance);
        let (energy, _, h) = self.roller_energy(*state, delta, slope);
        let (_, o) = self.contacts(*state, delta, slope);
        let [ka, kt] = self.spring;
        let (da, dt) = (state.approach - 0.5 * delta, state.tilt - 0.5 * slope);
        let gradient = [o.force - 0.5 * ka * da, -o.moment - 0.5 * kt * dt];
        // d²E/dv², d²E/dw dv (w = (a, τ), v = (δ_j, T_j)) and the Schur complement.
        let vv = [[o.h0 + 0.25 * ka, -o.h1], [-o.h1, o.h2 + 0.25 * kt]];
        let wv = [[-o.h0 - 0.5 * ka, o.h1], [o.h1, -o.h2 - 0.5 * kt]];
        let det = h[0][0] * h[1][1] - h[0][1] * h[1][0];
        let inverse = [
            [h[1][1] / det, -h[0][1] / det],
            [-h[1][0] / det, h[0][0] / det],
        ];
        let mut stiffness = vv;
        for (r, row) in stiffness.iter_mut().enumerate() {
            for (c, entry) in row.iter_mut().enumerate() {
                let mut schur = 0.0;
                for p in 0..2 {
                    for q in 0..2 {
                        schur += wv[p][r] * inverse[p][q] * wv[q][c];
                    }
                }
                *entry -= schur;
            }
        }
        Condensed {
            energy,
            gradient,
            stiffness,
            converged,
        }
    }

    /// The rollers' absolute tolerances: force and moment.
    fn roller_tolerance(&self, settings: &BearingSettings) -> [f64; 2] {
        let force = ROLLER_TOLERANCE * settings.tolerance * self.radial;
        [force, force * self.length]
    }

    /// The rings' potential, gradient and Hessian at `u`, every roller settled.
    fn rings(&self, u: &[f64], states: &mut [RollerState], settings: &BearingSettings) -> Rings {
        let n = self.unknowns();
        let tolerance = self.roller_tolerance(settings);
        let mut rings = Rings {
            potential: -self.radial * u[0],
            gradient: vec![0.0; n],
            hessian: Mat::zeros(n, n),
            converged: true,
            loaded: 0,
        };
        rings.gradient[0] = -self.radial;
        if let Tilt::Moment(m) = self.tilt {
            rings.potential += m * u[2];
            rings.gradient[2] = m;
        }
        for (j, state) in states.iter_mut().enumerate() {
            let c = self.condense(u, j, state, tolerance);
            rings.converged &= c.converged;
            rings.loaded += usize::from(c.gradient[0] > 0.0);
            rings.potential += c.energy;
            // ∂(δ_j, T_j)/∂u: the displacement's rows 0–1, the tilt's 2–3.
            let map = [
                (self.cos[j], 0, 0),
                (self.sin[j], 1, 0),
                (self.cos[j], 2, 1),
                (self.sin[j], 3, 1),
            ];
            for &(w, r, a) in map.iter().filter(|m| m.1 < n) {
                rings.gradient[r] += w * c.gradient[a];
                for &(v, s, b) in map.iter().filter(|m| m.1 < n) {
                    rings.hessian[(r, s)] += w * v * c.stiffness[a][b];
                }
            }
        }
        rings
    }

    /// The rings' imbalance: force over F_r, moment over F_r·L_we.
    fn residual(&self, gradient: &[f64]) -> f64 {
        gradient
            .iter()
            .enumerate()
            .map(|(r, g)| g.abs() / (self.radial * if r < 2 { 1.0 } else { self.length }))
            .fold(0.0, f64::max)
    }

    /// The approach \[mm\] at which the heaviest roller of Stribeck's distribution carries
    /// 5·F_r/Z.
    fn stribeck_approach(&self) -> f64 {
        (5.0 * self.radial / (self.cos.len() as f64 * self.line_constant)).powf(0.9)
    }

    /// A start that loads the roller nearest the load: its approach closes the clearance and
    /// the crowns and reaches Stribeck's.
    fn start(&self) -> Vec<f64> {
        let nearest = self.cos.iter().copied().fold(f64::MIN, f64::max);
        let drop = (0..self.x.len())
            .map(|k| self.drop_inner[k] + self.drop_outer[k])
            .fold(f64::MAX, f64::min);
        let mut u = vec![0.0; self.unknowns()];
        u[0] = (self.half_clearance + drop + self.stribeck_approach()) / nearest;
        u
    }

    /// Newton's steps from [`Model::start`] to the rings' equilibrium, each reported to
    /// `observer` with the rings' imbalance.
    fn solve(
        &self,
        settings: &BearingSettings,
        observer: &dyn Observer,
    ) -> Result<LoadDistribution> {
        let mut u = self.start();
        let symmetric = |j: usize, u: &[f64]| {
            let (delta, slope) = self.ring_motion(u, j);
            RollerState {
                approach: 0.5 * delta,
                tilt: 0.5 * slope,
            }
        };
        let mut states: Vec<RollerState> = (0..self.cos.len()).map(|j| symmetric(j, &u)).collect();
        let mut rings = self.rings(&u, &mut states, settings);
        let (tolerance, max_steps) = (settings.tolerance, settings.max_iterations);
        let mut driver = Driver::new(Method::RingEquilibrium, observer, tolerance, max_steps);
        let termination = match self.judge(&rings, settings) {
            Step::Next(_) => driver.run(|_, _| -> Result<Step> {
                let imbalance = self.residual(&rings.gradient);
                Ok(match self.step(&mut u, &mut states, &rings, settings) {
                    Some(next) => {
                        rings = next;
                        self.judge(&rings, settings)
                    }
                    None => Step::Last(
                        imbalance,
                        Termination::Stalled {
                            cause: Stall::NoDescent { imbalance },
                        },
                    ),
                })
            })?,
            Step::Last(_, end) | Step::Ended(end) => end,
        };
        driver.announce(&termination);
        Ok(self.distribution(&u, &states, driver.steps(), &rings, termination))
    }

    /// What the rings at `rings` come to: not finite, in equilibrium (every roller's contact
    /// converged too), or not yet, with their imbalance.
    fn judge(&self, rings: &Rings, settings: &BearingSettings) -> Step {
        let residual = self.residual(&rings.gradient);
        if !rings.potential.is_finite() || !residual.is_finite() {
            let quantity = Quantity::RingEquilibrium;
            return Step::Last(residual, Termination::NonFinite { quantity });
        }
        match residual <= settings.tolerance && rings.converged {
            true => Step::Last(residual, Termination::Converged),
            false => Step::Next(residual),
        }
    }

    /// One Newton step of the rings from `u`, with backtracking; when no roller is loaded (the
    /// Hessian vanishes), the rings move along the load by Stribeck's approach instead.
    fn step(
        &self,
        u: &mut Vec<f64>,
        states: &mut Vec<RollerState>,
        rings: &Rings,
        settings: &BearingSettings,
    ) -> Option<Rings> {
        let n = u.len();
        let rhs = Mat::from_fn(n, 1, |r, _| -rings.gradient[r]);
        let direction: Vec<f64> = match self.factor(&rings.hessian) {
            Some(llt) if rings.loaded > 0 => {
                let d = llt.solve(&rhs);
                (0..n).map(|r| d[(r, 0)]).collect()
            }
            _ => {
                let mut d = vec![0.0; n];
                d[0] = self.stribeck_approach();
                d
            }
        };
        let along: f64 = direction
            .iter()
            .zip(&rings.gradient)
            .map(|(d, g)| d * g)
            .sum();
        let mut alpha = 1.0;
        for _ in 0..MAX_HALVINGS {
            let trial: Vec<f64> = u
                .iter()
                .zip(&direction)
                .map(|(u, d)| u + alpha * d)
                .collect();
            let mut trial_states = states.clone();
            let next = self.rings(&trial, &mut trial_states, settings);
            if decreased(next.potential, rings.potential, alpha * along.min(0.0)) {
                *u = trial;
                *states = trial_states;
                return Some(next);
            }
            alpha *= 0.5;
        }
        None
    }

    /// The Cholesky factor of the rings' Hessian; where it is singular (a wide clearance
    /// leaves the rollers on the load line alone loaded, and the rings have no stiffness
    /// across the load), of the Hessian with [`SINGULAR`] times its largest diagonal term
    /// added to the diagonal: the step is then Newton's in the directions the rollers hold
    /// and none across them, where the gradient vanishes too.
    fn factor(&self, hessian: &Mat<f64>) -> Option<Llt<f64>> {
        if let Ok(llt) = Llt::new(hessian.as_ref(), Side::Lower) {
            return Some(llt);
        }
        let n = hessian.nrows();
        let largest = (0..n).map(|r| hessian[(r, r)].abs()).fold(0.0, f64::max);
        let mut shifted = hessian.clone();
        for r in 0..n {
            shifted[(r, r)] += SINGULAR * largest;
        }
        Llt::new(shifted.as_ref(), Side::Lower).ok()
    }

    /// The result at `u`: every roller's slice loads and tilts.
    fn distribution(
        &self,
        u: &[f64],
        states: &[RollerState],
        iterations: usize,
        rings: &Rings,
        termination: Termination,
    ) -> LoadDistribution {
        let round_off = ROUND_OFF * (u[0].hypot(u[1]) + self.half_clearance);
        let slice_loads = |e: &dyn Fn(usize) -> f64| -> Vec<f64> {
            (0..self.x.len())
                .map(|k| match e(k) {
                    e if e > round_off => self.kappa * e.powf(LINE_EXPONENT),
                    _ => 0.0,
                })
                .collect()
        };
        let mut moment = [0.0; 2];
        let rollers = (0..self.cos.len())
            .map(|j| {
                let (delta, slope) = self.ring_motion(u, j);
                let RollerState { approach: a, tilt } = states[j];
                let inner = slice_loads(&|k| a - self.x[k] * tilt - self.drop_inner[k]);
                let outer =
                    slice_loads(&|k| delta - a - self.x[k] * (slope - tilt) - self.drop_outer[k]);
                let carried: f64 = self.x.iter().zip(&outer).map(|(x, q)| x * q).sum();
                moment[0] += self.cos[j] * carried;
                moment[1] += self.sin[j] * carried;
                RollerLoad {
                    angle: self.sin[j].atan2(self.cos[j]),
                    load_n: outer.iter().sum(),
                    tilt_inner: tilt.atan(),
                    tilt_outer: (slope - tilt).atan(),
                    moment_nmm: self.x.iter().zip(&inner).map(|(x, q)| x * q).sum(),
                    inner_n: inner,
                    outer_n: outer,
                }
            })
            .collect();
        let tilt = match self.tilt {
            Tilt::Held(angle) => [angle, 0.0],
            Tilt::Moment(_) => [u[2].atan(), u[3].atan()],
        };
        LoadDistribution {
            displacement_mm: [u[0], u[1]],
            tilt,
            moment_nmm: moment,
            half_clearance_mm: self.half_clearance,
            slice_x_mm: self.x.clone(),
            rollers,
            iterations,
            residual: self.residual(&rings.gradient),
            termination,
        }
    }
}

/// The tests' bearing, shared by the crate's test modules: a 209 size, Z = 14 rollers of
/// 10 × 10 mm (chamfers 0.2 mm, L_we = 9.6 mm), pitch diameter 65 mm, straight crowns, no
/// clearance, `slices` slices.
#[cfg(test)]
pub(crate) fn bearing_209(slices: usize) -> CylindricalRollerBearing {
    CylindricalRollerBearing {
        rollers: 14,
        roller_diameter: 10.0,
        roller_length: 10.0,
        chamfer: 0.2,
        pitch_diameter: 65.0,
        clearance: 0.0,
        roller_crown: Crown::Straight,
        inner_crown: Crown::Straight,
        outer_crown: Crown::Straight,
        slices,
        first_roller: 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`bearing_209`] with ISO's roller crown, 30 slices and `clearance`.
    fn bearing(clearance: f64) -> CylindricalRollerBearing {
        CylindricalRollerBearing {
            clearance,
            roller_crown: Crown::iso(10.0).unwrap(),
            ..bearing_209(30)
        }
    }

    fn held(radial_n: f64, angle: f64) -> BearingLoad {
        BearingLoad {
            radial_n,
            tilt: Tilt::Held(angle),
        }
    }

    fn solve(b: &CylindricalRollerBearing, load: &BearingLoad) -> LoadDistribution {
        let d = b.solve(load, &BearingSettings::default()).unwrap();
        assert!(d.termination.is_converged(), "{:?}", d.termination);
        d
    }

    /// Two equal contacts in series are the standard's combined law: with straight raceways
    /// each roller's slices carry c_s·(δ_j − x·T_j − 2z(x))^(10/9) (ISO/TS 16281 eqs. 36–41,
    /// z the roller's crown), written out here from the rings' displacement, to 1e-6 of the
    /// heaviest slice; each roller tilts by half the rings' tilt against each ring; the load
    /// balances F_r to the tolerance. Misaligned by 4′ with a clearance of 20 µm.
    #[test]
    fn two_equal_contacts_are_the_standards_combined_law() {
        let b = bearing(0.02);
        let angle = (4.0f64 / 60.0).to_radians();
        let d = solve(&b, &held(8900.0, angle));
        let (x, length) = (b.slice_positions(), b.effective_length());
        let c_s = b.line_constant() / b.slices as f64;
        let top = d
            .rollers
            .iter()
            .flat_map(|r| r.outer_n.iter().copied())
            .fold(0.0, f64::max);
        let mut carried = 0.0;
        for r in &d.rollers {
            let (c, s) = (r.angle.cos(), r.angle.sin());
            let delta = c * d.displacement_mm[0] + s * d.displacement_mm[1] - 0.01;
            let slope = c * angle.tan();
            for (k, &xk) in x.iter().enumerate() {
                let e = delta - xk * slope - 2.0 * b.roller_crown.drop(xk, length).unwrap();
                let want = c_s * e.max(0.0).powf(LINE_EXPONENT);
                assert!(
                    (r.inner_n[k] - want).abs() < 1e-6 * top,
                    "{} {k}: {} vs {want}",
                    r.angle,
                    r.inner_n[k]
                );
                assert!((r.outer_n[k] - want).abs() < 1e-6 * top);
            }
            if r.load_n > 0.0 {
                assert!((r.tilt_inner - (0.5 * slope).atan()).abs() < 1e-9 * angle);
                assert!((r.tilt_outer - r.tilt_inner).abs() < 1e-9 * angle);
            }
            carried += c * r.load_n;
        }
        assert!((carried / 8900.0 - 1.0).abs() < 1e-9, "{carried}");
        // A positive tilt opens the gap at +x: the rollers lean on their −x ends.
        assert!(d.moment_nmm[0] < 0.0 && d.rollers[0].moment_nmm < 0.0);
    }

    /// Without clearance, straight crowns and Z = 12, each roller carries
    /// Q_max·cos^(10/9) ψ, so F_r = Q_max·Σ cos^(19/9) ψ (Stribeck's sum with the line
    /// contact's exponent; Q_max = 4.08·F_r/Z for many rollers): Q_max to 1e-9. The rollers at
    /// ±90°, on the zone's edge, carry nothing (not the 10⁻¹⁵ N of cos 90°'s round-off) and are
    /// not load cases.
    #[test]
    fn without_clearance_the_loads_follow_stribecks_sum() {
        let b = CylindricalRollerBearing {
            rollers: 12,
            ..bearing_209(30)
        };
        let d = solve(&b, &held(10_000.0, 0.0));
        let sum: f64 = (0..12)
            .map(|j| (j as f64 * PI / 6.0).cos())
            .filter(|&c| c > 1e-9)
            .map(|c| c.powf(19.0 / 9.0))
            .sum();
        let q_max = 10_000.0 / sum;
        assert!(
            (d.max_load() / q_max - 1.0).abs() < 1e-9,
            "{} vs {q_max}",
            d.max_load()
        );
        for r in &d.rollers {
            let want = q_max * r.angle.cos().max(0.0).powf(10.0 / 9.0);
            assert!(
                (r.load_n - want).abs() < 1e-9 * q_max,
                "{}: {}",
                r.angle,
                r.load_n
            );
        }
        let edge = |r: &&RollerLoad| (r.angle.abs() - 0.5 * PI).abs() < 1e-9;
        assert_eq!(d.rollers.iter().filter(edge).count(), 2);
        assert!(d.rollers.iter().filter(edge).all(|r| r.load_n == 0.0));
        assert_eq!(d.roller_cases(Raceway::Inner).len(), 5);
    }

    /// A held misalignment and the moment it takes are one equilibrium seen from two sides:
    /// freed under that moment, the inner ring tilts back to the misalignment (to 1e-6) and
    /// the rollers carry the same loads.
    #[test]
    fn held_tilt_and_its_moment_agree() {
        let b = bearing(0.01);
        let angle = (3.0f64 / 60.0).to_radians();
        let held = solve(&b, &held(6000.0, angle));
        let m = held.moment_nmm[0];
        let free = solve(
            &b,
            &BearingLoad {
                radial_n: 6000.0,
                tilt: Tilt::Moment(m),
            },
        );
        assert!(
            (free.tilt[0] / angle - 1.0).abs() < 1e-6,
            "{:?} vs {angle}",
            free.tilt
        );
        assert!(free.tilt[1].abs() < 1e-9 * angle);
        for (a, h) in free.rollers.iter().zip(&held.rollers) {
            assert!((a.load_n - h.load_n).abs() < 1e-6 * held.max_load());
        }
        // No moment: a symmetric bearing stays aligned.
        let none = solve(
            &b,
            &BearingLoad {
                radial_n: 6000.0,
                tilt: Tilt::Moment(0.0),
            },
        );
        assert!(none.tilt[0].abs() < 1e-12, "{:?}", none.tilt);
    }

    /// A crowned inner raceway and a straight outer one: each roller balances its inner and
    /// outer slice loads in force and moment, and tilts differently against the two rings.
    /// Roller 0 set off the load's line: the rings move across it so that the rollers carry
    /// nothing across.
    #[test]
    fn each_roller_balances_between_unequal_raceways() {
        let mut b = bearing(0.0);
        b.inner_crown = Crown::iso(10.0).unwrap();
        b.first_roller = 0.1;
        let angle = (2.0f64 / 60.0).to_radians();
        let d = solve(&b, &held(8000.0, angle));
        let x = b.slice_positions();
        let moment = |q: &[f64]| -> f64 { x.iter().zip(q).map(|(x, q)| x * q).sum() };
        for r in d.rollers.iter().filter(|r| r.load_n > 0.0) {
            let inner: f64 = r.inner_n.iter().sum();
            assert!(
                (inner - r.load_n).abs() < 1e-9 * 8000.0,
                "{inner} vs {}",
                r.load_n
            );
            assert!((moment(&r.inner_n) - moment(&r.outer_n)).abs() < 1e-9 * 8000.0 * 9.6);
            assert!((r.tilt_inner - r.tilt_outer).abs() > 1e-3 * angle);
        }
        let across: f64 = d.rollers.iter().map(|r| r.angle.sin() * r.load_n).sum();
        assert!(
            across.abs() < 1e-9 * 8000.0 && d.displacement_mm[1] != 0.0,
            "{across}"
        );
    }

    /// An equilibrium stopped short reports where it stood: its step count, its imbalance and
    /// the tolerance, every number finite.
    #[test]
    fn an_unmet_equilibrium_says_how_far_it_got() {
        let settings = BearingSettings {
            tolerance: 1e-12,
            max_iterations: 1,
        };
        let d = bearing(0.04).solve(&held(8900.0, 0.0), &settings).unwrap();
        match d.termination {
            Termination::StepLimit {
                steps,
                measure,
                tolerance,
            } => {
                assert!(steps == 1 && measure > tolerance && measure.is_finite());
            }
            other => panic!("{other:?}"),
        }
        assert!(d.rollers.iter().all(|r| r.load_n.is_finite()) && d.residual > 1e-12);
    }

    /// The equilibrium reports each Newton step to an observer, numbered from 1, its imbalance
    /// against the tolerance, the last event with how it ended; a stop ends it there.
    #[test]
    fn the_equilibrium_reports_its_steps() {
        use contopt_core::observe::{Event, Flow, Recorded};
        let seen = std::cell::RefCell::new(vec![]);
        let record = |e: &Event| {
            seen.borrow_mut().push(Recorded::of(e));
            Flow::Continue
        };
        let (b, load, settings) = (bearing(0.02), held(8900.0, 0.0), BearingSettings::default());
        let d = b.solve_observed(&load, &settings, &record).unwrap();
        let seen = seen.into_inner();
        let (last, steps) = seen.split_last().unwrap();
        assert!(d.termination.is_converged() && d.iterations == steps.len());
        assert!(steps.iter().enumerate().all(|(k, e)| e.iteration == k + 1
            && e.method == Method::RingEquilibrium
            && e.end.is_none()));
        assert_eq!(last.end, Some(Termination::Converged));
        assert!(last.measure <= settings.tolerance && d.residual <= settings.tolerance);
        let stop = |_: &Event| Flow::Stop;
        let stopped = b.solve_observed(&load, &settings, &stop).unwrap();
        assert_eq!(stopped.termination, Termination::Stopped { after: 1 });
    }

    /// The standard's constant is Palmgren's line contact, δ = 3.84·10⁻⁵·Q^0.9/l^0.8 for each of
    /// the roller's two contacts, to 4 % (Palmgren's gives (1/(2·3.84·10⁻⁵))^(10/9) = 37 318 for
    /// the pair; one contact's 80 600 would be 55 % off).
    #[test]
    fn line_constant_is_palmgrens_pair_of_contacts() {
        let pair = (1.0 / (2.0 * 3.84e-5f64)).powf(LINE_EXPONENT);
        assert!((LINE_CONTACT / pair - 1.0).abs() < 0.04, "{pair}");
        let b = bearing(0.0);
        assert!((b.line_constant() - LINE_CONTACT * 9.6f64.powf(8.0 / 9.0)).abs() < 1e-9);
    }

    /// Bad input is named: the field and its value.
    #[test]
    fn bad_bearings_are_named() {
        let s = BearingSettings::default();
        let error = |b: CylindricalRollerBearing, load: BearingLoad| {
            b.solve(&load, &s).unwrap_err().to_string()
        };
        let mut b = bearing(0.0);
        b.rollers = 2;
        assert!(error(b, held(1.0, 0.0)).contains("bearing.rollers"));
        let mut b = bearing(0.0);
        b.chamfer = 5.0;
        assert!(error(b, held(1.0, 0.0)).contains("bearing.chamfer_mm"));
        let mut b = bearing(0.0);
        b.rollers = 21;
        let e = error(b, held(1.0, 0.0));
        assert!(e.contains("roller_diameter_mm") && e.contains("fit"), "{e}");
        let mut b = bearing(0.0);
        b.clearance = f64::NAN;
        assert!(error(b, held(1.0, 0.0)).contains("clearance_mm"));
        assert!(error(bearing(0.0), held(-1.0, 0.0)).contains("load.radial_n"));
        assert!(error(bearing(0.0), held(1.0, 2.0)).contains("misalignment_rad"));
        let e = error(
            bearing(0.0),
            BearingLoad {
                radial_n: 1.0,
                tilt: Tilt::Moment(f64::INFINITY),
            },
        );
        assert!(e.contains("moment_nmm"), "{e}");
        let e = bearing(0.0)
            .solve(
                &held(1.0, 0.0),
                &BearingSettings {
                    tolerance: 0.0,
                    max_iterations: 5,
                },
            )
            .unwrap_err()
            .to_string();
        assert!(e.contains("settings.tolerance"), "{e}");
    }
}
