//! Run time against error for every contact solver — the QP (clarabel), the active set, the
//! penalty, the augmented Lagrangian and Polonsky–Keer — on two problems at several
//! resolutions. Writes `book/src/solver_benchmark.csv` and the chart
//! `book/src/solver_benchmark.{svg,png}` (error against time, log–log, one curve per solver, one
//! panel per problem) and prints the table of the book's performance section.
//!
//! **Hertz.** A rigid sphere, R = 10 mm, pressed by F = 1000 N into a half-space grid
//! (E = 2·10⁵ MPa, ν = 0.3): a = 0.3244 mm, p₀ = 4538 MPa. The resolution is the number of
//! cells per contact radius, a/Δx; the grid is (2k + 1)² cells, k = ⌈1.2·a/Δx⌉, the axis on the
//! centre of the middle cell. The error is the relative L2 error of the cell pressures against
//! the Hertz pressure averaged over each cell (the quantity a piecewise-constant pressure
//! approximates; 8 × 8 midpoints per cell), √(Σ (pᵢ − p̄ᵢ)²) / √(Σ p̄ᵢ²), the cells having one
//! area; the second error is |p_max − p₀| / p₀.
//!
//! **Table 1.** The paper's axisymmetric punch on its base (§4) under 100 MPa, zero initial
//! gap, without optimisation, meshed with as many quadratic elements through each body's height
//! as across the contact radius (the resolution). The error is that of the contact pressure at
//! the punch centre, read from the pressure field (the interface pressures' fit by the face
//! shape functions, [`InterfaceProblem::recovered_pressure`], extrapolated to r = 0 on the
//! innermost face), against a reference: the active set's centre pressure on 48, 96 and 192
//! elements, Richardson-extrapolated with the order those three give. The second error is the
//! W-weighted L2 difference of the field from the active set's on 192 elements, over that
//! field's L2 norm. The punch edge is a singular point (the pressure there grows without bound
//! under refinement), so this falls slowly, and it also holds the 192-element field's own error.
//!
//! **Penalty parameter.** Table 1: the paper's c = E·10⁴ MPa/mm. Hertz, two penalty curves:
//! that literal c, and c of the same stiffness relative to the grid as the paper's, c·(A w)ᵢᵢ
//! equal to the paper's c times the largest (A w)ᵢᵢ of its 18-element mesh (A the summed
//! influence, w the point weights: (A w)ᵢᵢ is the displacement of a point under a unit pressure
//! on itself, so c·(A w)ᵢᵢ compares the penalty spring with the body); the literal c is the
//! softer, relative to the grid, the finer the grid. The augmented Lagrangian uses the first
//! c (it converges to the QP's solution for any c). The penalty's error holds its O(1/c)
//! penetration; the column `vs_active_set` gives each solver's largest pressure difference from
//! the active set's at the same resolution, over p_max.
//!
//! **Timing.** `std::time::Instant` around building the interface problem of the prebuilt
//! bodies and solving it, so that a dense solver pays for its dense matrix (a fresh problem
//! each run: no matrix is reused); the median of three runs when one takes at most a second,
//! else one run. One thread: the workspace builds faer without rayon, and nothing else spawns
//! threads. A solver stops climbing the resolutions once its next solve is predicted (from its
//! last, with time growing like points³ for the dense solvers and points^1.5 for Polonsky–Keer)
//! to exceed 30 s, or when it fails; the CSV's `note` says which.
//!
//! `cargo run --release --example solver_benchmark` (add `quick` for the two smallest
//! resolutions of each problem only; the files are then not written; or `chart` to redraw the
//! chart from the CSV without solving).

use std::f64::consts::PI;
use std::fmt::Write as _;
use std::time::Instant;

use contopt::greens::HalfSpace;
use contopt::prelude::*;
use contopt::report::{log_log, Panel};
use contopt::scene::Built;

/// What can fail here: a solve, or a scene.
type Fallible<T> = std::result::Result<T, Box<dyn std::error::Error>>;

