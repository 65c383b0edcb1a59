//! The paper's optimisation examples (§4, Tables 1–3) with the bodies of
//! [`fem::paper`](crate::fem::paper): the punch on its base, the C¹ controller of Tables 1 and 3
//! with L₂ = R = 50 mm, the augmented Lagrangian with c = E·10⁴ as the contact solver.

use crate::contact::{ActiveSet, InterfaceProblem, Penalty};
use crate::fem::paper::{self, PaperMesh, PunchLoad};
use crate::fem::{Analysis, FeBody};
use crate::optimise::{Mode, Optimisation, Optimum, Profile};
use crate::{ElasticBody, Result};

/// The L₁ values of the tables \[mm\].
pub const L1: [f64; 5] = [0.0, 20.0, 30.0, 40.0, 50.0];

/// Table 1 as printed (axisymmetric, 100 MPa): (L₁ \[mm\], p_max \[MPa\], Δh_max \[µm\]).
pub const TABLE1: [(f64, f64, f64); 5] = [
    (0.0, 333.2, 93.67),
    (20.0, 196.9, 64.72),
    (30.0, 154.3, 48.71),
    (40.0, 123.2, 32.27),
    (50.0, 100.0, 10.87),
];

/// Table 3 as printed (plane stress, b = 10 mm, 100 MPa): (L₁, p_max, Δh_max \[µm\]). Its
/// p_max for L₁ = 0, 283.3, is a misprint: equilibrium gives 200, to which its Δh_max belongs.
pub const TABLE3: [(f64, f64, f64); 5] = [
    (0.0, 283.3, 88.35),
    (20.0, 142.9, 65.86),
    (30.0, 125.0, 52.02),
    (40.0, 111.1, 36.02),
    (50.0, 100.0, 12.69),
];

/// A printed row of Table 2: (k, p_max \[MPa\], Δh_max \[µm\], TOLH \[mm²\], iterp, iterd).
pub type PrintedRow = (usize, f64, f64, f64, usize, usize);

/// Table 2 as printed (axisymmetric, w = −0.05 mm): per L₁ its rows
/// (k, p_max \[MPa\], Δh_max \[µm\], TOLH \[mm²\], iterp, iterd).
pub const TABLE2: [(f64, &[PrintedRow]); 5] = [
    (
        50.0,
        &[
            (1, 338.9, 36.82, 0.9209e-2, 1, 1),
            (2, 167.2, 18.15, 0.2367e-2, 6, 3),
            (3, 113.5, 12.33, 0.2301e-3, 2, 1),
            (4, 111.7, 12.14, 0.2584e-6, 1, 1),
        ],
    ),
    (
        40.0,
        &[
            (1, 338.9, 85.57, 0.5830e-1, 1, 1),
            (2, 186.2, 47.00, 0.1184e-1, 10, 3),
            (3, 119.0, 30.03, 0.2292e-2, 9, 3),
            (4, 114.6, 28.94, 0.9594e-5, 7, 3),
            (5, 114.4, 28.89, 0.1540e-7, 2, 1),
        ],
    ),
    (
        30.0,
        &[
            (1, 338.9, 101.9, 0.1179, 1, 1),
            (2, 146.1, 43.96, 0.3813e-1, 10, 3),
            (3, 132.4, 39.83, 0.1936e-3, 7, 2),
            (4, 121.0, 36.40, 0.1335e-3, 4, 1),
            (5, 119.8, 36.04, 0.1454e-5, 7, 3),
            (6, 119.7, 36.01, 0.1079e-7, 2, 1),
        ],
    ),
    (
        20.0,
        &[
            (1, 338.9, 105.8, 0.1634, 1, 1),
            (2, 164.4, 51.34, 0.4332e-1, 8, 2),
            (3, 134.6, 42.03, 0.1267e-2, 8, 2),
            (4, 129.2, 40.35, 0.4119e-5, 4, 1),
            (5, 128.3, 40.07, 0.1110e-5, 4, 1),
            (6, 128.2, 40.03, 0.2525e-7, 3, 1),
        ],
    ),
    (
        0.0,
        &[
            (1, 338.9, 90.84, 0.1635, 1, 1),
            (2, 221.5, 59.38, 0.1960e-1, 8, 1),
            (3, 183.7, 49.24, 0.2039e-2, 9, 4),
            (4, 170.3, 45.64, 0.2565e-3, 20, 3),
            (5, 165.5, 44.35, 0.3277e-4, 6, 2),
            (6, 163.8, 43.90, 0.3989e-5, 5, 2),
            (7, 163.2, 43.75, 0.4636e-6, 9, 3),
        ],
    ),
];

