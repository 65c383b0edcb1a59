//! What a finite-element body costs to build: the paper's base block (r ≤ 100 mm, height
//! 50 mm, clamped bottom), axisymmetric Q8, condensed onto a 201-point interface (67 contact
//! faces under the punch), at about 10k, 50k and 200k unknowns: the size of the factor, the
//! time of each phase of one build and its peak heap. The table of the book's chapter on
//! finite-element bodies; `cargo bench --bench fem` times the phases with criterion.
//!
//! `cargo run --release --example fem_cost`

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use contopt::fem::{Analysis, Component, ElementKind, FeBody, FeModel, Material, Mesh, Spacing};
use contopt::ElasticBody;

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

/// The contact points of the base block.
const POINTS: usize = 201;

/// The meshes: elements outside the punch radius and layers through the height.
const SIZES: [(usize, usize); 3] = [(13, 20), (83, 55), (233, 110)];

/// The base block with 67 uniform faces under the punch (r ≤ 50 mm) and `outer` × `layers`
/// graded elements elsewhere, condensed onto those faces.
fn base_block(outer: usize, layers: usize) -> contopt::Result<FeBody> {
    let x = Spacing::uniform(0.0, 50.0, 67)?.then(&Spacing::geometric(50.0, 100.0, outer, 8.0)?)?;
    let y = Spacing::geometric(0.0, 50.0, layers, 0.2)?;
    let mesh = Mesh::rectangle(ElementKind::Q8, &x, &y)?;
    let mut model = FeModel::new(mesh, Material::new(2e5, 0.3)?, Analysis::Axisymmetric)?;
    let bottom = model.mesh().nodes_on_y(0.0, 0.0, 100.0);
    model
        .fix(&bottom, Component::X)?
        .fix(&bottom, Component::Y)?;
    let contact = model.mesh().faces_on_y(50.0, 0.0, 50.0);
    FeBody::new("base", model, &contact)
}

fn main() -> contopt::Result<()> {
    println!(
        "{:>9} {:>7} {:>8}  {:>11} {:>14} {:>14} {:>13} {:>9}",
        "unknowns",
        "face",
        "nnz(L)",
        "assembly",
        "factorisation",
        "condensation",
        "load solve",
        "peak MiB"
    );
    for (outer, layers) in SIZES {
        let base = LIVE.load(Ordering::Relaxed);
        PEAK.store(base, Ordering::Relaxed);
        let body = base_block(outer, layers)?;
        let peak = (PEAK.load(Ordering::Relaxed) - base) as f64 / (1 << 20) as f64;
        assert_eq!(body.interface().len(), POINTS);
        let s = *body.stats();
        let ms = |d: Duration| format!("{:.1} ms", d.as_secs_f64() * 1e3);
        println!(
            "{:>9} {:>7} {:>7.1}M  {:>11} {:>14} {:>14} {:>13} {peak:>9.0}",
            s.unknowns,
            s.face_unknowns,
            s.factor_nnz as f64 * 1e-6,
            ms(s.assembly),
            ms(s.factorisation),
            ms(s.condensation),
            ms(s.load_solve)
        );
    }
    Ok(())
}