const E: f64 = 2.0e5;
const NU: f64 = 0.3;
/// Sphere radius \[mm\] and force \[N\].
const SPHERE: f64 = 10.0;
const FORCE: f64 = 1000.0;
/// The paper's penalty parameter \[MPa/mm\].
const PAPER_C: f64 = E * 1e4;
/// Largest predicted time of one solve \[s\].
const LIMIT: f64 = 30.0;
/// Contact elements of the Table 1 reference meshes.
const REFERENCE_ELEMENTS: [usize; 3] = [48, 96, 192];
/// The label of the penalty with the paper's c.
const PAPER_PENALTY: &str = "penalty, c = E·10⁴ MPa/mm";
/// The label of Polonsky–Keer, whose errors the tables show beside the resolution.
const POLONSKY_KEER: &str = "Polonsky-Keer";
/// The punch's radius in the bundled scene `paper-table1` \[mm\].
const PUNCH_RADIUS: f64 = 50.0;

/// One measured (or skipped) solve.
struct Row {
    problem: &'static str,
    solver: String,
    resolution: usize,
    points: usize,
    time: Option<f64>,
    error: Option<f64>,
    error2: Option<f64>,
    vs_active_set: Option<f64>,
    iterations: Option<usize>,
    /// Whether the solver met its tolerance; `None` when it was not run.
    converged: Option<bool>,
    note: String,
}

/// A solver with its label and how its run time grows with the number of points (the
/// exponent), for predicting the next resolution's.
struct Entry {
    label: String,
    solver: Box<dyn ContactSolver>,
    growth: f64,
}

/// The solvers of a case, the active set first (the others are compared with it): the QP, the
/// penalty with each of `penalties` (label, c), the augmented Lagrangian with the first c, and
/// Polonsky–Keer.
fn solvers(penalties: &[(&str, f64)]) -> Result<Vec<Entry>> {
    let entry = |label: &str, solver: Box<dyn ContactSolver>, growth| Entry {
        label: label.to_string(),
        solver,
        growth,
    };
    let mut all = vec![
        entry(
            "active set",
            Box::new(ActiveSet::new(ActiveSetSettings::default())?),
            3.0,
        ),
        entry(
            "QP (clarabel)",
            Box::new(Qp::new(QpSettings::default())?),
            3.0,
        ),
    ];
    for &(label, c) in penalties {
        let settings = PenaltySettings { c_mpa_per_mm: c };
        all.push(entry(label, Box::new(Penalty::new(settings)?), 3.0));
    }
    let settings = AugmentedLagrangianSettings::new(penalties[0].1);
    all.push(entry(
        "augmented Lagrangian",
        Box::new(AugmentedLagrangian::new(settings)?),
        3.0,
    ));
    let settings = PolonskyKeerSettings::default();
    all.push(entry(
        POLONSKY_KEER,
        Box::new(PolonskyKeer::new(settings)?),
        1.5,
    ));
    Ok(all)
}

/// The median time of `run` over three runs when one takes at most a second, else one run's,
/// with the last run's result.
fn timed<T>(run: impl Fn() -> T) -> (f64, T) {
    let once = || {
        let t = Instant::now();
        let r = run();
        (t.elapsed().as_secs_f64(), r)
    };
    let (t, r) = once();
    if t > 1.0 {
        return (t, r);
    }
    let mut times = vec![t, once().0];
    let (t3, r) = once();
    times.push(t3);
    times.sort_by(f64::total_cmp);
    (times[1], r)
}

/// The largest pressure difference of `a` from `b`, over b's p_max.
fn difference(a: &[f64], b: &[f64]) -> f64 {
    let top = b.iter().fold(0.0f64, |m, &p| m.max(p));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / top
}

/// A problem at one resolution.
trait Case {
    /// Number of interface points.
    fn points(&self) -> usize;
    /// The solvers to run ([`solvers`]).
    fn solvers(&self) -> Result<Vec<Entry>>;
    /// Builds the interface problem and solves it with `solver`: what is timed.
    fn solve(&self, solver: &dyn ContactSolver) -> Result<ContactState>;
    /// The two errors of a solution.
    fn errors(&self, state: &ContactState) -> Fallible<(f64, f64)>;
}

