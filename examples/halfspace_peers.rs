//! Our half-space solver on the peers' cases (shared/peers/halfspace): Hertz and the flat
//! punch on an N × N grid of a 4 mm square, E = 210 GPa, ν = 0.3, load control, one thread.
//! Prints one JSON row per run with the peers' fields, so the tables can be joined; each run
//! is a fresh process. Sizes and, optionally, the cases (`hertz`, `punch`) are arguments:
//!
//! `cargo run --release --example halfspace_peers -- 256 512 hertz` (`--table`: a markdown
//! table of time, steps, memory and errors instead of JSON). Besides the peers' fields, each
//! row counts the steps on the N × N grid apart from those on the coarser grids of the nested
//! start, and times one influence product on the N × N grid (one padded FFT pair), measured
//! in the same process as the solve, with the solve's time as a multiple of it and of the
//! floor, the N × N grid's steps times that pair.

use std::cell::Cell;
use std::f64::consts::PI;
use std::time::Instant;

use contopt::greens::HalfSpace;
use contopt::prelude::*;

const E: f64 = 210e3;
const NU: f64 = 0.3;
const L: f64 = 4.0;

/// One run of `case` on an `n` × `n` grid: its figures.
fn run(case: &str, n: usize) -> Row {
    let estar = E / (1.0 - NU * NU);
    let h = L / n as f64;
    let origin = -((n / 2) as f64) * h;
    let t = Instant::now();
    let body = HalfSpace::grid(
        "half-space",
        Material::new(E, NU).unwrap(),
        n,
        n,
        h,
        h,
        [origin, origin],
    )
    .unwrap();
    let setup = t.elapsed().as_secs_f64();
    let (gap, force, p_ref, approach_ref): (Vec<f64>, f64, f64, f64) = match case {
        "hertz" => {
            let force = 4.0 * estar / (3.0 * 100.0);
            let gap = body
                .interface()
                .points()
                .iter()
                .map(|x| (x[0] * x[0] + x[1] * x[1]) / 200.0)
                .collect();
            (
                gap,
                force,
                (6.0 * force * estar * estar / (PI.powi(3) * 1e4)).cbrt(),
                0.01,
            )
        }
        _ => {
            let gap = body
                .interface()
                .points()
                .iter()
                .map(|x| if x[0].hypot(x[1]) <= 1.0 { 0.0 } else { 1.0 })
                .collect();
            (gap, 1000.0, 1000.0 / (2.0 * PI), 1000.0 / (2.0 * estar))
        }
    };
    let solver = PolonskyKeer::new(PolonskyKeerSettings {
        tolerance: 1e-10,
        ..PolonskyKeerSettings::default()
    })
    .unwrap();
    // Before the solve, so that its buffers are freed by then and the peak memory is the
    // solve's.
    let [pair, pair_cpu] = fft_pair_seconds(&body);
    let (t, cpu) = (Instant::now(), thread_cpu_seconds());
    let indenter =
        RigidBody::pressed("indenter", body.interface(), [0.0, 0.0, 1.0], force).unwrap();
    let problem = InterfaceProblem::new(&body, &indenter, &gap).unwrap();
    // The steps on each grid: the fine one (level 0), and each coarser grid of the nested
    // start one level deeper (its solve runs inside the finer one's).
    let steps: [Cell<usize>; LEVELS] = Default::default();
    let count = |e: &Event| {
        if e.end.is_none() {
            let level = &steps[e.level.min(LEVELS - 1)];
            level.set(level.get() + 1);
        }
        Flow::Continue
    };
    let state = solver.solve_observed(&problem, None, &count).unwrap();
    let seconds = t.elapsed().as_secs_f64();
    let cpu_seconds = thread_cpu_seconds() - cpu;
    let p = if case == "hertz" {
        state.p_max()
    } else {
        state.pressure[(n / 2) * n + n / 2]
    };
    let contact = state.active.iter().filter(|&&c| c).count() as f64 * h * h;
    let carried = body.interface().resultant(&state.pressure);
    Row {
        h,
        force,
        p_ref,
        seconds,
        cpu_seconds,
        setup,
        iterations: state.iterations,
        levels: steps.iter().map(Cell::get).collect(),
        pair,
        pair_cpu,
        converged: state.is_converged(),
        rss: contopt_validation::fixtures::peak_resident_mib(),
        err_force: carried / force - 1.0,
        err_approach: state.approach().unwrap_or(f64::NAN) / approach_ref - 1.0,
        p_max: state.p_max(),
        err_p0: p / p_ref - 1.0,
        err_radius: (contact / PI).sqrt() - 1.0,
        err_area: contact / PI - 1.0,
    }
}

