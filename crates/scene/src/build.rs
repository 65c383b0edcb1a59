//! From a case's scene to bodies, a solver and an optimisation, and its run.

use std::time::Instant;

use contopt_contact::{
    ActiveSet, AugmentedLagrangian, ContactSolver, InterfaceProblem, Penalty, PolonskyKeer, Qp,
};
use contopt_core::{ElasticBody, Error, GapShape, Material, Result, RigidBody};
use contopt_fem::{Analysis, FeBody};
use contopt_greens::{AxisymmetricHalfSpace, HalfPlane, HalfSpace, PlaneState};
use contopt_optimise::{
    Constant, Controller, EnvelopeOptimum, Mode, Optimisation, Optimum, Profile, Region,
};

use crate::envelope::LoadCase;
use crate::geometry::{block_spacings, half_space_block};
use crate::report::{
    CaseReport, EnvelopeCaseReport, IterationRow, PointReport, TunedProfile, PENETRATION_WARNING,
};
use crate::spec::{
    ControllerSpec, Indenter, MaterialSpec, ModeSpec, OmegaVSpec, Optimise, Problem, ProfileSpec,
    RigidLoad, SolverSpec,
};
use crate::{Case, SceneError};

/// The initial gap of a point beyond a flat punch's rim, in sizes of the interface: out of
/// reach, since the solvers refuse an elastic displacement larger than one size
/// ([`contopt_contact::SMALL_STRAIN`]), and in the units of the scene.
const OPEN_SIZES: f64 = 4.0;

/// A point this far beyond a flat punch's rim, relative to its radius, is under it: the
/// round-off of the points' coordinates.
const RIM_ROUND_OFF: f64 = 1e-12;

/// What a case designs.
enum Design<'s> {
    /// Nothing: the contact of the given bodies and gap.
    Contact,
    /// The gap for the scene's own load (a roller's `optimised` crown).
    Optimised(&'s Optimise),
    /// A roller's `robust` crown for its envelope.
    Robust(&'s Optimise),
    /// A roller's `fujiwara_kawase_tuned` crown for its envelope.
    Tuned,
}

/// A roller's envelope after the design: a gap change to solve the cases under, or the cases
/// solved already (with the tuned profile's parameters).
enum Envelope {
    Given(Vec<f64>),
    Solved(Vec<EnvelopeCaseReport>, Option<TunedProfile>),
}

/// A case's bodies, built once for every case of a scene that shares its problem.
pub(crate) struct Built {
    bodies: Bodies,
    /// The time their build took.
    took: std::time::Duration,
}

impl Built {
    /// The same bodies for a later case, which does not pay for their build.
    pub(crate) fn reused(self) -> Self {
        Self {
            took: std::time::Duration::ZERO,
            ..self
        }
    }
}

/// What a case's design and solves work on.
struct Solve<'p, 'o> {
    problem: &'p InterfaceProblem<'p>,
    bodies: &'p Bodies,
    /// A roller's envelope of load cases (empty otherwise).
    cases: &'p [LoadCase<'p>],
    solver: &'p dyn ContactSolver,
    observer: &'o dyn contopt_core::observe::Observer,
}

/// The elastic body, its rigid or elastic partner, and the initial gap.
struct Bodies {
    first: Box<dyn ElasticBody>,
    second: Box<dyn ElasticBody>,
    gap: Vec<f64>,
    /// A roller's cell size and crown (the `roller` kind).
    roller: Option<crate::roller::Info>,
}

impl Bodies {
    /// Whether both bodies have one stress field below the surface: a roller and raceway of
    /// one Poisson's ratio (two half-spaces on one grid under one pressure).
    fn shared_stresses(&self) -> bool {
        self.roller
            .as_ref()
            .is_some_and(|r| r.roller.roller.nu() == r.roller.raceway.nu())
    }
}

fn material(m: &MaterialSpec) -> Result<Material> {
    Material::new(m.e_mpa, m.nu)
}

/// The indenter's initial gap at a point at distance `r` from its axis (or `y` from a roller's);
/// infinite beyond a flat punch's rim.
fn indenter_gap(indenter: &Indenter, r: f64, y: f64) -> Result<f64> {
    let positive = |name: &str, v: f64| {
        if v > 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(Error::invalid(name, v, "must be positive"))
        }
    };
    Ok(match *indenter {
        Indenter::Sphere { radius_mm } => {
            r * r / (2.0 * positive("indenter.radius_mm", radius_mm)?)
        }
        Indenter::Cylinder { radius_mm } => {
            y * y / (2.0 * positive("indenter.radius_mm", radius_mm)?)
        }
        Indenter::FlatPunch { radius_mm } => {
            if r <= positive("indenter.radius_mm", radius_mm)? * (1.0 + RIM_ROUND_OFF) {
                0.0
            } else {
                f64::INFINITY
            }
        }
    })
}

