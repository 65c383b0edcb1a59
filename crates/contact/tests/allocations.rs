//! Kalker's iteration allocates a fixed number of times per solve on a contact set, whatever
//! the number of points: its buffers live in a workspace sized once per contact solve. A
//! Polonsky–Keer solve in a workspace kept from an earlier solve allocates nothing.
//!
//! A counting global allocator (one per test binary, hence this file) counts the allocations of
//! the current thread; an observer reads the count at each of Kalker's solves (`iterp`), so the
//! allocations of one step of the loop are the difference between two consecutive events.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use contopt_contact::{
    ActiveSet, ActiveSetSettings, AugmentedLagrangian, AugmentedLagrangianSettings, ContactSolver,
    InterfaceProblem, Penalty, PenaltySettings, PolonskyKeer, PolonskyKeerSettings,
    PolonskyKeerWorkspace, Workspace,
};
use contopt_core::observe::{Event, Flow, Method, Silent};
use contopt_core::{ElasticBody, Geometry, Interface, Material, RigidBody, RigidMode};
use contopt_greens::HalfSpace;
use faer::Mat;

/// The system allocator, counting the allocations (and reallocations) of each thread.
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

fn count() {
    // `try_with`: the counter may already be gone while a thread ends.
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

/// The allocations of this thread so far.
fn allocations() -> u64 {
    ALLOCATIONS.with(Cell::get)
}

// SAFETY: every call is forwarded to `System` unchanged; the counter is a thread-local `Cell`
// with a const initialiser, whose access does not allocate.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// A body given by its influence matrix; its product allocates nothing.
struct MatrixBody {
    interface: Interface,
    a: Mat<f64>,
    modes: Vec<RigidMode>,
}

impl ElasticBody for MatrixBody {
    fn name(&self) -> &str {
        "matrix body"
    }
    fn interface(&self) -> &Interface {
        &self.interface
    }
    fn apply_influence(&self, force: &[f64], out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            *o = (0..force.len()).map(|j| self.a[(i, j)] * force[j]).sum();
        }
    }
    fn load_displacement(&self) -> contopt_core::Result<Vec<f64>> {
        Ok(vec![0.0; self.a.nrows()])
    }
    fn rigid_modes(&self) -> &[RigidMode] {
        &self.modes
    }
}

/// n points on a line of a body with the compliance Aᵢⱼ = 10⁻³ e^(−|i−j|/3), floating (one
/// translation loaded by n/20 N) over a wavy parabolic gap: about 70 % of the points close, after
/// several changes of the contact set.
fn wavy_floating(n: usize) -> InterfaceProblem<'static> {
    let points = (0..n).map(|i| [i as f64, 0.0, 0.0]).collect();
    let interface = Interface::new(
        Geometry::Plane { thickness: 1.0 },
        points,
        vec![1.0; n],
        vec![[0.0, 1.0, 0.0]; n],
    )
    .unwrap();
    let a = Mat::from_fn(n, n, |i, j| 1e-3 * (-(i.abs_diff(j) as f64) / 3.0).exp());
    let mode = RigidMode {
        name: "translation".into(),
        interface_displacement: vec![1.0; n],
        load: -(n as f64) / 20.0,
    };
    let body = MatrixBody {
        interface,
        a,
        modes: vec![mode],
    };
    let rigid = RigidBody::fixed("rigid", body.interface());
    let gap: Vec<f64> = (0..n)
        .map(|i| {
            let x = (i as f64 - n as f64 / 2.0) / (n as f64 / 2.0);
            1e-3 * (x * x + 0.3 * (3.0 * i as f64).sin().abs())
        })
        .collect();
    InterfaceProblem::owned(Box::new(body), Box::new(rigid), &gap).unwrap()
}

/// What one solve allocated: in all, and between consecutive reports of `method`.
struct Counted {
    total: u64,
    steps: Vec<u64>,
    iterp: usize,
}

