//! The progress of a run on stderr: a bar over the scene's cases, with the current case, the
//! optimisation's step and the contact solver's iteration, from the observer each case runs
//! under. Hidden when stderr is not a terminal (indicatif draws nothing there) and with
//! `--quiet`; cleared when the run ends.

use std::cell::{Cell, RefCell};
use std::time::Duration;

use contopt_core::observe::{Flow, Iteration, Observer};
use contopt_scene::Case;
use indicatif::{ProgressBar, ProgressStyle};

/// How often the bar redraws while a case runs, so that the elapsed time moves on.
const TICK: Duration = Duration::from_millis(200);

/// The bar: `[00:00:12] ███████░░░░ 3/5 cases  L1 = 30 mm · optimisation step 4 ·
/// polonsky_keer iteration 127`.
const TEMPLATE: &str = "[{elapsed_precise}] {bar:24} {pos}/{len} cases  {wide_msg}";

/// The progress bar over a scene's cases, and the observer of each case's iterations.
pub struct Progress {
    bar: ProgressBar,
    case: RefCell<String>,
    /// The outer method (the optimisation, a roller's crown search) and its step.
    step: Cell<(&'static str, usize)>,
    /// The contact solver that reported last, and its iteration.
    solver: RefCell<(String, usize)>,
}

impl Progress {
    /// A bar on stderr, its length set by [`Progress::cases`]; hidden when `quiet`.
    pub fn new(quiet: bool) -> Self {
        let bar = if quiet {
            ProgressBar::hidden()
        } else {
            ProgressBar::new(0)
        };
        if let Ok(style) = ProgressStyle::with_template(TEMPLATE) {
            bar.set_style(style.progress_chars("█▌░"));
        }
        Self {
            bar,
            case: Default::default(),
            step: Cell::new(("", 0)),
            solver: Default::default(),
        }
    }

    /// The run has `count` cases.
    pub fn cases(&self, count: usize) {
        self.bar.set_length(count as u64);
    }

    /// A case begins.
    pub fn start(&self, case: &Case) {
        *self.case.borrow_mut() = contopt_report::words::legend(&case.label, &case.params);
        self.step.set(("", 0));
        *self.solver.borrow_mut() = Default::default();
        self.show();
        self.bar.enable_steady_tick(TICK);
    }

    /// The case has ended.
    pub fn done(&self) {
        self.bar.inc(1);
    }

    fn show(&self) {
        let mut message = self.case.borrow().clone();
        let (outer, step) = self.step.get();
        if step > 0 {
            message += &format!(" · {outer} step {step}");
        }
        let (method, k) = &*self.solver.borrow();
        if *k > 0 {
            message += &format!(" · {method} iteration {k}");
        }
        self.bar.set_message(message);
    }
}

impl Observer for Progress {
    fn observe(&self, iteration: &Iteration) -> Flow {
        let outer = contopt_scene::OUTER_METHODS
            .iter()
            .find(|m| **m == iteration.method);
        if let Some(outer) = outer {
            self.step.set((outer, iteration.iteration));
        } else {
            let mut solver = self.solver.borrow_mut();
            if solver.0 != iteration.method {
                solver.0 = iteration.method.to_string();
            }
            solver.1 = iteration.iteration;
        }
        self.show();
        Flow::Continue
    }
}

impl Drop for Progress {
    /// Clears the bar, so that what follows (an error, the table) starts on a clean line.
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}