/// A rigid indenter on `body`, pressed along `axis` (away from the body) by a force, which
/// floats it, or held at a given approach, which enters the initial gap once (h − a) and nowhere
/// else.
fn rigid_on(
    body: Box<dyn ElasticBody>,
    axis: [f64; 3],
    load: RigidLoad,
    gap: impl Fn([f64; 3]) -> Result<f64>,
) -> Result<Bodies> {
    let iface = body.interface();
    let mut h = iface
        .points
        .iter()
        .map(|&x| gap(x))
        .collect::<Result<Vec<_>>>()?;
    if h.iter().all(|v| v.is_infinite()) {
        let nearest = iface
            .points
            .iter()
            .map(|x| x[0].hypot(x[1]))
            .fold(f64::INFINITY, f64::min);
        return Err(Error::invalid(
            "indenter.radius_mm",
            format!("less than {nearest:.4e}"),
            "no interface point lies under the flat punch (that is the nearest point's distance \
             from its axis): enlarge the punch, or refine the rings or cells",
        ));
    }
    let open = OPEN_SIZES * iface.extent();
    h.iter_mut()
        .filter(|v| v.is_infinite())
        .for_each(|v| *v = open);
    let second = match load {
        RigidLoad::ForceN(f) => RigidBody::pressed("indenter", iface, axis, f)?,
        RigidLoad::ApproachMm(a) => {
            if !(a > 0.0 && a.is_finite()) {
                return Err(Error::invalid("load.approach_mm", a, "must be positive"));
            }
            h.iter_mut().for_each(|v| *v -= a);
            RigidBody::fixed("indenter", iface)
        }
    };
    Ok(Bodies {
        first: body,
        second: Box::new(second),
        gap: h,
        roller: None,
    })
}

/// The bodies of `problem`; files it names are read from `dir`, the scene file's folder.
fn bodies(problem: &Problem, dir: &std::path::Path) -> Result<Bodies> {
    match problem {
        Problem::Roller { .. } => roller_bodies(problem, dir),
        Problem::PunchOnBase(spec) => {
            let (base, punch) = spec.geometry()?.bodies()?;
            let n = base.interface().len();
            Ok(Bodies {
                first: Box::new(base),
                second: Box::new(punch),
                gap: vec![0.0; n],
                roller: None,
            })
        }
        Problem::RigidOnHalfSpace {
            material: m,
            cells,
            cell_mm,
            indenter,
            load,
        } => {
            let origin = [
                -0.5 * (cells[0] as f64 - 1.0) * cell_mm[0],
                -0.5 * (cells[1] as f64 - 1.0) * cell_mm[1],
            ];
            let body = HalfSpace::grid(
                "half-space",
                material(m)?,
                cells[0],
                cells[1],
                cell_mm[0],
                cell_mm[1],
                origin,
            )?;
            rigid_on(Box::new(body), [0.0, 0.0, 1.0], *load, |x| {
                indenter_gap(indenter, x[0].hypot(x[1]), x[1])
            })
        }
        Problem::RigidOnAxisymmetricHalfSpace {
            material: m,
            rings,
            radius_mm,
            indenter,
            load,
        } => {
            let edges = clustered(*rings, *radius_mm, "rings", |t| t.sin(), 0.5)?;
            let body = AxisymmetricHalfSpace::new("half-space", material(m)?, &edges)?;
            rigid_on(Box::new(body), [0.0, 1.0, 0.0], *load, |x| {
                no_roller(indenter)?;
                indenter_gap(indenter, x[0], 0.0)
            })
        }
        Problem::RigidOnHalfPlane { .. } => half_plane_bodies(problem),
        Problem::RigidOnBlock {
            material: m,
            zone_mm,
            elements,
            size_mm,
            indenter,
            load,
        } => {
            let (model, contact) = half_space_block(*zone_mm, *elements, *size_mm, material(m)?)?;
            let body = FeBody::new("block", model, &contact)?;
            rigid_on(Box::new(body), [0.0, 1.0, 0.0], *load, |x| {
                no_roller(indenter)?;
                indenter_gap(indenter, x[0], 0.0)
            })
        }
    }
}

