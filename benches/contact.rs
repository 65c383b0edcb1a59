//! Every contact solver on interfaces of about 50, 200 and 1000 points: a rigid sphere
//! (Hertz) pressed into the half-space stand-in block, contact radius 1 mm inside a 1.5 mm
//! candidate zone, so a third of the points stay open. Reports time (criterion) and, against
//! the QP reference (printed table), the error of the pressure, of the gap and of the
//! indenter's approach. With three Gauss points per quadratic face the QP's minimisers share
//! d and λ but not p at elements partly in contact, so the pressure column there measures
//! which minimiser a method returns rather than its accuracy.
//!
//! `cargo bench --bench contact`

use std::time::{Duration, Instant};

use contopt::prelude::*;
use contopt_validation::fixtures::hertz_on_block;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode};

const E: f64 = 2.0e5;

/// The solvers with their labels, the QP (the reference) first.
fn solvers() -> Vec<(&'static str, Box<dyn ContactSolver>)> {
    let c = E * 1e4;
    vec![
        (
            "QP (clarabel)",
            Box::new(Qp::new(QpSettings::default()).unwrap()),
        ),
        (
            "active set",
            Box::new(ActiveSet::new(ActiveSetSettings::default()).unwrap()),
        ),
        (
            "augmented Lagrangian",
            Box::new(AugmentedLagrangian::new(AugmentedLagrangianSettings::new(c)).unwrap()),
        ),
        (
            "penalty",
            Box::new(Penalty::new(PenaltySettings { c_mpa_per_mm: c }).unwrap()),
        ),
    ]
}

fn bench(c: &mut Criterion) {
    let sizes = [17, 67, 333];
    let problems: Vec<InterfaceProblem> =
        sizes.iter().map(|&f| hertz_on_block(f).unwrap()).collect();
    println!(
        "{:>6} {:>22} {:>10} {:>10} {:>10} {:>10} {:>6} {:>6} {:>6}",
        "points", "solver", "time ms", "p error", "d error", "λ error", "iters", "iterp", "iterd"
    );
    for problem in &problems {
        let reference = solvers()[0].1.solve(problem).unwrap();
        let approach = reference.approach().unwrap();
        for (label, solver) in solvers() {
            let t = Instant::now();
            let st = solver.solve(problem).unwrap();
            let ms = t.elapsed().as_secs_f64() * 1e3;
            let diff = |a: &[f64], b: &[f64]| {
                a.iter()
                    .zip(b)
                    .map(|(x, y)| (x - y).abs())
                    .fold(0.0, f64::max)
            };
            // Pressure relative to p_max; gap relative to the approach; approach relative.
            let dp = diff(&st.pressure, &reference.pressure) / reference.p_max();
            let dd = diff(&st.gap, &reference.gap) / approach.abs();
            let dl = (st.approach().unwrap() / approach - 1.0).abs();
            println!(
                "{:>6} {:>22} {ms:>10.2} {dp:>10.1e} {dd:>10.1e} {dl:>10.1e} {:>6} {:>6} {:>6}",
                problem.len(),
                label,
                st.iterations,
                st.iterp,
                st.iterd
            );
        }
    }
    let mut group = c.benchmark_group("contact");
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(300));
    for problem in &problems {
        for (label, solver) in solvers() {
            group.bench_with_input(
                BenchmarkId::new(label.replace(' ', "_"), problem.len()),
                problem,
                |b, p| b.iter(|| solver.solve(p).unwrap()),
            );
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
