//! The finite roller on its raceway as two solids (issue 37, point 3b), against the half-space
//! model of the roller crate without and with free ends.
//!
//! The roller of `roller-study` (D = l = 10 mm, Q = 5446 N, steel on steel, a flat raceway),
//! straight and under ISO/TS 16281's crown, with 0.2 mm chamfers beyond the effective length
//! (the end faces at ±5.2 mm, as `Roller::free_end_bodies` places them), is meshed as a solid
//! of 27-node hexahedra and pressed onto a solid raceway block that runs on past its ends.
//! A quarter of each: the symmetry planes x = 0 (mid-length; x runs along the axis, as in the
//! roller crate) and y = 0 (across the contact), and of the roller only the half below its
//! axis, that plane held along z and moving as one (the roller's translation, loaded by the
//! quarter of Q): a roller between two equal raceways is symmetric about its axial plane,
//! whose points therefore move only as the roller does.
//!
//! Both solids are read on one grid of cells: the half-space model's cells of 0.1 mm over the
//! last 0.6 mm of the half-length, merged to 0.2–1 mm towards the middle, and its rows across
//! (0.0225 mm, the first halved by the symmetry plane) to 1.2 b (`CELL_X`, `ROWS`). A cell is
//! never finer than the faces under it (else the cells would outnumber what the faces can tell
//! apart). Each is the library's cell (`SolidSample::cells`): its displacement the mean of its
//! body's face over the cell and its force spread over it as a uniform pressure, so the
//! influence of a cell is that of its pressure, not of a point force. The pressure along the
//! centre line — at mid-length, at its peak and where that sits, and towards the end — is
//! compared with the half-space model's means over the same cells (on 100 × 41 and 200 × 81
//! cells over the effective length and ±2.6 b), without free ends and with the image of
//! weight w at the end faces (`greens::FreeEnds`): 1.37 (the scenes' default), 1.388 (the
//! finest fit to Hetényi under a Hertz strip), 1.58 and 1.95 (the fits of
//! `examples/quarter_space.rs`); and the weight at which each of the half-space model's
//! figures equals the solids'.
//!
//! Point 4: the straight roller's crown designed as `roller-study`'s "optimised L1 = 5 mm"
//! (Ω_v the centre row, v = 1 along the length, the rest of each column Ω_nv) with the solids
//! of every resolution and with the half-space model without and with free ends, each by the
//! load split and by the linear programme (3.5) on the dense influence; the pressure across
//! the end column of each design says why the solids' programme is infeasible where it is.
//!
//! The output is the book's (`cargo xtask book --only finite_roller`, a slow source), its
//! parts marked by mdBook anchors.
//!
//! ```text
//! cargo run --release --example finite_roller       # four solid pairs per crown, 6-7 min
//! cargo run --release --example finite_roller -- 1  # the coarse pair only, ~1 min
//! cargo run --release --example finite_roller -- 0  # the half-space models only, ~8 s
//! ```
//!
//! (Wall clock on the shared 2-core machine at load 7–9; 2.6 minutes of CPU in all.)

use std::collections::HashMap;
use std::time::Instant;

use contopt::contact::FreeMode;
use contopt::fem::solid::{
    Axis, Cell, Condensation, SolidBody, SolidFace, SolidKind, SolidMesh, SolidModel, SolidSample,
    SolidSettings,
};
use contopt::prelude::*;
use contopt::roller::{Crown, Roller, RollerEnds};

/// Roller diameter and effective length \[mm\], the axial width of each chamfer \[mm\], and the
/// load \[N\] (`scenes/roller-study.toml`, `scenes/bearing.toml`'s chamfers).
const DIAMETER: f64 = 10.0;
const LENGTH: f64 = 10.0;
const CHAMFER: f64 = 0.2;
const LOAD: f64 = 5446.0;
/// The half-space model's grid: cells along the length, across, and its reach in b.
const CELLS: [usize; 2] = [100, 41];
const REACH: f64 = 2.6;
/// The half-space model on cells half as large each way (its means over the solids' cells
/// converged?).
const FINE_CELLS: [usize; 2] = [200, 81];
/// The image weights compared.
const WEIGHTS: [f64; 4] = [1.37, 1.388, 1.58, 1.95];
/// The raceway block's quarter: its length along the axis, half-width and depth \[mm\].
const BLOCK: [f64; 3] = [8.0, 5.0, 6.0];
/// A block twice as large each way (how much the finite raceway's size matters).
const LARGE_BLOCK: [f64; 3] = [16.0, 10.0, 12.0];
/// The roller's core square, as a fraction of its radius (an O-grid: the core and two
/// blocks of rays from the axis to the surface).
const CORE: f64 = 0.45;
/// The ISO crown's drop on the mesh stops growing this close to the end of the effective
/// length (the profile's logarithm is infinite at the end; no contact reaches it).
const CROWN_CAP: f64 = 0.01;
/// The elements: 27-node hexahedra, whose faces' 9-node quadrilaterals spread a cell's
/// pressure to every node with a positive weight (a 20-node face's corners take a negative
/// share of a uniform pressure, −1/12, and the cells' pressures then zigzag along the axis).
const KIND: SolidKind = SolidKind::Hex27;
/// The growth ratio of elements away from the grid (beyond its reach, the roller's ends).
const FAR: f64 = 2.0;
/// Layers below the contact that grow by the resolution's ratio (the deeper ones by `FAR`).
const NEAR: usize = 4;
/// The largest angle an element of the roller's section spans, away from the contact.
const ANGLE: f64 = 0.27;
/// Nodes of the two meshes closer than this are one node \[mm\].
const MERGE: f64 = 1e-7;
/// A node is on a plane within this \[mm\].
const ON: f64 = 1e-9;