/// A roller on its raceway, both half-spaces (the `roller` kind).
fn roller_bodies(problem: &Problem, dir: &std::path::Path) -> Result<Bodies> {
    let Problem::Roller {
        diameter_mm,
        length_mm,
        raceway_diameter_mm,
        roller,
        raceway,
        load_n,
        tilt_arcmin,
        cells,
        reach_b,
        profile,
    } = problem
    else {
        return Err(Error::invalid("problem.kind", "not a roller", "a roller"));
    };
    let built = crate::roller::build(
        *diameter_mm,
        *length_mm,
        *raceway_diameter_mm,
        [material(roller)?, material(raceway)?],
        *load_n,
        *tilt_arcmin,
        *cells,
        *reach_b,
        profile,
        dir,
    )?;
    Ok(Bodies {
        first: built.raceway,
        second: built.roller,
        gap: built.gap,
        roller: Some(built.info),
    })
}

/// A rigid indenter on a half-plane (the `rigid_on_half_plane` kind).
fn half_plane_bodies(problem: &Problem) -> Result<Bodies> {
    let Problem::RigidOnHalfPlane {
        material: m,
        analysis,
        strips,
        half_width_mm,
        datum_mm,
        indenter,
        load,
    } = problem
    else {
        return Err(Error::invalid(
            "problem.kind",
            "not a half-plane",
            "a half-plane",
        ));
    };
    let (state, thickness) = match *analysis {
        Analysis::PlaneStress { thickness } => (PlaneState::Stress, thickness),
        Analysis::PlaneStrain { thickness } => (PlaneState::Strain, thickness),
        Analysis::Axisymmetric => {
            return Err(Error::invalid(
                "analysis",
                "axisymmetric",
                "a half-plane is plane_stress or plane_strain",
            ))
        }
    };
    let edges = clustered(*strips, *half_width_mm, "strips", |t| -t.cos(), 1.0)?;
    let body = HalfPlane::new(
        "half-plane",
        material(m)?,
        state,
        thickness,
        &edges,
        *datum_mm,
    )?;
    rigid_on(Box::new(body), [0.0, 1.0, 0.0], *load, |x| {
        indenter_gap(indenter, x[0].abs(), x[0])
    })
}

fn no_roller(indenter: &Indenter) -> Result<()> {
    match indenter {
        Indenter::Cylinder { .. } => Err(Error::invalid(
            "indenter.shape",
            "cylinder",
            "an axisymmetric body takes a sphere or a flat punch",
        )),
        _ => Ok(()),
    }
}

/// `count` + 1 edges a·f(π k / (2 count) · span), narrowing towards the rim.
fn clustered(
    count: usize,
    size: f64,
    name: &str,
    f: impl Fn(f64) -> f64,
    span: f64,
) -> Result<Vec<f64>> {
    if count == 0 {
        return Err(Error::invalid(name, count, "must be at least 1"));
    }
    Ok((0..=count)
        .map(|k| size * f(std::f64::consts::PI * span * k as f64 / count as f64))
        .collect())
}

fn solver(spec: &SolverSpec) -> Result<Box<dyn ContactSolver>> {
    Ok(match *spec {
        SolverSpec::Qp => Box::new(Qp::default()),
        SolverSpec::ActiveSet => Box::new(ActiveSet),
        SolverSpec::Penalty { c_mpa_per_mm } => Box::new(Penalty { c: c_mpa_per_mm }),
        SolverSpec::AugmentedLagrangian {
            c_mpa_per_mm,
            tolerance,
            max_steps,
        } => {
            let mut al = AugmentedLagrangian::new(c_mpa_per_mm);
            al.tolerance = tolerance.unwrap_or(al.tolerance);
            al.max_steps = max_steps.unwrap_or(al.max_steps);
            Box::new(al)
        }
        SolverSpec::PolonskyKeer {
            tolerance,
            max_steps,
        } => {
            let mut pk = PolonskyKeer::default();
            pk.tolerance = tolerance.unwrap_or(pk.tolerance);
            pk.max_steps = max_steps.unwrap_or(pk.max_steps);
            Box::new(pk)
        }
    })
}

fn controller(spec: &ControllerSpec) -> Result<Box<dyn Controller>> {
    Ok(match spec {
        ControllerSpec::Constant { level } => Box::new(Constant::new(*level)?),
        ControllerSpec::Trapezoid { l1_mm, l2_mm, axis } => {
            Box::new(Profile::trapezoid(*l1_mm, *l2_mm)?.along(*axis)?)
        }
        ControllerSpec::Cubic { l1_mm, l2_mm, axis } => {
            Box::new(Profile::cubic(*l1_mm, *l2_mm)?.along(*axis)?)
        }
        ControllerSpec::Product { a, b } => {
            let (a, b) = (controller(a)?, controller(b)?);
            Box::new(move |x: [f64; 3]| a.value(x) * b.value(x))
        }
    })
}