/// Runs every solver over the cases that `case` builds at `resolutions`, coarse to fine; a
/// solver stops at the first resolution where its predicted time exceeds [`LIMIT`] or where it
/// fails.
fn benchmark<C: Case>(
    problem: &'static str,
    resolutions: &[usize],
    case: impl Fn(usize) -> Fallible<C>,
) -> Fallible<Vec<Row>> {
    let mut rows = vec![];
    // Per solver: the last (points, time), or None once it has stopped climbing.
    let mut last: Vec<Option<(usize, f64)>> = vec![];
    for &resolution in resolutions {
        let case = case(resolution)?;
        let n = case.points();
        let mut active_set: Option<Vec<f64>> = None;
        for (k, entry) in case.solvers()?.into_iter().enumerate() {
            if last.len() <= k {
                last.push(Some((n, 0.0)));
            }
            let Some((n0, t0)) = last[k] else { continue };
            let mut row = Row {
                problem,
                solver: entry.label,
                resolution,
                points: n,
                time: None,
                error: None,
                error2: None,
                vs_active_set: None,
                iterations: None,
                converged: None,
                note: String::new(),
            };
            let predicted = t0 * (n as f64 / n0 as f64).powf(entry.growth);
            if predicted > LIMIT {
                row.note = format!("not run here or finer: predicted {predicted:.0} s");
                rows.push(row);
                last[k] = None;
                continue;
            }
            let (time, outcome) = timed(|| case.solve(entry.solver.as_ref()));
            match outcome {
                Ok(state) => {
                    let (e1, e2) = case.errors(&state)?;
                    row.time = Some(time);
                    row.error = Some(e1);
                    row.error2 = Some(e2);
                    row.iterations = Some(state.iterations);
                    row.converged = Some(state.is_converged());
                    if !state.is_converged() {
                        row.note = state.termination.to_string();
                    }
                    match &active_set {
                        Some(p) => row.vs_active_set = Some(difference(&state.pressure, p)),
                        None if k == 0 => active_set = Some(state.pressure),
                        None => {}
                    }
                    last[k] = Some((n, time));
                }
                Err(e) => {
                    row.converged = Some(false);
                    row.note = e.to_string();
                    last[k] = None;
                }
            }
            eprintln!(
                "{problem}, {resolution}, {} ({n} points): {} s, error {} {}",
                row.solver,
                opt(row.time, |t| format!("{t:.3e}")),
                opt(row.error, |e| format!("{e:.3e}")),
                row.note
            );
            rows.push(row);
        }
    }
    Ok(rows)
}

/// Hertz on a half-space grid.
struct Hertz {
    body: HalfSpace,
    gap: Vec<f64>,
    /// The Hertz pressure averaged over each cell \[MPa\].
    exact: Vec<f64>,
    p0: f64,
    /// The penalty parameter relative to the grid \[MPa/mm\].
    c: f64,
}

impl Hertz {
    /// `cells` cells per contact radius; the penalty's stiffness `ratio`, c·(A w)ᵢᵢ.
    fn new(cells: usize, ratio: f64) -> Result<Self> {
        let estar = E / (1.0 - NU * NU);
        let a = (3.0 * FORCE * SPHERE / (4.0 * estar)).cbrt();
        let p0 = 3.0 * FORCE / (2.0 * PI * a * a);
        let dx = a / cells as f64;
        let half = (1.2 * cells as f64).ceil() as usize;
        let side = 2 * half + 1;
        let origin = -(half as f64) * dx;
        let body = HalfSpace::grid(
            "half-space",
            Material::new(E, NU)?,
            side,
            side,
            dx,
            dx,
            [origin, origin],
        )?;
        let points = body.interface().points();
        let gap = points
            .iter()
            .map(|x| (x[0] * x[0] + x[1] * x[1]) / (2.0 * SPHERE))
            .collect();
        const SUB: usize = 8;
        let midpoint = |k: usize| dx * ((k as f64 + 0.5) / SUB as f64 - 0.5);
        let exact = points
            .iter()
            .map(|x| {
                if x[0].hypot(x[1]) > a + dx {
                    return 0.0;
                }
                let mut sum = 0.0;
                for i in 0..SUB {
                    for j in 0..SUB {
                        let (u, v) = (x[0] + midpoint(i), x[1] + midpoint(j));
                        sum += (1.0 - (u * u + v * v) / (a * a)).max(0.0).sqrt();
                    }
                }
                p0 * sum / (SUB * SUB) as f64
            })
            .collect();
        // The centre cell's displacement under a unit pressure on itself: (A w)ᵢᵢ.
        let centre = half * side + half;
        let mut force = vec![0.0; side * side];
        force[centre] = dx * dx;
        let mut u = vec![0.0; side * side];
        body.apply_influence(&force, &mut u);
        Ok(Self {
            body,
            gap,
            exact,
            p0,
            c: ratio / u[centre],
        })
    }
}

