//! The paper's examples (§4, Tables 1–3): the printed values, and the bundled scenes
//! `paper-table1`, `paper-table2` and `paper-table3` run on a chosen mesh.

use contopt_optimise::{Controller, Profile};
use contopt_scene::{CaseReport, Scene, SceneError};

/// The L₁ values of the tables \[mm\].
pub const L1: [f64; 5] = [0.0, 20.0, 30.0, 40.0, 50.0];

/// The contact radius R = L₂ of the tables' controller \[mm\].
pub const PUNCH_RADIUS: f64 = 50.0;

/// The paper's convergence criterion TOLH ≤ 0.5·10⁻⁶ (§4) \[mm²\].
pub const TOLH: f64 = 0.5e-6;

/// A printed row of Table 1 or 3: (L₁ \[mm\], p_max \[MPa\], Δh_max \[µm\]).
pub type GivenLoadRow = (f64, f64, f64);

/// Table 1 as printed (axisymmetric, 100 MPa).
pub const TABLE1: [GivenLoadRow; 5] = [
    (0.0, 333.2, 93.67),
    (20.0, 196.9, 64.72),
    (30.0, 154.3, 48.71),
    (40.0, 123.2, 32.27),
    (50.0, 100.0, 10.87),
];

/// Table 3 as printed (plane stress, b = 10 mm, 100 MPa). Its p_max for L₁ = 0, 283.3, is a
/// misprint: equilibrium gives 200, to which its Δh_max belongs.
pub const TABLE3: [GivenLoadRow; 5] = [
    (0.0, 283.3, 88.35),
    (20.0, 142.9, 65.86),
    (30.0, 125.0, 52.02),
    (40.0, 111.1, 36.02),
    (50.0, 100.0, 12.69),
];

/// A printed row of Table 2: (k, p_max \[MPa\], Δh_max \[µm\], TOLH \[mm²\], iterp, iterd).
pub type PrintedRow = (usize, f64, f64, f64, usize, usize);

/// Table 2 as printed (axisymmetric, w = −0.05 mm): per L₁ its rows.
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

/// The refinement study of the tables: 18, 36 and 72 uniform quadratic elements across the
/// contact radius, as many layers through each body.
pub const MESHES: [usize; 3] = [18, 36, 72];

/// The bundled scene `name` with `elements` quadratic elements across the contact zone (and as
/// many layers through each body), and `edits` of other keys: a dotted path and its TOML
/// value, or `None` to remove a top-level key.
pub fn scene(
    name: &str,
    elements: usize,
    edits: &[(&str, Option<&str>)],
) -> Result<Scene, SceneError> {
    let elements = elements.to_string();
    let mut all = vec![("contact.zone.elements", Some(elements.as_str()))];
    all.extend_from_slice(edits);
    Scene::bundled_with(name, &all)
}

/// Runs every case of `scene` (one per L₁ of the sweep), in sweep order, building the bodies
/// once.
pub fn run(scene: &Scene) -> Result<Vec<CaseReport>, SceneError> {
    scene.run().collect()
}

/// p_max of a given load from equilibrium alone: the punch's load p̃·(area) carried by
/// v·p_max with the C¹ controller (L₁, L₂ = R), p_max = p̃·∫dA / ∫v dA over 0 ≤ r ≤ R
/// (2πr dr when `axisymmetric`, b dx in the plane), by Simpson's rule on 20 000 intervals.
pub fn equilibrium_p_max(axisymmetric: bool, pressure: f64, l1: f64) -> f64 {
    const INTERVALS: usize = 20_000;
    let Ok(controller) = Profile::cubic(l1, PUNCH_RADIUS) else {
        return f64::NAN;
    };
    let measure = |r: f64| if axisymmetric { r } else { 1.0 };
    let h = PUNCH_RADIUS / INTERVALS as f64;
    let (mut area, mut carried) = (0.0, 0.0);
    for k in 0..=INTERVALS {
        let r = k as f64 * h;
        let simpson = match k {
            0 | INTERVALS => 1.0,
            k if k % 2 == 1 => 4.0,
            _ => 2.0,
        };
        area += simpson * measure(r);
        carried += simpson * measure(r) * controller.value([r, 0.0, 0.0]);
    }
    pressure * area / carried
}

/// Percentage difference of `ours` from `paper`.
pub fn percent(ours: f64, paper: f64) -> f64 {
    100.0 * (ours / paper - 1.0)
}

/// Table 1 (`paper-table1`, axisymmetric) or Table 3 (`paper-table3`, plane stress): the scene on
/// each of [`MESHES`], our p_max beside equilibrium and the `printed` table, and Δh_max on each
/// mesh beside the printed value.
pub fn given_load_table(
    name: &str,
    printed: &[GivenLoadRow; 5],
    axisymmetric: bool,
) -> Result<String, SceneError> {
    use std::fmt::Write;
    let runs = MESHES
        .iter()
        .map(|&m| run(&scene(name, m, &[])?))
        .collect::<Result<Vec<_>, _>>()?;
    let mut out = format!(
        "{:>5} | {:>9} {:>11} {:>9} {:>8} | {:>10} {:>10} {:>10} {:>9} {:>8}\n",
        "L1",
        "p_max",
        "equilibrium",
        "paper",
        "diff %",
        "Δh 18 µm",
        "Δh 36 µm",
        "Δh 72 µm",
        "paper",
        "diff %"
    );
    for (k, &(l1, p_paper, dh_paper)) in printed.iter().enumerate() {
        let finest = &runs[MESHES.len() - 1][k];
        let p_max = finest.bound_p_max_mpa.unwrap_or(f64::NAN);
        let dh: Vec<f64> = runs
            .iter()
            .map(|r| r[k].dh_max_um.unwrap_or(f64::NAN))
            .collect();
        let _ = writeln!(
            out,
            "{l1:>5} | {p_max:>9.2} {:>11.2} {p_paper:>9.1} {:>+8.2} | {:>10.3} {:>10.3} {:>10.3} {dh_paper:>9.2} {:>+8.2}",
            equilibrium_p_max(axisymmetric, 100.0, l1),
            percent(p_max, p_paper),
            dh[0],
            dh[1],
            dh[2],
            percent(dh[2], dh_paper)
        );
    }
    out.push_str(
        "p_max is the level of p ≤ v·p_max that carries the 100 MPa on the punch; Δh_max at the \
         face nodes for 18, 36 and 72 uniform Q8 elements across the contact radius; diff % \
         against the paper for 72.\n",
    );
    Ok(out)
}