/// Checks `problem` without factorising anything: a finite-element body by its dimensions,
/// materials, supports, load and mesh; the other kinds, which factorise nothing, are built.
fn check_problem(problem: &Problem, dir: &std::path::Path) -> Result<()> {
    match problem {
        Problem::PunchOnBase(spec) => spec.geometry()?.check(),
        Problem::RigidOnBlock {
            material: m,
            zone_mm,
            elements,
            size_mm,
            indenter,
            load,
        } => {
            material(m)?;
            block_spacings(*zone_mm, *elements, *size_mm)?;
            no_roller(indenter)?;
            indenter_gap(indenter, 0.0, 0.0)?;
            check_rigid_load(*load)
        }
        _ => bodies(problem, dir).map(|_| ()),
    }
}

/// A rigid indenter's force or approach: positive and finite.
fn check_rigid_load(load: RigidLoad) -> Result<()> {
    let (field, value) = match load {
        RigidLoad::ForceN(f) => ("load.force_n", f),
        RigidLoad::ApproachMm(a) => ("load.approach_mm", a),
    };
    if value > 0.0 && value.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(field, value, "must be positive and finite"))
    }
}

impl Case {
    /// Checks every value without solving and without factorising: the problem's dimensions,
    /// mesh and memory estimate (bodies that factorise nothing are built), the solver and the
    /// controller.
    pub fn check(&self) -> std::result::Result<(), SceneError> {
        self.check_memory()?;
        check_problem(&self.spec.problem, self.dir()).map_err(|e| self.invalid("problem", e))?;
        self.check_without_bodies()
    }

    /// The key of the case's bodies: the canonical form of its problem (the `Debug` form,
    /// exact in every number). Cases with one key share their bodies.
    pub(crate) fn problem_key(&self) -> String {
        format!("{:?}", self.spec.problem)
    }

    /// Builds the case's bodies: assembled, factorised and condensed.
    pub(crate) fn build(&self) -> std::result::Result<Built, SceneError> {
        self.check_memory()?;
        let start = Instant::now();
        let bodies =
            bodies(&self.spec.problem, self.dir()).map_err(|e| self.invalid("problem", e))?;
        Ok(Built {
            bodies,
            took: start.elapsed(),
        })
    }

    /// The checks of [`Case::check`] that do not build the bodies (for a case whose problem
    /// another case has checked).
    pub(crate) fn check_without_bodies(&self) -> std::result::Result<(), SceneError> {
        let spec = &self.spec;
        solver(&spec.solver).map_err(|e| self.invalid("solver", e))?;
        match &spec.problem {
            Problem::Roller { profile, .. } => {
                let needs = match profile {
                    ProfileSpec::Optimised if spec.optimisation.is_none() => {
                        Some(("optimised", "an optimised crown needs [optimisation]"))
                    }
                    ProfileSpec::Robust if spec.optimisation.is_none() => {
                        Some(("robust", "a robust crown needs [optimisation]"))
                    }
                    ProfileSpec::Robust if spec.envelope.is_none() => Some((
                        "robust",
                        "a robust crown needs the [envelope] of load cases it serves",
                    )),
                    _ => None,
                };
                if let Some((kind, why)) = needs {
                    let e = Error::invalid("profile.kind", kind, why);
                    return Err(self.invalid("problem.profile", e));
                }
            }
            _ if spec.envelope.is_some() => {
                let e = Error::invalid("envelope", "given", "only a roller has an envelope");
                return Err(self.invalid("envelope", e));
            }
            _ => {}
        }
        self.dense_limit()?;
        if let Some(sub) = &spec.output.subsurface {
            crate::subsurface::check(sub).map_err(|e| self.invalid("output.subsurface", e))?;
        }
        if let Some(opt) = &spec.optimisation {
            controller(&opt.controller).map_err(|e| self.invalid("optimisation.controller", e))?;
            if let Some(omega_v) = &opt.omega_v {
                omega_v
                    .check()
                    .map_err(|e| self.invalid("optimisation.omega_v", e))?;
            }
        }
        Ok(())
    }

    /// The case's memory estimate against its limit, before anything is built.
    pub(crate) fn check_memory(&self) -> std::result::Result<u64, SceneError> {
        let limit = crate::budget::limit(self.spec.memory_limit_mb)
            .map_err(|e| self.invalid("memory_limit_mb", e))?;
        crate::budget::check(&self.spec, limit).map_err(|e| self.invalid("problem", e))
    }

    /// The folder of the scene file, where the files it names are read.
    fn dir(&self) -> &std::path::Path {
        self.file.parent().unwrap_or(std::path::Path::new("."))
    }

