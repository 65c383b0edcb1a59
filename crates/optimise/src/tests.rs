//! The optimisation loops, their events and how they end, on a rigid strip of half-width 5 mm
//! pressed into a plane-stress half-plane under a constant-pressure controller (p_max = force /
//! area), and on a rigid sphere pressed into rings of an axisymmetric half-space.

use std::cell::RefCell;
use std::f64::consts::PI;

use contopt_contact::{
    ActiveSet, ActiveSetSettings, ContactSolver, InterfaceProblem, PolonskyKeer,
    PolonskyKeerSettings, Workspace,
};
use contopt_core::observe::{Event, Flow, Method, Observer, Recorded};
use contopt_core::{ElasticBody, GapShape, Material, RigidBody, Termination};
use contopt_greens::{AxisymmetricHalfSpace, HalfPlane, PlaneState};

use crate::{
    Controller, IterationSettings, LinearProgrammeSettings, LoadSplitSettings, Mode, Optimisation,
    OptimisationMethod, Optimum, Profile, Reference,
};

/// The constant-pressure controller, v = 1.
pub(crate) const CONSTANT: fn([f64; 3]) -> f64 = |_| 1.0;

/// Half-width a \[mm\], pressure p \[MPa\] and thickness b \[mm\] of the strip.
const A: f64 = 5.0;
const P: f64 = 100.0;
const B: f64 = 10.0;

/// Young's modulus \[MPa\] and Poisson's ratio of the paper's steel.
const E: f64 = 2e5;
const NU: f64 = 0.3;

pub(crate) fn active_set() -> ActiveSet {
    ActiveSet::new(ActiveSetSettings::default()).unwrap()
}

/// Iterations to a TOLH far below round-off, so that the loop closes on its second pass.
fn tight(max_iterations: usize) -> IterationSettings {
    IterationSettings {
        tolh_mm2: 1e-20,
        max_iterations,
    }
}

fn half_plane() -> HalfPlane {
    let n = 40;
    let edges: Vec<f64> = (0..=n)
        .map(|k| -A * (PI * k as f64 / n as f64).cos())
        .collect();
    let material = Material::new(E, NU).unwrap();
    HalfPlane::new("half-plane", material, PlaneState::Stress, B, &edges, 100.0).unwrap()
}

/// Runs `run` on the strip's optimisation under `controller`, observed by `observer`.
fn with_strip<T>(
    controller: &dyn Controller,
    observer: &dyn Observer,
    run: impl FnOnce(&Optimisation) -> T,
) -> T {
    let body = half_plane();
    let force = P * 2.0 * A * B;
    let strip = RigidBody::pressed("strip", body.interface(), [0.0, 1.0, 0.0], force).unwrap();
    let problem = InterfaceProblem::new(&body, &strip, &vec![0.0; body.interface().len()]).unwrap();
    let shape = GapShape::pointwise(body.interface());
    let optimisation = Optimisation::new(&problem, &shape, controller)
        .unwrap()
        .with_observer(observer);
    run(&optimisation)
}

/// Records every event, and stops the level-0 loop after `stop_after` passes.
#[derive(Default)]
struct Recorder {
    events: RefCell<Vec<Recorded>>,
    stop_after: Option<usize>,
}

impl Recorder {
    /// The events at `level` that go on (not a method's last).
    fn steps(&self, level: usize) -> Vec<Recorded> {
        let events = self.events.borrow();
        let at = events
            .iter()
            .filter(|e| e.level == level && e.end.is_none());
        at.cloned().collect()
    }

    /// The last event at level 0: how the loop ended.
    fn end(&self) -> Recorded {
        let events = self.events.borrow();
        let mut ends = events.iter().filter(|e| e.level == 0 && e.end.is_some());
        ends.next_back().cloned().expect("the loop's last event")
    }
}

impl Observer for Recorder {
    fn observe(&self, e: &Event) -> Flow {
        self.events.borrow_mut().push(Recorded::of(e));
        match self.stop_after {
            Some(k) if e.level == 0 && e.iteration >= k => Flow::Stop,
            _ => Flow::Continue,
        }
    }
}

