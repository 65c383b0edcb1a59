//! The restricted linear programme (3.5) of one pass, as contopt's `linear_programme` builds it
//! from the load split's (roller) or the iteration's (punch) contact set, solved whole by HiGHS
//! (dual simplex, and its interior point) and by clarabel, against contopt's own pass (the
//! equalities eliminated by a rank-revealing QR, clarabel on what is left), on one thread.
//! Prints the table of the book's optimisation chapter (`book/src/lp_highs.md`).
//!
//! `cargo run --release` for the rollers of 20 × 21 to 50 × 27 cells and the punch;
//! `cargo run --release -- large` for the roller of 100 × 53 cells alone (minutes).

use std::time::Instant;

use clarabel::algebra::CscMatrix;
use clarabel::solver::{DefaultSettingsBuilder, DefaultSolver, IPSolver, SupportedConeT};
use contopt::prelude::*;
use contopt::scene::Scene;
use contopt_validation::roller::Roller;

const SOLVER_ACCURACY: f64 = 1e-6;

/// The full restricted programme: variables p (closed or free, not Ω_v) | p_max | Δh (free
/// nodes) | λ, in contopt's units; rows: equalities, then `a·x + b ≥ 0` inequalities; sign
/// bounds on p and p_max as column bounds.
struct Full {
    nvar: usize,
    i_max: usize,
    ih: usize,
    free: Vec<usize>,
    equal: Vec<(Vec<(usize, f64)>, f64)>,
    at_least: Vec<(Vec<(usize, f64)>, f64)>,
    /// Columns bounded below by 0.
    nonneg: Vec<usize>,
    unit_p: f64,
    unit_g: f64,
}

fn full(
    problem: &InterfaceProblem,
    shape: &GapShape,
    v: &[f64],
    regions: &[Region],
    pressure: &[f64],
    gap: &[f64],
) -> Full {
    let n = problem.len();
    let a = problem.dense_influence(3).unwrap();
    let (w, rigid, q, g) = (
        problem.weights(),
        problem.rigid(),
        problem.load(),
        problem.free_gap(),
    );
    let compliance = (0..n)
        .map(|i| (0..n).map(|j| a[(i, j)] * w[j]).sum::<f64>().abs())
        .fold(0.0, f64::max);
    let area: f64 = w.iter().sum();
    let unit_p = q.iter().map(|x| x.abs()).fold(0.0, f64::max) / area;
    let unit_g = unit_p * compliance;
    let rigid_scale: Vec<f64> = (0..q.len())
        .map(|m| (0..n).map(|i| rigid[(i, m)].abs()).fold(0.0, f64::max))
        .collect();
    // Contact set as contopt classifies it: 0 closed, 1 open, 2 free.
    let p_top = pressure.iter().fold(0.0f64, |m, p| m.max(*p));
    let class: Vec<u8> = (0..n)
        .map(|i| {
            if regions[i] == Region::OmegaV || pressure[i] > SOLVER_ACCURACY * p_top {
                0
            } else if gap[i] > SOLVER_ACCURACY * unit_g {
                1
            } else {
                2
            }
        })
        .collect();
    let mut col = vec![usize::MAX; n];
    let mut np = 0;
    for i in 0..n {
        if regions[i] != Region::OmegaV && class[i] != 1 {
            col[i] = np;
            np += 1;
        }
    }
    let i_max = np;
    let ih = np + 1;
    let nodes = shape.nodes();
    let pin = (0..nodes.len())
        .min_by(|&a, &b| {
            let r = |k: usize| nodes[k].iter().map(|c| c * c).sum::<f64>();
            r(a).total_cmp(&r(b))
        })
        .unwrap();
    let free: Vec<usize> = (0..nodes.len()).filter(|&k| k != pin).collect();
    let mut slot = vec![usize::MAX; nodes.len()];
    free.iter().enumerate().for_each(|(c, &k)| slot[k] = c);
    let il = ih + free.len();
    let nvar = il + q.len();
    let pressures = |factor: &dyn Fn(usize) -> f64| {
        let mut e = vec![];
        let mut on_v = 0.0;
        for j in 0..n {
            if col[j] != usize::MAX {
                e.push((col[j], factor(j)));
            } else if regions[j] == Region::OmegaV {
                on_v += factor(j) * v[j];
            }
        }
        e.push((i_max, on_v));
        e
    };
    let gap_row = |i: usize| {
        let mut e = pressures(&|j| a[(i, j)] * w[j] * unit_p / unit_g);
        for m in 0..q.len() {
            e.push((il + m, rigid[(i, m)] / rigid_scale[m]));
        }
        for &(k, wt) in shape.row(i) {
            if slot[k] != usize::MAX {
                e.push((ih + slot[k], wt));
            }
        }
        (e, g[i] / unit_g)
    };
    let mut equal = vec![];
    for m in 0..q.len() {
        let scale = area * rigid_scale[m];
        equal.push((
            pressures(&|i| rigid[(i, m)] * w[i] / scale),
            q[m] / (unit_p * scale),
        ));
    }
    let mut at_least = vec![];
    let mut nonneg = vec![i_max];
    for i in 0..n {
        match class[i] {
            0 => equal.push(gap_row(i)),
            _ => at_least.push(gap_row(i)),
        }
        if col[i] != usize::MAX {
            nonneg.push(col[i]);
            if regions[i] == Region::OmegaNv {
                at_least.push((vec![(i_max, v[i]), (col[i], -1.0)], 0.0));
            }
        }
    }
    Full {
        nvar,
        i_max,
        ih,
        free,
        equal,
        at_least,
        nonneg,
        unit_p,
        unit_g,
    }
}