/// The paper's convergence criterion TOLH ≤ 0.5·10⁻⁶ (§4) \[mm²\].
pub const TOLH: f64 = 0.5e-6;

/// How a case is optimised.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// The iteration of §3.2 with the paper's penalty contact elements (c = E·10⁴) inside. The
    /// penalty's W/c term keeps the Gauss-point pressure free of the sawtooth that the exact
    /// limit (augmented Lagrangian, QP) can carry next to a receding contact edge, where three
    /// points per quadratic face over-constrain the face's two displacement unknowns.
    Iteration,
    /// The restricted linear programme (3.5).
    LinearProgramme,
}

/// One optimised case of a table.
pub struct Case {
    /// L₁ \[mm\].
    pub l1: f64,
    /// The optimum.
    pub optimum: Optimum,
    /// r (or x) of the interface points \[mm\].
    pub points: Vec<f64>,
    /// r (or x) of the design nodes \[mm\].
    pub nodes: Vec<f64>,
    /// The bodies and the problem, for closing the loop.
    pub base: FeBody,
    /// The punch.
    pub punch: FeBody,
}

/// The case L₁ of a table: `analysis` (axisymmetric for Tables 1–2, plane stress b = 10 mm
/// for Table 3), the punch `load` (100 MPa for Tables 1 and 3; −0.05 mm for Table 2).
pub fn case(
    analysis: Analysis,
    load: PunchLoad,
    mesh: &PaperMesh,
    l1: f64,
    method: Method,
) -> Result<Case> {
    let (base, punch) = paper::bodies(analysis, load, mesh)?;
    let optimum = {
        let problem = InterfaceProblem::new(&base, &punch, &vec![0.0; base.interface().len()])?;
        let controller = Profile::cubic(l1, paper::PUNCH_RADIUS)?;
        let optimisation = Optimisation::new(&problem, base.gap_shape(), &controller)?;
        match method {
            Method::Iteration => {
                let mode = match load {
                    PunchLoad::Pressure(_) => Mode::GivenLoad,
                    PunchLoad::Displacement(_) => Mode::GivenDisplacement,
                };
                let solver = Penalty { c: paper::E * 1e4 };
                optimisation.iterate(mode, &solver, TOLH, 100)?
            }
            Method::LinearProgramme => optimisation.linear_programme(&ActiveSet)?,
        }
    };
    Ok(Case {
        l1,
        optimum,
        points: base.interface().points.iter().map(|x| x[0]).collect(),
        nodes: base.gap_shape().nodes().iter().map(|x| x[0]).collect(),
        base,
        punch,
    })
}

/// p_max of a given load from equilibrium alone: the punch's load p̃·(area) carried by
/// v·p_max, p_max = p̃·∫dA / ∫v dA over 0 ≤ r ≤ R (2πr dr axisymmetric, b dx plane), by
/// Simpson's rule on 20 000 intervals.
pub fn equilibrium_p_max(analysis: Analysis, pressure: f64, l1: f64) -> Result<f64> {
    let controller = Profile::cubic(l1, paper::PUNCH_RADIUS)?;
    let measure = |r: f64| match analysis {
        Analysis::Axisymmetric => r,
        _ => 1.0,
    };
    let n = 20_000;
    let h = paper::PUNCH_RADIUS / n as f64;
    let (mut area, mut carried) = (0.0, 0.0);
    for k in 0..=n {
        let r = k as f64 * h;
        let simpson = if k == 0 || k == n {
            1.0
        } else if k % 2 == 1 {
            4.0
        } else {
            2.0
        };
        area += simpson * measure(r);
        carried +=
            simpson * measure(r) * crate::optimise::Controller::value(&controller, [r, 0.0, 0.0]);
    }
    Ok(pressure * area / carried)
}

