//! How a solid body's build and contact solve grow with its size: a quarter of a steel block
//! (symmetry planes x = 0 and y = 0, bottom clamped) of 20-node hexahedra graded towards the
//! contact, pressed by a rigid roller quarter (R = 5 mm, half-length 5 mm, F/4 = 2500 N)
//! along y over a top region of 2 × 6 mm, read on cells (one per contact face; see
//! [`face_cells`]), each point its cell's mean and its force a uniform pressure over the
//! cell, as the roller study reads its half-spaces. The influence is
//! applied through the sparse factorisation: the face's unknowns ordered last, each product a
//! forward and backward solve through the factor's trailing block, so the matrix-free
//! Polonsky–Keer solver runs on it unchanged. The table of the book's performance chapter
//! ("Solids"), a `cargo xtask book` source (slow).
//!
//! ```text
//! cargo run --release --example solid_scaling            # sizes 1..=4 and 6.3 (54 289 and 202 527 nodes)
//! cargo run --release --example solid_scaling -- 2 amd natural dissection   # one size, three orderings
//! cargo run --release --example solid_scaling -- 4 dissection dense   # the influence condensed once
//! ```
//!
//! Columns: nodes and free unknowns; contact points; the ordering; the influence's form;
//! `assemble` the element integration and assembly; `factor` ordering, symbolic and numeric
//! Cholesky; `condense` the dense influence (zero for products); nnz(L) and the numeric
//! factor's floating-point operations; `load solve` one full solve (the load case); the contact
//! solve (its products) and its steps; the CPU time of the build (everything before the
//! contact solve) and of the contact solve; the peak heap of the whole case (the design
//! included); p_max. A size whose factor exceeds the body's memory limit prints the refusal.
//! Times in seconds: wall-clock for the phases, CPU for the two last (the machine is shared;
//! CPU time is what one idle core would take).
//!
//! The second table, the design: one influence product through the factor (the mean CPU time
//! of [`PRODUCTS`] products of the contact's forces after a first) and the heap it allocates
//! (bytes above the live heap before those products); the roller's crown designed on the
//! quarter model as the roller study designs it (the load split with Polonsky–Keer, Ω_v the
//! centre row next to x = 0, the C¹ controller with L1 = L2 = the half-length, the
//! gap change a profile along the roller's axis), its wall-clock and CPU time, passes and
//! Polonsky–Keer steps, the crown's largest drop and p_max, and how the load split ended.
//! `nodesign` leaves the design out.

use std::time::Instant;

use contopt::fem::solid::{
    Axis, Cell, Condensation, SolidBody, SolidFace, SolidKind, SolidMesh, SolidModel, SolidSample,
    SolidSettings,
};
use contopt::fem::Ordering;
use contopt::prelude::*;
use contopt_validation::fixtures::PeakAlloc;

#[global_allocator]
static ALLOC: PeakAlloc = PeakAlloc;

/// Products timed per size for the product's mean (after a first that sizes the buffers).
const PRODUCTS: usize = 1000;

/// The load split's tolerance, the roller study's (`examples/roller_scaling.rs`).
const SPLIT_TOLERANCE: f64 = 1e-8;

/// Block quarter [0, 10] × [0, 16] × [−10, 0] mm.
const BLOCK: [f64; 3] = [10.0, 16.0, 10.0];
/// The rigid roller: radius and half-length \[mm\], quarter load \[N\].
const RADIUS: f64 = 5.0;
const HALF_LENGTH: f64 = 5.0;
const QUARTER_LOAD: f64 = 2500.0;

/// Cells (x, y, z) of size `k`: 8k × 4k × 6k, about 850·k³ nodes (54 289 at k = 4, 202 527
/// at k = 6.3).
fn cells(k: f64) -> [usize; 3] {
    [8.0 * k, 4.0 * k, 6.0 * k].map(|c| (c.round() as usize).max(1))
}