/// The iteration of §3.2 reports each pass at level 0 with its TOLH, one event per row of
/// the optimum, its contact solves at level 1, and a last event whose termination is the
/// optimum's; the optimum is the equilibrium pressure.
#[test]
fn iteration_reports_every_pass_and_its_end() {
    let recorder = Recorder::default();
    let optimum = with_strip(&CONSTANT, &recorder, |opt| {
        opt.iterate(Mode::GivenLoad, &active_set(), &tight(10))
            .unwrap()
    });
    assert_eq!(optimum.termination, Termination::Converged);
    assert!((optimum.p_max / P - 1.0).abs() < 1e-9, "{}", optimum.p_max);
    let steps = recorder.steps(0);
    assert_eq!(steps.len(), optimum.passes.len());
    for (seen, row) in steps.iter().zip(&optimum.passes) {
        assert_eq!(seen.method, Method::GapIteration);
        assert_eq!(
            (seen.iteration, seen.measure, seen.tolerance),
            (row.k, row.tolh, 1e-20)
        );
    }
    let inner = recorder.steps(1);
    assert!(!inner.is_empty() && inner.iter().all(|e| e.method == Method::ActiveSet));
    let end = recorder.end();
    assert_eq!(end.method, Method::GapIteration);
    assert_eq!(end.end, Some(optimum.termination.clone()));
    assert_eq!(optimum.method, Method::GapIteration);
}

/// An observer that stops the loop after its first pass ends it with Stopped after one pass,
/// as an outcome: the optimum holds the first pass's contact solution, without a gap change.
#[test]
fn stop_after_one_pass_is_an_outcome() {
    let recorder = Recorder {
        stop_after: Some(1),
        ..Recorder::default()
    };
    let optimum = with_strip(&CONSTANT, &recorder, |opt| {
        opt.iterate(Mode::GivenLoad, &active_set(), &tight(10))
            .unwrap()
    });
    assert_eq!(optimum.termination, Termination::Stopped { after: 1 });
    assert_eq!(optimum.passes.len(), 1);
    assert!(optimum.gap_change.iter().all(|&c| c == 0.0));
    assert!(optimum.pressure.iter().all(|p| p.is_finite()));
    assert_eq!(recorder.end().end, Some(optimum.termination));
}

/// The active set, its every solve marked as stopped at a step limit.
struct Failing;

impl ContactSolver for Failing {
    fn method(&self) -> Method {
        Method::ActiveSet
    }

    fn dense_copies(&self, points: usize) -> u64 {
        active_set().dense_copies(points)
    }

    fn solve_in(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        observer: &dyn Observer,
        workspace: &mut Workspace,
    ) -> contopt_core::Result<contopt_core::ContactState> {
        let mut state = active_set().solve_in(problem, start, observer, workspace)?;
        state.termination = Termination::StepLimit {
            steps: state.iterp,
            measure: 1.0,
            tolerance: 0.0,
        };
        Ok(state)
    }
}

/// A step limit is an outcome with the last TOLH; so is a contact solve that stops short,
/// seen as Inner of the solver's method, the first solve's own state held without a gap
/// change.
#[test]
fn step_limits_and_inner_failures_are_outcomes() {
    let optimum = with_strip(&CONSTANT, &Recorder::default(), |opt| {
        opt.iterate(Mode::GivenLoad, &active_set(), &tight(1))
            .unwrap()
    });
    match &optimum.termination {
        Termination::StepLimit {
            steps,
            measure,
            tolerance,
        } => {
            assert_eq!((*steps, *tolerance), (1, 1e-20));
            assert_eq!(*measure, optimum.passes[0].tolh);
        }
        other => panic!("{other}"),
    }
    let short = PolonskyKeer::new(PolonskyKeerSettings {
        max_steps: 1,
        ..PolonskyKeerSettings::default()
    })
    .unwrap();
    let recorder = Recorder::default();
    let optimum = with_strip(&CONSTANT, &recorder, |opt| {
        opt.iterate(Mode::GivenLoad, &short, &tight(10)).unwrap()
    });
    match &optimum.termination {
        Termination::Inner {
            method,
            termination,
        } => {
            assert_eq!(*method, Method::PolonskyKeer);
            assert!(matches!(**termination, Termination::StepLimit { .. }));
        }
        other => panic!("{other}"),
    }
    assert!(optimum.passes.is_empty() && optimum.dh.iter().all(|&d| d == 0.0));
    assert!(optimum.pressure.iter().all(|p| p.is_finite()));
    assert_eq!(recorder.end().end, Some(optimum.termination.clone()));
    let split = with_strip(&CONSTANT, &Recorder::default(), |opt| {
        opt.load_split(&Failing, &LoadSplitSettings::default())
            .unwrap()
    });
    assert!(
        matches!(
            split.termination,
            Termination::Inner {
                method: Method::ActiveSet,
                ..
            }
        ),
        "{}",
        split.termination
    );
}

