//! A scene's cases run on several threads ([`Scene::run_parallel`]), their reports bit for bit
//! those of a run on one.
//!
//! The unit of work is a group of cases that share their bodies (one key, [`crate::Run`]):
//! a group runs on one thread, in the scene's order, on one build of its bodies, as the
//! sequential run does, so that no case sees another thread's state. With fewer groups than
//! threads the largest groups are halved (contiguous halves, each built on its own: a build is
//! deterministic, so a case solved on its own build of the bodies gives the same bits as on a
//! shared one) until every thread has work or every group is one case: a study of one pair of
//! bodies (crowns compared under one load) pays one build per thread for the threads it uses.
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
use std::sync::{Condvar, Mutex, PoisonError};

use contopt_core::observe::Silent;
use contopt_results::CaseReport;

use crate::{Case, Scene, SceneError};

/// The stack of a case \[bytes\]: the main thread's on Linux, where a run on one thread
/// solves them (rayon's default is 2 MiB).
const CASE_STACK_BYTES: usize = 8 << 20;

/// A case's report, or why it could not run.
pub type CaseResult = Result<CaseReport, SceneError>;

impl Scene {
    /// Runs the cases `range` (cut to the scene's cases) on `jobs` threads (at least one),
    /// calling `done` as each case ends: their results in the scene's order, each the same to
    /// the bit as [`Scene::run_cases`] gives, for any `jobs`. At most `jobs` groups of cases
    /// that share their bodies run at once, and only as many as the scene's memory limit holds
    /// (module [`crate::parallel`]'s notes). An error starting the threads is the scene's.
    pub fn run_parallel(
        &self,
        range: Range<usize>,
        jobs: usize,
        done: &(dyn Fn() + Sync),
    ) -> Result<Vec<CaseResult>, SceneError> {
        let all = self.cases();
        let cases = &all[range.start.min(all.len())..range.end.min(all.len())];
        let groups = split(groups(cases), jobs);
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
                ran.extend(pool.install(|| run_group(cases, group, done)));
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
        Ok(results.into_iter().flatten().collect())
    }
}

/// The cases grouped by their bodies' key, each group in the scene's order, the groups in the
/// order of their first case.
fn groups(cases: &[Case]) -> Vec<Vec<usize>> {
    let mut groups: Vec<Vec<usize>> = vec![];
    let mut keys: Vec<&crate::prepare::BuildKey> = vec![];
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

/// Runs a group's cases in order on one build of their bodies, as [`crate::Run`] does; a
/// build that fails is every case's error.
fn run_group(
    cases: &[Case],
    group: &[usize],
    done: &(dyn Fn() + Sync),
) -> Vec<(usize, CaseResult)> {
    let mut built = None;
    group
        .iter()
        .map(|&k| {
            let case = &cases[k];
            let result = match built.take() {
                Some(b) => Ok(crate::build::Built::reused(b)),
                None => case.build(),
            }
            .and_then(|b| {
                let report = case.run_on(&b, &Silent);
                built = Some(b);
                report
            });
            done();
            (k, result)
        })
        .collect()
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