impl Case for Hertz {
    fn points(&self) -> usize {
        self.gap.len()
    }

    fn solvers(&self) -> Result<Vec<Entry>> {
        solvers(&[
            ("penalty, c relative to the grid", self.c),
            (PAPER_PENALTY, PAPER_C),
        ])
    }

    fn solve(&self, solver: &dyn ContactSolver) -> Result<ContactState> {
        let sphere = RigidBody::pressed("sphere", self.body.interface(), [0.0, 0.0, 1.0], FORCE)?;
        let problem = InterfaceProblem::new(&self.body, &sphere, &self.gap)?;
        solver.solve(&problem)
    }

    fn errors(&self, state: &ContactState) -> Fallible<(f64, f64)> {
        let (mut diff, mut norm) = (0.0, 0.0);
        for (p, q) in state.pressure.iter().zip(&self.exact) {
            diff += (p - q).powi(2);
            norm += q * q;
        }
        Ok(((diff / norm).sqrt(), (state.p_max() / self.p0 - 1.0).abs()))
    }
}

/// The pressure field of the punch's interface on a uniform mesh: on each face (consecutive
/// triples of points by radius) the quadratic through its three values.
struct Field {
    /// (r, w, p) of each point, sorted by r.
    points: Vec<(f64, f64, f64)>,
}

impl Field {
    fn new(interface: &Interface, pressure: &[f64]) -> Self {
        let (x, w) = (interface.points(), interface.weights());
        let mut points: Vec<(f64, f64, f64)> = (0..pressure.len())
            .map(|i| (x[i][0], w[i], pressure[i]))
            .collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        Self { points }
    }

    /// The field at `r`, on the face that holds it.
    fn at(&self, r: f64) -> f64 {
        let faces = self.points.len() / 3;
        let face = ((r / PUNCH_RADIUS * faces as f64) as usize).min(faces - 1);
        let q = &self.points[3 * face..3 * face + 3];
        (0..3)
            .map(|i| {
                let others = (0..3).filter(|&j| j != i);
                q[i].2
                    * others
                        .map(|j| (r - q[j].0) / (q[i].0 - q[j].0))
                        .product::<f64>()
            })
            .sum()
    }

    /// The L2 norm of the difference of `other` from this field, over this field's norm, both
    /// integrated by this field's points.
    fn l2_difference(&self, other: &Field) -> f64 {
        let (mut diff, mut norm) = (0.0, 0.0);
        for &(r, w, p) in &self.points {
            diff += w * (other.at(r) - p).powi(2);
            norm += w * p * p;
        }
        (diff / norm).sqrt()
    }
}

/// The Table 1 reference: the centre pressure extrapolated from the active set's on
/// [`REFERENCE_ELEMENTS`] (coarse to fine, each twice the last), and the finest field.
struct Reference {
    centre: f64,
    field: Field,
}

impl Reference {
    fn new() -> Fallible<Self> {
        let mut centres = vec![];
        let mut field = None;
        let active_set = ActiveSet::new(ActiveSetSettings::default())?;
        for n in REFERENCE_ELEMENTS {
            let case = Table1::new(n, None)?;
            let state = active_set.solve(&case.problem()?)?;
            if !state.is_converged() {
                return Err(format!("the reference on {n} elements: {}", state.termination).into());
            }
            let f = case.field(&state)?;
            centres.push(f.at(0.0));
            field = Some(f);
        }
        let [p0, p1, p2] = centres[..] else {
            unreachable!("three meshes")
        };
        // Richardson: the differences fall by a ratio 2^q from one mesh to the next.
        let ratio = (p1 - p0) / (p2 - p1);
        let centre = p2 + (p2 - p1) / (ratio - 1.0);
        println!(
            "Table 1 reference: the active set's centre pressure on {REFERENCE_ELEMENTS:?} elements, \
             {} MPa, Richardson-extrapolated (order {:.2}): {centre:.4} MPa\n",
            centres.iter().map(|p| format!("{p:.4}")).collect::<Vec<_>>().join(", "),
            ratio.log2()
        );
        Ok(Self {
            centre,
            field: field.expect("three meshes"),
        })
    }
}

