//! Hetényi's quarter-space checked by a finite solid (issue 37, point 3a): a uniform pressure
//! on a square patch a × a at the free edge x = 0 of a large steel block (a quarter of it:
//! the symmetry plane y = 0 through the patch's centre, the bottom clamped 8a below), its
//! surface deflection along the patch's centre line against
//!
//! - the half-space (Love's cells), u_h = C p;
//! - the image of the sliding end, u_h + C M p (`greens::FreeEnds` of weight 1);
//! - Hetényi's free face, C (T + M T) with T from `greens::hetenyi_load`;
//!
//! and the image weight w that fits each, u ≈ C p + w C M p (+ a constant for the solid: a
//! finite block sinks less than a half-space by nearly the same amount everywhere under the
//! patch), against the roller's 1.388 (`book/src/bearing.md`, fitted to Hetényi under a
//! Hertz strip).
//!
//! ```text
//! cargo run --release --example quarter_space          # three meshes, about a minute
//! ```

use contopt::fem::solid::{Axis, SolidKind, SolidMesh, SolidModel};
use contopt::greens::{hetenyi_load, FacedGrid, FreeEnds, HetenyiSettings};
use contopt::prelude::*;

/// The patch's side \[mm\] and pressure \[MPa\].
const A: f64 = 1.0;
const P: f64 = 100.0;
/// The block's quarter: a depth, length and half-width of `BLOCK` patches.
const BLOCK: f64 = 8.0;
/// The half-space grid: cells of a/`CELLS` over [−3a, 0] × [−a, a].
const CELLS: usize = 16;

