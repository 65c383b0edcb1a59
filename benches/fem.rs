//! Assembly, factorisation and condensation of axisymmetric finite-element bodies of about
//! 10k, 50k and 200k unknowns, condensed onto a 201-point contact interface (67 quadratic
//! faces, the paper's base block).
//!
//! `cargo bench --bench fem` prints criterion's timings per phase; `cargo run --release
//! --example fem_cost` prints the table of one build (sizes, phases, peak heap).

use std::time::Duration;

use contopt::fem::FeBody;
use contopt_validation::fixtures::base_block;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode};

const SIZES: [(&str, usize, usize); 3] = [("10k", 13, 20), ("50k", 83, 55), ("200k", 233, 110)];

fn build(outer: usize, layers: usize) -> FeBody {
    base_block(outer, layers).unwrap()
}

fn phases(c: &mut Criterion) {
    let mut group = c.benchmark_group("fe_body");
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(500));
    type Phase = fn(&contopt::fem::BuildStats) -> Duration;
    let phase_list: [(&str, Phase); 3] = [
        ("assembly", |s| s.assembly),
        ("factorisation", |s| s.factorisation),
        ("condensation", |s| s.condensation),
    ];
    for (label, outer, layers) in SIZES {
        for (name, phase) in phase_list {
            group.bench_with_input(
                BenchmarkId::new(name, label),
                &(outer, layers),
                |b, &(o, l)| {
                    b.iter_custom(|iters| (0..iters).map(|_| phase(build(o, l).stats())).sum())
                },
            );
        }
    }
    group.finish();
}

criterion_group!(benches, phases);
criterion_main!(benches);
