//! Hertz's point contact between two solids meshed apart: a quarter of a steel sphere
//! (R = 20 mm) pressed by a pressure on its flat top onto a quarter of a steel block
//! (`meshes/solid-sphere-on-block.geo.inc`), with the force that makes the contact radius
//! a = 1 mm. The block's top face is read over a grid of cells over the contact, coarser than
//! its nodes (so that the pair's influence is definite), each cell as its mean
//! ([`SolidSample::cells`]), the sphere over the same cells along the block's normal
//! ([`SolidSample::facing`]); the initial gap is each cell's mean distance between the meshed
//! faces ([`SolidSample::initial_gap`]). The centre cell's pressure is compared with Hertz's
//! mean over it, and the contact radius is the one of the Hertz pressure with the cells' second
//! moment ([`sphere_radius_from_moment`]).

use contopt_contact::{ActiveSet, ActiveSetSettings, ContactSolver, InterfaceProblem};
use contopt_core::{ElasticBody, Error, Material, Result};
use contopt_fem::solid::{
    Axis, Cell, SolidBody, SolidFace, SolidMesh, SolidModel, SolidSample, SolidSettings,
};
use contopt_gmsh::Volumes;
use contopt_greens::HalfSpace;

use crate::closed_form::{
    contact_modulus, fit_sphere_cells, hertz_cell_mean, sphere_radius_from_moment, HertzSphere,
};

/// The sphere's radius and the contact radius aimed at \[mm\].
pub const RADIUS: f64 = 20.0;
/// See [`RADIUS`].
pub const CONTACT_RADIUS: f64 = 1.0;
/// The contact points are a grid over this many contact radii from the axis.
const CANDIDATES: f64 = 1.6;
/// The grid's spacing in the block's element edges at the contact: the points fewer than the
/// face nodes, so that the pair's influence is definite and the point pressures unique.
const SPACING_IN_EDGES: f64 = 0.75;

/// What one mesh gives against Hertz.
#[derive(Clone, Copy, Debug)]
pub struct HertzCheck {
    /// Nodes of both solids.
    pub nodes: usize,
    /// Contact points.
    pub points: usize,
    /// p₀ from the centre cell: its pressure over Hertz's mean of p/p₀ on it (0.99 of p₀ on
    /// the bundled mesh's cells), and Hertz's p₀ \[MPa\].
    pub p0: [f64; 2],
    /// The contact radius of the Hertz pressure with the cells' second moment about the axis
    /// ([`sphere_radius_from_moment`]), and Hertz's a \[mm\].
    pub a: [f64; 2],
    /// p₀ \[MPa\] and a \[mm\] of Hertz's cell means fitted to every cell's pressure
    /// ([`fit_sphere_cells`]): the contact's edge found to a cell.
    pub fitted: [f64; 2],
    /// p₀ \[MPa\] and a \[mm\] of the line p² = p₀²(1 − r²/a²) through the loaded cells'
    /// pressures at their centres, the estimate of earlier versions.
    pub centres: [f64; 2],
    /// The cells' side \[mm\].
    pub cell: f64,
    /// The largest sub-rule k (parts along a cell's side) of the block's cells and of the
    /// sphere's.
    pub sub_rule: [usize; 2],
}

/// Steel.
pub fn steel() -> Material {
    Material::new(2.0e5, 0.3).expect("steel")
}

/// The sphere on the block read from `path`, solved, against Hertz.
pub fn sphere_on_block(path: &str) -> Result<HertzCheck> {
    let gmsh = contopt_gmsh::read(path)?;
    let hertz = HertzSphere {
        radius: RADIUS,
        modulus: contact_modulus(&[steel(), steel()]),
    };
    let quarter = hertz.force(CONTACT_RADIUS) / 4.0;

    let block = gmsh.import_solid(Volumes::Group("block"))?;
    let mut model = SolidModel::new(block.mesh.clone(), steel());
    model.fix(block.nodes("block_x0")?, Axis::X)?;
    model.fix(block.nodes("block_y0")?, Axis::Y)?;
    for axis in Axis::ALL {
        model.fix(block.nodes("block_bottom")?, axis)?;
    }
    let top = block.faces("block_top")?;
    let first = grid_samples(model.mesh(), top)?;
    let block_body = SolidBody::sampled("block", model, &first, SolidSettings::default())?;

    let sphere = gmsh.import_solid(Volumes::Group("sphere"))?;
    let mut model = SolidModel::new(sphere.mesh.clone(), steel());
    model.fix(sphere.nodes("sphere_x0")?, Axis::X)?;
    model.fix(sphere.nodes("sphere_y0")?, Axis::Y)?;
    let top_area = std::f64::consts::PI * RADIUS * RADIUS / 4.0;
    model.add_pressure(sphere.faces("sphere_top")?, quarter / top_area)?;
    let second = SolidSample::facing(model.mesh(), sphere.faces("sphere_face")?, &first)?;
    let gap = SolidSample::initial_gap(&first, &second);
    let sphere_body = SolidBody::sampled("sphere", model, &second, SolidSettings::default())?;

    let problem = InterfaceProblem::new(&block_body, &sphere_body, &gap)?;
    let state = ActiveSet::new(ActiveSetSettings::default())?.solve(&problem)?;
    let points = block_body.interface().points();
    let h = first[0].sides[0][0];
    let cells: Vec<([f64; 2], f64, f64)> = (points.iter().zip(&state.pressure))
        .map(|(x, &p)| ([x[0], x[1]], h, p))
        .collect();
    let no_fit = || Error::invalid("pressure", "all zero", "a contact to fit Hertz's sphere to");
    let fitted = fit_sphere_cells(&cells).ok_or_else(no_fit)?;
    let a = sphere_radius_from_moment(&cells).ok_or_else(no_fit)?;
    let centres = fit_centres(&cells).ok_or_else(no_fit)?;
    // The centre cell's pressure against Hertz's mean over it.
    let centre = (cells.iter())
        .min_by(|a, b| a.0[0].hypot(a.0[1]).total_cmp(&b.0[0].hypot(b.0[1])))
        .ok_or_else(no_fit)?;
    let centre_mean = hertz_cell_mean(centre.0, centre.1, CONTACT_RADIUS);
    let rule = |s: &[SolidSample]| {
        (s.iter().flat_map(SolidSample::sub_rule))
            .max()
            .unwrap_or(1)
    };
    Ok(HertzCheck {
        nodes: block.mesh.nodes().len() + sphere.mesh.nodes().len(),
        points: points.len(),
        p0: [centre.2 / centre_mean, hertz.peak_pressure(CONTACT_RADIUS)],
        a: [a, CONTACT_RADIUS],
        fitted: [fitted.0, fitted.1],
        centres,
        cell: h,
        sub_rule: [rule(&first), rule(&second)],
    })
}

