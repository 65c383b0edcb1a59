//! The reader's run time on a large mesh (the book's design notes, "Gmsh reader"):
//!
//! ```sh
//! python3 meshes/generate.py --bench target/gmsh-bench
//! cargo build --release -p contopt-gmsh --example read_large
//! /usr/bin/time -v target/release/examples/read_large target/gmsh-bench/rectangle-200k.msh
//! ```
//!
//! prints the time to read the file and to import its body (the best of `RUNS` runs), and
//! the mesh's size; `/usr/bin/time -v` gives the peak memory ("Maximum resident set size").
//! With `--read-only` the file is read once and not imported (the reader's own peak memory).

use std::time::{Duration, Instant};

use contopt_gmsh::Surfaces;

/// Runs timed; the best is printed.
const RUNS: usize = 5;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args
        .iter()
        .find(|a| !a.starts_with("--"))
        .ok_or("usage: read_large FILE.msh [--read-only]")?;
    if args.iter().any(|a| a == "--read-only") {
        let gmsh = contopt_gmsh::read(path)?;
        println!("{} nodes read", gmsh.coords().len());
        return Ok(());
    }
    let (mut read, mut import) = (Duration::MAX, Duration::MAX);
    let mut sizes = (0, 0, 0);
    for _ in 0..RUNS {
        let start = Instant::now();
        let gmsh = contopt_gmsh::read(path)?;
        let read_end = Instant::now();
        let imported = gmsh.import(Surfaces::All)?;
        import = import.min(read_end.elapsed());
        read = read.min(read_end - start);
        let faces: usize = imported.groups.iter().map(|g| g.faces.len()).sum();
        sizes = (
            imported.mesh.nodes().len(),
            imported.mesh.elements().len(),
            faces,
        );
    }
    println!("{path}");
    println!(
        "nodes {}, elements {}, group faces {}",
        sizes.0, sizes.1, sizes.2
    );
    println!("read   {:8.1} ms", read.as_secs_f64() * 1e3);
    println!("import {:8.1} ms", import.as_secs_f64() * 1e3);
    Ok(())
}
