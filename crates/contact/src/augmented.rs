//! The augmented Lagrangian technique (§2.2, eqs. 2.18–2.20): Uzawa's updates, each step one
//! Kalker iteration.

use contopt_core::drive::{Driver, Step};
use contopt_core::observe::{Method, Nested, Observer};
use contopt_core::{check, ContactState, Result, Termination};
use serde::{Deserialize, Serialize};

use crate::kalker::{self, Iterate, KalkerWorkspace, Subproblem};
use crate::watch::{self, Watch};
use crate::{ContactSolver, InterfaceProblem, Workspace};

/// The settings of the [`AugmentedLagrangian`]: the penalty parameter, which has no default,
/// and the stopping rule, which has.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AugmentedLagrangianSettings {
    /// Penalty parameter c \[MPa/mm\]: any c > 0 converges to the QP's solution; a small c
    /// costs more Uzawa steps.
    pub c_mpa_per_mm: f64,
    /// Stop when no pressure changes by more than `tolerance`·p_max in a step.
    #[serde(default = "AugmentedLagrangianSettings::default_tolerance")]
    pub tolerance: f64,
    /// Largest number of Uzawa steps.
    #[serde(default = "AugmentedLagrangianSettings::default_max_steps")]
    pub max_steps: usize,
    /// Once a step leaves the contact set unchanged, solve for the iteration's limit directly.
    /// Without it, plain Uzawa steps continue to the tolerance; along directions the interface
    /// hardly feels (elements partly in contact) that can take thousands of steps.
    #[serde(default = "AugmentedLagrangianSettings::default_accelerate")]
    pub accelerate: bool,
}

impl AugmentedLagrangianSettings {
    /// The default tolerance on the pressure change of a step, relative to p_max
    /// (convergence: six orders above round-off, far below any engineering need).
    pub const TOLERANCE: f64 = 1e-10;
    /// The default limit on Uzawa steps: far more than an accelerated solve takes (a few).
    pub const MAX_STEPS: usize = 2000;

    /// Penalty parameter `c` \[MPa/mm\] with the default stopping rule, accelerated.
    pub fn new(c_mpa_per_mm: f64) -> Self {
        Self {
            c_mpa_per_mm,
            tolerance: Self::TOLERANCE,
            max_steps: Self::MAX_STEPS,
            accelerate: Self::default_accelerate(),
        }
    }

    fn default_tolerance() -> f64 {
        Self::TOLERANCE
    }

    fn default_max_steps() -> usize {
        Self::MAX_STEPS
    }

    fn default_accelerate() -> bool {
        true
    }
}

/// The augmented Lagrangian technique (§2.2, eqs. 2.18–2.20): Uzawa updates
/// p ← ⟨p − c d⟩, each solved by Kalker's active-set iteration, whose solves are counted as
/// `iterp` and its penetration checks as `iterd` (the paper's counts). Converges to the
/// solution of the QP (2.14) for any c > 0.
#[derive(Clone, Copy, Debug)]
pub struct AugmentedLagrangian {
    settings: AugmentedLagrangianSettings,
}

impl AugmentedLagrangian {
    /// The method with `settings`, checked: c positive and finite, the tolerance in (0, 1), at
    /// least one step.
    pub fn new(settings: AugmentedLagrangianSettings) -> Result<Self> {
        check::positive("c_mpa_per_mm", settings.c_mpa_per_mm)?;
        check::between("tolerance", settings.tolerance, 0.0, 1.0)?;
        check::count("max_steps", settings.max_steps, 1, usize::MAX)?;
        Ok(Self { settings })
    }

    /// Its settings.
    pub fn settings(&self) -> &AugmentedLagrangianSettings {
        &self.settings
    }
}

impl ContactSolver for AugmentedLagrangian {
    fn method(&self) -> Method {
        Method::AugmentedLagrangian
    }

    fn dense_copies(&self, _points: usize) -> u64 {
        kalker::DENSE_COPIES
    }

    /// Reports each Uzawa step (`iterations`) with its largest pressure change relative to
    /// p_max as the measure and `tolerance`; and, one level deeper, each inner Kalker solve
    /// (`iterp`) as [`Method::Kalker`], measured by the number of points that break a sign
    /// condition (tolerance 0). Solves from scratch: a `start` is not used.
    ///
    /// In the workspace's [`KalkerWorkspace`].
    fn solve_in(
        &self,
        problem: &InterfaceProblem,
        _start: Option<&[f64]>,
        observer: &dyn Observer,
        workspace: &mut Workspace,
    ) -> Result<ContactState> {
        let state = uzawa(problem, &self.settings, observer, &mut workspace.kalker)?;
        watch::announce(observer, &state);
        Ok(state)
    }
}

