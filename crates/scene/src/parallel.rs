//! A scene's cases run on several threads ([`Scene::run_parallel`]), their reports bit for bit
//! those of a run on one.
//!
//! The unit of work is a group of cases that share their bodies (one key, [`crate::Run`]):
//! a group runs on one thread, in the scene's order, on one build of its bodies, as the
//! sequential run does, so that no case sees another thread's state. With fewer groups than
//! threads the largest groups are halved (contiguous halves) until every thread has work or
//! every group is one case; the halves of one key share one build of their bodies, made by the
//! first that needs it (the others wait for it) and dropped when the last is done, so that a
//! study of one pair of bodies (crowns compared under one load) builds it once on any number
//! of threads. The bodies are only read while a case runs, so a case gives the same bits on a
//! shared build as alone.
//! Groups run at once only while the sum of their memory
//! estimates stays within the scene's memory limit (a group's estimate is its largest case's,
//! as its cases run one after another); a group that fits only alone waits for the others.
//!
//! The threads of one pool (`jobs` of them) do all the work: the groups' cases and the
//! contact solves inside a case that run at once (an envelope's cases,
//! [`contopt_contact::parallel`]), so that a case never adds threads to those of the others:
//! a case alone on the pool has every thread for its solves, cases side by side share them.
//! A group is handed to the pool by a runner thread that first waits for its memory at the
//! gate, so that no pool thread ever waits there (a pool thread waiting for its solves may
//! take up another group's case meanwhile, on its own stack: the stack holds one case per
//! runner).

use std::ops::Range;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex, PoisonError};
use std::time::Duration;

use contopt_core::observe::{Observer, Silent};
use contopt_results::CaseReport;

use crate::build::Built;
use crate::plan::BuildKey;
use crate::{Case, Scene, SceneError};

/// The stack of a case \[bytes\]: the main thread's on Linux, where a run on one thread
/// solves them (rayon's default is 2 MiB).
const CASE_STACK_BYTES: usize = 8 << 20;

/// A case's report, or why it could not run.
pub type CaseResult = Result<CaseReport, SceneError>;

/// What a run on several threads gives: every case's result, and how many pairs of bodies it
/// built.
#[derive(Debug)]
pub struct Ran {
    /// The cases' results, in the scene's order.
    pub results: Vec<CaseResult>,
    /// The pairs of bodies built: one per distinct key, on any number of threads.
    pub builds: usize,
}

impl Scene {
    /// Runs the cases `range` (cut to the scene's cases) on `jobs` threads (at least one),
    /// calling `done` as each case ends: their results in the scene's order ([`Ran`]), each the same to
    /// the bit as [`Scene::run_cases`] gives, for any `jobs`. At most `jobs` groups of cases
    /// that share their bodies run at once, and only as many as the scene's memory limit holds
    /// (module [`crate::parallel`]'s notes). An error starting the threads is the scene's.
    pub fn run_parallel(
        &self,
        range: Range<usize>,
        jobs: usize,
        done: &(dyn Fn() + Sync),
    ) -> Result<Ran, SceneError> {
        self.run_parallel_observed(range, jobs, &Silent, done)
    }