    /// The scene's memory limit for dense matrices \[bytes\].
    fn dense_limit(&self) -> std::result::Result<u64, SceneError> {
        match self.spec.dense_limit_mb {
            None => Ok(contopt_contact::DEFAULT_DENSE_LIMIT_BYTES),
            Some(mb) if mb > 0.0 && mb.is_finite() => Ok((mb * 1e6) as u64),
            Some(mb) => Err(self.invalid(
                "dense_limit_mb",
                Error::invalid("dense_limit_mb", mb, "must be positive and finite"),
            )),
        }
    }

    /// Solves the case. A solver or an optimisation that does not converge gives a report with
    /// `converged: false` and the error; bad input is an error.
    pub fn run(&self) -> std::result::Result<CaseReport, SceneError> {
        self.run_observed(&contopt_core::observe::Silent)
    }

    /// [`Case::run`], reporting each iteration of the contact solves and of the optimisation
    /// to `observer`, which may stop them early (the case then reports `converged: false`).
    pub fn run_observed(
        &self,
        observer: &dyn contopt_core::observe::Observer,
    ) -> std::result::Result<CaseReport, SceneError> {
        self.run_on(&self.build()?, observer)
    }

    /// Runs the case on bodies built for its problem (by this case, or by an earlier case of
    /// the scene with the same problem: its `build` time is then only the interface's).
    pub(crate) fn run_on(
        &self,
        built: &Built,
        observer: &dyn contopt_core::observe::Observer,
    ) -> std::result::Result<CaseReport, SceneError> {
        let spec = &self.spec;
        let solver = solver(&spec.solver).map_err(|e| self.invalid("solver", e))?;
        let dense_limit = self.dense_limit()?;
        self.check_memory()?;
        let mut report = CaseReport::new(&self.label, &self.params);
        let start = Instant::now();
        let bodies = &built.bodies;
        let problem =
            InterfaceProblem::new(bodies.first.as_ref(), bodies.second.as_ref(), &bodies.gap)
                .map_err(|e| self.invalid("problem", e))?
                .with_dense_limit(dense_limit);
        report.timings_ms.insert(
            "build".into(),
            1e3 * (built.took + start.elapsed()).as_secs_f64(),
        );
        let cases = match &bodies.roller {
            Some(info) => crate::envelope::load_cases(&problem, info, spec.envelope.as_ref())
                .map_err(|e| self.invalid("envelope", e))?,
            None => vec![],
        };
        let context = Solve {
            problem: &problem,
            bodies,
            cases: &cases,
            solver: solver.as_ref(),
            observer,
        };
        let (mut report, envelope) = self.design_and_solve(report, &context)?;
        report.settle();
        if let (Some(info), true) = (&bodies.roller, report.converged) {
            self.roller_figures(&mut report, envelope, &context, info);
        }
        if let (Some(sub), true) = (&spec.output.subsurface, report.converged) {
            let started = Instant::now();
            let pressure: Vec<f64> = report.interface.iter().map(|q| q.p).collect();
            report.subsurface = crate::subsurface::compute(
                sub,
                [bodies.first.as_ref(), bodies.second.as_ref()],
                bodies.shared_stresses(),
                &pressure,
                bodies.roller.is_some(),
            )
            .map_err(|e| self.invalid("output.subsurface", e))?;
            report.time("subsurface", started);
        }
        report.reference = crate::reference::curve(spec, &report);
        Ok(report)
    }

    /// The design of [`Case::design`] and the contact under it: the report, and the gap change
    /// a roller's envelope is solved under (or its cases solved already).
    fn design_and_solve(
        &self,
        mut report: CaseReport,
        c: &Solve<'_, '_>,
    ) -> std::result::Result<(CaseReport, Envelope), SceneError> {
        let started = Instant::now();
        let roller = c.bodies.roller.as_ref();
        Ok(match self.design() {
            Design::Contact => {
                let outcome = c
                    .solver
                    .solve_observed(c.problem, None, c.observer)
                    .map_err(|e| self.invalid("solver", e))?
                    .solved(c.solver.name());
                report.time("solve", started);
                let crown = roller.map_or(&[][..], |r| r.crown.as_slice());
                let report = contact_report(report, c.problem, crown, outcome);
                (report, Envelope::Given(vec![0.0; c.problem.len()]))
            }
            Design::Optimised(opt) => {
                let outcome = self.optimise(c.problem, opt, c, None)?;
                report.time("optimise", started);
                match outcome {
                    Ok(found) => {
                        let change = found.optimum.gap_change.clone();
                        let report = optimum_report(report, c.problem, &found.optimum);
                        (report, Envelope::Given(change))
                    }
                    Err(e) => {
                        report.error = Some(e.to_string());
                        (report, Envelope::Given(vec![]))
                    }
                }
            }
            Design::Robust(opt) => {
                let info = roller.ok_or_else(|| self.not_a_roller())?;
                let (report, cases) = self.robust(report, opt, c, info)?;
                (report, Envelope::Solved(cases, None))
            }
            Design::Tuned => {
                let info = roller.ok_or_else(|| self.not_a_roller())?;
                let (report, cases, tuned) = self.tuned(report, c, info)?;
                (report, Envelope::Solved(cases, tuned))
            }
        })
    }