fn steel() -> Material {
    Material::new(2.1e5, 0.3).expect("steel")
}

fn roller(crown: Crown) -> Roller {
    Roller {
        diameter: DIAMETER,
        length: LENGTH,
        raceway_diameter: None,
        roller: steel(),
        raceway: steel(),
        load: LOAD,
        tilt: 0.0,
        crown,
    }
}

/// The solids' cells along the axis \[mm\]: the half-space grid's cells of 0.1 mm over the
/// last 0.6 mm of the half-length, merged towards the middle (where the pressure hardly
/// changes along the axis and the elements are long).
const CELL_X: [f64; 15] = [
    0.0, 1.0, 2.0, 3.0, 3.5, 3.8, 4.0, 4.2, 4.4, 4.5, 4.6, 4.7, 4.8, 4.9, 5.0,
];
/// Where the cells of 0.1 mm start, and the elements may be split along the axis \[mm\].
const END: f64 = 4.4;
/// The solids' cells across, in the half-space grid's rows: its rows (the first halved by the
/// symmetry plane) up to `ROWS` + ½, over 1.2 b, then the elements' growing ones.
const ROWS: usize = 9;

/// The mesh's sizes: elements per cell along the axis and per two rows across, the first
/// element's depth in rows, and the ratio by which elements grow away from the contact.
#[derive(Clone, Copy, Debug)]
struct Resolution {
    name: &'static str,
    x_split: usize,
    y_split: usize,
    depth: f64,
    growth: f64,
    /// The raceway block's quarter \[mm\].
    block: [f64; 3],
}

const RESOLUTIONS: [Resolution; 4] = [
    Resolution {
        name: "coarse",
        x_split: 1,
        y_split: 1,
        depth: 2.0,
        growth: 1.5,
        block: BLOCK,
    },
    Resolution {
        name: "fine at the end",
        x_split: 2,
        y_split: 1,
        depth: 1.0,
        growth: 1.35,
        block: BLOCK,
    },
    Resolution {
        name: "fine across",
        x_split: 1,
        y_split: 2,
        depth: 1.0,
        growth: 1.35,
        block: BLOCK,
    },
    Resolution {
        name: "coarse, the block twice as large",
        x_split: 1,
        y_split: 1,
        depth: 2.0,
        growth: 1.5,
        block: LARGE_BLOCK,
    },
];

/// Mesh lines from `start` to `end` (either order): the first element `first` long, each next
/// `growth` times longer up to `cap`, all scaled to end exactly at `end`.
fn growing(start: f64, end: f64, first: f64, growth: f64, cap: f64) -> Vec<f64> {
    let span = (end - start).abs();
    let mut sizes = vec![];
    let (mut h, mut total) = (first.min(span), 0.0);
    while total + 0.5 * h < span {
        sizes.push(h);
        total += h;
        h = (h * growth).min(cap);
    }
    if sizes.is_empty() {
        sizes.push(span);
        total = span;
    }
    let (scale, sign) = (span / total, (end - start).signum());
    let mut lines = vec![start];
    let mut at = 0.0;
    for s in sizes {
        at += s * scale;
        lines.push(start + sign * at);
    }
    *lines.last_mut().expect("one line") = end;
    lines
}

/// Each interval of `lines` cut into `parts` equal ones.
fn split(lines: &[f64], parts: usize) -> Vec<f64> {
    let mut out = vec![lines[0]];
    for w in lines.windows(2) {
        out.extend((1..=parts).map(|k| w[0] + (w[1] - w[0]) * k as f64 / parts as f64));
    }
    out
}

/// The position at reference coordinate `t` ∈ [0, 1] of a block meshed between `lines`: node
/// k/2 of the block's 2n + 1 along it sits on line k/2 or midway between two (the same
/// position from every block that shares the lines).
fn along(lines: &[f64], t: f64) -> f64 {
    let n = lines.len() - 1;
    let half = (t * (2 * n) as f64).round() as usize;
    let i = (half / 2).min(n - 1);
    let f = 0.5 * (half - 2 * i) as f64;
    lines[i] + f * (lines[i + 1] - lines[i])
}

/// The solids' quarter grid of the contact: cells between the lines `xs` along the axis and
/// `ys` across, the first row at y = 0 halved by the symmetry plane (its point on the plane:
/// the half-space grid's centre row), cell k = i + nx·j.
struct Grid {
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// The half-space grid's row height \[mm\].
    dy: f64,
}

impl Grid {
    fn new(r: &Roller) -> Result<Self> {
        let [_, dy] = r.cell(CELLS[0], CELLS[1], REACH)?;
        let mut ys: Vec<f64> = std::iter::once(0.0)
            .chain((0..=ROWS).map(|k| (k as f64 + 0.5) * dy))
            .collect();
        let last = ys.pop().expect("a line");
        let reach = (CELLS[1] as f64 / 2.0) * dy;
        ys.extend(growing(last, reach, 2.0 * dy, 1.5, f64::INFINITY));
        Ok(Self {
            xs: CELL_X.to_vec(),
            ys,
            dy,
        })
    }

