//! Work with the GIL released. A scene's run ([`watched`]) runs on a thread of its own while
//! the calling thread waits without the GIL, waking every [`POLL`] to run Python's signal
//! handlers (Ctrl-C) and the caller's progress callback; one solve ([`watched_here`]) runs on
//! the calling thread, its own iterations running the signal handlers. A `KeyboardInterrupt`,
//! or an exception the callback raises, asks the work to stop at its next iteration ([`Watch`]
//! is the methods' observer); the work ends cleanly (its threads joined, its buffers dropped)
//! and that exception comes back as itself.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::Mutex;
use std::thread::ThreadId;
use std::time::{Duration, Instant};

use contopt_core::observe::{Event, Flow, Method, Observer};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// How often the waiting thread runs signal handlers and the progress callback.
const POLL: Duration = Duration::from_millis(50);

/// The stack of the working thread \[bytes\]: a main thread's on Linux, which a case's run
/// assumes (`contopt_scene::parallel`).
const STACK_BYTES: usize = 8 << 20;

/// What the progress callback is given: how many cases are done and the method running now.
#[pyclass(module = "contopt", frozen, get_all)]
#[derive(Clone, Debug)]
pub struct Progress {
    /// Cases finished.
    pub cases_done: usize,
    /// Cases in the run.
    pub cases: usize,
    /// The method that reported last (`"polonsky_keer"`, `"gap_iteration"`, …), or None.
    pub method: Option<String>,
    /// How deep it runs (0: the outermost method of a case).
    pub level: usize,
    /// Its iteration.
    pub iteration: usize,
}

#[pymethods]
impl Progress {
    fn __repr__(&self) -> String {
        let method = self
            .method
            .as_ref()
            .map_or("None".into(), |m| format!("{m:?}"));
        format!(
            "Progress(cases_done={}, cases={}, method={method}, level={}, iteration={})",
            self.cases_done, self.cases, self.level, self.iteration
        )
    }
}

/// The observer of the work's methods: keeps the latest event for the waiting thread and
/// stops every method once asked to. Shared by every thread of a run.
#[derive(Default)]
pub struct Watch {
    stop: AtomicBool,
    cases_done: AtomicUsize,
    /// Events seen: the waiting thread calls back only when it moved.
    events: AtomicUsize,
    latest: Mutex<Option<(Method, usize, usize)>>,
    /// A solve run on the calling thread ([`watched_here`]): that thread, when it last ran
    /// Python's signal handlers, and the exception they raised.
    here: Option<Here>,
}

/// The calling thread of a solve run on it, polled for signals from the solve's own events.
struct Here {
    thread: ThreadId,
    polled: Mutex<Instant>,
    failure: Mutex<Option<PyErr>>,
}

impl Watch {
    /// Counts a case done (from any thread).
    pub fn case_done(&self) {
        self.cases_done.fetch_add(1, Ordering::Relaxed);
        self.events.fetch_add(1, Ordering::Relaxed);
    }

    /// On the calling thread of a solve run on it, at most every [`POLL`]: Python's signal
    /// handlers, with the GIL taken back for them; an exception they raise stops the solve.
    fn poll_here(&self, here: &Here) {
        if std::thread::current().id() != here.thread {
            return;
        }
        let mut polled = here.polled.lock().unwrap_or_else(|e| e.into_inner());
        if polled.elapsed() < POLL {
            return;
        }
        *polled = Instant::now();
        if let Err(e) = Python::attach(|py| py.check_signals()) {
            self.stop.store(true, Ordering::Relaxed);
            *here.failure.lock().unwrap_or_else(|e| e.into_inner()) = Some(e);
        }
    }

    fn progress(&self, cases: usize) -> Progress {
        let latest = *self.latest.lock().unwrap_or_else(|e| e.into_inner());
        Progress {
            cases_done: self.cases_done.load(Ordering::Relaxed),
            cases,
            method: latest.map(|(m, _, _)| m.id().to_string()),
            level: latest.map_or(0, |(_, level, _)| level),
            iteration: latest.map_or(0, |(_, _, k)| k),
        }
    }
}