/// Table 1 without optimisation: the paper's axisymmetric punch on its base under 100 MPa,
/// built by the bundled scene `paper-table1`.
struct Table1<'r> {
    /// The base (below the zone) and the punch.
    bodies: Built,
    /// The initial gap: zero.
    gap: Vec<f64>,
    reference: Option<&'r Reference>,
}

impl<'r> Table1<'r> {
    /// `elements` uniform contact elements and as many layers in each body.
    fn new(elements: usize, reference: Option<&'r Reference>) -> Fallible<Self> {
        let elements = elements.to_string();
        let edits = [
            ("contact.zone.elements", Some(elements.as_str())),
            ("sweep", None),
        ];
        let scene = Scene::bundled_with("paper-table1", &edits)?;
        let case = &scene.cases()[0];
        let bodies = case.build()?;
        let gap = case.initial_gap(&bodies)?;
        Ok(Self {
            bodies,
            gap,
            reference,
        })
    }

    /// A fresh problem of the bodies: no dense matrix built yet.
    fn problem(&self) -> Result<InterfaceProblem<'_>> {
        InterfaceProblem::new(self.bodies.first(), self.bodies.second(), &self.gap)
    }

    /// The recovered pressure field of a state.
    fn field(&self, state: &ContactState) -> Result<Field> {
        let p = self.problem()?.recovered_pressure(&state.pressure)?;
        Ok(Field::new(self.bodies.first().interface(), &p))
    }

    /// The largest (A w)ᵢᵢ of the interface: a point's displacement under a unit pressure on
    /// itself \[mm/MPa\].
    fn compliance(&self) -> Result<f64> {
        let problem = self.problem()?;
        let a = problem.dense_influence(3)?;
        Ok(problem
            .weights()
            .iter()
            .enumerate()
            .map(|(i, w)| a[(i, i)] * w)
            .fold(0.0, f64::max))
    }
}

impl Case for Table1<'_> {
    fn points(&self) -> usize {
        self.gap.len()
    }

    fn solvers(&self) -> Result<Vec<Entry>> {
        solvers(&[(PAPER_PENALTY, PAPER_C)])
    }

    fn solve(&self, solver: &dyn ContactSolver) -> Result<ContactState> {
        solver.solve(&self.problem()?)
    }

    fn errors(&self, state: &ContactState) -> Fallible<(f64, f64)> {
        let reference = self
            .reference
            .ok_or("a benchmark case of Table 1 has a reference")?;
        let field = self.field(state)?;
        Ok((
            (field.at(0.0) / reference.centre - 1.0).abs(),
            reference.field.l2_difference(&field),
        ))
    }
}

/// `v` formatted, or nothing.
fn opt<T>(v: Option<T>, format: impl Fn(T) -> String) -> String {
    v.map_or(String::new(), format)
}

/// The (time, error) curve of each solver of `problem`, from its converged solves.
fn curves(rows: &[Row], problem: &str) -> Vec<(String, Vec<(f64, f64)>)> {
    let mut names: Vec<String> = vec![];
    for r in rows.iter().filter(|r| r.problem == problem) {
        if !names.contains(&r.solver) {
            names.push(r.solver.clone());
        }
    }
    names
        .into_iter()
        .map(|name| {
            let points = rows
                .iter()
                .filter(|r| r.problem == problem && r.solver == name && r.converged == Some(true))
                .filter_map(|r| Some((r.time?, r.error?)))
                .collect();
            (name, points)
        })
        .collect()
}