    /// [`Scene::run_parallel`], reporting each iteration of every case's methods to
    /// `observer` from the thread that runs it, which may stop them early (each case then
    /// reports how it was stopped): a caller's progress and its Ctrl-C.
    pub fn run_parallel_observed(
        &self,
        range: Range<usize>,
        jobs: usize,
        observer: &(dyn Observer + Sync),
        done: &(dyn Fn() + Sync),
    ) -> Result<Ran, SceneError> {
        let all = self.cases();
        let cases = &all[range.start.min(all.len())..range.end.min(all.len())];
        let groups = split(groups(cases), jobs);
        let builds = Builds::new(cases, &groups);
        let limit = cases
            .iter()
            .map(|c| c.plan.memory.limit_bytes)
            .min()
            .unwrap_or(0);
        let gate = Gate::new(limit);
        let runners = jobs.max(1).min(groups.len().max(1));
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(jobs.max(1))
            .stack_size(CASE_STACK_BYTES.saturating_mul(runners))
            .build()
            .map_err(|e| SceneError::Io {
                file: self.file.clone(),
                source: std::io::Error::other(format!("could not start {jobs} threads: {e}")),
            })?;
        let next = AtomicUsize::new(0);
        let runner = || {
            let mut ran = vec![];
            while let Some(group) = groups.get(next.fetch_add(1, Ordering::Relaxed)) {
                let need = group
                    .iter()
                    .map(|&k| cases[k].plan.memory.estimate_bytes)
                    .max();
                let _held = gate.hold(need.unwrap_or(0));
                ran.extend(pool.install(|| run_group(cases, group, &builds, observer, done)));
            }
            ran
        };
        let ran: Vec<(usize, CaseResult)> = std::thread::scope(|s| {
            let runners: Vec<_> = (0..runners).map(|_| s.spawn(runner)).collect();
            runners
                .into_iter()
                .flat_map(|r| r.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
                .collect()
        });
        let mut results: Vec<Option<CaseResult>> = (0..cases.len()).map(|_| None).collect();
        for (k, result) in ran {
            results[k] = Some(result);
        }
        Ok(Ran {
            results: results.into_iter().flatten().collect(),
            builds: builds.made.load(Ordering::Relaxed),
        })
    }
}

/// The cases grouped by their bodies' key, each group in the scene's order, the groups in the
/// order of their first case.
fn groups(cases: &[Case]) -> Vec<Vec<usize>> {
    let mut groups: Vec<Vec<usize>> = vec![];
    let mut keys: Vec<&BuildKey> = vec![];
    for (k, case) in cases.iter().enumerate() {
        match keys.iter().position(|key| **key == case.plan.key) {
            Some(g) => groups[g].push(k),
            None => {
                keys.push(&case.plan.key);
                groups.push(vec![k]);
            }
        }
    }
    groups
}

/// `groups` with the largest halved, again and again, until there are `jobs` of them or each
/// is one case; halves stay in the scene's order.
fn split(mut groups: Vec<Vec<usize>>, jobs: usize) -> Vec<Vec<usize>> {
    while groups.len() < jobs {
        let longest = groups.iter().map(Vec::len).max().unwrap_or(0);
        let Some(g) = groups.iter().position(|group| group.len() == longest) else {
            break;
        };
        if longest < 2 {
            break;
        }
        let tail = groups[g].split_off(longest / 2);
        groups.insert(g + 1, tail);
    }
    groups
}

/// Runs a group's cases in order on the one build of their bodies that `builds` shares; a
/// build that fails is every case's error.
fn run_group(
    cases: &[Case],
    group: &[usize],
    builds: &Builds,
    observer: &(dyn Observer + Sync),
    done: &(dyn Fn() + Sync),
) -> Vec<(usize, CaseResult)> {
    let ran = group
        .iter()
        .map(|&k| {
            let case = &cases[k];
            let result = builds
                .bodies(cases, k)
                .and_then(|(built, took)| case.run_built(&built, took, observer));
            done();
            (k, result)
        })
        .collect();
    if let Some(&first) = group.first() {
        builds.finished(first);
    }
    ran
}

/// One build of the bodies of each key, shared by the groups of that key on every thread.
struct Builds {
    /// Per distinct key (in the order of [`groups`]): the build, and the groups still to end.
    slots: Vec<Mutex<Slot>>,
    /// The key of each case, as an index into `slots`.
    key_of: Vec<usize>,
    /// The builds made.
    made: AtomicUsize,
}

/// The build of one key's bodies.
struct Slot {
    built: Option<Arc<Built>>,
    groups_left: usize,
}

impl Builds {
    /// No build yet for the keys of `cases`, each awaited by its groups of `groups`.
    fn new(cases: &[Case], groups: &[Vec<usize>]) -> Self {
        let mut keys: Vec<&BuildKey> = vec![];
        let key_of = cases
            .iter()
            .map(
                |case| match keys.iter().position(|key| **key == case.plan.key) {
                    Some(i) => i,
                    None => {
                        keys.push(&case.plan.key);
                        keys.len() - 1
                    }
                },
            )
            .collect::<Vec<_>>();
        let mut slots: Vec<Slot> = (0..keys.len())
            .map(|_| Slot {
                built: None,
                groups_left: 0,
            })
            .collect();
        for group in groups {
            if let Some(&first) = group.first() {
                slots[key_of[first]].groups_left += 1;
            }
        }
        Self {
            slots: slots.into_iter().map(Mutex::new).collect(),
            key_of,
            made: AtomicUsize::new(0),
        }
    }