/// Hertz's sphere between two steel half-spaces solved on the half-space grid, square cells of
/// side `h` \[mm\] over [−1.6a, 1.6a]², the axis at a cell's corner as in the solids' quarter:
/// the contact radius by the cells' second moment ([`sphere_radius_from_moment`]) and by the
/// fit of Hertz's cell means ([`fit_sphere_cells`]) \[mm\]. The grid's influence is exact
/// for uniform cell pressures, so what is left is the estimators' own error on cells of that
/// size.
pub fn half_space_estimates(h: f64) -> Result<[f64; 2]> {
    let hertz = HertzSphere {
        radius: RADIUS,
        modulus: contact_modulus(&[steel(), steel()]),
    };
    let n = 2 * (CANDIDATES * CONTACT_RADIUS / h).ceil() as usize;
    let origin = -0.5 * (n - 1) as f64 * h;
    let grid = |name| HalfSpace::grid(name, steel(), n, n, h, h, [origin, origin]);
    let block = grid("block")?;
    let sphere = (grid("sphere")?.upper()).pressed(hertz.force(CONTACT_RADIUS))?;
    let gap = hertz.gaps(block.interface());
    let problem = InterfaceProblem::new(&block, &sphere, &gap)?;
    let state = ActiveSet::new(ActiveSetSettings::default())?.solve(&problem)?;
    let cells: Vec<([f64; 2], f64, f64)> = (block.interface().points().iter())
        .zip(&state.pressure)
        .map(|(x, &p)| ([x[0], x[1]], h, p))
        .collect();
    let no_fit = || Error::invalid("pressure", "all zero", "a contact to fit Hertz's sphere to");
    let moment = sphere_radius_from_moment(&cells).ok_or_else(no_fit)?;
    let fitted = fit_sphere_cells(&cells).ok_or_else(no_fit)?;
    Ok([moment, fitted.1])
}

/// p₀ and a from the least-squares line p² = p₀² − (p₀/a)² r² through the loaded cells'
/// pressures at their centres (the cells across the contact's edge, loaded with their centres
/// outside a, pull a outwards: [`fit_sphere_cells`] compares the cells' means instead).
fn fit_centres(cells: &[([f64; 2], f64, f64)]) -> Option<[f64; 2]> {
    let loaded: Vec<(f64, f64)> = (cells.iter())
        .filter(|c| c.2 > 0.0)
        .map(|c| (c.0[0].powi(2) + c.0[1].powi(2), c.2 * c.2))
        .collect();
    let n = loaded.len() as f64;
    let (mx, my) = (loaded.iter()).fold((0.0, 0.0), |(a, b), &(x, y)| (a + x / n, b + y / n));
    let (sxy, sxx) = loaded.iter().fold((0.0, 0.0), |(a, b), &(x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx).powi(2))
    });
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    (slope < 0.0 && intercept > 0.0).then(|| [intercept.sqrt(), (intercept / -slope).sqrt()])
}

/// A grid of square cells over [0, 1.6a]² on the block's top face (the quarter's contact), of
/// spacing [`SPACING_IN_EDGES`] times the median edge of the top faces there, each read as
/// its mean over the faces.
fn grid_samples(mesh: &SolidMesh, top: &[SolidFace]) -> Result<Vec<SolidSample>> {
    let reach = CANDIDATES * CONTACT_RADIUS;
    let mut edges: Vec<f64> = top
        .iter()
        .filter_map(|&f| {
            let nodes = mesh.face_nodes(f);
            let (p, q) = (mesh.nodes()[nodes[0]], mesh.nodes()[nodes[1]]);
            (p[0].hypot(p[1]) < reach).then(|| (p[0] - q[0]).hypot(p[1] - q[1]))
        })
        .collect();
    edges.sort_by(f64::total_cmp);
    let median = edges.get(edges.len() / 2).copied().unwrap_or(reach);
    let cells = (reach / (SPACING_IN_EDGES * median)).ceil() as usize;
    let h = reach / cells as f64;
    let grid: Vec<Cell> = (0..cells * cells)
        .map(|k| {
            let centre = [
                (k % cells) as f64 * h + 0.5 * h,
                (k / cells) as f64 * h + 0.5 * h,
                0.0,
            ];
            Cell::xy(centre, [h, h])
        })
        .collect();
    SolidSample::cells(mesh, top, &grid, [0.0, 0.0, 1.0])
}