impl Observer for Watch {
    fn observe(&self, event: &Event) -> Flow {
        *self.latest.lock().unwrap_or_else(|e| e.into_inner()) =
            Some((event.method, event.level, event.iteration));
        self.events.fetch_add(1, Ordering::Relaxed);
        if let Some(here) = self.here.as_ref() {
            self.poll_here(here);
        }
        if self.stop.load(Ordering::Relaxed) {
            Flow::Stop
        } else {
            Flow::Continue
        }
    }
}

/// Runs `work` on a thread of its own with the GIL released, `cases` cases long; the calling
/// thread runs Python's signal handlers and `progress(Progress)` while it waits (the callback
/// at most every [`POLL`], when something moved, and once at the end). An exception from
/// either stops the work and is returned once it has ended.
pub fn watched<T: Send>(
    py: Python<'_>,
    progress: Option<&Bound<'_, PyAny>>,
    cases: usize,
    work: impl FnOnce(&Watch) -> T + Send,
) -> PyResult<T> {
    let watch = &Watch::default();
    let callback = progress.map(|p| p.clone().unbind());
    let (outcome, failure) = py.detach(|| {
        std::thread::scope(|s| {
            let (sender, receiver) = mpsc::channel::<()>();
            let worker = std::thread::Builder::new()
                .name("contopt".into())
                .stack_size(STACK_BYTES)
                .spawn_scoped(s, move || {
                    let out = work(watch);
                    let _ = sender.send(());
                    out
                });
            let worker = match worker {
                Ok(worker) => worker,
                Err(e) => {
                    let e = PyRuntimeError::new_err(format!("could not start a thread: {e}"));
                    return (None, Some(e));
                }
            };
            let mut failure = None;
            let mut seen = usize::MAX;
            loop {
                match receiver.recv_timeout(POLL) {
                    Ok(()) | Err(RecvTimeoutError::Disconnected) => break,
                    Err(RecvTimeoutError::Timeout) => {}
                }
                if failure.is_none() {
                    let events = watch.events.load(Ordering::Relaxed);
                    let moved = events != seen;
                    seen = events;
                    let checked = Python::attach(|py| {
                        py.check_signals()?;
                        match (&callback, moved) {
                            (Some(f), true) => f.call1(py, (watch.progress(cases),)).map(drop),
                            _ => Ok(()),
                        }
                    });
                    if let Err(e) = checked {
                        watch.stop.store(true, Ordering::Relaxed);
                        failure = Some(e);
                    }
                }
            }
            match worker.join() {
                Ok(out) => (Some(out), failure),
                Err(panic) => std::panic::resume_unwind(panic),
            }
        })
    });
    if let Some(e) = failure {
        return Err(e);
    }
    if let Some(f) = &callback {
        f.call1(py, (watch.progress(cases),))?;
    }
    outcome.ok_or_else(|| PyRuntimeError::new_err("the work did not run"))
}

/// Runs one solve, `work`, on the calling thread with the GIL released: its events run
/// Python's signal handlers at most every [`POLL`] (Ctrl-C stops it at its next iteration, and
/// the `KeyboardInterrupt` is returned once it has ended). No thread is started, so the solve
/// reuses the calling thread's memory from one call to the next (a thread of its own per call
/// costs a fresh allocator arena: 3–15 % of a 256² solve).
pub fn watched_here<T: Send>(py: Python<'_>, work: impl FnOnce(&Watch) -> T + Send) -> PyResult<T> {
    let watch = Watch {
        here: Some(Here {
            thread: std::thread::current().id(),
            polled: Mutex::new(Instant::now()),
            failure: Mutex::new(None),
        }),
        ..Watch::default()
    };
    let out = py.detach(|| work(&watch));
    let failure = (watch.here.as_ref())
        .and_then(|h| h.failure.lock().unwrap_or_else(|e| e.into_inner()).take());
    match failure {
        Some(e) => Err(e),
        None => Ok(out),
    }
}