fn block(k: f64) -> Result<SolidModel> {
    let c = cells(k);
    // Graded towards x = 0 and z = 0 (the contact), uniform along the roller.
    let mesh =
        SolidMesh::block(SolidKind::Hex20, [1.0, 1.0, 1.0], [c[0], c[1], c[2]])?.map(|q| {
            let g = |t: f64| t * (0.15 + 0.85 * t);
            [
                BLOCK[0] * g(q[0]),
                BLOCK[1] * q[1],
                -BLOCK[2] * g(1.0 - q[2]),
            ]
        })?;
    let mut model = SolidModel::new(mesh, Material::new(2.0e5, 0.3)?);
    let on = |c: usize, v: f64| move |x: [f64; 3]| (x[c] - v).abs() < 1e-9;
    let x0 = model.mesh().nodes_where(on(0, 0.0));
    let y0 = model.mesh().nodes_where(on(1, 0.0));
    let bottom = model.mesh().nodes_where(on(2, -BLOCK[2]));
    model.fix(&x0, Axis::X)?;
    model.fix(&y0, Axis::Y)?;
    for axis in Axis::ALL {
        model.fix(&bottom, axis)?;
    }
    Ok(model)
}

/// The block's outward normal on its top face, along which the roller presses.
const UP: [f64; 3] = [0.0, 0.0, 1.0];

/// The contact region read on cells, one per contact face (the face's extent in x and y: the
/// faces are the block's top, axis-aligned rectangles), as the roller study reads its
/// half-spaces: each point a cell's mean, its force a uniform pressure over the cell
/// (`SolidSample::cells`), the centre row (Ω_v) the cells next to x = 0.
///
/// A cell is never finer than the face under it (as in `examples/finite_roller.rs`). The
/// influence among the cells has rank at most the faces' node count, about 3 per 8-node face
/// (4 corners shared by 4 faces, 4 mid-sides by 2): the faces' 9 Gauss points made it
/// singular and their pressures alternate. Two cells per face across the roller keep it
/// regular but still let the pressure alternate between each face's two cells.
fn face_cells(model: &SolidModel, contact: &[SolidFace]) -> Vec<Cell> {
    let mesh = model.mesh();
    (contact.iter())
        .map(|&face| {
            let xs = mesh.face_nodes(face).into_iter().map(|a| mesh.nodes()[a]);
            let (lo, hi) = xs.fold(
                ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
                |(lo, hi), x| {
                    (
                        [lo[0].min(x[0]), lo[1].min(x[1])],
                        [hi[0].max(x[0]), hi[1].max(x[1])],
                    )
                },
            );
            Cell::xy(
                [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.0],
                [hi[0] - lo[0], hi[1] - lo[1]],
            )
        })
        .collect()
}

/// CPU time of the calling thread so far \[s\] (Linux: the first field of
/// `/proc/thread-self/schedstat`, nanoseconds on the CPU), NaN where it cannot be read. The
/// machine is shared: wall-clock times of a run that waits for the core say little, its CPU
/// time what one idle core would take.
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|t| t.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| ns * 1e-9)
}

