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
    /// The roller as built (its crown straight when the run designs it).
    pub roller: Roller,
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
        info: Info { dy, crown, roller },
    })
}

fn crown(roller: &Roller, profile: &ProfileSpec, dir: &Path) -> Result<Crown> {
    let (q, l, e_star) = (roller.load, roller.length, roller.e_star());
    match profile {
        ProfileSpec::Straight
        | ProfileSpec::Optimised
        | ProfileSpec::Robust
        | ProfileSpec::FujiwaraKawaseTuned => Ok(Crown::Straight),
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
    let unreadable = |why: String| Error::invalid("profile.file", path.display(), why);
    let file = std::fs::File::open(path).map_err(|e| unreadable(format!("cannot be read: {e}")))?;
    if !file.metadata().is_ok_and(|m| m.is_file()) {
        return Err(unreadable("is not a regular file".into()));
    }
    let text = crate::read_at_most(file).map_err(|e| unreadable(format!("cannot be read: {e}")))?;
    if text.len() as u64 > crate::MAX_TEXT_BYTES {
        return Err(unreadable(format!(
            "is over {} bytes: a crown table is a page of numbers",
            crate::MAX_TEXT_BYTES
        )));
    }
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
pub(crate) const EDGE_LOADING: f64 = 1.1;

/// The columns of a roller grid: the distinct x of its points, in order.
struct Columns<'a> {
    points: &'a [[f64; 3]],
    first: f64,
    last: f64,
    middle: f64,
}

/// Points closer than this along the axis \[mm\] are one column (geometry: far below any
/// cell).
const SAME_COLUMN: f64 = 1e-9;

impl<'a> Columns<'a> {
    fn new(points: &'a [[f64; 3]]) -> Self {
        let mut xs: Vec<f64> = points.iter().map(|x| x[0]).collect();
        xs.sort_by(f64::total_cmp);
        xs.dedup_by(|a, b| (*a - *b).abs() < SAME_COLUMN);
        let middle = xs
            .iter()
            .copied()
            .min_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap_or(0.0);
        Self {
            points,
            first: xs.first().copied().unwrap_or(0.0),
            last: xs.last().copied().unwrap_or(0.0),
            middle,
        }
    }

    /// The points of the column at `c`.
    fn column(&self, c: f64) -> impl Iterator<Item = usize> + '_ {
        (0..self.points.len()).filter(move |&i| (self.points[i][0] - c).abs() < SAME_COLUMN)
    }

    fn peak(&self, c: f64, pressure: &[f64]) -> f64 {
        self.column(c).map(|i| pressure[i]).fold(0.0, f64::max)
    }

    /// The larger end's peak over the peak at mid-length (infinite when mid-length is open).
    fn end_ratio(&self, pressure: &[f64]) -> f64 {
        let end = self
            .peak(self.first, pressure)
            .max(self.peak(self.last, pressure));
        match self.peak(self.middle, pressure) {
            mid if mid > 0.0 => end / mid,
            _ if end > 0.0 => f64::INFINITY,
            _ => 0.0,
        }
    }
}

/// The larger end's peak pressure over the peak at mid-length: above [`EDGE_LOADING`], the
/// ends are edge loaded.
pub(crate) fn end_ratio(points: &[[f64; 3]], pressure: &[f64]) -> f64 {
    Columns::new(points).end_ratio(pressure)
}

/// The point of largest pressure: x, y \[mm\].
fn peak_at(points: &[[f64; 3]], pressure: &[f64]) -> [f64; 2] {
    let top = (0..points.len())
        .max_by(|&a, &b| pressure[a].total_cmp(&pressure[b]))
        .unwrap_or(0);
    [points[top][0], points[top][1]]
}

/// A roller case's figures from its interface: points, pressure, crown drop per point and the
/// cell size across.
pub(crate) fn report(
    points: &[[f64; 3]],
    pressure: &[f64],
    drop: &[f64],
    dy: f64,
) -> crate::RollerReport {
    let columns = Columns::new(points);
    let half_width =
        |c: f64| 0.5 * dy * columns.column(c).filter(|&i| pressure[i] > 0.0).count() as f64;
    let end_drop = columns
        .column(columns.first)
        .chain(columns.column(columns.last))
        .map(|i| drop[i])
        .fold(0.0, f64::max);
    crate::RollerReport {
        p_max_at_mm: peak_at(points, pressure),
        edge_loading: columns.end_ratio(pressure) > EDGE_LOADING,
        half_width_mm: [
            half_width(columns.middle),
            0.5 * (half_width(columns.first) + half_width(columns.last)),
        ],
        crown_drop_end_um: 1e3 * end_drop,
        envelope: vec![],
        worst_p_max: None,
        tuned: None,
    }
}

/// One case of an envelope from its contact: load, tilt, points, pressure, approach \[mm\] and
/// the cell size across (for the centre row).
pub(crate) fn envelope_case(
    [load_n, tilt_arcmin]: [f64; 2],
    points: &[[f64; 3]],
    pressure: &[f64],
    approach: f64,
    dy: f64,
) -> crate::EnvelopeCaseReport {
    crate::EnvelopeCaseReport {
        load_n,
        tilt_arcmin,
        p_max: pressure.iter().fold(0.0, |m: f64, p| m.max(*p)),
        p_max_at_mm: peak_at(points, pressure),
        edge_loading: end_ratio(points, pressure) > EDGE_LOADING,
        approach_um: 1e3 * approach,
        centre_line: (0..points.len())
            .filter(|&i| points[i][1].abs() < 0.5 * dy)
            .map(|i| [points[i][0], pressure[i]])
            .collect(),
    }
}