    /// The bodies of case `k` and the time their build took (zero when another case built
    /// them): built now, while the groups of its key wait, or shared.
    fn bodies(&self, cases: &[Case], k: usize) -> Result<(Arc<Built>, Duration), SceneError> {
        let mut slot = self.slots[self.key_of[k]]
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        if let Some(built) = &slot.built {
            return Ok((built.clone(), Duration::ZERO));
        }
        let built = Arc::new(cases[k].build()?);
        self.made.fetch_add(1, Ordering::Relaxed);
        slot.built = Some(built.clone());
        let took = built.took();
        Ok((built, took))
    }

    /// A group of case `first`'s key has ended: the last drops the build.
    fn finished(&self, first: usize) {
        let mut slot = self.slots[self.key_of[first]]
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        slot.groups_left = slot.groups_left.saturating_sub(1);
        if slot.groups_left == 0 {
            slot.built = None;
        }
    }
}

/// Memory held by the groups running: a group waits until its estimate fits beside theirs
/// under the limit (or nothing else runs).
struct Gate {
    limit: u64,
    held: Mutex<u64>,
    freed: Condvar,
}

/// A group's share of the [`Gate`], given back when dropped.
struct Held<'g> {
    gate: &'g Gate,
    bytes: u64,
}

impl Gate {
    fn new(limit: u64) -> Self {
        Self {
            limit,
            held: Mutex::new(0),
            freed: Condvar::new(),
        }
    }

    /// Waits until `bytes` fit beside what is held (or nothing is), and holds them.
    fn hold(&self, bytes: u64) -> Held<'_> {
        let mut held = self.held.lock().unwrap_or_else(PoisonError::into_inner);
        while *held > 0 && held.saturating_add(bytes) > self.limit {
            held = self
                .freed
                .wait(held)
                .unwrap_or_else(PoisonError::into_inner);
        }
        *held += bytes;
        Held { gate: self, bytes }
    }
}

impl Drop for Held<'_> {
    fn drop(&mut self) {
        let mut held = self
            .gate
            .held
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        *held -= self.bytes;
        self.gate.freed.notify_all();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicU64;

    /// The largest groups are halved until the threads have work; cases stay in order.
    #[test]
    fn groups_are_halved_for_idle_threads() {
        let groups = vec![vec![0, 2, 3, 5], vec![1], vec![4]];
        assert_eq!(split(groups.clone(), 2), groups);
        assert_eq!(
            split(groups.clone(), 4),
            [vec![0, 2], vec![3, 5], vec![1], vec![4]]
        );
        assert_eq!(split(vec![vec![0, 1, 2]], 8), [vec![0], vec![1], vec![2]]);
    }

    /// Holders never hold more than the limit together, except one alone; all get through.
    #[test]
    fn the_gate_keeps_the_sum_under_its_limit() {
        let gate = Gate::new(10);
        let peak = AtomicU64::new(0);
        let now = AtomicU64::new(0);
        let sizes = [4u64, 7, 3, 12, 5, 6, 2, 9];
        std::thread::scope(|s| {
            for &bytes in &sizes {
                let (gate, peak, now) = (&gate, &peak, &now);
                s.spawn(move || {
                    let _held = gate.hold(bytes);
                    let total = now.fetch_add(bytes, Ordering::SeqCst) + bytes;
                    peak.fetch_max(total, Ordering::SeqCst);
                    assert!(total <= 10 || total == bytes, "{total} held at once");
                    std::thread::sleep(std::time::Duration::from_millis(5));
                    now.fetch_sub(bytes, Ordering::SeqCst);
                });
            }
        });
        assert_eq!(*gate.held.lock().unwrap(), 0);
        assert!(peak.load(Ordering::SeqCst) >= 12);
    }
}