/// Where the mesh lines of a side of `length` lie: `fine` cells of a/`fine`... uniform over
/// [0, `patch`], then growing by a common ratio to `length` over `coarse` cells; `s` the
/// fractional cell index (midside nodes at half cells).
fn graded(s: f64, patch: f64, fine: usize, coarse: usize, length: f64) -> f64 {
    let h = patch / fine as f64;
    let m = fine as f64;
    if s <= m {
        return h * s;
    }
    // x(s) = patch + h (r^(s−m) − 1)/ln r reaches `length` at s = m + coarse.
    let reach = |r: f64| patch + h * (r.powf(coarse as f64) - 1.0) / r.ln();
    let (mut lo, mut hi) = (1.0 + 1e-9, 4.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if reach(mid) < length {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let r = 0.5 * (lo + hi);
    patch + h * (r.powf(s - m) - 1.0) / r.ln()
}

/// The solid's top deflection (into the block, mm) along y = 0 at `xs`, interpolated
/// linearly between its surface nodes, with the mesh's node count.
fn solid_deflection(fine: usize, coarse: usize, xs: &[f64]) -> Result<(Vec<f64>, usize)> {
    let (nx, ny) = (fine + coarse, fine / 2 + coarse);
    let nz = fine + coarse;
    let mesh = SolidMesh::block(SolidKind::Hex20, [1.0; 3], [nx, ny, nz])?.map(|q| {
        let side = |t: f64, n: usize, f: usize| {
            graded(
                t * n as f64,
                A * f as f64 / fine as f64,
                f,
                n - f,
                BLOCK * A,
            )
        };
        [
            -side(1.0 - q[0], nx, fine),
            side(q[1], ny, fine / 2),
            -side(1.0 - q[2], nz, fine),
        ]
    })?;
    let mut model = SolidModel::new(mesh, Material::new(2.1e5, 0.3)?);
    let y0 = model.mesh().nodes_where(|x| x[1].abs() < 1e-9);
    let bottom = model
        .mesh()
        .nodes_where(|x| (x[2] + BLOCK * A).abs() < 1e-9);
    model.fix(&y0, Axis::Y)?;
    for axis in Axis::ALL {
        model.fix(&bottom, axis)?;
    }
    let patch = model
        .mesh()
        .faces_where(|x| x[2].abs() < 1e-9 && x[0] >= -A - 1e-9 && x[1] <= 0.5 * A + 1e-9);
    model.add_pressure(&patch, P)?;
    let u = model.solve()?;
    let mut line: Vec<(f64, f64)> = model
        .mesh()
        .nodes_where(|x| x[1].abs() < 1e-9 && x[2].abs() < 1e-9)
        .into_iter()
        .map(|k| (model.mesh().nodes()[k][0], -u[3 * k + 2]))
        .collect();
    line.sort_by(|a, b| a.0.total_cmp(&b.0));
    let at = |x: f64| {
        let j = line.partition_point(|p| p.0 < x).clamp(1, line.len() - 1);
        let ((x0, u0), (x1, u1)) = (line[j - 1], line[j]);
        u0 + (u1 - u0) * (x - x0) / (x1 - x0)
    };
    Ok((
        xs.iter().map(|&x| at(x)).collect(),
        model.mesh().nodes().len(),
    ))
}

/// Least squares of `u` ≈ `half` + w·`image` (+ c when `offset`): (w, c).
fn fit_weight(u: &[f64], half: &[f64], image: &[f64], offset: bool) -> (f64, f64) {
    let r: Vec<f64> = u.iter().zip(half).map(|(a, b)| a - b).collect();
    let n = u.len() as f64;
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    if !offset {
        return (dot(&r, image) / dot(image, image), 0.0);
    }
    let (si, sr) = (image.iter().sum::<f64>(), r.iter().sum::<f64>());
    let (sii, sir) = (dot(image, image), dot(image, &r));
    let det = n * sii - si * si;
    let w = (n * sir - si * sr) / det;
    (w, (sr - w * si) / n)
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    contopt::faer::set_global_parallelism(contopt::faer::Par::Seq);
    let steel = Material::new(2.1e5, 0.3)?;
    let (nx, ny) = (3 * CELLS, 2 * CELLS + 1);
    let d = A / CELLS as f64;
    let origin = [-3.0 * A + 0.5 * d, -(CELLS as f64) * d];
    let pressure: Vec<f64> = (0..nx * ny)
        .map(|k| {
            let (x, y) = (
                origin[0] + (k % nx) as f64 * d,
                origin[1] + (k / nx) as f64 * d,
            );
            if x > -A && y.abs() < 0.5 * A {
                P
            } else {
                0.0
            }
        })
        .collect();
    let faces = [None, Some(0.0)];
    let half = HalfSpace::grid("half", steel, nx, ny, d, d, origin)?;
    let image = FreeEnds::grid("image", steel, nx, ny, d, d, origin, faces, 1.0)?;
    let grid = FacedGrid {
        nx,
        ny,
        dx: d,
        dy: d,
        origin,
        nu: 0.3,
        faces,
    };
    let hetenyi = hetenyi_load(&grid, &pressure, &HetenyiSettings::default())?;
    // The grids' products take cell forces p·d².
    let apply = |body: &dyn ElasticBody, p: &[f64]| {
        let force: Vec<f64> = p.iter().map(|p| p * d * d).collect();
        let mut u = vec![0.0; nx * ny];
        body.apply_influence(&force, &mut u);
        u
    };
    let row = |u: &[f64]| u[(ny / 2) * nx..(ny / 2 + 1) * nx].to_vec();
    let u_half = row(&apply(&half, &pressure));
    let u_image: Vec<f64> = row(&apply(&image, &pressure))
        .iter()
        .zip(&u_half)
        .map(|(a, b)| a - b)
        .collect();
    let u_het = row(&apply(&image, &hetenyi.load));
    let xs: Vec<f64> = (0..nx).map(|i| origin[0] + i as f64 * d).collect();
    let edge = nx - 1;
    let (w_het, _) = fit_weight(&u_het, &u_half, &u_image, false);
    println!("Uniform pressure {P} MPa on a {A} × {A} mm patch at the free edge x = 0, steel (E = 210 GPa, ν = 0.3).");
    println!("Deflection along the patch's centre line at the cells of a/{CELLS} over [−3a, 0]; u(edge) at x = −a/{}:", 2 * CELLS);
    println!();
    println!("model | nodes | u(edge) µm | u(−a/2) µm | edge / centre | fitted weight | max |u − Hetényi| / u(edge)");
    println!("---|---|---|---|---|---|---");
    let centre = xs.iter().position(|&x| x > -0.5 * A).unwrap_or(0);
    let line = |name: &str, nodes: String, u: &[f64], w: String| {
        let misfit = u
            .iter()
            .zip(&u_het)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        println!(
            "{name} | {nodes} | {:.3} | {:.3} | {:.3} | {w} | {:.1} %",
            1e3 * u[edge],
            1e3 * u[centre],
            u[edge] / u[centre],
            100.0 * misfit / u_het[edge]
        );
    };
    line("half-space", "-".into(), &u_half, "0".into());
    let sliding: Vec<f64> = u_half.iter().zip(&u_image).map(|(a, b)| a + b).collect();
    line("image (sliding end)", "-".into(), &sliding, "1".into());
    line(
        &format!("Hetényi ({} rounds)", hetenyi.rounds),
        "-".into(),
        &u_het,
        format!("{w_het:.3}"),
    );
    for (fine, coarse) in [(4, 6), (8, 8), (12, 10)] {
        let (u, nodes) = solid_deflection(fine, coarse, &xs)?;
        let (w, c) = fit_weight(&u, &u_half, &u_image, true);
        let shifted: Vec<f64> = u.iter().map(|v| v - c).collect();
        line(
            &format!("solid, a/{fine} elements (+{:.3} µm)", -1e3 * c),
            nodes.to_string(),
            &shifted,
            format!("{w:.3}"),
        );
    }
    Ok(())
}