/// Table 2 (`paper-table2`, w = −0.05 mm): per L₁ the rows (k, p_max, Δh_max, TOLH, iterp,
/// iterd) of the iteration of §3.2 on 18 elements beside the paper's, then the optimum of the
/// linear programme (3.5) on each of [`MESHES`].
pub fn given_displacement_table() -> Result<String, SceneError> {
    use std::fmt::Write;
    let iterated = run(&scene("paper-table2", MESHES[0], &[])?)?;
    let lp = MESHES
        .iter()
        .map(|&m| run(&scene("paper-table2", m, &LP_EDITS)?))
        .collect::<Result<Vec<_>, _>>()?;
    let mut out = String::new();
    for (k, &l1) in L1.iter().enumerate() {
        let (_, rows) = TABLE2
            .iter()
            .find(|(l, _)| *l == l1)
            .expect("TABLE2 has every L1");
        let _ = writeln!(out, "L1 = {l1} mm (18 elements; paper in brackets)");
        out.push_str(&iteration_rows(&iterated[k], rows));
        let (_, p_paper, dh_paper, ..) = rows[rows.len() - 1];
        let p: Vec<f64> = lp
            .iter()
            .map(|r| r[k].bound_p_max_mpa.unwrap_or(f64::NAN))
            .collect();
        let dh: Vec<f64> = lp
            .iter()
            .map(|r| r[k].dh_max_um.unwrap_or(f64::NAN))
            .collect();
        let _ = writeln!(
            out,
            "linear programme (3.5), 18 / 36 / 72 elements: p_max {:.2} / {:.2} / {:.2} MPa \
             (paper {p_paper}, {:+.2} %), Δh_max {:.3} / {:.3} / {:.3} µm (paper {dh_paper}, \
             {:+.2} %)\n",
            p[0],
            p[1],
            p[2],
            percent(p[2], p_paper),
            dh[0],
            dh[1],
            dh[2],
            percent(dh[2], dh_paper)
        );
    }
    Ok(out)
}

/// The linear programme (3.5) with the active set as its contact solver, in place of a scene's
/// method and solver.
const LP_EDITS: [(&str, Option<&str>); 2] = [
    ("optimisation.method", Some("\"linear_programme\"")),
    ("solver", Some("\"active_set\"")),
];

/// The rows of one case's iteration beside the printed ones, "ours [paper]".
fn iteration_rows(case: &CaseReport, printed: &[PrintedRow]) -> String {
    use std::fmt::Write;
    let mut out = format!(
        "{:>3} {:>18} {:>20} {:>24} {:>9} {:>9}\n",
        "k", "p_max MPa", "Δh_max µm", "TOLH mm²", "iterp", "iterd"
    );
    if !case.is_solved() {
        let _ = writeln!(out, "    our iteration stopped: {}", case.termination);
    }
    let ours = &case.passes;
    for k in 0..ours.len().max(printed.len()) {
        let (mine, theirs) = (ours.get(k), printed.get(k));
        let cell = |a: Option<String>, b: Option<String>| {
            let dash = || "-".to_string();
            format!("{} [{}]", a.unwrap_or_else(dash), b.unwrap_or_else(dash))
        };
        let _ = writeln!(
            out,
            "{:>3} {:>18} {:>20} {:>24} {:>9} {:>9}",
            k + 1,
            cell(
                mine.map(|r| format!("{:.1}", r.bound_p_max_mpa)),
                theirs.map(|r| format!("{:.1}", r.1))
            ),
            cell(
                mine.map(|r| format!("{:.2}", r.dh_max_um)),
                theirs.map(|r| format!("{:.2}", r.2))
            ),
            cell(
                mine.map(|r| format!("{:.3e}", r.tolh_mm2)),
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
    out
}

/// One L₁ of the bundled scene `name` on `elements` elements: by the scene's own method, or by
/// the linear programme (3.5) with the active set when `lp`.
pub fn case(name: &str, elements: usize, l1: f64, lp: bool) -> Result<CaseReport, SceneError> {
    let l1 = format!("{l1:?}");
    let mut edits = vec![
        ("sweep", None),
        ("optimisation.controller.l1_mm", Some(l1.as_str())),
    ];
    if lp {
        edits.extend(LP_EDITS);
    }
    let cases = run(&scene(name, elements, &edits)?)?;
    Ok(cases
        .into_iter()
        .next()
        .expect("a scene without a sweep has one case"))
}