    /// A converged roller case's figures, with its envelope solved under the gap change
    /// (unless the design solved it already).
    fn roller_figures(
        &self,
        report: &mut CaseReport,
        envelope: Envelope,
        c: &Solve<'_, '_>,
        info: &crate::roller::Info,
    ) {
        let mut roller = roller_report(report, info);
        let outcome = match envelope {
            Envelope::Given(change) if self.spec.envelope.is_some() => {
                let started = Instant::now();
                let states =
                    crate::envelope::solve_cases(c.cases, &change, c.solver, None, c.observer);
                report.time("envelope", started);
                states.map(|s| crate::envelope::state_reports(c.cases, &s, info.dy))
            }
            Envelope::Given(_) => Ok(vec![]),
            Envelope::Solved(reports, tuned) => {
                roller.tuned = tuned;
                Ok(reports)
            }
        };
        match outcome {
            Ok(reports) => {
                roller.worst_p_max = self
                    .spec
                    .envelope
                    .is_some()
                    .then(|| reports.iter().map(|c| c.p_max).fold(0.0, f64::max));
                roller.envelope = reports;
            }
            Err(e) => {
                report.converged = false;
                report.error = Some(format!("a case of the envelope: {e}"));
            }
        }
        report.roller = Some(roller);
        report.settle();
    }