    fn nx(&self) -> usize {
        self.xs.len() - 1
    }

    fn len(&self) -> usize {
        self.nx() * (self.ys.len() - 1)
    }

    /// Cell k's extent along x and y.
    fn cell(&self, k: usize) -> [[f64; 2]; 2] {
        let (i, j) = (k % self.nx(), k / self.nx());
        [[self.xs[i], self.xs[i + 1]], [self.ys[j], self.ys[j + 1]]]
    }

    /// Cell k as the solids read it: the library's cell, its centre and sides
    /// (`SolidSample::cells` spreads a force over it and reads its mean).
    fn cell_of(&self, k: usize) -> Cell {
        let [x, y] = self.cell(k);
        Cell::xy(
            [0.5 * (x[0] + x[1]), 0.5 * (y[0] + y[1]), 0.0],
            [x[1] - x[0], y[1] - y[0]],
        )
    }

    /// Where cell k's gap is taken: its centre, but y = 0 on the first row, the half of the
    /// half-space grid's centre row that the symmetry plane cuts (the gap at that cell's
    /// centre, as the half-space model takes it).
    fn gap_point(&self, k: usize) -> [f64; 2] {
        let [x, y] = self.cell(k);
        let centre_y = if k < self.nx() {
            0.0
        } else {
            0.5 * (y[0] + y[1])
        };
        [0.5 * (x[0] + x[1]), centre_y]
    }

    /// The outer edge of the grid across \[mm\].
    fn reach(&self) -> f64 {
        self.ys[self.ys.len() - 1]
    }
}

/// Mesh lines shared by the roller and the block over the contact: along the axis (the cells
/// split, then over the chamfer) and across (pairs of rows, split, then the cells' growing
/// ones); the first element's depth.
struct Lines {
    x: Vec<f64>,
    chamfer: Vec<f64>,
    y: Vec<f64>,
    depth: f64,
}

impl Lines {
    fn new(res: &Resolution, grid: &Grid) -> Self {
        let parts = |w: &[f64]| if w[0] >= END - ON { res.x_split } else { 1 };
        let mut x = vec![0.0];
        for w in grid.xs.windows(2) {
            x.extend(&split(w, parts(w))[1..]);
        }
        let half = 0.5 * LENGTH;
        let n_chamfer = 2 * res.x_split;
        let chamfer = (0..=n_chamfer)
            .map(|k| half + CHAMFER * k as f64 / n_chamfer as f64)
            .collect();
        // Pairs of rows: the half row and the first whole one, then two by two.
        let pairs: Vec<f64> = std::iter::once(0.0)
            .chain((1..=ROWS).step_by(2).map(|k| (k as f64 + 0.5) * grid.dy))
            .collect();
        let mut y = split(&pairs, res.y_split);
        y.extend(grid.ys.iter().filter(|&&v| v > pairs[pairs.len() - 1] + ON));
        Self {
            x,
            chamfer,
            y,
            depth: res.depth * grid.dy,
        }
    }

    /// The roller's lines along the axis, chamfer included.
    fn roller_x(&self) -> Vec<f64> {
        let mut x = self.x.clone();
        x.extend(&self.chamfer[1..]);
        x
    }

    /// The block's: the roller's, then growing to the block's end.
    fn block_x(&self, block: [f64; 3]) -> Vec<f64> {
        let mut x = self.roller_x();
        let last = x.pop().expect("a line");
        let step = last - x[x.len() - 1];
        x.extend(growing(
            last,
            block[0],
            step,
            FAR,
            2.0 * block[0] / BLOCK[0],
        ));
        x
    }

    /// The depths below a surface to `depth`, the first layer the resolution's depth: the
    /// first `NEAR` layers grow by the resolution's ratio, the others by `FAR`.
    fn depths(&self, depth: f64, res: &Resolution) -> Vec<f64> {
        let mut d: Vec<f64> = (0..=NEAR)
            .map(|k| self.depth * (res.growth.powi(k as i32) - 1.0) / (res.growth - 1.0))
            .collect();
        let last = d.pop().expect("a layer");
        let step = last - d[d.len() - 1];
        d.extend(growing(last, depth, step * FAR, FAR, f64::INFINITY));
        d
    }
}

/// One mesh of several blocks, the nodes they share merged.
fn merged(blocks: &[SolidMesh]) -> Result<SolidMesh> {
    let key = |p: [f64; 3]| p.map(|c| (c / (4.0 * MERGE)).floor() as i64);
    let mut nodes: Vec<[f64; 3]> = vec![];
    let mut cells: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    let mut elements = vec![];
    for block in blocks {
        let index: Vec<usize> = (block.nodes().iter())
            .map(|&p| {
                let k = key(p);
                let near = (0..27).find_map(|n| {
                    let d = [n % 3, (n / 3) % 3, n / 9].map(|d| d as i64 - 1);
                    let c = [k[0] + d[0], k[1] + d[1], k[2] + d[2]];
                    cells.get(&c)?.iter().copied().find(|&a| {
                        let q: [f64; 3] = nodes[a];
                        (0..3).all(|c| (q[c] - p[c]).abs() <= MERGE)
                    })
                });
                near.unwrap_or_else(|| {
                    nodes.push(p);
                    cells.entry(k).or_default().push(nodes.len() - 1);
                    nodes.len() - 1
                })
            })
            .collect();
        for e in 0..block.n_elements() {
            let conn = block.element(e).iter().map(|&a| index[a]).collect();
            elements.push((block.kind(e), conn));
        }
    }
    SolidMesh::new(nodes, elements)
}