/// Three significant digits of a time in milliseconds.
fn milliseconds(seconds: f64) -> String {
    let ms = 1e3 * seconds;
    match ms {
        ms if ms >= 100.0 => format!("{ms:.0}"),
        ms if ms >= 10.0 => format!("{ms:.1}"),
        ms if ms >= 1.0 => format!("{ms:.2}"),
        ms => format!("{ms:.3}"),
    }
}

/// A leading column of a [`pivot`]: its name and its value from the rows of one resolution.
type Lead<'a> = (&'a str, &'a dyn Fn(&[&Row]) -> String);

/// One markdown table of `problem`: a row per resolution, the columns `lead` (name, value of
/// the resolution's rows) and then one per solver with `cell` of its row ("—" when not run).
fn pivot(
    rows: &[Row],
    (problem, resolution_name): (&str, &str),
    lead: &[Lead],
    cell: &dyn Fn(&Row) -> Option<String>,
) {
    let mine: Vec<&Row> = rows.iter().filter(|r| r.problem == problem).collect();
    let mut solvers: Vec<&str> = vec![];
    let mut resolutions: Vec<usize> = vec![];
    for r in &mine {
        if !solvers.contains(&r.solver.as_str()) {
            solvers.push(&r.solver);
        }
        if !resolutions.contains(&r.resolution) {
            resolutions.push(r.resolution);
        }
    }
    let names: Vec<&str> = [resolution_name, "points"]
        .into_iter()
        .chain(lead.iter().map(|(name, _)| *name))
        .chain(solvers.iter().copied())
        .collect();
    println!("| {} |", names.join(" | "));
    println!("|{}", " --- |".repeat(names.len()));
    for resolution in resolutions {
        let at: Vec<&Row> = mine
            .iter()
            .copied()
            .filter(|r| r.resolution == resolution)
            .collect();
        let cells: Vec<Option<String>> = solvers
            .iter()
            .map(|s| at.iter().find(|r| r.solver == *s).and_then(|r| cell(r)))
            .collect();
        // A row with nothing to show is left out.
        if lead.is_empty() && cells.iter().all(Option::is_none) {
            continue;
        }
        let mut fields = vec![resolution.to_string(), at[0].points.to_string()];
        fields.extend(lead.iter().map(|(_, value)| value(&at)));
        fields.extend(cells.into_iter().map(|c| c.unwrap_or_else(|| "—".into())));
        println!("| {} |", fields.join(" | "));
    }
    println!();
}

/// The book's tables: per problem, the times of every solver (with the errors of the exact
/// solvers, Polonsky–Keer's) and each solver's largest difference from the active set's
/// pressure; on Hertz also each solver's p_max error.
fn print_tables(rows: &[Row]) {
    let exact = |at: &[&Row], e: fn(&Row) -> Option<f64>| {
        at.iter()
            .find(|r| r.solver == POLONSKY_KEER)
            .and_then(|r| e(r))
            .map_or("—".into(), |x| format!("{x:.2e}"))
    };
    let first: &dyn Fn(&[&Row]) -> String = &|at| exact(at, |r| r.error);
    let second: &dyn Fn(&[&Row]) -> String = &|at| exact(at, |r| r.error2);
    let sci = |v: Option<f64>| v.map(|x| format!("{x:.1e}"));
    let problems = [
        ("Hertz", "a/Δx", "L2 error", "p_max error"),
        ("Table 1", "elements", "centre error", "L2 difference"),
    ];
    for (problem, resolution, error, error2) in problems {
        println!("{problem}, time ms of each solver:\n");
        pivot(
            rows,
            (problem, resolution),
            &[(error, first), (error2, second)],
            &|r| r.time.map(milliseconds),
        );
        println!("{problem}, each solver's largest pressure difference from the active set's, over p_max:\n");
        pivot(rows, (problem, resolution), &[], &|r| sci(r.vs_active_set));
        if problem == "Hertz" {
            println!("{problem}, each solver's {error2}:\n");
            pivot(rows, (problem, resolution), &[], &|r| sci(r.error2));
        }
    }
}

/// The table the book's performance section shows; `chart` redraws its chart from it.
const CSV: &str = "book/src/solver_benchmark.csv";

