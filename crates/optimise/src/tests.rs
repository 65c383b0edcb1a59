//! The optimisation loop and its observer, on a rigid strip of half-width 5 mm pressed into a
//! plane-stress half-plane under a constant-pressure controller (p_max = force / area).

use std::cell::{Cell, RefCell};

use contopt_contact::{ActiveSet, ContactSolver, InterfaceProblem};
use contopt_core::observe::{Flow, Iteration as Report, Observer};
use contopt_core::{ContactState, ElasticBody, Error, GapShape, Material, Result, RigidBody};
use contopt_greens::{HalfPlane, PlaneState};

use crate::{Controller, Mode, Optimisation, Profile};

/// The constant-pressure controller, v = 1.
const CONSTANT: fn([f64; 3]) -> f64 = |_| 1.0;

/// Half-width a \[mm\], pressure p \[MPa\] and thickness b \[mm\] of the strip.
const A: f64 = 5.0;
const P: f64 = 100.0;
const B: f64 = 10.0;

fn half_plane() -> HalfPlane {
    let n = 40;
    let edges: Vec<f64> = (0..=n)
        .map(|k| -A * (std::f64::consts::PI * k as f64 / n as f64).cos())
        .collect();
    let material = Material::new(2e5, 0.3).unwrap();
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

/// Records the reports of the loop ("optimisation") and counts the others.
#[derive(Default)]
struct Recorder {
    loop_reports: RefCell<Vec<(usize, f64, f64)>>,
    inner: Cell<usize>,
    /// Stop the loop after this many passes.
    stop_after: Option<usize>,
}

impl Observer for Recorder {
    fn observe(&self, it: &Report) -> Flow {
        if it.method != "optimisation" {
            self.inner.set(self.inner.get() + 1);
            return Flow::Continue;
        }
        self.loop_reports
            .borrow_mut()
            .push((it.iteration, it.measure, it.tolerance));
        match self.stop_after {
            Some(k) if it.iteration >= k => Flow::Stop,
            _ => Flow::Continue,
        }
    }
}

/// A contact solver that reports one iteration of its own to the observer it is given, then
/// solves by the active set: it shows which observer the loop hands its contact solves.
struct Reporting;

impl ContactSolver for Reporting {
    fn name(&self) -> &str {
        "reporting"
    }

    fn solve(&self, problem: &InterfaceProblem) -> Result<ContactState> {
        ActiveSet.solve(problem)
    }

    fn solve_observed(
        &self,
        problem: &InterfaceProblem,
        _start: Option<&[f64]>,
        observer: &dyn Observer,
    ) -> Result<ContactState> {
        let it = Report {
            method: "reporting",
            iteration: 1,
            measure: 0.0,
            tolerance: 0.0,
        };
        let _ = observer.observe(&it);
        ActiveSet.solve(problem)
    }
}

/// The iteration of §3.2 reports each pass with its TOLH, one report per row of the optimum,
/// and hands the observer to its contact solves (one per pass); the optimum is the
/// equilibrium pressure.
#[test]
fn iteration_reports_every_pass() {
    let recorder = Recorder::default();
    let optimum = with_strip(&CONSTANT, &recorder, |opt| {
        opt.iterate(Mode::GivenLoad, &Reporting, 1e-20, 10).unwrap()
    });
    assert!((optimum.p_max / P - 1.0).abs() < 1e-9, "{}", optimum.p_max);
    let reports = recorder.loop_reports.borrow();
    assert_eq!(reports.len(), optimum.iterations.len());
    for (report, row) in reports.iter().zip(&optimum.iterations) {
        assert_eq!(*report, (row.k, row.tolh, 1e-20));
    }
    assert_eq!(recorder.inner.get(), optimum.iterations.len());
}

/// An observer that stops the loop after its first pass ends it with NotConverged after one
/// iteration, saying why.
#[test]
fn stop_after_one_pass() {
    let recorder = Recorder {
        stop_after: Some(1),
        ..Recorder::default()
    };
    let err = with_strip(&CONSTANT, &recorder, |opt| {
        opt.iterate(Mode::GivenLoad, &ActiveSet, 1e-20, 10)
            .unwrap_err()
    });
    match err {
        Error::NotConverged {
            iterations, detail, ..
        } => {
            assert_eq!(iterations, 1);
            assert!(detail.contains("stopped by an observer"), "{detail}");
        }
        other => panic!("{other}"),
    }
    assert_eq!(recorder.loop_reports.borrow().len(), 1);
}

/// The load split reports each update with its miss of v·p_max against the tolerance, one
/// report per row, and stops when asked to; the linear programme reports its passes, the last
/// with no point carrying pressure across an open gap.
#[test]
fn load_split_and_programme_report() {
    let recorder = Recorder::default();
    let optimum = with_strip(&CONSTANT, &recorder, |opt| {
        opt.load_split(&ActiveSet, 1e-6, 50).unwrap()
    });
    assert!((optimum.p_max / P - 1.0).abs() < 1e-5, "{}", optimum.p_max);
    let reports = recorder.loop_reports.borrow().clone();
    assert_eq!(reports.len(), optimum.iterations.len());
    let (_, miss, tolerance) = *reports.last().unwrap();
    assert!(miss <= tolerance && tolerance == 1e-6, "{reports:?}");

    let stopper = Recorder {
        stop_after: Some(1),
        ..Recorder::default()
    };
    // Under a falling controller the first shares (F ∝ L v²) miss, so the split needs more
    // than one update.
    let falling = Profile::trapezoid(0.0, 2.0 * A).unwrap();
    let err = with_strip(&falling, &stopper, |opt| {
        opt.load_split(&ActiveSet, 1e-12, 50)
    })
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("in 1 iterations") && err.contains("stopped by an observer"),
        "{err}"
    );

    let recorder = Recorder::default();
    let optimum = with_strip(&CONSTANT, &recorder, |opt| {
        opt.linear_programme(&ActiveSet).unwrap()
    });
    let reports = recorder.loop_reports.borrow();
    assert_eq!(reports.len(), optimum.iterations[0].k);
    assert_eq!(reports.last().map(|r| r.1), Some(0.0));
}