/// Solves `problem` by `solver`, counting this thread's allocations, and at each event of
/// `method` (Kalker's solves).
fn counted(solver: &dyn ContactSolver, problem: &InterfaceProblem, method: Method) -> Counted {
    // Build the dense matrix first: it is shared by every solve of the problem.
    problem.dense_influence(1).unwrap();
    let marks = std::cell::RefCell::new(Vec::with_capacity(10_000));
    let observer = |e: &Event| {
        if e.method == method && e.end.is_none() {
            marks.borrow_mut().push(allocations());
        }
        Flow::Continue
    };
    let start = allocations();
    let state = solver.solve_observed(problem, None, &observer).unwrap();
    let total = allocations() - start;

    assert!(state.is_converged(), "{}", state.termination);
    let marks = marks.into_inner();
    Counted {
        total,
        steps: marks.windows(2).map(|w| w[1] - w[0]).collect(),
        iterp: state.iterp,
    }
}

/// Allocations of a step of Kalker's loop in steady state (the difference between two
/// consecutive solves on a contact set). Measured: 0, for n = 50 and 200 and every solver here,
/// Cholesky and spectral solves alike (faer factorises and multiplies in the workspace's
/// buffers and scratch). The margin is for faer's matrix products, which may allocate packing
/// buffers on other processors; before the workspace, each step allocated 26 to 44 times (the
/// index lists, the contact-set matrix, its factor, the right-hand sides, the gaps).
const STEP: u64 = 2;

/// Allocations of the one step that switches from the Cholesky solves at c_stiff to the
/// spectral ones (the active set's exact solves, a penalty or a Uzawa step with c above
/// c_stiff): the eigenvectors, the eigenvalues, the eigen-decomposition's scratch, the
/// contact-set matrix resized to the set, a product and the subproblem's zero shift. Measured:
/// 6 or 7.
const SWITCH: u64 = 10;

/// Allocations of a whole contact solve less its steps: the workspace (the free gap, R and q,
/// the iterate, the gaps, the index lists and the right-hand sides, each once), the contact
/// set, the zero reference and shift, and the contact state with its gap. Measured: 30 to 37
/// whatever n and the number of solves (for the augmented Lagrangian, 125 to 128 of them).
const SOLVE: u64 = 45;

/// Kalker's loop reuses one workspace for every solve on a contact set: its steps allocate
/// nothing (beyond a small margin for faer's kernels), whatever the number of points, so that a
/// contact solve allocates a fixed number of times however many steps it takes.
#[test]
fn kalker_steps_allocate_a_fixed_number_of_times() {
    let active_set = ActiveSet::new(ActiveSetSettings::default()).unwrap();
    let stiff_penalty = Penalty::new(PenaltySettings { c_mpa_per_mm: 1e12 }).unwrap();
    // Plain Uzawa steps (not accelerated) at c below c_stiff = 10⁶ / maxᵢ(Aᵢᵢ wᵢ) = 10⁹ (Cholesky
    // solves, over a hundred of them) and above it (spectral solves).
    let uzawa = |c| {
        AugmentedLagrangian::new(AugmentedLagrangianSettings {
            accelerate: false,
            ..AugmentedLagrangianSettings::new(c)
        })
        .unwrap()
    };
    let (soft, stiff) = (uzawa(1e3), uzawa(1.5e9));
    let solvers: [(&dyn ContactSolver, Method); 4] = [
        (&active_set, Method::ActiveSet),
        (&stiff_penalty, Method::Penalty),
        (&soft, Method::Kalker),
        (&stiff, Method::Kalker),
    ];
    let mut totals = vec![];
    for n in [50, 200] {
        let problem = wavy_floating(n);
        for (solver, method) in solvers {
            let c = counted(solver, &problem, method);
            let what = format!("{} on {n} points ({} solves)", solver.method(), c.iterp);
            println!(
                "{what}: {} allocations, between solves {:?}",
                c.total, c.steps
            );
            assert!(c.iterp >= 5, "{what}: too few solves for the test");
            let mut steps = c.steps.clone();
            steps.sort_unstable();
            if let Some(switch) = steps.pop() {
                assert!(switch <= SWITCH, "{what}: {switch} allocations in one step");
            }
            assert!(
                steps.iter().all(|&s| s <= STEP),
                "{what}: steps allocate {:?}",
                c.steps
            );
            let bound = SOLVE + STEP * c.iterp as u64;
            assert!(
                c.total <= bound,
                "{what}: {} allocations > {bound}",
                c.total
            );
            totals.push(c.total);
        }
    }
    // Independent of n: four times the points, the same count to a few.
    let (small, large) = totals.split_at(solvers.len());
    for (s, l) in small.iter().zip(large) {
        assert!(
            l.abs_diff(*s) <= 2,
            "{small:?} for 50 points, {large:?} for 200"
        );
    }
}

