//! Assembly, factorisation and condensation of axisymmetric finite-element bodies of about
//! 10k, 50k and 200k unknowns, condensed onto a 201-point contact interface (67 quadratic
//! faces, the paper's base block), with the peak heap memory of one build.
//!
//! `cargo bench --bench fem` prints criterion's timings per phase and a summary table.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use contopt::fem::{Analysis, Component, ElementKind, FeBody, FeModel, Material, Mesh, Spacing};
use contopt::ElasticBody;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode};

/// Counts live and peak heap bytes.
struct PeakAlloc;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for PeakAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let live = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(live, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
}

#[global_allocator]
static ALLOC: PeakAlloc = PeakAlloc;

/// The paper's base block (r ≤ 100 mm, height 50 mm, clamped bottom) with 67 uniform faces
/// under the punch (r ≤ 50 mm) and `outer` × `layers` graded elements elsewhere.
fn base_block(outer: usize, layers: usize) -> (FeModel, Vec<contopt::fem::Face>) {
    let x = Spacing::uniform(0.0, 50.0, 67)
        .unwrap()
        .then(&Spacing::geometric(50.0, 100.0, outer, 8.0).unwrap())
        .unwrap();
    let y = Spacing::geometric(0.0, 50.0, layers, 0.2).unwrap();
    let mesh = Mesh::rectangle(ElementKind::Q8, &x, &y).unwrap();
    let mut model = FeModel::new(
        mesh,
        Material::new(2e5, 0.3).unwrap(),
        Analysis::Axisymmetric,
    )
    .unwrap();
    let bottom = model.mesh().nodes_on_y(0.0, 0.0, 100.0);
    model
        .fix(&bottom, Component::X)
        .unwrap()
        .fix(&bottom, Component::Y)
        .unwrap();
    let contact = model.mesh().faces_on_y(50.0, 0.0, 50.0);
    (model, contact)
}

const SIZES: [(&str, usize, usize); 3] = [("10k", 13, 20), ("50k", 83, 55), ("200k", 233, 110)];

fn build(outer: usize, layers: usize) -> FeBody {
    let (model, contact) = base_block(outer, layers);
    FeBody::new("base", model, &contact).unwrap()
}

fn phases(c: &mut Criterion) {
    println!(
        "{:>6} {:>9} {:>7} {:>12} {:>10} {:>10} {:>10} {:>10} {:>9}",
        "mesh", "unknowns", "face", "nnz(L)", "assembly", "factor", "condense", "load", "peak MiB"
    );
    for (label, outer, layers) in SIZES {
        let base = LIVE.load(Ordering::Relaxed);
        PEAK.store(base, Ordering::Relaxed);
        let body = build(outer, layers);
        let peak = (PEAK.load(Ordering::Relaxed) - base) as f64 / (1 << 20) as f64;
        let s = *body.stats();
        assert_eq!(body.interface().len(), 201);
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        println!(
            "{label:>6} {:>9} {:>7} {:>12} {:>8.1}ms {:>8.1}ms {:>8.1}ms {:>8.1}ms {peak:>9.1}",
            s.unknowns,
            s.face_unknowns,
            s.factor_nnz,
            ms(s.assembly),
            ms(s.factorisation),
            ms(s.condensation),
            ms(s.load_solve)
        );
    }
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
