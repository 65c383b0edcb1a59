//! The progress of a run on stderr: a bar over the scene's cases, with the current case and
//! every method running in it, outermost first (`L1 = 30 mm · gap iteration (§3.2) step 4 ·
//! Polonsky–Keer solve iteration 127`), from the events the case's methods report with their
//! nesting level. Hidden when stderr is not a terminal (indicatif draws nothing there) and with
//! `--quiet`; cleared when the run ends.

use std::cell::RefCell;
use std::time::Duration;

use contopt_core::observe::{Event, Flow, Method, Observer};
use indicatif::{ProgressBar, ProgressStyle};

/// How often the bar redraws while a case runs, so that the elapsed time moves on.
const TICK: Duration = Duration::from_millis(200);

/// The bar: `[00:00:12] ███████░░░░ 3/5 cases  L1 = 30 mm · …`.
const TEMPLATE: &str = "[{elapsed_precise}] {bar:24} {pos}/{len} cases  {wide_msg}";

/// The progress bar over a scene's cases, and the observer of each case's methods.
pub struct Progress {
    bar: ProgressBar,
    case: RefCell<String>,
    /// The method running at each level and its iteration.
    methods: RefCell<Vec<(Method, usize)>>,
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
            methods: Default::default(),
        }
    }

    /// The run has `count` cases.
    pub fn cases(&self, count: usize) {
        self.bar.set_length(count as u64);
    }

    /// A case begins.
    pub fn start(&self, label: &str) {
        *self.case.borrow_mut() = label.to_string();
        self.methods.borrow_mut().clear();
        self.show();
        self.bar.enable_steady_tick(TICK);
    }

    /// Counts a case done, from any thread (a run of several cases at once).
    pub fn counter(&self) -> impl Fn() + Sync {
        let bar = self.bar.clone();
        move || bar.inc(1)
    }

    /// The case has ended.
    pub fn done(&self) {
        self.bar.inc(1);
    }

    fn show(&self) {
        let mut message = self.case.borrow().clone();
        for (method, k) in self.methods.borrow().iter() {
            message += &format!(" · {method} {k}");
        }
        self.bar.set_message(message);
    }
}

impl Observer for Progress {
    /// Keeps the method at the event's level and drops the deeper ones (they ended); a
    /// method's last event takes it off the line.
    fn observe(&self, event: &Event) -> Flow {
        {
            let mut methods = self.methods.borrow_mut();
            methods.truncate(event.level);
            if event.end.is_none() {
                methods.push((event.method, event.iteration));
            }
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
