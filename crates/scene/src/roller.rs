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
    pub dy: f64,
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
    Ok(Built {
        raceway: Box::new(raceway),
        roller: Box::new(body),
        gap,
        dy,
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