/// The load split reports each update with its miss of v·p_max against the tolerance, one
/// event per row, and stops when asked to; the linear programme reports its passes, the last
/// with no point carrying pressure across an open gap.
#[test]
fn load_split_and_programme_report() {
    let recorder = Recorder::default();
    let settings = LoadSplitSettings {
        tolerance: 1e-6,
        max_iterations: 50,
    };
    let optimum = with_strip(&CONSTANT, &recorder, |opt| {
        opt.load_split(&active_set(), &settings).unwrap()
    });
    assert!(optimum.is_converged(), "{}", optimum.termination);
    assert!((optimum.p_max / P - 1.0).abs() < 1e-5, "{}", optimum.p_max);
    let steps = recorder.steps(0);
    assert_eq!(steps.len(), optimum.passes.len());
    let last = steps.last().unwrap();
    assert_eq!(last.method, Method::LoadSplit);
    assert!(
        last.measure <= last.tolerance && last.tolerance == 1e-6,
        "{steps:?}"
    );

    let stopper = Recorder {
        stop_after: Some(1),
        ..Recorder::default()
    };
    // Under a falling controller the first shares (F ∝ L v²) miss, so the split needs more
    // than one update.
    let falling = Profile::trapezoid(0.0, 2.0 * A).unwrap();
    let tight_split = LoadSplitSettings {
        tolerance: 1e-12,
        max_iterations: 50,
    };
    let stopped = with_strip(&falling, &stopper, |opt| {
        opt.load_split(&active_set(), &tight_split).unwrap()
    });
    assert_eq!(stopped.termination, Termination::Stopped { after: 1 });
    assert_eq!(stopper.end().end, Some(stopped.termination.clone()));

    let recorder = Recorder::default();
    let optimum = with_strip(&CONSTANT, &recorder, |opt| {
        let method = OptimisationMethod::LinearProgramme(LinearProgrammeSettings::default());
        method.run(opt, &active_set()).unwrap()
    });
    assert!(optimum.is_converged());
    let steps = recorder.steps(0);
    assert_eq!(steps.len(), optimum.passes.last().unwrap().k);
    assert_eq!(steps.last().map(|r| r.measure), Some(0.0));
    assert_eq!(recorder.end().method, Method::LinearProgramme);
}

/// Bad settings are errors naming the field, before any solve.
#[test]
fn bad_settings_are_named() {
    let e = with_strip(&CONSTANT, &Recorder::default(), |opt| {
        let bad = IterationSettings {
            tolh_mm2: -1.0,
            max_iterations: 10,
        };
        opt.iterate(Mode::GivenLoad, &active_set(), &bad)
            .unwrap_err()
            .to_string()
    });
    assert!(e.contains("invalid tolh_mm2 = -1"), "{e}");
    let e = with_strip(&CONSTANT, &Recorder::default(), |opt| {
        let bad = LinearProgrammeSettings {
            max_passes: 0,
            ..LinearProgrammeSettings::default()
        };
        opt.linear_programme(&active_set(), &bad)
            .unwrap_err()
            .to_string()
    });
    assert!(e.contains("invalid max_passes = 0"), "{e}");
}

/// Rings of an axisymmetric half-space to radius `radius`, clustered at the rim.
fn rings(radius: f64, n: usize) -> AxisymmetricHalfSpace {
    let edges: Vec<f64> = (0..=n)
        .map(|k| radius * (0.5 * PI * k as f64 / n as f64).sin())
        .collect();
    AxisymmetricHalfSpace::new("half-space", Material::new(E, NU).unwrap(), &edges).unwrap()
}

/// The sphere's radius \[mm\]: its gap at the rim, a²/2R = 50 µm, is fifteen times the
/// deflection difference of a uniform pressure, so the gap change is least at the rim.
const SPHERE_RADIUS: f64 = 1000.0;

/// Δh_max of a rigid flat punch under a uniform pressure p on a circle of radius a,
/// 4(1 − ν²) p a (π/2 − 1)/(π E) (Timoshenko & Goodier §138: the deflection at the centre
/// less that at the rim).
fn centre_minus_rim(p: f64, a: f64) -> f64 {
    4.0 * (1.0 - NU * NU) * p * a * (0.5 * PI - 1.0) / (PI * E)
}