/// The chart of `rows`: `book/src/solver_benchmark.{svg,png}`.
fn chart(rows: &[Row]) -> std::io::Result<()> {
    let (hertz, table1) = (curves(rows, "Hertz"), curves(rows, "Table 1"));
    fn series(c: &[(String, Vec<(f64, f64)>)]) -> Vec<(&str, &[(f64, f64)])> {
        c.iter().map(|(n, p)| (n.as_str(), p.as_slice())).collect()
    }
    let (hs, ts) = (series(&hertz), series(&table1));
    let figure = log_log(
        "Contact solvers: error against run time (one thread)",
        &[
            Panel {
                title: "Hertz, half-space grid: L2 error of p",
                x_label: "run time [s]",
                y_label: "relative error",
                series: &hs,
            },
            Panel {
                title: "Table 1, no optimisation: p at the centre",
                x_label: "run time [s]",
                y_label: "relative error",
                series: &ts,
            },
        ],
    )?;
    for (name, bytes) in figure.files("book/src/solver_benchmark")? {
        std::fs::write(name, bytes)?;
    }
    Ok(())
}

/// The rows of a CSV this example wrote: the fields the chart needs (problem, solver,
/// resolution, points, time, error, converged), the others left empty.
fn read_rows(csv: &str) -> Vec<Row> {
    let fields = |line: &str| -> Vec<String> {
        let (mut out, mut field, mut quoted) = (vec![], String::new(), false);
        for c in line.chars() {
            match c {
                '"' => quoted = !quoted,
                ',' if !quoted => out.push(std::mem::take(&mut field)),
                c => field.push(c),
            }
        }
        out.push(field);
        out
    };
    csv.lines()
        .skip(1)
        .map(fields)
        .filter(|f| f.len() >= 10)
        .map(|f| Row {
            problem: if f[0] == "Hertz" { "Hertz" } else { "Table 1" },
            solver: f[1].clone(),
            resolution: f[2].parse().unwrap_or(0),
            points: f[3].parse().unwrap_or(0),
            time: f[4].parse().ok(),
            error: f[5].parse().ok(),
            error2: None,
            vs_active_set: None,
            iterations: None,
            converged: f[9].parse().ok(),
            note: String::new(),
        })
        .collect()
}

fn main() -> Fallible<()> {
    if std::env::args().any(|a| a == "chart") {
        chart(&read_rows(&std::fs::read_to_string(CSV)?))?;
        eprintln!("written: book/src/solver_benchmark.{{svg,png}} from {CSV}");
        return Ok(());
    }
    let quick = std::env::args().any(|a| a == "quick");
    let hertz_cells: &[usize] = if quick {
        &[4, 6]
    } else {
        &[4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256]
    };
    let table1_elements: &[usize] = if quick {
        &[6, 12]
    } else {
        &[6, 12, 18, 24, 36, 48, 72]
    };

    let paper_ratio = PAPER_C * Table1::new(18, None)?.compliance()?;
    println!(
        "the paper's c times the largest (A w)_ii of its 18-element mesh: {paper_ratio:.3e}\n"
    );
    let reference = Reference::new()?;
    let mut rows = benchmark("Hertz", hertz_cells, |n| Ok(Hertz::new(n, paper_ratio)?))?;
    rows.extend(benchmark("Table 1", table1_elements, |n| {
        Table1::new(n, Some(&reference))
    })?);

    print_tables(&rows);
    let mut csv = String::from(
        "problem,solver,resolution,points,time_s,error,error2,vs_active_set,iterations,converged,note\n",
    );
    for r in &rows {
        let g = |v| opt(v, |x| format!("{x:e}"));
        let _ = writeln!(
            csv,
            "{},\"{}\",{},{},{},{},{},{},{},{},\"{}\"",
            r.problem,
            r.solver,
            r.resolution,
            r.points,
            g(r.time),
            g(r.error),
            g(r.error2),
            g(r.vs_active_set),
            opt(r.iterations, |k| k.to_string()),
            opt(r.converged, |c| c.to_string()),
            r.note.replace('"', "'")
        );
    }
    if quick {
        return Ok(());
    }
    std::fs::write(CSV, csv)?;
    chart(&rows)?;
    eprintln!("written: book/src/solver_benchmark.{{csv,svg,png}}");
    Ok(())
}