/// A solve's p_max \[MPa\], Δh per node (min 0) \[mm\], iterations, seconds, status.
struct Answer {
    p_max: f64,
    dh: Vec<f64>,
    iterations: i64,
    seconds: f64,
    status: String,
}

impl Full {
    fn answer(
        &self,
        x: &[f64],
        nodes: usize,
        iterations: i64,
        t: Instant,
        status: String,
    ) -> Answer {
        let mut dh = vec![0.0; nodes];
        for (c, &k) in self.free.iter().enumerate() {
            dh[k] = x[self.ih + c] * self.unit_g;
        }
        let least = dh.iter().fold(f64::INFINITY, |m: f64, v| m.min(*v));
        dh.iter_mut().for_each(|v| *v -= least);
        Answer {
            p_max: x[self.i_max] * self.unit_p,
            dh,
            iterations,
            seconds: t.elapsed().as_secs_f64(),
            status,
        }
    }

    fn highs(&self, nodes: usize, solver: &str) -> Answer {
        let t = Instant::now();
        let mut pb = highs::RowProblem::default();
        let mut lower = vec![f64::NEG_INFINITY; self.nvar];
        self.nonneg.iter().for_each(|&c| lower[c] = 0.0);
        let cols: Vec<highs::Col> = (0..self.nvar)
            .map(|c| {
                let cost = if c == self.i_max { 1.0 } else { 0.0 };
                pb.add_column(cost, lower[c]..)
            })
            .collect();
        for (e, b) in &self.equal {
            let row: Vec<(highs::Col, f64)> = e.iter().map(|&(j, v)| (cols[j], v)).collect();
            pb.add_row(-b..=-b, &row);
        }
        for (e, b) in &self.at_least {
            let row: Vec<(highs::Col, f64)> = e.iter().map(|&(j, v)| (cols[j], v)).collect();
            pb.add_row(-b.., &row);
        }
        let mut model = pb.optimise(highs::Sense::Minimise);
        model.make_quiet();
        model.set_option("solver", solver);
        model.set_option("threads", 1);
        model.set_option("time_limit", 600.0);
        let solved = model.solve();
        let status = format!("{:?}", solved.status());
        let iterations = solved.simplex_iteration_count() + solved.ipm_iteration_count();
        let x = solved.get_solution().columns().to_vec();
        self.answer(&x, nodes, iterations, t, status)
    }

    fn clarabel(&self, nodes: usize) -> Answer {
        let t = Instant::now();
        let (mut ii, mut jj, mut vv, mut b) = (vec![], vec![], vec![], vec![]);
        let mut r = 0;
        for (e, c) in &self.equal {
            for &(j, v) in e {
                ii.push(r);
                jj.push(j);
                vv.push(v);
            }
            b.push(-c);
            r += 1;
        }
        let nz = r;
        for (e, c) in &self.at_least {
            for &(j, v) in e {
                ii.push(r);
                jj.push(j);
                vv.push(-v);
            }
            b.push(*c);
            r += 1;
        }
        for &c in &self.nonneg {
            ii.push(r);
            jj.push(c);
            vv.push(-1.0);
            b.push(0.0);
            r += 1;
        }
        let a = CscMatrix::new_from_triplets(r, self.nvar, ii, jj, vv);
        let mut c = vec![0.0; self.nvar];
        c[self.i_max] = 1.0;
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .tol_feas(1e-10)
            .tol_gap_abs(1e-10)
            .tol_gap_rel(1e-10)
            .max_iter(200)
            .build()
            .unwrap();
        let cones = [
            SupportedConeT::ZeroConeT(nz),
            SupportedConeT::NonnegativeConeT(r - nz),
        ];
        let mut solver = DefaultSolver::new(
            &CscMatrix::zeros((self.nvar, self.nvar)),
            &c,
            &a,
            &b,
            &cones,
            settings,
        )
        .unwrap();
        solver.solve();
        let s = &solver.solution;
        self.answer(
            &s.x,
            nodes,
            s.iterations as i64,
            t,
            format!("{:?}", s.status),
        )
    }
}

fn row(grid: &str, name: &str, a: &Answer, reference: &Optimum) {
    let top = reference.dh_max();
    let ddh =
        a.dh.iter()
            .zip(&reference.dh)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
            / top;
    println!(
        "| {grid} | {name} | {} | {} | {:.2} | {:+.1e} | {:.1e} |",
        a.status,
        a.iterations,
        a.seconds,
        a.p_max / reference.p_max - 1.0,
        ddh
    );
}

