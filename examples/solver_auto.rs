//! `solver = "auto"` against the two exact solvers it chooses between, on every bundled scene:
//! the first case's contact problem (its bodies built once, its initial gap, no optimisation)
//! solved from scratch by Kalker's dense active set, by Polonsky–Keer and by the automatic
//! choice ([`Auto`]), each the fastest of five runs, the three interleaved (one run when a solve takes over a second). Prints
//! the table of the book's performance chapter: each time, auto's choice and its time over the
//! faster one's. Times are the process's CPU time: on the 2-core machine shared with other jobs
//! a millisecond solve's wall time varies tenfold with the wait for a core.
//!
//! The dense active set is not run past [`DENSE_TIMED`] points: its n³ factorisation would
//! take minutes (the solver benchmark's Hertz rows: 1.2 s at 3 481 points against 0.016 s for
//! Polonsky–Keer, 8 s at 6 241), and a scene's problem refuses its dense matrices past its
//! memory limit.
//!
//! `cargo run --release --example solver_auto`

use contopt::prelude::*;

/// The largest interface the dense active set is timed on.
const DENSE_TIMED: usize = 5000;
/// Runs of each solver per scene.
const ROUNDS: usize = 5;

/// The CPU time of this process \[s\] (one thread solves): what a solve costs, without the
/// waits for a core that its wall time holds on a shared machine.
fn cpu_seconds() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes the timespec it is given and nothing else.
    let done = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) };
    assert_eq!(done, 0, "CLOCK_PROCESS_CPUTIME_ID is Linux's");
    t.tv_sec as f64 + 1e-9 * t.tv_nsec as f64
}

/// The fastest of [`ROUNDS`] runs of each solver, interleaved (one run each when a solve takes
/// over a second): on a machine shared with other jobs the least time is the one least
/// disturbed. A time, or why there is none.
fn times(solvers: &[&dyn ContactSolver], problem: &InterfaceProblem) -> Vec<Result<f64, String>> {
    let mut best: Vec<Result<f64, String>> = vec![Ok(f64::INFINITY); solvers.len()];
    for round in 0..ROUNDS {
        for (solver, best) in solvers.iter().zip(best.iter_mut()) {
            let Ok(fastest) = best else { continue };
            let t = cpu_seconds();
            let state = solver.solve(problem);
            let elapsed = cpu_seconds() - t;
            *best = match state {
                Ok(st) if st.is_converged() => Ok(fastest.min(elapsed)),
                Ok(st) => Err(st.termination.to_string()),
                Err(e) => Err(e.to_string()),
            };
        }
        let slowest = best
            .iter()
            .filter_map(|t| t.as_ref().ok())
            .fold(0.0, |a: f64, &b| a.max(b));
        if round == 0 && slowest > 1.0 {
            break;
        }
    }
    best
}

/// A time for the table \[ms\].
fn cell(t: &Result<f64, String>) -> String {
    match t {
        Ok(t) => format!("{:.3}", 1e3 * t),
        Err(_) => "—".into(),
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dense = ActiveSet::new(ActiveSetSettings::default())?;
    let iterative = PolonskyKeer::new(PolonskyKeerSettings::default())?;
    let auto = Auto::new()?;
    println!("| scene | points | auto's choice | active set ms | Polonsky–Keer ms | auto ms | auto / faster |");
    println!("| --- | --- | --- | --- | --- | --- | --- |");
    let mut worst: f64 = 0.0;
    let mut notes = vec![];
    for bundled in contopt::scene::BUNDLED {
        let scene = Scene::bundled(bundled.name)?;
        let problem = scene.cases()[0].problem()?;
        let n = problem.len();
        let mut solvers: Vec<&dyn ContactSolver> = vec![&iterative, &auto];
        if n <= DENSE_TIMED {
            solvers.push(&dense);
        }
        let mut t = times(&solvers, &problem);
        if n > DENSE_TIMED {
            t.push(Err(format!("not timed past {DENSE_TIMED} points")));
        }
        let best = [&t[0], &t[2]]
            .into_iter()
            .filter_map(|t| t.as_ref().ok())
            .fold(f64::INFINITY, |a, &b| a.min(b));
        let ratio = match &t[1] {
            Ok(t) if best.is_finite() => {
                worst = worst.max(t / best);
                format!("{:.2}", t / best)
            }
            _ => "—".into(),
        };
        println!(
            "| {} | {n} | {} | {} | {} | {} | {ratio} |",
            bundled.name,
            auto.method_for(&problem),
            cell(&t[2]),
            cell(&t[0]),
            cell(&t[1]),
        );
        for (name, t) in [("active set", &t[2]), ("Polonsky–Keer", &t[0])] {
            if let Err(why) = t {
                notes.push(format!("- {}, {name}: {why}", bundled.name));
            }
        }
    }
    println!("\nWithout a time:\n");
    println!("{}", notes.join("\n"));
    println!("\nauto's time over the faster exact solver's, at most: {worst:.2}");
    Ok(())
}