/// A rigid sphere pressed by p·πa² into 120 rings to radius a = 10 mm, pointwise gap shape,
/// v = 1: `run` on its optimisation with `reference`.
pub(crate) fn with_sphere<T>(
    reference: Reference,
    run: impl FnOnce(&Optimisation, &[f64]) -> T,
) -> T {
    let (a, n) = (10.0, 120);
    let body = rings(a, n);
    let force = P * PI * a * a;
    let sphere = RigidBody::pressed("sphere", body.interface(), [0.0, 1.0, 0.0], force).unwrap();
    let h0: Vec<f64> = body
        .interface()
        .points()
        .iter()
        .map(|x| x[0] * x[0] / (2.0 * SPHERE_RADIUS))
        .collect();
    let problem = InterfaceProblem::new(&body, &sphere, &h0).unwrap();
    let shape = GapShape::pointwise(body.interface());
    let optimisation = Optimisation::new(&problem, &shape, &CONSTANT)
        .unwrap()
        .with_reference(reference)
        .unwrap();
    run(&optimisation, &h0)
}

/// The optimum of the centred sphere: uniform pressure p, Δh ≥ 0 with min Δh = 0, and the
/// optimised initial gap h₀ + Δh that of a flat punch, rim less centre = the closed form
/// within 0.5 % (the rings' discretisation, as for the flat punch).
fn assert_flat_punch(name: &str, optimum: &Optimum, h0: &[f64]) {
    assert!(optimum.is_converged(), "{name}: {}", optimum.termination);
    assert!(
        (optimum.p_max / P - 1.0).abs() < 1e-6,
        "{name}: {}",
        optimum.p_max
    );
    let least = optimum.dh.iter().fold(f64::INFINITY, |m, &v| m.min(v));
    assert_eq!(least, 0.0, "{name}");
    let total: Vec<f64> = h0
        .iter()
        .zip(&optimum.gap_change)
        .map(|(h, d)| h + d)
        .collect();
    let rise = total[total.len() - 1] - total[0];
    let exact = centre_minus_rim(P, 10.0);
    eprintln!(
        "sphere on rings, {name}: rim − centre of h₀ + Δh {:+.3} % from the closed form, \
         Δh_max {:.3} µm",
        100.0 * (rise / exact - 1.0),
        1e3 * optimum.dh_max()
    );
    assert!(
        (rise / exact - 1.0).abs() < 0.005,
        "{name}: {rise} vs {exact}"
    );
    let dp = optimum
        .pressure
        .iter()
        .map(|p| (p / P - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(dp < 1e-5, "{name}: {dp}");
}

/// The old failing case: a rigid sphere centred on rings under a given load with v = 1. With
/// the reference at the centre (the old default, the node nearest the axis) the gap change
/// comes out negative at the rim and is refused as an invalid reference (the iteration) or
/// found infeasible (the programme, with Δh ≥ 0); with the reference where it is least (the
/// default) the iteration, the programme and the load split find the flat punch's closed form.
#[test]
fn centred_sphere_optimises_to_the_closed_form() {
    let solver = active_set();
    let e = with_sphere(Reference::Node(0), |opt, _| {
        opt.iterate(Mode::GivenLoad, &solver, &tight(10))
            .unwrap_err()
            .to_string()
    });
    assert!(e.contains("invalid reference"), "{e}");
    let lp = with_sphere(Reference::Node(0), |opt, _| {
        opt.linear_programme(&solver, &LinearProgrammeSettings::default())
            .unwrap()
    });
    assert!(
        matches!(lp.termination, Termination::Infeasible { .. }),
        "{}",
        lp.termination
    );
    assert!(lp.pressure.iter().all(|p| p.is_finite()));
    with_sphere(Reference::Least, |opt, h0| {
        let iterated = opt.iterate(Mode::GivenLoad, &solver, &tight(10)).unwrap();
        assert_flat_punch("iteration", &iterated, h0);
        let lp = opt
            .linear_programme(&solver, &LinearProgrammeSettings::default())
            .unwrap();
        assert_flat_punch("LP", &lp, h0);
        let settings = LoadSplitSettings {
            tolerance: 1e-9,
            max_iterations: 100,
        };
        let split = opt.load_split(&solver, &settings).unwrap();
        assert_flat_punch("load split", &split, h0);
        // The shifted approaches keep each optimum's gap that of its contact solution.
        for o in [&iterated, &lp, &split] {
            let gap = opt.problem.gap(&o.pressure, &o.rigid);
            let dg = gap
                .iter()
                .zip(&o.gap_change)
                .zip(&o.gap)
                .map(|((g, c), d)| (g + c - d).abs())
                .fold(0.0, f64::max);
            assert!(dg < 1e-9, "{dg:e}");
        }
    });
}

/// Ω_opt an inner disc (r < 6 mm) of the sphere's rings to 10 mm: the pressure is uniform on
/// it, the outer points keep their gap (no gap change there, their design nodes at 0) and are
/// only in contact (p ≥ 0, d ≥ 0, pd = 0), and the load is carried; the iteration and the
/// programme agree.
#[test]
fn omega_opt_from_a_mask() {
    let solver = active_set();
    with_sphere(Reference::Least, |opt, _| {
        let points = opt.problem.interface().points();
        let inner: Vec<bool> = points.iter().map(|x| x[0] < 6.0).collect();
        let masked = Optimisation::new(opt.problem, opt.shape.as_ref(), &CONSTANT)
            .unwrap()
            .with_omega(&inner, &inner)
            .unwrap();
        let iterated = masked
            .iterate(Mode::GivenLoad, &solver, &tight(20))
            .unwrap();
        let lp = masked
            .linear_programme(&solver, &LinearProgrammeSettings::default())
            .unwrap();
        for (name, o) in [("iteration", &iterated), ("LP", &lp)] {
            assert!(o.is_converged(), "{name}: {}", o.termination);
            let w = opt.problem.weights();
            let load: f64 = o.pressure.iter().zip(w).map(|(p, w)| p * w).sum();
            assert!(
                (load / (P * PI * 100.0) - 1.0).abs() < 1e-6,
                "{name}: {load}"
            );
            for (i, &inside) in inner.iter().enumerate() {
                if inside {
                    assert!((o.pressure[i] / o.p_max - 1.0).abs() < 1e-5, "{name} {i}");
                    continue;
                }
                assert_eq!((o.gap_change[i], o.dh[i]), (0.0, 0.0), "{name} {i}");
                let (p, d) = (o.pressure[i], o.gap[i]);
                assert!(
                    p >= 0.0 && d > -1e-9 && (p * d).abs() < 1e-6,
                    "{name} {i}: {p} {d}"
                );
            }
            assert_eq!(o.dh.iter().fold(f64::INFINITY, |m, &v| m.min(v)), 0.0);
        }
        let ratio = iterated.p_max / lp.p_max;
        assert!(
            (ratio - 1.0).abs() < 1e-4,
            "{} vs {}",
            iterated.p_max,
            lp.p_max
        );
        let e = masked
            .load_split(&solver, &LoadSplitSettings::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("outside Ω_opt"), "{e}");
        let e = Optimisation::new(opt.problem, opt.shape.as_ref(), &CONSTANT)
            .unwrap()
            .with_omega(&vec![true; points.len()], &inner)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("omega_v["), "{e}");
    });
}

/// Under a given displacement (the strip pushed 10 µm into the half-plane, Table 2's case)
/// with the cubic controller of Tables 1–3, the gap change is least at the middle, so the
/// default reference gives what the middle node as reference gives (the old default).
#[test]
fn given_displacement_least_is_the_middle() {
    let body = half_plane();
    let strip = RigidBody::fixed("strip", body.interface());
    let n = body.interface().len();
    let problem = InterfaceProblem::new(&body, &strip, &vec![-0.01; n]).unwrap();
    let shape = GapShape::pointwise(body.interface());
    let cubic = Profile::cubic(2.0, A).unwrap();
    let middle = (0..n)
        .min_by(|&a, &b| {
            let x = body.interface().points();
            x[a][0].abs().total_cmp(&x[b][0].abs())
        })
        .unwrap();
    let run = |reference| {
        Optimisation::new(&problem, &shape, &cubic)
            .unwrap()
            .with_reference(reference)
            .unwrap()
            .iterate(
                Mode::GivenDisplacement,
                &active_set(),
                &IterationSettings::default(),
            )
            .unwrap()
    };
    let (least, node) = (run(Reference::Least), run(Reference::Node(middle)));
    assert!(least.is_converged() && node.is_converged());
    assert_eq!(least.passes.len(), node.passes.len());
    assert!(
        (least.p_max / node.p_max - 1.0).abs() < 1e-9,
        "{} {}",
        least.p_max,
        node.p_max
    );
    let ddh = least
        .dh
        .iter()
        .zip(&node.dh)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(ddh < 1e-9 * node.dh_max(), "{ddh:e}");
}