    /// What the case designs: nothing (a contact solve), a gap for the scene's load, or a
    /// roller's crown for its envelope (optimised or tuned).
    fn design(&self) -> Design<'_> {
        let opt = self.spec.optimisation.as_ref();
        match (&self.spec.problem, opt) {
            (Problem::Roller { profile, .. }, _) => match (profile, opt) {
                (ProfileSpec::Optimised, Some(opt)) => Design::Optimised(opt),
                (ProfileSpec::Robust, Some(opt)) => Design::Robust(opt),
                (ProfileSpec::FujiwaraKawaseTuned, _) => Design::Tuned,
                _ => Design::Contact,
            },
            (_, Some(opt)) => Design::Optimised(opt),
            (_, None) => Design::Contact,
        }
    }

    fn not_a_roller(&self) -> SceneError {
        self.invalid(
            "problem.profile",
            Error::invalid("problem.kind", "not a roller", "a crown needs a roller"),
        )
    }

    /// The robust crown over the envelope `cases`: the report of the scene's own case (the
    /// first) and of every case.
    fn robust(
        &self,
        mut report: CaseReport,
        opt: &Optimise,
        c: &Solve<'_, '_>,
        info: &crate::roller::Info,
    ) -> std::result::Result<(CaseReport, Vec<EnvelopeCaseReport>), SceneError> {
        let cases = c.cases;
        let started = Instant::now();
        let design = crate::envelope::design_case(cases);
        let others: Vec<InterfaceProblem> = (0..cases.len())
            .filter(|&k| k != design)
            .map(|k| cases[k].problem.clone())
            .collect();
        let outcome = self.optimise(&cases[design].problem, opt, c, Some(&others))?;
        report.time("optimise", started);
        let found = match outcome {
            Ok(found) => found,
            Err(e) => {
                report.error = Some(e.to_string());
                return Ok((report, vec![]));
            }
        };
        let optimum = &found.optimum;
        // The cases' contact in their own order, the design case's from the optimum.
        let mut rest = found.cases.iter();
        let (mut pressures, mut approaches, mut own) = (vec![], vec![], None);
        for k in 0..cases.len() {
            let (p, gap, rigid) = if k == design {
                (&optimum.pressure, &optimum.gap, &optimum.rigid)
            } else {
                match rest.next() {
                    Some(s) => (&s.pressure, &s.gap, &s.rigid),
                    None => break,
                }
            };
            if k == 0 {
                own = Some(Optimum {
                    pressure: p.clone(),
                    gap: gap.clone(),
                    rigid: rigid.clone(),
                    ..optimum.clone()
                });
            }
            pressures.push(p.as_slice());
            approaches.push(-rigid[0]);
        }
        let reports = crate::envelope::reports(cases, &pressures, &approaches, info.dy);
        let own = own.unwrap_or_else(|| optimum.clone());
        Ok((optimum_report(report, &cases[0].problem, &own), reports))
    }

    /// The Fujiwara–Kawase profile tuned for the envelope `cases`: the report of the scene's
    /// own case under it, the cases' reports and the parameters; a contact solve that does not
    /// converge during the search leaves the report unconverged, with its error.
    fn tuned(
        &self,
        mut report: CaseReport,
        c: &Solve<'_, '_>,
        info: &crate::roller::Info,
    ) -> std::result::Result<(CaseReport, Vec<EnvelopeCaseReport>, Option<TunedProfile>), SceneError>
    {
        let cases = c.cases;
        let started = Instant::now();
        let outcome = crate::envelope::tune_fujiwara_kawase(cases, info, c.solver, c.observer);
        report.time("tune", started);
        match outcome {
            Ok((tuned, drop, states)) => {
                let reports = crate::envelope::state_reports(cases, &states, info.dy);
                let own = states.into_iter().next();
                let own = own.ok_or_else(|| Error::invalid("envelope", "no case", "one case"));
                let report = contact_report(report, &cases[0].problem, &drop, own);
                Ok((report, reports, Some(tuned)))
            }
            Err(e @ Error::NotConverged { .. }) => {
                report.error = Some(e.to_string());
                Ok((report, vec![], None))
            }
            Err(e) => Err(self.invalid("problem.profile", e)),
        }
    }

    /// Runs the optimisation `opt` of `problem`: the optimum, or the error of a method that did
    /// not converge; bad input is a scene error. A roller's Ω_v defaults to its centre row and
    /// its profile to the axis. With `envelope`, the further cases of a robust crown, the
    /// profile is symmetric and found by the envelope load split.
    fn optimise(
        &self,
        problem: &InterfaceProblem,
        opt: &Optimise,
        c: &Solve<'_, '_>,
        envelope: Option<&[InterfaceProblem]>,
    ) -> std::result::Result<std::result::Result<EnvelopeOptimum, Error>, SceneError> {
        let (solver, roller) = (c.solver, c.bodies.roller.as_ref());
        let v =
            controller(&opt.controller).map_err(|e| self.invalid("optimisation.controller", e))?;
        let iface = problem.interface();
        let axis = opt.profile_axis.or(roller.map(|_| 0));
        let shape = match (axis, problem.pressure_basis()) {
            (Some(axis), _) if envelope.is_some() => GapShape::symmetric(iface, axis),
            (Some(axis), _) => GapShape::extruded(iface, axis),
            (None, Some(basis)) => Ok(basis.clone()),
            (None, None) => Ok(GapShape::pointwise(iface)),
        }
        .map_err(|e| self.invalid("optimisation.profile_axis", e))?;
        let mut optimisation = Optimisation::new(problem, &shape, v.as_ref())
            .map_err(|e| self.invalid("optimisation", e))?
            .with_observer(c.observer);
        let omega_v = opt.omega_v.or(roller.map(|r| OmegaVSpec::Strip {
            axis: 1,
            from_mm: -0.5 * r.dy,
            to_mm: 0.5 * r.dy,
        }));
        if let Some(omega_v) = omega_v {
            omega_v
                .check()
                .map_err(|e| self.invalid("optimisation.omega_v", e))?;
            optimisation = optimisation
                .with_regions(regions(&omega_v, iface))
                .map_err(|e| self.invalid("optimisation.omega_v", e))?;
        }
        match run_mode(&optimisation, opt, solver, envelope) {
            Err(e @ Error::NotConverged { .. }) => Ok(Err(e)),
            Err(e) => Err(self.invalid("optimisation", e)),
            Ok(optimum) => Ok(Ok(optimum)),
        }
    }
}

/// Each interface point's region: Ω_v inside `omega_v`, Ω_nv outside.
fn regions(omega_v: &OmegaVSpec, iface: &contopt_core::Interface) -> Vec<Region> {
    (iface.points.iter().zip(&iface.normals))
        .map(|(&x, &normal)| {
            if omega_v.contains(x, normal) {
                Region::OmegaV
            } else {
                Region::OmegaNv
            }
        })
        .collect()
}

