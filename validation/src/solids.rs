//! Hertz's point contact between two solids meshed apart: a quarter of a steel sphere
//! (R = 20 mm) pressed by a pressure on its flat top onto a quarter of a steel block
//! (`meshes/solid-sphere-on-block.geo.inc`), with the force that makes the contact radius
//! a = 1 mm. The block's top faces are sampled at their Gauss points within 1.6a of the axis,
//! the sphere where the block's normals meet it ([`SolidSample::facing`]); the initial gap is
//! the distance between the meshed faces.

use contopt_contact::{ActiveSet, ActiveSetSettings, ContactSolver, InterfaceProblem};
use contopt_core::{ElasticBody, Material, Result};
use contopt_fem::solid::{Axis, SolidBody, SolidModel, SolidSample, SolidSettings};
use contopt_gmsh::Volumes;

use crate::closed_form::{contact_modulus, HertzSphere};

/// The sphere's radius and the contact radius aimed at \[mm\].
pub const RADIUS: f64 = 20.0;
/// See [`RADIUS`].
pub const CONTACT_RADIUS: f64 = 1.0;
/// Points within this many contact radii of the axis are candidates.
const CANDIDATES: f64 = 1.6;

/// What one mesh gives against Hertz.
#[derive(Clone, Copy, Debug)]
pub struct HertzCheck {
    /// Nodes of both solids.
    pub nodes: usize,
    /// Contact points.
    pub points: usize,
    /// The largest pressure and Hertz's p₀ \[MPa\].
    pub p0: [f64; 2],
    /// The contact radius from the pressure's shape and Hertz's a \[mm\].
    pub a: [f64; 2],
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
    let reach = CANDIDATES * CONTACT_RADIUS;
    let top: Vec<_> = (block.faces("block_top")?.iter().copied())
        .filter(|&f| {
            let nodes = model.mesh().face_nodes(f);
            nodes.iter().any(|&n| {
                let x = model.mesh().nodes()[n];
                x[0].hypot(x[1]) < reach
            })
        })
        .collect();
    let first = SolidSample::gauss(model.mesh(), &top);
    let block_body = SolidBody::sampled("block", model, &first, SolidSettings::default())?;

    let sphere = gmsh.import_solid(Volumes::Group("sphere"))?;
    let mut model = SolidModel::new(sphere.mesh.clone(), steel());
    model.fix(sphere.nodes("sphere_x0")?, Axis::X)?;
    model.fix(sphere.nodes("sphere_y0")?, Axis::Y)?;
    let top_area = std::f64::consts::PI * RADIUS * RADIUS / 4.0;
    model.add_pressure(sphere.faces("sphere_top")?, quarter / top_area)?;
    let second = SolidSample::facing(model.mesh(), sphere.faces("sphere_face")?, &first)?;
    let gap: Vec<f64> = second.iter().map(|s| -s.offset).collect();
    let sphere_body = SolidBody::sampled("sphere", model, &second, SolidSettings::default())?;

    let problem = InterfaceProblem::new(&block_body, &sphere_body, &gap)?;
    let state = ActiveSet::new(ActiveSetSettings::default())?.solve(&problem)?;
    // The pressure as the faces' field (the Gauss-point sawtooth that moves nothing dropped).
    let pressure = problem.recovered_pressure(&state.pressure)?;
    let points = block_body.interface().points();
    let p0 = pressure.iter().fold(0.0f64, |m, &p| m.max(p));
    // a from the elliptic shape p = p₀√(1 − r²/a²) at the points loaded 0.2p₀ to 0.9p₀.
    let loaded: Vec<f64> = (0..points.len())
        .filter(|&i| (0.2 * p0..0.9 * p0).contains(&pressure[i]))
        .map(|i| {
            let r2 = points[i][0].powi(2) + points[i][1].powi(2);
            (r2 / (1.0 - (pressure[i] / p0).powi(2))).sqrt()
        })
        .collect();
    let a = loaded.iter().sum::<f64>() / loaded.len().max(1) as f64;
    Ok(HertzCheck {
        nodes: block.mesh.nodes().len() + sphere.mesh.nodes().len(),
        points: points.len(),
        p0: [p0, hertz.peak_pressure(CONTACT_RADIUS)],
        a: [a, CONTACT_RADIUS],
    })
}