/// Allocations of a Kalker solve in a workspace kept from an earlier solve of the same size:
/// the returned state (its pressure, rigid amplitudes, contact set and gap, with the gap's two
/// product buffers), the reference iterate, the zero shifts and the first contact set; none of
/// the workspace's. Measured: 11 to 14 (38 or 39 in a fresh workspace).
const KEPT_SOLVE: u64 = 16;

/// Solves in a kept [`Workspace`] reuse Kalker's buffers: after the first, a solve allocates
/// only what it returns and a few per-solve vectors, whatever the number of points.
#[test]
fn kalker_solves_reuse_a_kept_workspace() {
    let active_set = ActiveSet::new(ActiveSetSettings::default()).unwrap();
    let stiff_penalty = Penalty::new(PenaltySettings { c_mpa_per_mm: 1e12 }).unwrap();
    for n in [50, 200] {
        let problem = wavy_floating(n);
        problem.dense_influence(1).unwrap();
        for solver in [&active_set as &dyn ContactSolver, &stiff_penalty] {
            let mut workspace = Workspace::default();
            let counts: Vec<u64> = (0..3)
                .map(|_| {
                    let before = allocations();
                    let state = solver
                        .solve_in(&problem, None, &Silent, &mut workspace)
                        .unwrap();
                    assert!(state.is_converged(), "{}", state.termination);
                    allocations() - before
                })
                .collect();
            let what = format!("{} on {n} points", solver.method());
            println!("{what}: allocations per solve in a kept workspace {counts:?}");
            assert!(
                counts[1..].iter().all(|&c| c <= KEPT_SOLVE),
                "{what}: {counts:?}"
            );
        }
    }
}

/// Cells along each side of the periodic grid: odd, so that the grid neither coarsens nor
/// restricts, and every allocation of a solve is the solver's own.
const PERIODIC_SIDE: usize = 63;

/// A rigid sphere of radius 10 mm pressed by 100 N into a steel half-space that repeats a
/// `side` × `side` grid over 2 mm × 2 mm: a Hertz contact of radius about 0.15 mm (ten cells
/// across on 63²), far from the period.
fn periodic_hertz(side: usize) -> (HalfSpace, RigidBody, Vec<f64>) {
    let dx = 2.0 / side as f64;
    let origin = -1.0 + dx / 2.0;
    let steel = Material::new(2e5, 0.3).unwrap();
    let body = HalfSpace::periodic("half-space", steel, side, side, dx, dx, [origin; 2])
        .unwrap()
        .pressed(100.0)
        .unwrap();
    let sphere = RigidBody::fixed("sphere", body.interface());
    let gap = body
        .interface()
        .points()
        .iter()
        .map(|x| (x[0] * x[0] + x[1] * x[1]) / 20.0)
        .collect();
    (body, sphere, gap)
}