/// The refinement study of the tables: 18, 36 and 72 uniform quadratic elements across the
/// contact radius (and as many layers through each body).
pub const MESHES: [usize; 3] = [18, 36, 72];

fn mesh(elements: usize) -> PaperMesh {
    PaperMesh {
        contact_elements: elements,
        layers: elements,
        ..PaperMesh::default()
    }
}

/// Percentage difference of `ours` from `paper`.
fn percent(ours: f64, paper: f64) -> f64 {
    100.0 * (ours / paper - 1.0)
}

/// Writes the plots of Δh(r) and p(r) for each L₁ into `dir` as `dh.svg` and `p.svg`.
fn plots(cases: &[Case], x_label: &str, dir: &std::path::Path) -> Result<()> {
    let series = |f: &dyn Fn(&Case) -> Vec<(f64, f64)>| -> Vec<(String, Vec<(f64, f64)>)> {
        cases
            .iter()
            .map(|c| (format!("L1 = {}", c.l1), f(c)))
            .collect()
    };
    let sorted = |mut v: Vec<(f64, f64)>| {
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        v
    };
    let dh = series(&|c| {
        sorted(
            c.nodes
                .iter()
                .zip(&c.optimum.dh)
                .map(|(x, d)| (*x, 1e3 * d))
                .collect(),
        )
    });
    let p = series(&|c| {
        sorted(
            c.points
                .iter()
                .zip(&c.optimum.pressure)
                .map(|(x, p)| (*x, *p))
                .collect(),
        )
    });
    let write = |name: &str, title: &str, y: &str, data: &[(String, Vec<(f64, f64)>)]| {
        let refs: Vec<(&str, &[(f64, f64)])> = data
            .iter()
            .map(|(n, v)| (n.as_str(), v.as_slice()))
            .collect();
        std::fs::write(
            dir.join(name),
            crate::plot::line_plot(title, x_label, y, &refs),
        )
        .map_err(|e| crate::Error::invalid("output", dir.display(), e.to_string()))
    };
    std::fs::create_dir_all(dir)
        .map_err(|e| crate::Error::invalid("output", dir.display(), e.to_string()))?;
    write(
        "dh.svg",
        "Optimal change of the initial gap",
        "Δh [µm]",
        &dh,
    )?;
    write(
        "p.svg",
        "Contact pressure after optimisation",
        "p [MPa]",
        &p,
    )?;
    Ok(())
}

/// Table 1 (axisymmetric) or Table 3 (plane stress, b = 10 mm), given load 100 MPa: our table
/// beside the paper's `printed` one, with the refinement of Δh_max over [`MESHES`], plots in
/// `dir`. Returns the report.
pub fn given_load_report(
    analysis: Analysis,
    printed: &[(f64, f64, f64); 5],
    dir: &std::path::Path,
) -> Result<String> {
    use std::fmt::Write;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{:>5} | {:>9} {:>9} {:>8} | {:>10} {:>10} {:>10} {:>9} {:>8}",
        "L1", "p_max", "paper", "diff %", "Δh 18 µm", "Δh 36 µm", "Δh 72 µm", "paper", "diff %"
    );
    let mut finest = vec![];
    for &(l1, p_paper, dh_paper) in printed {
        let mut dh = vec![];
        let mut last = None;
        for &m in &MESHES {
            let case = case(
                analysis,
                PunchLoad::Pressure(100.0),
                &mesh(m),
                l1,
                Method::Iteration,
            )?;
            dh.push(1e3 * case.optimum.dh_max());
            last = Some(case);
        }
        let case = last.expect("MESHES is not empty");
        let p_max = case.optimum.p_max;
        let _ = writeln!(
            out,
            "{l1:>5} | {p_max:>9.2} {p_paper:>9.1} {:>+8.2} | {:>10.3} {:>10.3} {:>10.3} {dh_paper:>9.2} {:>+8.2}",
            percent(p_max, p_paper),
            dh[0],
            dh[1],
            dh[2],
            percent(dh[2], dh_paper)
        );
        finest.push(case);
    }
    let _ = writeln!(
        out,
        "p_max from equilibrium (v·p_max carries the 100 MPa on the punch); Δh_max at the face \
         nodes for 18, 36 and 72 uniform Q8 elements across the contact radius; diff % against \
         the paper for 72."
    );
    plots(&finest, "r [mm]", dir)?;
    Ok(out)
}

