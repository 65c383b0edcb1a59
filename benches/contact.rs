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

use contopt::contact::{
    ActiveSet, AugmentedLagrangian, ContactSolver, InterfaceProblem, Penalty, Qp,
};
use contopt_validation::fixtures::hertz_on_block;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode};

const E: f64 = 2.0e5;

fn solvers() -> Vec<Box<dyn ContactSolver>> {
    vec![
        Box::new(Qp::default()),
        Box::new(ActiveSet),
        Box::new(AugmentedLagrangian::new(E * 1e4)),
        Box::new(Penalty { c: E * 1e4 }),
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
        let reference = Qp::default().solve(problem).unwrap();
        for solver in solvers() {
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
            let dd = diff(&st.gap, &reference.gap) / reference.rigid[0].abs();
            let dl = (st.rigid[0] / reference.rigid[0] - 1.0).abs();
            println!(
                "{:>6} {:>22} {ms:>10.2} {dp:>10.1e} {dd:>10.1e} {dl:>10.1e} {:>6} {:>6} {:>6}",
                problem.len(),
                solver.name(),
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
        for solver in solvers() {
            group.bench_with_input(
                BenchmarkId::new(solver.name().replace(' ', "_"), problem.len()),
                problem,
                |b, p| b.iter(|| solver.solve(p).unwrap()),
            );
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