/// Runs the optimisation's mode (with `envelope`, a robust crown's load split).
fn run_mode(
    optimisation: &Optimisation,
    opt: &Optimise,
    solver: &dyn ContactSolver,
    envelope: Option<&[InterfaceProblem]>,
) -> Result<EnvelopeOptimum> {
    let single = |outcome: Result<Optimum>| {
        outcome.map(|optimum| EnvelopeOptimum {
            optimum,
            cases: vec![],
        })
    };
    match (opt.mode, envelope) {
        (ModeSpec::LoadSplit, Some(cases)) => {
            optimisation.envelope_split(cases, solver, opt.tolerance, opt.max_iterations)
        }
        (mode, Some(_)) => Err(Error::invalid(
            "optimisation.mode",
            format!("{mode:?}"),
            "a robust crown is found by the load split: mode = \"load_split\"",
        )),
        (ModeSpec::GivenLoad, None) => {
            single(optimisation.iterate(Mode::GivenLoad, solver, opt.tolh_mm2, opt.max_iterations))
        }
        (ModeSpec::GivenDisplacement, None) => single(optimisation.iterate(
            Mode::GivenDisplacement,
            solver,
            opt.tolh_mm2,
            opt.max_iterations,
        )),
        (ModeSpec::LinearProgramme, None) => single(optimisation.linear_programme(solver)),
        (ModeSpec::LoadSplit, None) => {
            single(optimisation.load_split(solver, opt.tolerance, opt.max_iterations))
        }
    }
}

/// The report of a contact solve: the points with their pressure, gap and `dh` (a roller's
/// crown, or nothing).
fn contact_report(
    mut report: CaseReport,
    problem: &InterfaceProblem,
    dh: &[f64],
    outcome: Result<contopt_core::ContactState>,
) -> CaseReport {
    match outcome {
        Ok(state) => {
            report.converged = true;
            report.approach_um = state.rigid.first().map(|l| -1e3 * l);
            let points_x = &problem.interface().points;
            report.interface = points(points_x, &state.pressure, &state.gap, dh);
            let elastic = problem.elastic_displacement(&state.gap, &state.rigid);
            penetration(&mut report, elastic);
        }
        Err(e) => report.error = Some(e.to_string()),
    }
    report
}

/// The report's largest penetration, and a warning when it exceeds [`PENETRATION_WARNING`] of
/// the largest elastic displacement `elastic` \[mm\].
fn penetration(report: &mut CaseReport, elastic: f64) {
    let largest = report.interface.iter().fold(0.0f64, |m, q| m.max(-q.d));
    report.penetration_um = Some(1e3 * largest);
    if largest > PENETRATION_WARNING * elastic {
        let share = if elastic > 0.0 {
            format!("{:.2} % of", 100.0 * largest / elastic)
        } else {
            "more than".to_string()
        };
        report.warnings.push(format!(
            "the solution penetrates by {largest:.3e} mm, {share} its largest elastic \
             displacement ({elastic:.3e} mm): raise the penalty parameter solver.c (the paper \
             takes E·10⁴) or use an exact solver"
        ));
    }
}

/// A roller's figures from a converged report.
fn roller_report(report: &CaseReport, info: &crate::roller::Info) -> crate::RollerReport {
    let points: Vec<[f64; 3]> = report.interface.iter().map(|q| q.x).collect();
    let p: Vec<f64> = report.interface.iter().map(|q| q.p).collect();
    let dh: Vec<f64> = report.interface.iter().map(|q| q.dh).collect();
    crate::roller::report(&points, &p, &dh, info.dy)
}

fn points(x: &[[f64; 3]], p: &[f64], d: &[f64], dh: &[f64]) -> Vec<PointReport> {
    (0..x.len())
        .map(|i| PointReport {
            x: x[i],
            p: p[i],
            d: d[i],
            dh: dh.get(i).copied().unwrap_or(0.0),
        })
        .collect()
}

fn optimum_report(
    mut report: CaseReport,
    problem: &InterfaceProblem,
    optimum: &Optimum,
) -> CaseReport {
    report.converged = true;
    report.bound_p_max = Some(optimum.p_max);
    report.approach_um = optimum.rigid.first().map(|l| -1e3 * l);
    report.dh_max_um = Some(1e3 * optimum.dh_max());
    report.iterations = optimum
        .iterations
        .iter()
        .map(|r| IterationRow {
            k: r.k,
            bound_p_max: r.p_max,
            dh_max_um: 1e3 * r.dh_max,
            tolh: r.tolh,
            iterp: r.iterp,
            iterd: r.iterd,
        })
        .collect();
    report.interface = points(
        &problem.interface().points,
        &optimum.pressure,
        &optimum.gap,
        &optimum.gap_change,
    );
    let elastic_gap: Vec<f64> = report.interface.iter().map(|q| q.d - q.dh).collect();
    penetration(
        &mut report,
        problem.elastic_displacement(&elastic_gap, &optimum.rigid),
    );
    report
}