/// Table 2: the given displacement w = −0.05 mm, the iteration of §3.2 per L₁ on 18
/// elements, every row (k, p_max, Δh_max, TOLH, iterp, iterd) beside the paper's (or why it
/// stopped), then the optimum of the linear programme (3.5) on the meshes of [`MESHES`]; plots
/// of the LP's optimum in `dir`.
pub fn given_displacement_report(dir: &std::path::Path) -> Result<String> {
    use std::fmt::Write;
    let mut out = String::new();
    let mut finest = vec![];
    for &(l1, rows) in &TABLE2 {
        let mut converged = vec![];
        for &m in &MESHES {
            let case = case(
                Analysis::Axisymmetric,
                PunchLoad::Displacement(-0.05),
                &mesh(m),
                l1,
                Method::LinearProgramme,
            )?;
            converged.push((case.optimum.p_max, 1e3 * case.optimum.dh_max()));
            if m == MESHES[MESHES.len() - 1] {
                finest.push(case);
            }
        }
        let iterated = case(
            Analysis::Axisymmetric,
            PunchLoad::Displacement(-0.05),
            &mesh(MESHES[0]),
            l1,
            Method::Iteration,
        );
        let _ = writeln!(out, "L1 = {l1} mm (18 elements; paper in brackets)");
        let _ = writeln!(
            out,
            "{:>3} {:>18} {:>20} {:>24} {:>9} {:>9}",
            "k", "p_max MPa", "Δh_max µm", "TOLH mm²", "iterp", "iterd"
        );
        let ours = match &iterated {
            Ok(case) => case.optimum.iterations.clone(),
            Err(e) => {
                let _ = writeln!(out, "    our iteration stopped: {e}");
                vec![]
            }
        };
        for k in 0..ours.len().max(rows.len()) {
            let mine = ours.get(k);
            let theirs = rows.get(k);
            let cell = |a: Option<String>, b: Option<String>| {
                format!(
                    "{} [{}]",
                    a.unwrap_or_else(|| "-".into()),
                    b.unwrap_or_else(|| "-".into())
                )
            };
            let _ = writeln!(
                out,
                "{:>3} {:>18} {:>20} {:>24} {:>9} {:>9}",
                k + 1,
                cell(
                    mine.map(|r| format!("{:.1}", r.p_max)),
                    theirs.map(|r| format!("{:.1}", r.1))
                ),
                cell(
                    mine.map(|r| format!("{:.2}", 1e3 * r.dh_max)),
                    theirs.map(|r| format!("{:.2}", r.2))
                ),
                cell(
                    mine.map(|r| format!("{:.3e}", r.tolh)),
                    theirs.map(|r| format!("{:.3e}", r.3))
                ),
                cell(
                    mine.map(|r| r.iterp.to_string()),
                    theirs.map(|r| r.4.to_string())
                ),
                cell(
                    mine.map(|r| r.iterd.to_string()),
                    theirs.map(|r| r.5.to_string())
                ),
            );
        }
        let (_, p_paper, dh_paper, ..) = rows[rows.len() - 1];
        let _ = writeln!(
            out,
            "linear programme (3.5), 18 / 36 / 72 elements: p_max {:.2} / {:.2} / {:.2} MPa (paper {p_paper}, {:+.2} %), \
             Δh_max {:.3} / {:.3} / {:.3} µm (paper {dh_paper}, {:+.2} %)\n",
            converged[0].0,
            converged[1].0,
            converged[2].0,
            percent(converged[2].0, p_paper),
            converged[0].1,
            converged[1].1,
            converged[2].1,
            percent(converged[2].1, dh_paper)
        );
    }
    plots(&finest, "r [mm]", dir)?;
    Ok(out)
}