/// Uzawa's iteration p⁽ᵏ⁺¹⁾ = ⟨p⁽ᵏ⁾ − c d⁽ᵏ⁾⟩ (2.19)–(2.20), each step a Kalker subproblem,
/// from p = 0 with every point in contact, until the pressure changes by less than
/// `tolerance`·p_max or the gap on the contact set is at round-off; with `accelerate`, until
/// a step leaves the contact set unchanged, when the iteration's limit is solved for directly.
fn uzawa(
    problem: &InterfaceProblem,
    al: &AugmentedLagrangianSettings,
    observer: &dyn Observer,
    ws: &mut KalkerWorkspace,
) -> Result<ContactState> {
    let nested = Nested(observer);
    let inner_watch = Watch::new(&nested, Method::Kalker);
    let (n, m) = (problem.len(), problem.modes().len());
    // One workspace for every step: the steps allocate nothing of their own.
    ws.prepare(problem);
    let mut uzawa = Uzawa {
        problem,
        settings: al,
        inner_watch,
        spectral: al.c_mpa_per_mm > kalker::stiff_penalty(problem)?,
        active: vec![true; n],
        counts: [0, 0],
        current: Iterate::zero(n, m),
        shift: vec![0.0; n],
        stopped: None,
        linear: false,
    };
    let started = kalker::start(
        problem,
        al.c_mpa_per_mm,
        &mut uzawa.active,
        &mut uzawa.counts,
        inner_watch,
        &mut uzawa.current,
        ws,
    )?;
    if let Some(stopped) = started {
        let (active, counts) = (uzawa.active, uzawa.counts);
        return Ok(kalker::finish(
            problem, METHOD, stopped, ws, active, 0, counts,
        ));
    }
    let mut driver = Driver::new(METHOD, observer, al.tolerance, al.max_steps);
    let end = driver.run(|_, _| uzawa.step(ws))?;
    uzawa.finish(end, driver.steps(), ws)
}

/// The method Uzawa's steps report as.
const METHOD: Method = Method::AugmentedLagrangian;

/// Uzawa's iteration under way: its iterate, the contact set, Kalker's counts so far and how
/// its last step came out.
struct Uzawa<'s> {
    problem: &'s InterfaceProblem<'s>,
    settings: &'s AugmentedLagrangianSettings,
    /// Where the inner Kalker solves report, one level deeper.
    inner_watch: Watch<'s>,
    /// Whether the subproblems are solved spectrally (c above c_stiff).
    spectral: bool,
    active: Vec<bool>,
    /// Kalker's solves and penetration checks so far (`iterp`, `iterd`).
    counts: [usize; 2],
    current: Iterate,
    /// The pressure p⁽ᵏ⁾ a step starts from.
    shift: Vec<f64>,
    /// An inner solve that ended the iteration short.
    stopped: Option<kalker::Inner>,
    /// With `accelerate`, the last step left the contact set unchanged: the rest of Uzawa's
    /// iteration is linear.
    linear: bool,
}

impl Uzawa<'_> {
    /// One Uzawa step, the pressure's largest change relative to p_max its measure.
    fn step(&mut self, ws: &mut KalkerWorkspace) -> Result<Step> {
        let al = self.settings;
        self.shift.copy_from_slice(&self.current.pressure);
        let (rho, spectral) = (1.0 / al.c_mpa_per_mm, self.spectral);
        let inner = Subproblem::new(self.problem, rho, &self.shift, spectral, &self.current, ws)?
            .solve(&mut self.active, self.inner_watch.after(self.counts[0]))?;
        if let Some(halt) = inner.stopped.clone() {
            self.stopped = Some(inner);
            return Ok(Step::Ended(halt));
        }
        self.counts[0] += inner.iterp;
        self.counts[1] += inner.iterd;
        let pressure = &ws.solution().pressure;
        let p_max = pressure.iter().fold(0.0f64, |s, v| s.max(*v));
        let relative = largest_difference(pressure, &self.shift) / p_max.max(f64::MIN_POSITIVE);
        // Converged when the pressure settles, or when the gap on the contact set is at
        // round-off: with a large c, c·(round-off) would otherwise keep p drifting along the
        // directions that do not move the interface.
        let converged =
            relative <= al.tolerance || ws.open_on_contact(&self.active) <= inner.gap_floor;
        self.linear = al.accelerate && inner.unchanged();
        ws.swap_solution(&mut self.current);
        Ok(match converged || self.linear {
            true => Step::Last(relative, Termination::Converged),
            false => Step::Next(relative),
        })
    }

    /// The state after `steps` steps that ended as `end`: an inner solve's that stopped short;
    /// when the last step left the contact set unchanged, the exact solve on it from the
    /// current iterate (the fixed point of the rest of the iteration, which keeps the
    /// iterate's components along directions that do not move the interface, as the
    /// iteration would); else the current iterate's.
    fn finish(
        self,
        end: Termination,
        steps: usize,
        ws: &mut KalkerWorkspace,
    ) -> Result<ContactState> {
        let Self {
            problem,
            mut active,
            counts,
            current,
            ..
        } = self;
        if let Some(inner) = self.stopped {
            let steps = steps + 1;
            return Ok(kalker::finish(
                problem, METHOD, inner, ws, active, steps, counts,
            ));
        }
        if self.linear {
            let watch = self.inner_watch.after(counts[0]);
            let jump = kalker::solve_exact(problem, &current, &mut active, watch, ws)?;
            return Ok(kalker::finish(
                problem, METHOD, jump, ws, active, steps, counts,
            ));
        }
        let counted = [steps, counts[0], counts[1]];
        let mut state = problem.state(METHOD, current.pressure, current.rigid, active, counted);
        if !end.is_converged() {
            watch::end(&mut state, end);
        }
        Ok(state)
    }
}

/// maxᵢ |aᵢ − bᵢ|.
fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |s, (a, b)| s.max((a - b).abs()))
}