fn main() {
    let large = std::env::args().any(|a| a == "large");
    println!("| case | solver | status | iterations | time s | p_max / reference − 1 | largest Δh difference / Δh_max |");
    println!("| --- | --- | --- | --- | --- | --- | --- |");
    let grids = match large {
        true => vec![(100, 53)],
        false => vec![(20, 21), (26, 31), (40, 21), (50, 27)],
    };
    let pk = PolonskyKeer::new(PolonskyKeerSettings::default()).unwrap();
    let v = Profile::cubic(3.0, 5.0).unwrap();
    for (nx, ny) in grids {
        let grid = Roller::grid(nx, ny).unwrap();
        let iface = grid.body.interface();
        let rigid = RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], Roller::LOAD).unwrap();
        let problem = InterfaceProblem::new(&grid.body, &rigid, &grid.gap).unwrap();
        let shape = GapShape::extruded(iface, 0).unwrap();
        let regions = grid.centre_row(Region::OmegaNv);
        let opt = Optimisation::new(&problem, &shape, &v)
            .unwrap()
            .with_regions(regions.clone())
            .unwrap();
        let split = opt.load_split(&pk, &Default::default()).unwrap();
        let t = Instant::now();
        let ours = opt
            .linear_programme(&pk, &LinearProgrammeSettings::default())
            .unwrap();
        let ours_s = t.elapsed().as_secs_f64();
        let vs: Vec<f64> = iface.points().iter().map(|&x| v.value(x)).collect();
        let t = Instant::now();
        let f = full(&problem, &shape, &vs, &regions, &split.pressure, &split.gap);
        let build = t.elapsed().as_secs_f64();
        let grid = format!(
            "roller {nx} × {ny} ({} vars, {} + {} rows, built in {build:.2} s)",
            f.nvar,
            f.equal.len(),
            f.at_least.len()
        );
        let nodes = shape.nodes().len();
        println!(
            "| {grid} | contopt (QR elimination + clarabel), seed included | {} | {} | {ours_s:.2} | {:+.1e} | |",
            ours.termination,
            ours.passes.iter().map(|p| p.iterp).sum::<usize>(),
            ours.p_max / split.p_max - 1.0
        );
        row(
            &grid,
            "HiGHS dual simplex",
            &f.highs(nodes, "simplex"),
            &split,
        );
        row(
            &grid,
            "HiGHS interior point",
            &f.highs(nodes, "ipm"),
            &split,
        );
        row(
            &grid,
            "clarabel, whole programme",
            &f.clarabel(nodes),
            &split,
        );
    }
    if !large {
        rim();
    }
}

/// The steel punch with its rim in Ω_nv, seeded by the iteration.
fn rim() {
    let edits = [("optimisation.omega_v.radius_mm", Some("19.8"))];
    let scene = Scene::bundled_with("steel-on-aluminium", &edits).unwrap();
    let active = ActiveSet::new(ActiveSetSettings::default()).unwrap();
    for case in scene.cases().iter().take(2) {
        let problem = case.problem().unwrap();
        let shape = problem.pressure_basis().unwrap().clone();
        let v = Profile::cubic(10.0, 20.0).unwrap();
        let points = problem.interface().points();
        let regions: Vec<Region> = points
            .iter()
            .map(|x| match x[0] <= 19.8 {
                true => Region::OmegaV,
                false => Region::OmegaNv,
            })
            .collect();
        let opt = Optimisation::new(&problem, &shape, &v)
            .unwrap()
            .with_regions(regions.clone())
            .unwrap();
        let seed = opt
            .iterate(Mode::GivenLoad, &active, &IterationSettings::default())
            .unwrap();
        let t = Instant::now();
        let ours = opt
            .linear_programme(&active, &LinearProgrammeSettings::default())
            .unwrap();
        let ours_s = t.elapsed().as_secs_f64();
        let vs: Vec<f64> = points.iter().map(|&x| v.value(x)).collect();
        let f = full(&problem, &shape, &vs, &regions, &seed.pressure, &seed.gap);
        let grid = format!("punch, rim in Ω_nv, case {} ({} vars)", case.label, f.nvar);
        println!(
            "| {grid} | contopt (QR elimination + clarabel), seed included | {} | {} | {ours_s:.3} | {:+.1e} | (reference) |",
            ours.termination,
            ours.passes.iter().map(|p| p.iterp).sum::<usize>(),
            0.0
        );
        let nodes = shape.nodes().len();
        row(
            &grid,
            "HiGHS dual simplex",
            &f.highs(nodes, "simplex"),
            &ours,
        );
        row(&grid, "HiGHS interior point", &f.highs(nodes, "ipm"), &ours);
        row(
            &grid,
            "clarabel, whole programme",
            &f.clarabel(nodes),
            &ours,
        );
    }
}