/// A Polonsky–Keer solve in a kept workspace allocates nothing once an earlier solve has sized
/// it: the conjugate-gradient buffers, the modes' form, the iterate and the returned state are
/// the workspace's, and the half-space's FFT products work in buffers of their own. The first
/// solve sizes the workspace; cold and warm solves after it allocate nothing, and give the
/// state a fresh workspace gives.
#[test]
fn polonsky_keer_allocates_nothing_in_a_kept_workspace() {
    let (body, sphere, gap) = periodic_hertz(PERIODIC_SIDE);
    let problem = InterfaceProblem::new(&body, &sphere, &gap).unwrap();
    let solver = PolonskyKeer::new(PolonskyKeerSettings::default()).unwrap();
    let fresh = solver.solve(&problem).unwrap();
    assert!(fresh.is_converged(), "{}", fresh.termination);
    let mut workspace = PolonskyKeerWorkspace::default();
    let mut counts = vec![];
    for start in [None, None, Some(fresh.pressure.as_slice())] {
        let before = allocations();
        let state = solver
            .solve_with(&problem, start, &Silent, &mut workspace)
            .unwrap();
        counts.push(allocations() - before);
        assert!(state.is_converged(), "{}", state.termination);
        if start.is_none() {
            assert_eq!(*state, fresh);
        }
    }
    println!("Polonsky–Keer on {PERIODIC_SIDE}² cells: allocations per solve {counts:?}");
    assert!(counts[0] > 0, "the first solve sizes the workspace");
    assert_eq!(counts[1..], [0, 0], "solves in a sized workspace allocate");
}

/// A rigid sphere of radius 10 mm pressed by 100 N into a steel half-space under a free
/// (zero-padded) `side` × `side` grid over 2 mm × 2 mm: the contact (radius about 0.15 mm)
/// covers a small part of the grid, so a solve restricts itself to a box about it and starts
/// from the coarser grids' solutions (nested iteration).
fn free_hertz(side: usize) -> (HalfSpace, RigidBody, Vec<f64>) {
    let dx = 2.0 / side as f64;
    let origin = -1.0 + dx / 2.0;
    let steel = Material::new(2e5, 0.3).unwrap();
    let body = HalfSpace::grid("half-space", steel, side, side, dx, dx, [origin; 2])
        .unwrap()
        .pressed(100.0)
        .unwrap();
    let sphere = RigidBody::fixed("sphere", body.interface());
    let gap = body
        .interface()
        .points()
        .iter()
        .map(|x| (x[0] * x[0] + x[1] * x[1]) / 20.0)
        .collect();
    (body, sphere, gap)
}

/// On a free grid a Polonsky–Keer solve works on parts of the interface and on coarser grids,
/// whose bodies (with their FFT plans and spectra) the kept workspace keeps: after the first
/// cold solve, cold solves of the same problem allocate nothing, and give the state a fresh
/// workspace gives; so do warm solves after the first, which derives the part about the
/// start's contact.
#[test]
fn polonsky_keer_on_free_grids_allocates_nothing_in_a_kept_workspace() {
    for side in [64, 256] {
        let (body, sphere, gap) = free_hertz(side);
        let problem = InterfaceProblem::new(&body, &sphere, &gap).unwrap();
        let solver = PolonskyKeer::new(PolonskyKeerSettings::default()).unwrap();
        let fresh = solver.solve(&problem).unwrap();
        assert!(fresh.is_converged(), "{}", fresh.termination);
        let mut workspace = PolonskyKeerWorkspace::default();
        let mut counts = vec![];
        let warm = Some(fresh.pressure.as_slice());
        for start in [None, None, warm, warm] {
            let before = allocations();
            let state = solver
                .solve_with(&problem, start, &Silent, &mut workspace)
                .unwrap();
            counts.push(allocations() - before);
            assert!(state.is_converged(), "{}", state.termination);
            if start.is_none() {
                assert_eq!(*state, fresh);
            }
        }
        println!("Polonsky–Keer on a free {side}² grid: allocations per solve {counts:?}");
        assert!(counts[0] > 0, "the first solve sizes the workspace");
        assert_eq!(
            [counts[1], counts[3]],
            [0, 0],
            "solves in a sized workspace allocate"
        );
    }
}