/// Grid levels whose steps are counted apart (the last counts any deeper too): 4096² coarsens
/// nine times down to 16².
const LEVELS: usize = 12;

/// The steps of each level, finest first, as `18 + 20 + 14`, the empty coarsest left out.
fn per_level(levels: &[usize]) -> String {
    let used = levels.iter().rposition(|&k| k > 0).map_or(1, |k| k + 1);
    let parts: Vec<String> = levels[..used].iter().map(usize::to_string).collect();
    parts.join(" + ")
}

/// The CPU time this thread has run \[s\] (Linux's `/proc/thread-self/schedstat`, in ns);
/// NaN where it cannot be read.
fn thread_cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| ns * 1e-9)
}

/// Repetitions of the product whose fastest is the FFT pair's cost.
const PAIR_RUNS: usize = 5;

/// The fastest of at least [`PAIR_RUNS`] influence products on the whole grid in wall time, and
/// their mean CPU time over at least [`PAIR_CPU`] \[s\]: one padded FFT
/// pair (forward and inverse over the 2N × 2N grid) with the spectrum's product, the unit of a
/// Polonsky–Keer step (which applies on its part of the grid the direction's product, the
/// preconditioner over the part's own, unpadded grid, and the residual's product only after a
/// step that changed the contact set).
fn fft_pair_seconds(body: &HalfSpace) -> [f64; 2] {
    let n = body.interface().len();
    let force: Vec<f64> = (0..n).map(|i| (i % 7) as f64).collect();
    let mut out = vec![0.0; n];
    let (mut wall, mut runs, cpu) = (f64::INFINITY, 0, thread_cpu_seconds());
    while runs < PAIR_RUNS || (thread_cpu_seconds() - cpu < PAIR_CPU && runs < 100 * PAIR_RUNS) {
        let t = Instant::now();
        body.apply_influence(&force, &mut out);
        wall = wall.min(t.elapsed().as_secs_f64());
        runs += 1;
    }
    [wall, (thread_cpu_seconds() - cpu) / runs as f64]
}

/// The CPU time over which the pair's CPU time is averaged \[s\]: the thread's clock
/// advances in scheduler ticks of a few ms, longer than a pair at 256².
const PAIR_CPU: f64 = 0.2;

/// A run's figures as a JSON row in the peers' fields, or a markdown table row when `table`.
fn format_row(case: &str, n: usize, row: &Row, table: bool) -> String {
    let (h, force, p_ref) = (row.h, row.force, row.p_ref);
    if table {
        let steps = match row.converged {
            true => row.iterations.to_string(),
            false => format!("{} (not converged)", row.iterations),
        };
        format!(
            "| {case} | {n} | {:.3} s | {:.3} s | {steps} | {} | {:.2} ms | {:.0} | {:.1} | {:.0} MiB | {:+.3} % | {:+.3} % |",
            row.seconds,
            row.cpu_seconds,
            per_level(&row.levels),
            1e3 * row.pair_cpu,
            row.cpu_seconds / row.pair_cpu,
            row.cpu_seconds / (row.levels[0] as f64 * row.pair_cpu),
            row.rss,
            100.0 * row.err_p0,
            100.0 * row.err_radius
        )
    } else {
        format!(
            "{{\"tool\": \"contopt\", \"version\": \"{}\", \"case\": \"{case}\", \"bc\": \"free (non-periodic)\", \"N\": {n}, \"threads\": 1, \
             \"seconds\": {:.6}, \"cpu_seconds\": {:.6}, \"setup_s\": {:.6}, \"iterations\": {}, \"steps_per_level\": {:?}, \"fft_pair_s\": {:e}, \"fft_pair_cpu_s\": {:e}, \"converged\": {}, \"max_rss_MiB\": {:.1}, \"F\": {force}, \
             \"h_mm\": {h}, \"rel_err_force\": {:e}, \"rel_err_approach\": {:e}, \"p0_ref\": {p_ref}, \"p_max\": {}, \"rel_err_p0\": {:e}, \
             \"rel_err_contact_radius\": {:e}, \"rel_err_contact_area\": {:e}, \"status\": \"ok\"}}",
            env!("CARGO_PKG_VERSION"),
            row.seconds,
            row.cpu_seconds,
            row.setup,
            row.iterations,
            row.levels,
            row.pair,
            row.pair_cpu,
            row.converged,
            row.rss,
            row.err_force,
            row.err_approach,
            row.p_max,
            row.err_p0,
            row.err_radius,
            row.err_area,
        )
    }
}