/// One size: prints its row of the first table and returns its row of the second (none when
/// refused).
fn run(
    k: f64,
    ordering: Ordering,
    condensation: Condensation,
    design: bool,
) -> std::result::Result<Option<String>, Box<dyn std::error::Error>> {
    let heap = PeakAlloc::start();
    let build_cpu = cpu_seconds();
    let model = block(k)?;
    let contact = model
        .mesh()
        .faces_where(|x| x[2].abs() < 1e-9 && x[0] <= 2.0 + 1e-9 && x[1] <= 6.0 + 1e-9);
    let settings = SolidSettings {
        condensation,
        ordering,
        ..Default::default()
    };
    let nodes = model.mesh().nodes().len();
    let samples = SolidSample::cells(model.mesh(), &contact, &face_cells(&model, &contact), UP)?;
    let body = match SolidBody::sampled("block", model, &samples, settings) {
        Err(e @ Error::TooLarge { .. }) => {
            let cpu = cpu_seconds() - build_cpu;
            let peak = PeakAlloc::peak_since(heap);
            println!("| {nodes:>6} | refused after {cpu:.1} s CPU, peak {peak:.0} MiB: {e} |");
            return Ok(None);
        }
        body => body?,
    };
    let build_cpu = cpu_seconds() - build_cpu;
    let roller = RigidBody::pressed("roller", body.interface(), [0.0, 0.0, 1.0], QUARTER_LOAD)?;
    // A straight roller over y ≤ 5 mm; beyond its end the gap opens by 1 mm.
    let gap: Vec<f64> = (body.interface().points().iter())
        .map(|x| x[0] * x[0] / (2.0 * RADIUS) + if x[1] > HALF_LENGTH { 1.0 } else { 0.0 })
        .collect();
    let problem = InterfaceProblem::new(&body, &roller, &gap)?;
    let start = Instant::now();
    let solve_cpu = cpu_seconds();
    let state = PolonskyKeer::new(PolonskyKeerSettings::default())?.solve(&problem)?;
    let solve = start.elapsed();
    let solve_cpu = cpu_seconds() - solve_cpu;
    let forces: Vec<f64> = (state.pressure.iter().zip(body.interface().weights()))
        .map(|(p, w)| p * w)
        .collect();
    let (product, product_heap) = product_cost(&body, &forces);
    let crown = design
        .then(|| designed(&problem, body.interface()))
        .transpose()?;
    let peak = PeakAlloc::peak_since(heap);
    let s = body.stats();
    let p_max = state.pressure.iter().fold(0.0f64, |m, &p| m.max(p));
    println!(
        "| {:>6} | {:>7} | {:>5} | {:?} | {} | {:>7.2} | {:>7.2} | {:>6.2} | {:>6.1} | {:>6.1} | {:>7.4} | {:>6.2} | {:>6} | {:>6.2} | {:>6.2} | {:>6.0} | {:>7.1} |",
        s.nodes,
        s.unknowns,
        body.interface().len(),
        ordering,
        if s.dense { "dense" } else { "products" },
        s.assembly.as_secs_f64(),
        s.factorisation.as_secs_f64(),
        s.condensation.as_secs_f64(),
        s.factor_nnz as f64 / 1e6,
        s.factor_flops / 1e9,
        s.solve.as_secs_f64(),
        solve.as_secs_f64(),
        state.iterations,
        build_cpu,
        solve_cpu,
        peak,
        p_max,
    );
    assert!(state.is_converged(), "{}", state.termination);
    let design = match crown {
        Some(d) => format!(
            "{:>7.2} | {:>6.2} | {:>3} | {:>6} | {:>5.2} | {:>7.1} | {} |",
            d.seconds,
            d.cpu,
            d.optimum.passes.len(),
            d.optimum.passes.iter().map(|p| p.iterp).sum::<usize>(),
            1e3 * d.optimum.dh_max(),
            d.optimum.p_max,
            ending(&d.optimum),
        ),
        None => "– | – | – | – | – | – | – |".into(),
    };
    Ok(Some(format!(
        "| {:>6} | {:>5} | {:>8.1} | {:>4} | {design}",
        s.nodes,
        body.interface().len(),
        1e6 * product,
        product_heap,
    )))
}

/// One influence product's mean CPU time \[s\] over [`PRODUCTS`] products of `force` after a
/// first (CPU time: a product is short, and wall-clock time on a shared core counts the
/// waits), and the heap those products allocated \[bytes\]: none, the body's work buffers
/// being reused.
fn product_cost(body: &SolidBody, force: &[f64]) -> (f64, usize) {
    let mut displacement = vec![0.0; force.len()];
    body.apply_influence(force, &mut displacement);
    // Reading the CPU time allocates: it is read outside the heap's measurement.
    let start = cpu_seconds();
    let live = PeakAlloc::start();
    for _ in 0..PRODUCTS {
        body.apply_influence(force, &mut displacement);
    }
    let heap = PeakAlloc::peak_since(live) * (1u64 << 20) as f64;
    let seconds = (cpu_seconds() - start) / PRODUCTS as f64;
    (seconds, heap.round() as usize)
}

/// How a load split ended, in a table cell: converged, infeasible by how much on Ω_nv, or
/// the termination's own words.
fn ending(optimum: &Optimum) -> String {
    match (&optimum.termination, optimum.omega_nv_excess) {
        (Termination::Converged, _) => "converged".into(),
        (Termination::Infeasible { .. }, Some(excess)) => {
            format!("infeasible: Ω_nv {excess:.1} MPa over v·p_max")
        }
        (other, _) => other.to_string(),
    }
}

