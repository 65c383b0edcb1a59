//! How a solid body's build and contact solve grow with its size: a quarter of a steel block
//! (symmetry planes x = 0 and y = 0, bottom clamped) of 20-node hexahedra graded towards the
//! contact, pressed by a rigid roller quarter (R = 5 mm, half-length 5 mm, F/4 = 2500 N)
//! along y over a top region of 2 × 6 mm, sampled at its faces' Gauss points. The influence is
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
//! contact solve) and of the contact solve; the peak heap of the whole case; p_max. A size whose
//! factor exceeds the body's memory limit prints the refusal, made after the symbolic analysis
//! before the factor is allocated. Times in seconds: wall-clock for the phases, CPU for the two
//! last (the machine is shared; CPU time is what one idle core would take).

use std::time::Instant;

use contopt::fem::solid::{
    Axis, Condensation, SolidBody, SolidKind, SolidMesh, SolidModel, SolidSettings,
};
use contopt::fem::Ordering;
use contopt::prelude::*;
use contopt_validation::fixtures::PeakAlloc;

#[global_allocator]
static ALLOC: PeakAlloc = PeakAlloc;

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

fn run(
    k: f64,
    ordering: Ordering,
    condensation: Condensation,
) -> std::result::Result<(), Box<dyn std::error::Error>> {
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
    let body = match SolidBody::new("block", model, &contact, settings) {
        Err(e @ Error::TooLarge { .. }) => {
            let cpu = cpu_seconds() - build_cpu;
            let peak = PeakAlloc::peak_since(heap);
            println!("| {nodes:>6} | refused after {cpu:.1} s CPU, peak {peak:.0} MiB: {e} |");
            return Ok(());
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
    Ok(())
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
    println!("| nodes | unknowns | points | ordering | influence | assemble s | factor s | condense s | nnz(L) M | factor GFlop | load solve s | contact s | steps | build CPU s | contact CPU s | peak MiB | p_max MPa |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for k in sizes {
        for &ordering in &orderings {
            run(k, ordering, condensation)?;
        }
    }
    Ok(())
}