/// One run's figures, in the peers' fields.
struct Row {
    /// Cell size \[mm\].
    h: f64,
    /// Load \[N\].
    force: f64,
    /// The closed form's peak (Hertz) or centre (punch) pressure \[MPa\].
    p_ref: f64,
    seconds: f64,
    /// The solve's CPU time (this thread's) \[s\]: on a shared machine, what other jobs
    /// disturb least.
    cpu_seconds: f64,
    setup: f64,
    iterations: usize,
    /// Steps on the N × N grid, then on each coarser grid of the nested start.
    levels: Vec<usize>,
    /// One influence product on the N × N grid (a padded FFT pair) \[s\].
    pair: f64,
    /// The same product's CPU time \[s\].
    pair_cpu: f64,
    converged: bool,
    rss: f64,
    err_force: f64,
    err_approach: f64,
    p_max: f64,
    err_p0: f64,
    err_radius: f64,
    err_area: f64,
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    // One run in this process: `--one <case> <N>` (what the driver below spawns).
    if let [flag, case, n] = args.as_slice() {
        if flag == "--one" || flag == "--one-row" {
            let n = n.parse().expect("N is a number");
            println!(
                "{}",
                format_row(case, n, &run(case, n), flag == "--one-row")
            );
            return;
        }
    }
    // `--table`: a markdown table instead of JSON (the book's column beside the peers').
    let table = args.iter().any(|a| a == "--table");
    // Each run in a fresh process, as the peers' harness does, so the peak memory is that
    // run's own.
    let sizes: Vec<usize> = args.iter().filter_map(|a| a.parse().ok()).collect();
    let sizes = if sizes.is_empty() {
        vec![64, 128, 256, 512]
    } else {
        sizes
    };
    let cases: Vec<&str> = ["hertz", "punch"]
        .into_iter()
        .filter(|c| {
            args.iter()
                .all(|a| a.parse::<usize>().is_ok() || a == "--table")
                || args.iter().any(|a| a == c)
        })
        .collect();
    let exe = std::env::current_exe().expect("the example's own path");
    let mut rows = Vec::new();
    for case in cases {
        for &n in &sizes {
            let out = std::process::Command::new(&exe)
                .args([
                    if table { "--one-row" } else { "--one" },
                    case,
                    &n.to_string(),
                ])
                .output()
                .expect("the example can run itself");
            let row = String::from_utf8_lossy(&out.stdout).trim().to_string();
            eprintln!(
                "{case} N = {n}: {}",
                if out.status.success() {
                    "done"
                } else {
                    "failed"
                }
            );
            rows.push(row);
        }
    }
    if table {
        println!("| case | N | time | CPU time | steps | steps per grid, finest first | FFT pair (CPU) | CPU time / pair | CPU time / floor | peak memory | p₀ error | contact-radius error |");
        println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
        println!("{}", rows.join("\n"));
    } else {
        println!("{{\"rows\": [\n{}\n]}}", rows.join(",\n"));
    }
}