/// Coordinates closer than this are one \[mm\].
const ON: f64 = 1e-9;

/// The crown's gap change: one design value per distinct y under the roller (y ≤ the
/// half-length), the same across the row (a profile along the axis), each point beyond the
/// roller's end moving with the last (its 1 mm step kept).
fn crown_shape(iface: &Interface) -> Result<GapShape> {
    let mut ys: Vec<f64> = (iface.points().iter())
        .map(|x| x[1])
        .filter(|&y| y <= HALF_LENGTH + ON)
        .collect();
    ys.sort_by(f64::total_cmp);
    ys.dedup_by(|a, b| (*a - *b).abs() <= ON);
    let last = ys.len() - 1;
    let rows = (iface.points().iter())
        .map(|x| vec![(ys.partition_point(|&y| y < x[1] - ON).min(last), 1.0)])
        .collect();
    GapShape::new(ys.iter().map(|&y| [0.0, y, 0.0]).collect(), rows)
}

/// A crown designed on the quarter model, with its times.
struct Design {
    optimum: Optimum,
    seconds: f64,
    cpu: f64,
}

/// The roller's crown designed as the roller study designs it: the load split with
/// Polonsky–Keer to [`SPLIT_TOLERANCE`], Ω_v the centre row (the points nearest x = 0) under
/// the roller, Ω_nv the rest, the gap change a profile along the axis ([`crown_shape`]), the
/// C¹ controller v = 1 up to the roller's end (y = the half-length).
fn designed(problem: &InterfaceProblem, iface: &Interface) -> Result<Design> {
    let centre = (iface.points().iter()).fold(f64::INFINITY, |m, x| m.min(x[0]));
    let regions = (iface.points().iter())
        .map(|x| match x[0] <= centre + ON && x[1] <= HALF_LENGTH + ON {
            true => Region::OmegaV,
            false => Region::OmegaNv,
        })
        .collect();
    let shape = crown_shape(iface)?;
    let controller = Profile::cubic(HALF_LENGTH, HALF_LENGTH)?.along(1)?;
    let split = LoadSplitSettings {
        tolerance: SPLIT_TOLERANCE,
        max_iterations: 100,
    };
    let start = Instant::now();
    let cpu = cpu_seconds();
    let optimum = Optimisation::new(problem, &shape, &controller)?
        .with_regions(regions)?
        .load_split(&PolonskyKeer::new(PolonskyKeerSettings::default())?, &split)?;
    Ok(Design {
        optimum,
        seconds: start.elapsed().as_secs_f64(),
        cpu: cpu_seconds() - cpu,
    })
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    contopt::faer::set_global_parallelism(contopt::faer::Par::Seq);
    let args: Vec<String> = std::env::args().skip(1).collect();
    let sizes: Vec<f64> = match args.first().and_then(|a| a.parse().ok()) {
        Some(k) => vec![k],
        None => vec![1.0, 2.0, 3.0, 4.0, 6.3],
    };
    let mut orderings: Vec<Ordering> = args
        .iter()
        .filter_map(|a| match a.as_str() {
            "amd" => Some(Ordering::Amd),
            "natural" => Some(Ordering::Natural),
            "dissection" => Some(Ordering::Dissection),
            _ => None,
        })
        .collect();
    // `dense`: the influence condensed once (a block of solves) instead of products.
    let condensation = if args.iter().any(|a| a == "dense") {
        Condensation::Dense
    } else {
        Condensation::Products
    };
    if orderings.is_empty() {
        orderings.push(Ordering::Dissection);
    }
    let design = !args.iter().any(|a| a == "nodesign");
    println!("| nodes | unknowns | points | ordering | influence | assemble s | factor s | condense s | nnz(L) M | factor GFlop | load solve s | contact s | steps | build CPU s | contact CPU s | peak MiB | p_max MPa |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let mut designs = Vec::new();
    for k in sizes {
        for &ordering in &orderings {
            designs.extend(run(k, ordering, condensation, design)?);
        }
    }
    println!();
    println!("| nodes | points | product CPU µs | product heap B | design s | design CPU s | passes | steps | Δh_max µm | p_max MPa | ending |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for row in designs {
        println!("{row}");
    }
    Ok(())
}
