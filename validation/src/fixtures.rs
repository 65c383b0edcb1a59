//! Bodies and instruments the benchmarks share.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use contopt_contact::{ContactSolver, InterfaceProblem, PolonskyKeer, Workspace};
use contopt_core::observe::{Method, Observer};
use contopt_core::{ContactState, Result};
use contopt_fem::{Analysis, Component, ElementKind, FeBody, FeModel, Material, Mesh, Spacing};
use contopt_scene::{Format, Scene, SceneError};

/// The paper's base block (r ≤ 100 mm, height 50 mm, clamped bottom, axisymmetric Q8) with 67
/// uniform faces under the punch (r ≤ 50 mm) and `outer` × `layers` graded elements elsewhere,
/// condensed onto those faces (201 contact points).
pub fn base_block(outer: usize, layers: usize) -> Result<FeBody> {
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

/// A global allocator that counts the live and the peak heap bytes: a benchmark declares
/// `#[global_allocator] static ALLOC: PeakAlloc = PeakAlloc;` and reads [`PeakAlloc::peak_since`].
pub struct PeakAlloc;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

impl PeakAlloc {
    /// Starts a measurement: the live bytes now, to pass to [`PeakAlloc::peak_since`].
    pub fn start() -> usize {
        let live = LIVE.load(Ordering::Relaxed);
        PEAK.store(live, Ordering::Relaxed);
        live
    }

    /// The peak heap above `start` since [`PeakAlloc::start`] \[MiB\].
    pub fn peak_since(start: usize) -> f64 {
        PEAK.load(Ordering::Relaxed).saturating_sub(start) as f64 / (1 << 20) as f64
    }
}

// SAFETY: every call is forwarded to the system allocator; the counters are atomics.
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

/// The peak resident memory of this process so far \[MiB\] (Linux's `VmHWM`), or NaN where
/// `/proc/self/status` does not say.
pub fn peak_resident_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kib| kib / 1024.0)
}

/// Hertz's contact of the benchmarks on a finite-element block: a rigid sphere of radius
/// 100 mm pressed by 4E*/(3R) N into the clamped axisymmetric block of a scene's `fe_block`
/// (1.5 mm contact zone of `faces` quadratic faces, three points each; 30 mm block), steel
/// E = 2·10⁵ MPa, ν = 0.3.
pub fn hertz_on_block(faces: usize) -> std::result::Result<InterfaceProblem<'static>, SceneError> {
    const E: f64 = 2.0e5;
    const NU: f64 = 0.3;
    const RADIUS: f64 = 100.0;
    let force = 4.0 * E / (1.0 - NU * NU) / (3.0 * RADIUS);
    let text = format!(
        r#"name = "hertz-on-block"
[contact]
zone = {{ kind = "faces", analysis = "axisymmetric", radius_mm = 1.5, elements = {faces} }}
gap = {{ kind = "sphere", radius_mm = {RADIUS:?} }}
load = {{ force_n = {force:?} }}
[[body]]
kind = "fe_block"
material = {{ e_mpa = {E:?}, nu = {NU:?} }}
size_mm = 30.0
[[body]]
kind = "rigid"
name = "sphere"
"#
    );
    let scene = Scene::parse(&text, Format::Toml, std::path::Path::new("hertz-on-block"))?;
    scene.cases()[0].problem()
}

/// Polonsky–Keer with its tolerance fixed: it offers no looser one
/// ([`ContactSolver::loosened`]), so an optimiser solves every contact to the full tolerance,
/// the reference its inexact solves are measured against.
pub struct Exact(pub PolonskyKeer);

impl ContactSolver for Exact {
    fn method(&self) -> Method {
        self.0.method()
    }

    fn dense_copies(&self, points: usize) -> u64 {
        self.0.dense_copies(points)
    }

    fn solve_in(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        observer: &dyn Observer,
        workspace: &mut Workspace,
    ) -> Result<ContactState> {
        self.0.solve_in(problem, start, observer, workspace)
    }

    fn solve_observed(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        observer: &dyn Observer,
    ) -> Result<ContactState> {
        self.0.solve_observed(problem, start, observer)
    }
}
