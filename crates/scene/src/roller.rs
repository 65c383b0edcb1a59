//! The `roller` problem kind: a bearing roller on its raceway, with its crown.

use std::path::Path;

use contopt_core::{ElasticBody, Error, Material, Result};
use contopt_roller::{Crown, Roller};

use crate::spec::ProfileSpec;

/// A roller and raceway built from a scene: the two half-spaces, the initial gap and the cell
/// size across (for Ω_v, the centre row).
pub(crate) struct Built {
    pub raceway: Box<dyn ElasticBody>,
    pub roller: Box<dyn ElasticBody>,
    pub gap: Vec<f64>,
    pub info: Info,
}

/// What the run keeps of a roller for its defaults and its report.
pub(crate) struct Info {
    /// The cell size across \[mm\].
    pub dy: f64,
    /// The crown's drop at each point \[mm\].
    pub crown: Vec<f64>,
}

/// The scene's roller: `dir` is the scene file's folder, where a table profile is read.
#[allow(clippy::too_many_arguments)]
pub(crate) fn build(
    diameter: f64,
    length: f64,
    raceway_diameter: Option<f64>,
    materials: [Material; 2],
    load: f64,
    tilt_arcmin: f64,
    cells: [usize; 2],
    reach: f64,
    profile: &ProfileSpec,
    dir: &Path,
) -> Result<Built> {
    let mut roller = Roller {
        diameter,
        length,
        raceway_diameter,
        roller: materials[0],
        raceway: materials[1],
        load,
        tilt: (tilt_arcmin / 60.0).to_radians(),
        crown: Crown::Straight,
    };
    roller.crown = crown(&roller, profile, dir)?;
    let (raceway, body, gap) = roller.bodies(cells[0], cells[1], reach)?;
    let dy = reach * roller.hertz()?.0 / ((cells[1] - 1) / 2) as f64;
    let crown = raceway
        .interface()
        .points
        .iter()
        .map(|x| roller.crown.drop(x[0], length))
        .collect::<Result<Vec<f64>>>()?;
    Ok(Built {
        raceway: Box::new(raceway),
        roller: Box::new(body),
        gap,
        info: Info { dy, crown },
    })
}

fn crown(roller: &Roller, profile: &ProfileSpec, dir: &Path) -> Result<Crown> {
    let (q, l, e_star) = (roller.load, roller.length, roller.e_star());
    match profile {
        ProfileSpec::Straight | ProfileSpec::Optimised => Ok(Crown::Straight),
        ProfileSpec::Iso => Crown::iso(roller.diameter),
        ProfileSpec::Lundberg => Crown::lundberg(q, l, e_star),
        ProfileSpec::JohnsGohar => Crown::johns_gohar(q, l, e_star, roller.hertz()?.0),
        ProfileSpec::FujiwaraKawase { k1, k2, z_m_mm } => {
            Crown::fujiwara_kawase(*k1, *k2, *z_m_mm, q, l, e_star)
        }
        ProfileSpec::Table { file } => table(&dir.join(file)),
    }
}

/// A crown table from a CSV file of `x_mm, drop_mm` rows; a first line that is not numbers is
/// a header.
fn table(path: &Path) -> Result<Crown> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        Error::invalid(
            "profile.file",
            path.display(),
            format!("cannot be read: {e}"),
        )
    })?;
    let (mut x, mut drop) = (vec![], vec![]);
    for (k, line) in text.lines().enumerate() {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.iter().all(|f| f.is_empty()) {
            continue;
        }
        let numbers: Option<Vec<f64>> = fields.iter().map(|f| f.parse().ok()).collect();
        match numbers.as_deref() {
            Some([a, b]) => {
                x.push(*a);
                drop.push(*b);
            }
            None if k == 0 => {}
            _ => {
                return Err(Error::invalid(
                    format!("{}:{}", path.display(), k + 1),
                    line,
                    "a row of two numbers, x_mm and drop_mm",
                ))
            }
        }
    }
    Crown::table(x, drop)
}

/// Ends that carry more than this over the pressure at mid-length are edge loading.
const EDGE_LOADING: f64 = 1.1;

/// A roller case's figures from its interface: points, pressure, crown drop per point and the
/// cell size across.
pub(crate) fn report(
    points: &[[f64; 3]],
    pressure: &[f64],
    drop: &[f64],
    dy: f64,
) -> crate::RollerReport {
    let mut xs: Vec<f64> = points.iter().map(|x| x[0]).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let (first, last) = (xs[0], xs[xs.len() - 1]);
    let middle = xs
        .iter()
        .copied()
        .min_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap_or(0.0);
    let column = |c: f64| (0..points.len()).filter(move |&i| (points[i][0] - c).abs() < 1e-9);
    let peak = |c: f64| column(c).map(|i| pressure[i]).fold(0.0, f64::max);
    let half_width = |c: f64| 0.5 * dy * column(c).filter(|&i| pressure[i] > 0.0).count() as f64;
    let top = (0..points.len())
        .max_by(|&a, &b| pressure[a].total_cmp(&pressure[b]))
        .unwrap_or(0);
    let end_drop = column(first)
        .chain(column(last))
        .map(|i| drop[i])
        .fold(0.0, f64::max);
    crate::RollerReport {
        p_max_at_mm: [points[top][0], points[top][1]],
        edge_loading: peak(first).max(peak(last)) > EDGE_LOADING * peak(middle),
        half_width_mm: [
            half_width(middle),
            0.5 * (half_width(first) + half_width(last)),
        ],
        crown_drop_end_um: 1e3 * end_drop,
    }
}