/// The roller's radius at `x` \[mm\]: R less the crown's drop and the chamfer's.
fn surface(crown: &Crown, x: f64) -> Result<f64> {
    let half = 0.5 * LENGTH;
    let drop = crown.drop(x.min(half - CROWN_CAP), LENGTH)?;
    Ok(0.5 * DIAMETER - drop - (x - half).max(0.0))
}

/// The roller's quarter below its axis (the axis at z = R, its lowest line on z = 0 but for
/// the crown's drop): an O-grid of its section — the core square of side `CORE`·R and two
/// blocks of rays from the axis, the lower one (the contact) at angles θ with R sin θ on the
/// contact's lines — swept along the axis; its radius at x is R less the crown's drop and
/// the chamfer's.
fn roller_mesh(lines: &Lines, res: &Resolution, crown: &Crown) -> Result<SolidMesh> {
    let radius = 0.5 * DIAMETER;
    let surface = |x: f64| surface(crown, x);
    let xs = lines.roller_x();
    // The lower block's angles: the contact's lines, then growing to π/4.
    let mut lower: Vec<f64> = lines.y.iter().map(|y| (y / radius).asin()).collect();
    let last = lower.pop().expect("a line");
    let quarter = std::f64::consts::FRAC_PI_4;
    let step = last - lower[lower.len() - 1];
    lower.extend(growing(last, quarter, step, FAR, ANGLE));
    let side = growing(quarter, std::f64::consts::FRAC_PI_2, ANGLE, 1.0, ANGLE);
    let core = CORE * radius;
    let depths = lines.depths(radius - core, res);
    // A ray from the axis at angle θ from straight down, from the surface (c = 0) to the
    // core's side at distance `inner`.
    let ray = |x: f64, theta: f64, c: f64, inner: f64| -> Result<[f64; 3]> {
        let outer = surface(x)?;
        let r = outer - c * (outer - inner) / (radius - core);
        Ok([x, r * theta.sin(), radius - r * theta.cos()])
    };
    let block = |cells: [usize; 3]| SolidMesh::block(KIND, [1.0; 3], cells);
    let fail = std::cell::Cell::new(None);
    let keep = |p: Result<[f64; 3]>| {
        p.unwrap_or_else(|e| {
            fail.set(Some(e));
            [0.0; 3]
        })
    };
    let n = |l: &[f64]| l.len() - 1;
    let lower_block = block([n(&xs), n(&lower), n(&depths)])?.map(|q| {
        let theta = along(&lower, q[1]);
        let c = along(&depths, q[2]);
        keep(ray(along(&xs, q[0]), theta, c, core / theta.cos()))
    })?;
    let side_block = block([n(&xs), n(&side), n(&depths)])?.map(|q| {
        let theta = along(&side, q[1]);
        let c = along(&depths, q[2]);
        keep(ray(along(&xs, q[0]), theta, c, core / theta.sin()))
    })?;
    let core_block = block([n(&xs), n(&lower), n(&side)])?.map(|q| {
        let (a, b) = (along(&lower, q[1]), along(&side, q[2]));
        [along(&xs, q[0]), core * a.tan(), radius - core / b.tan()]
    })?;
    if let Some(e) = fail.take() {
        return Err(e);
    }
    merged(&[lower_block, side_block, core_block])
}

/// The raceway block's quarter: [0, L] × [0, W] × [−H, 0] (the resolution's block), on the
/// roller's lines along the axis and across the contact, growing beyond.
fn block_mesh(lines: &Lines, res: &Resolution) -> Result<SolidMesh> {
    let xs = lines.block_x(res.block);
    let mut ys = lines.y.clone();
    let last = ys.pop().expect("a line");
    let step = last - ys[ys.len() - 1];
    ys.extend(growing(last, res.block[1], step, FAR, f64::INFINITY));
    let mut zs: Vec<f64> = lines.depths(res.block[2], res).iter().map(|d| -d).collect();
    zs.reverse();
    let n = |l: &[f64]| l.len() - 1;
    SolidMesh::block(KIND, [1.0; 3], [n(&xs), n(&ys), n(&zs)])?
        .map(|q| [along(&xs, q[0]), along(&ys, q[1]), along(&zs, q[2])])
}

/// What a solid's build cost.
struct Built {
    body: SolidBody,
    seconds: f64,
}

/// The solid `model` read on the grid's cells from its faces `contact`, along `normal` (its
/// outward normal): each cell's displacement its face's mean over the cell, its force a
/// uniform pressure over it (`SolidSample::cells`), the influence among the cells dense.
fn cell_body(
    name: &str,
    model: SolidModel,
    contact: &[SolidFace],
    grid: &Grid,
    normal: [f64; 3],
) -> Result<Built> {
    let start = Instant::now();
    let cells: Vec<Cell> = (0..grid.len()).map(|k| grid.cell_of(k)).collect();
    let samples = SolidSample::cells(model.mesh(), contact, &cells, normal)?;
    let settings = SolidSettings {
        condensation: Condensation::Dense,
        ..SolidSettings::default()
    };
    let body = SolidBody::sampled(name, model, &samples, settings)?;
    Ok(Built {
        body,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// The roller's translation along z, loaded by a quarter of Q: every cell moves into the
/// roller alike. Its axial plane, held along z in the model, moves as the roller does (the
/// plane of symmetry between two equal raceways).
fn translation(points: usize) -> FreeMode {
    FreeMode {
        name: "translation of `roller`".into(),
        points: (0..points).collect(),
        displacement: vec![1.0; points],
        load: -0.25 * LOAD,
    }
}

/// The two solids of `crown` at resolution `res`, read on the grid's cells: the raceway
/// block (supported: symmetry planes and its base held along z) and the roller (symmetry
/// planes, its axial plane held along z: its translation is the problem's, [`translation`]).
fn solids(crown: &Crown, res: &Resolution, grid: &Grid) -> Result<[Built; 2]> {
    let lines = Lines::new(res, grid);
    let half = 0.5 * LENGTH;
    let reach = grid.reach() + ON;

    let mut block = SolidModel::new(block_mesh(&lines, res)?, steel());
    let held = |m: &SolidModel, f: &dyn Fn([f64; 3]) -> bool| m.mesh().nodes_where(f);
    let (x0, y0) = (
        held(&block, &|p| p[0].abs() < ON),
        held(&block, &|p| p[1].abs() < ON),
    );
    let base = held(&block, &|p| (p[2] + res.block[2]).abs() < ON);
    block.fix(&x0, Axis::X)?;
    block.fix(&y0, Axis::Y)?;
    block.fix(&base, Axis::Z)?;
    let top = block
        .mesh()
        .faces_where(|p| p[2].abs() < ON && p[0] <= half + ON && p[1] <= reach);
    let raceway = cell_body("raceway", block, &top, grid, [0.0, 0.0, 1.0])?;

    let radius = 0.5 * DIAMETER;
    let mut model = SolidModel::new(roller_mesh(&lines, res, crown)?, steel());
    let (x0, y0) = (
        held(&model, &|p| p[0].abs() < ON),
        held(&model, &|p| p[1].abs() < ON),
    );
    let axial = held(&model, &|p| (p[2] - radius).abs() < ON);
    model.fix(&x0, Axis::X)?;
    model.fix(&y0, Axis::Y)?;
    model.fix(&axial, Axis::Z)?;
    // The faces on its surface within the contact's lines.
    let lowest = model.mesh().faces_where(|p| {
        let r = p[1].hypot(radius - p[2]);
        let on = surface(crown, p[0]).is_ok_and(|s| (r - s).abs() < MERGE);
        p[0] <= half + ON && p[1] <= reach && on
    });
    let roller = cell_body("roller", model, &lowest, grid, [0.0, 0.0, -1.0])?;
    Ok([raceway, roller])
}

/// The centre line's pressure of a solved model on the solids' cells along the axis (the
/// half-space's means over them).
struct Line {
    name: String,
    pressure: Vec<f64>,
}

/// The half-space model's centre line on a full grid of `cells`, its roller's ends free with
/// the image's `weight` (or a half-space roller): its pressure's means over the solids' first
/// row of cells.
fn half_space(r: &Roller, grid: &Grid, cells: [usize; 2], weight: Option<f64>) -> Result<Line> {
    let [nx, ny] = cells;
    let solver = PolonskyKeer::new(PolonskyKeerSettings::default())?;
    let state = on_half_spaces(r, cells, weight, |problem| solver.solve(problem))?;
    let [dx, dy] = r.cell(nx, ny, REACH)?;
    let overlap = |a: [f64; 2], b: [f64; 2]| (a[1].min(b[1]) - a[0].max(b[0])).max(0.0);
    let first_row = [0.0, grid.ys[1]];
    let pressure = (grid.xs.windows(2))
        .map(|w| {
            let (mut sum, mut area) = (0.0, 0.0);
            for j in 0..=(ny - 1) / 2 {
                let y = [(j as f64 - 0.5).max(0.0) * dy, (j as f64 + 0.5) * dy];
                for i in 0..nx / 2 {
                    let x = [i as f64 * dx, (i + 1) as f64 * dx];
                    let a = overlap(x, [w[0], w[1]]) * overlap(y, first_row);
                    sum += a * state.pressure[(ny - 1) / 2 * nx + j * nx + nx / 2 + i];
                    area += a;
                }
            }
            sum / area
        })
        .collect();
    Ok(Line {
        name: match weight {
            None => format!("half-space, no free ends, {nx} × {ny}"),
            Some(w) => format!("half-space, image w = {w}, {nx} × {ny}"),
        },
        pressure,
    })
}

/// The solids' centre line at resolution `res`, with the nodes of each and the time, and,
/// with `crown`, the crowns designed for it (point 4).
fn finite(
    r: &Roller,
    grid: &Grid,
    res: &Resolution,
    crown: bool,
) -> Result<(Line, Option<Designs>)> {
    let start = Instant::now();
    let [raceway, roller] = solids(&r.crown, res, grid)?;
    let gap: Vec<f64> = (0..grid.len())
        .map(|k| {
            let [x, y] = grid.gap_point(k);
            Ok(y * y / (2.0 * r.radius()?) + r.crown.drop(x, LENGTH)?)
        })
        .collect::<Result<_>>()?;
    let problem = InterfaceProblem::new(&raceway.body, &roller.body, &gap)?
        .with_modes(vec![translation(grid.len())])?;
    let solver = ActiveSet::new(ActiveSetSettings::default())?;
    let state = solver.solve(&problem)?;
    let force: f64 = (state.pressure.iter().zip(problem.weights()))
        .map(|(p, w)| p * w)
        .sum();
    let line = Line {
        name: format!(
            "solids, {} ({} + {} nodes, {:.0} + {:.0} s, {:.0} s in all; F/4 = {:.1} N)",
            res.name,
            raceway.body.stats().nodes,
            roller.body.stats().nodes,
            raceway.seconds,
            roller.seconds,
            start.elapsed().as_secs_f64(),
            force
        ),
        pressure: state.pressure[..grid.nx()].to_vec(),
    };
    let designs = crown
        .then(|| designed(&problem, &solver, grid.dy))
        .transpose()?;
    Ok((line, designs))
}

/// A crown designed two ways on one model: by the load split, and by the linear programme
/// (3.5) on the dense influence, seeded by the split's contact set.
struct Designs {
    split: Optimum,
    programme: Optimum,
    interface: Interface,
    /// The half-space grid's row height: Ω_v is |y| ≤ `dy`/2 \[mm\].
    dy: f64,
}

/// The crown roller-study's "optimised L1 = 5 mm" designs: Ω_v the centre row
/// (|y| ≤ `dy`/2), the rest of each column Ω_nv, the gap change a profile along the axis
/// symmetric about mid-length, v = 1 along the whole length (the cubic controller with
/// L1 = L2 = l/2); by the load split and by the linear programme.
fn designed(problem: &InterfaceProblem, solver: &dyn ContactSolver, dy: f64) -> Result<Designs> {
    let interface = problem.interface();
    let shape = GapShape::symmetric(interface, 0)?;
    let regions = (interface.points().iter())
        .map(|x| match x[1].abs() <= 0.5 * dy {
            true => Region::OmegaV,
            false => Region::OmegaNv,
        })
        .collect();
    let controller = Profile::cubic(0.5 * LENGTH, 0.5 * LENGTH)?;
    let optimisation = Optimisation::new(problem, &shape, &controller)?.with_regions(regions)?;
    Ok(Designs {
        split: optimisation.load_split(solver, &LoadSplitSettings::default())?,
        programme: optimisation.linear_programme(solver, &LinearProgrammeSettings::default())?,
        interface: interface.clone(),
        dy,
    })
}

/// The half-space model's designed crown on `cells`, without free ends or with the image of
/// `weight`.
fn half_space_design(r: &Roller, cells: [usize; 2], weight: Option<f64>) -> Result<Designs> {
    let [nx, ny] = cells;
    let [_, dy] = r.cell(nx, ny, REACH)?;
    let solver = PolonskyKeer::new(PolonskyKeerSettings::default())?;
    on_half_spaces(r, cells, weight, |problem| designed(problem, &solver, dy))
}

/// `run` on the half-space model of `r` on a full grid of `cells`: its roller's ends free
/// with the image's `weight`, or a half-space roller.
fn on_half_spaces<T>(
    r: &Roller,
    [nx, ny]: [usize; 2],
    weight: Option<f64>,
    run: impl FnOnce(&InterfaceProblem) -> Result<T>,
) -> Result<T> {
    match weight {
        None => {
            let (a, b, gap) = r.bodies(nx, ny, REACH)?;
            let problem = InterfaceProblem::new(&a, &b, &gap)?;
            run(&problem)
        }
        Some(weight) => {
            let ends = RollerEnds {
                chamfer_mm: CHAMFER,
                weight,
            };
            let (a, b, gap) = r.free_end_bodies(nx, ny, REACH, &ends)?;
            let problem = InterfaceProblem::new(&a, &b, &gap)?;
            run(&problem)
        }
    }
}

/// Where the designed crowns' drops are compared: the solids' cell centres towards the end
/// \[mm\].
const CROWN_AT: [f64; 6] = [3.65, 4.1, 4.45, 4.65, 4.85, 4.95];

/// The end column's cell centre along the axis \[mm\], where the rows across are compared.
const END_CELL: f64 = 4.95;
/// The rows across compared at the end column, the centre row's included.
const ACROSS: usize = 4;
/// The linear programme's name in the tables.
const LP: &str = "LP (3.5)";

impl Designs {
    /// Both designs' rows of the crown's table: p_max, the drop at `CROWN_AT` (the centre
    /// row's point nearest each), the largest excess of p over v·p_max = p_max on Ω_nv and
    /// where, and "converged" (the programme's p_max against the split's) or a mark sending to
    /// the design's ending below the table. A design without a gap change (a programme that
    /// ended short holds the contact without one) shows only its ending.
    fn crown_rows(&self, name: &str, notes: &mut Vec<String>) -> Vec<String> {
        let points = self.interface.points();
        let centre = |at: f64| {
            (0..points.len())
                .filter(|&k| points[k][1].abs() <= 0.5 * self.dy && points[k][0] > 0.0)
                .min_by(|&a, &b| {
                    (points[a][0] - at)
                        .abs()
                        .total_cmp(&(points[b][0] - at).abs())
                })
                .expect("a centre row")
        };
        self.each()
            .map(|(method, o)| {
                let ends = match o.is_converged() {
                    true if method == LP => format!(
                        "converged, p_max / split's − 1 = {:+.1e}",
                        o.p_max / self.split.p_max - 1.0
                    ),
                    true => "converged".to_string(),
                    false => {
                        notes.push(format!(
                            "{}. {name}, {method}: {}",
                            notes.len() + 1,
                            o.termination
                        ));
                        format!("({})", notes.len())
                    }
                };
                if o.dh_max() <= 0.0 {
                    let none = vec!["-"; CROWN_AT.len() + 2].join(" | ");
                    return format!("{name} | {method} | {none} | {ends}");
                }
                let drops: Vec<String> = (CROWN_AT.iter())
                    .map(|&at| format!("{:.2}", 1e3 * o.gap_change[centre(at)]))
                    .collect();
                let (excess, k) = (0..points.len())
                    .filter(|&k| points[k][1] > 0.5 * self.dy && points[k][0] > 0.0)
                    .map(|k| (o.pressure[k] - o.p_max, k))
                    .max_by(|a, b| a.0.total_cmp(&b.0))
                    .expect("an Ω_nv point");
                let [x, y, _] = points[k];
                format!(
                    "{name} | {method} | {:.1} | {} | {excess:+.1} at ({x:.2}, {y:.4}) | {ends}",
                    o.p_max,
                    drops.join(" | "),
                )
            })
            .collect()
    }

    /// The load split's pressure across the end column (x = `END_CELL`) at the rows
    /// y = j·dy (the solids' first row: its half, [0, dy/2]), and the second row's over the
    /// first's, as a table row.
    fn end_row(&self, name: &str) -> String {
        let points = self.interface.points();
        let row = |j: usize| {
            let at = [END_CELL, j as f64 * self.dy];
            let off = |k: usize| (points[k][0] - at[0]).abs() + (points[k][1] - at[1]).abs();
            (0..points.len())
                .filter(|&k| points[k][0] > 0.0 && points[k][1] > -ON)
                .min_by(|&a, &b| off(a).total_cmp(&off(b)))
                .expect("a point")
        };
        let p = &self.split.pressure;
        let across: Vec<String> = (0..ACROSS).map(|j| format!("{:.0}", p[row(j)])).collect();
        let ratio = p[row(1)] / p[row(0)];
        format!("{name} | {} | {ratio:.4}", across.join(" | "))
    }

    /// The two designs with their methods' names.
    fn each(&self) -> impl Iterator<Item = (&'static str, &Optimum)> {
        [("load split", &self.split), (LP, &self.programme)].into_iter()
    }
}

/// A figure that moves less than this with the weight \[MPa\] matches none.
const FLAT: f64 = 1.0;

/// The centre line's figures whose image weights are matched: the mean pressure over the
/// cells between two positions along the axis \[mm\], weighted by the cells' lengths.
const FIGURES: [(&str, f64, f64); 4] = [
    ("mid-length, 0–1 mm", 0.0, 1.0),
    ("towards the end, 4.4–4.8 mm", 4.4, 4.8),
    ("the last 0.2 mm", 4.8, 5.0),
    ("the end cell, 4.9–5.0 mm", 4.9, 5.0),
];

/// The mean of `line` over the cells of `grid` between `from` and `to`.
fn mean(grid: &Grid, line: &Line, from: f64, to: f64) -> f64 {
    let (mut sum, mut length) = (0.0, 0.0);
    for (w, p) in grid.xs.windows(2).zip(&line.pressure) {
        if w[0] >= from - ON && w[1] <= to + ON {
            sum += p * (w[1] - w[0]);
            length += w[1] - w[0];
        }
    }
    sum / length
}

/// The image weight w at which the half-space model's figure `of(w)` (given at w = 0 and at
/// `WEIGHTS`) equals `target`: piecewise linear between them, extrapolated from the nearest
/// two beyond; `None` where the figure hardly moves with w (less than `FLAT` MPa from w = 0
/// to the largest weight: an unloaded cell).
fn matching(target: f64, of: &[(f64, f64)]) -> Option<f64> {
    let last = of.len() - 1;
    if (of[last].1 - of[0].1).abs() < FLAT {
        return None;
    }
    let k = (1..last)
        .find(|&k| (of[k].1 - target) * (of[k - 1].1 - target) <= 0.0)
        .unwrap_or(if (target - of[0].1).abs() < (target - of[last].1).abs() {
            1
        } else {
            last
        });
    let ((w0, q0), (w1, q1)) = (of[k - 1], of[k]);
    (q1 != q0).then(|| w0 + (target - q0) * (w1 - w0) / (q1 - q0))
}

/// Prints the centre line of each model and the weights that match the solids' figures.
fn report(grid: &Grid, lines: &[Line]) {
    let head: Vec<String> = (grid.xs.windows(2))
        .map(|w| format!("{:.1}–{:.1}", w[0], w[1]))
        .collect();
    println!("the centre line's pressure [MPa] over x [mm] (the solids' cells; the half-space's means over them)\n");
    println!("model | {}", head.join(" | "));
    println!("---{}", "|---".repeat(head.len()));
    for l in lines {
        let cells: Vec<String> = l.pressure.iter().map(|p| format!("{p:.0}")).collect();
        println!("{} | {}", l.name, cells.join(" | "));
    }
    println!("\nthe image weight at which the half-space model's figure equals the solids' (piecewise linear in w over 0, {WEIGHTS:?}; beyond, extrapolated)\n");
    let per_grid = WEIGHTS.len() + 1;
    let (half, solids) = lines.split_at(2 * per_grid);
    println!(
        "solids | half-space cells | {}",
        FIGURES.map(|f| f.0).join(" | ")
    );
    println!("---|---{}", "|---".repeat(FIGURES.len()));
    for s in solids {
        for (g, set) in half.chunks(per_grid).enumerate() {
            let cells = [CELLS, FINE_CELLS][g];
            let ws: Vec<String> = FIGURES
                .iter()
                .map(|&(_, from, to)| {
                    let of: Vec<(f64, f64)> = std::iter::once(0.0)
                        .chain(WEIGHTS)
                        .zip(set)
                        .map(|(w, l)| (w, mean(grid, l, from, to)))
                        .collect();
                    let target = mean(grid, s, from, to);
                    match matching(target, &of) {
                        Some(w) => format!("{target:.0} MPa: w = {w:.2}"),
                        None => format!("{target:.0} MPa: -"),
                    }
                })
                .collect();
            let name = s.name.split(" (").next().unwrap_or("");
            println!("{name} | {} × {} | {}", cells[0], cells[1], ws.join(" | "));
        }
    }
    println!();
}

/// Prints the crowns designed from the straight roller (point 4): each model's drop and p_max
/// by both methods with how each ended, then the pressure across the end column.
fn crowns(designs: &[(String, Designs)]) {
    let at: Vec<String> = CROWN_AT.iter().map(|x| format!("{x}")).collect();
    println!("<!-- ANCHOR: crown -->");
    println!("the crown designed from the straight roller (Ω_v the centre row, v = 1 along the length, the rest of each column Ω_nv): its drop [µm] at x [mm]\n");
    println!(
        "model | method | p_max MPa | {} | largest p − p_max on Ω_nv MPa (at x, y mm) | ends",
        at.join(" | ")
    );
    println!("---|---|---{}|---|---", "|---".repeat(at.len()));
    let mut notes = vec![];
    for (name, d) in designs {
        (d.crown_rows(name, &mut notes).iter()).for_each(|row| println!("{row}"));
    }
    println!();
    notes.iter().for_each(|note| println!("{note}"));
    let rows: Vec<String> = (0..ACROSS)
        .map(|j| match j {
            0 => "y = 0".to_string(),
            1 => "y = dy".to_string(),
            _ => format!("y = {j} dy"),
        })
        .collect();
    println!("\nthe load split's pressure across the end column (x = {END_CELL} mm) [MPa], at the rows y = j·dy (the solids' first row: its half [0, dy/2]), and the second row's over the first's\n");
    println!("model | {} | second / first", rows.join(" | "));
    println!("---{}|---", "|---".repeat(rows.len()));
    for (name, d) in designs {
        println!("{}", d.end_row(name));
    }
    println!("<!-- ANCHOR_END: crown -->\n");
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    contopt::faer::set_global_parallelism(contopt::faer::Par::Seq);
    let levels: usize = std::env::args()
        .nth(1)
        .map_or(Ok(RESOLUTIONS.len()), |a| a.parse())?;
    for (label, anchor, crown) in [
        ("straight", "straight", Crown::Straight),
        ("ISO/TS 16281", "iso", Crown::iso(DIAMETER)?),
    ] {
        let r = roller(crown);
        let (b, p0) = r.hertz()?;
        let grid = Grid::new(&r)?;
        let mut lines = vec![];
        for cells in [CELLS, FINE_CELLS] {
            lines.push(half_space(&r, &grid, cells, None)?);
            for w in WEIGHTS {
                lines.push(half_space(&r, &grid, cells, Some(w))?);
            }
        }
        let straight = matches!(r.crown, Crown::Straight);
        let mut designs = vec![];
        if straight {
            for weight in [None, Some(1.388)] {
                let name = match weight {
                    None => "half-space, no free ends".to_string(),
                    Some(w) => format!("half-space, image w = {w}"),
                };
                designs.push((name, half_space_design(&r, CELLS, weight)?));
            }
        }
        for res in &RESOLUTIONS[..levels.min(RESOLUTIONS.len())] {
            let (line, design) = finite(&r, &grid, res, straight)?;
            designs.extend(design.map(|d| (format!("solids, {}", res.name), d)));
            lines.push(line);
        }
        println!("<!-- ANCHOR: {anchor} -->");
        println!("**The {label} roller**: D = l = {DIAMETER} mm, {CHAMFER} mm chamfers, Q = {LOAD} N; Hertz (line): b = {b:.4} mm, p₀ = {p0:.1} MPa\n");
        report(&grid, &lines);
        println!("<!-- ANCHOR_END: {anchor} -->\n");
        if !designs.is_empty() {
            crowns(&designs);
        }
    }
    Ok(())
}
