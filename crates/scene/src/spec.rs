//! The scene schema: what a scene file may say. Keys carry their units (`_mm`, `_mpa`, `_n`);
//! unknown keys are errors.

use contopt_core::{Error, Material, Result};
use contopt_fem::Analysis;
use serde::{Deserialize, Serialize};

use crate::geometry::{Cylinder, PunchLoad, PunchMesh, PunchOnBase, Support};

/// A whole scene.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSpec {
    /// Short name; names the results folder.
    pub name: String,
    /// What the scene shows.
    #[serde(default)]
    pub description: String,
    /// The bodies, their loads and the contact zone.
    pub problem: Problem,
    /// The contact solver.
    pub solver: SolverSpec,
    /// The optimisation of the initial gap (none: only the contact problem is solved).
    #[serde(default)]
    pub optimisation: Option<Optimise>,
    /// Cases over one numeric key.
    #[serde(default)]
    pub sweep: Option<Sweep>,
    /// Named cases, each the scene with some values replaced (`[[case]]`): a study over
    /// anything, where a sweep varies one number.
    #[serde(default)]
    pub case: Vec<CaseSpec>,
    /// Load cases that share a roller's crown (the `roller` kind): each case is also solved
    /// under every load and tilt of the envelope, and a `robust` crown is designed for all.
    #[serde(default)]
    pub envelope: Option<EnvelopeSpec>,
    /// Memory the dense matrices of a solve may take \[MB\] (default 2000); past it a dense
    /// solver or the linear programme refuses the case before allocating.
    #[serde(default)]
    pub dense_limit_mb: Option<f64>,
    /// Memory the whole case may take by its estimate before anything is built \[MB\]
    /// (default 4000): bodies, dense matrices, results.
    #[serde(default)]
    pub memory_limit_mb: Option<f64>,
    /// What the results gain beyond the contact pressure.
    #[serde(default)]
    pub output: OutputSpec,
}

/// What the results gain beyond the contact pressure (`[output]`).
#[derive(Clone, Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Stresses below the surface (`[output.subsurface]`): their peaks in the report, the
    /// sections as CSV and von Mises heat maps.
    #[serde(default)]
    pub subsurface: Option<SubsurfaceSpec>,
}

/// Stresses below the surface of every elastic body that computes them (half-spaces,
/// half-planes, finite-element bodies), under each case's contact pressure.
#[derive(Clone, Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SubsurfaceSpec {
    /// Deepest depth \[mm\]; default twice the contact's half-width (the smaller half-extent
    /// of the contact area; its radius on an axisymmetric body), where the largest shear of a
    /// Hertz contact (0.5–0.8 half-widths down) lies well inside.
    #[serde(default)]
    pub max_depth_mm: Option<f64>,
    /// Number of depths, evenly spaced from max_depth/depths down to max_depth (default 40).
    #[serde(default = "forty")]
    pub depths: usize,
    /// Vertical sections of a grid; default: along x and along y through the largest
    /// pressure (a roller: across the contact at mid-length, at the largest pressure and at
    /// the end cell). A plane or axisymmetric body has one section, its own plane.
    #[serde(default)]
    pub sections: Vec<SectionSpec>,
}

fn forty() -> usize {
    40
}

/// A vertical section through a grid.
#[derive(Clone, Copy, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SectionSpec {
    /// `"x"` or `"y"`: the direction of the section along the surface.
    pub along: contopt_core::SectionAxis,
    /// The other surface coordinate \[mm\] (the nearest row or column of cells is taken).
    pub at_mm: f64,
}

/// A sweep: the scene is run once per value of `key`, a dotted path to a number in the scene
/// (`optimisation.controller.l1_mm`).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Sweep {
    /// Dotted path of the swept number.
    pub key: String,
    /// Its values: integers where the scene has an integer (`problem.mesh.elements`).
    pub values: Vec<serde_json::Number>,
}

/// A named case of a study: the dotted keys of the scene it replaces, with their values
/// (`set = { "problem.profile" = { kind = "iso" } }`).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CaseSpec {
    /// The case's name in tables and plots.
    pub label: String,
    /// Dotted key → its value in this case.
    pub set: std::collections::BTreeMap<String, serde_json::Value>,
}

/// An envelope of load cases for a roller: every combination of a load factor (of `load_n`)
/// and a tilt. The scene's own load and tilt are always a case.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct EnvelopeSpec {
    /// Loads as multiples of `load_n`, each positive.
    pub load_factors: Vec<f64>,
    /// Misalignments \[arc-minutes\].
    pub tilts_arcmin: Vec<f64>,
}

/// An isotropic linear-elastic material.
#[derive(Clone, Copy, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// Young's modulus E \[MPa\].
    pub e_mpa: f64,
    /// Poisson's ratio ν.
    pub nu: f64,
}

/// A punch on a base (`kind = "punch_on_base"`): the scene's form of
/// [`PunchOnBase`](crate::geometry::PunchOnBase), with its materials in the scene's units and a
/// shorthand for one material shared by both bodies.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PunchOnBaseSpec {
    /// `"axisymmetric"`, `{ plane_stress = { thickness_mm } }` or
    /// `{ plane_strain = { thickness_mm } }` (the out-of-plane length).
    pub analysis: Analysis,
    /// The material of each body that names none of its own.
    #[serde(default)]
    pub material: Option<MaterialSpec>,
    /// The punch, whose radius is the contact zone's.
    pub punch: BodySpec,
    /// The base and its supports.
    pub base: BaseSpec,
    /// Load on the punch's top face: `{ pressure_mpa }` or `{ displacement_mm }`.
    pub load: PunchLoad,
    /// The mesh.
    pub mesh: PunchMesh,
}

/// The punch of a punch on a base.
#[derive(Clone, Copy, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Radius (plane: half-width) \[mm\].
    pub radius_mm: f64,
    /// Height \[mm\].
    pub height_mm: f64,
    /// Its material (default: the problem's `material`).
    #[serde(default)]
    pub material: Option<MaterialSpec>,
}

/// The base of a punch on a base.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BaseSpec {
    /// Radius (plane: half-width) \[mm\], larger than the punch's.
    pub radius_mm: f64,
    /// Height \[mm\].
    pub height_mm: f64,
    /// Its material (default: the problem's `material`).
    #[serde(default)]
    pub material: Option<MaterialSpec>,
    /// `"clamped"` or `"axial"` for the bottom face, and `"symmetry"` for a plane model's
    /// line x = 0.
    pub supports: Vec<Support>,
}

impl PunchOnBaseSpec {
    /// The geometry, its materials checked; the rest is checked by
    /// [`PunchOnBase::check`].
    pub fn geometry(&self) -> Result<PunchOnBase> {
        let material = |own: Option<MaterialSpec>, body: &str| -> Result<Material> {
            let m = own.or(self.material).ok_or_else(|| {
                Error::invalid(
                    format!("{body}.material"),
                    "missing",
                    "give each body a material, or one `material` for both",
                )
            })?;
            // A body's own material is named by its body.
            Material::new(m.e_mpa, m.nu).map_err(|e| match (own, e) {
                (
                    Some(_),
                    Error::InvalidInput {
                        field,
                        value,
                        reason,
                    },
                ) => Error::InvalidInput {
                    field: format!("{body}.{field}"),
                    value,
                    reason,
                },
                (_, e) => e,
            })
        };
        if self.material.is_some() && self.punch.material.is_some() && self.base.material.is_some()
        {
            return Err(Error::invalid(
                "material",
                "given",
                "both bodies name their own material: remove the shared one",
            ));
        }
        Ok(PunchOnBase {
            analysis: self.analysis,
            punch: Cylinder {
                radius: self.punch.radius_mm,
                height: self.punch.height_mm,
                material: material(self.punch.material, "punch")?,
            },
            base: Cylinder {
                radius: self.base.radius_mm,
                height: self.base.height_mm,
                material: material(self.base.material, "base")?,
            },
            supports: self.base.supports.clone(),
            load: self.load,
            mesh: self.mesh,
        })
    }
}

/// How a rigid indenter is driven.
#[derive(Clone, Copy, Debug, Deserialize, Serialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum RigidLoad {
    /// Pressed by a force \[N\]; it floats.
    ForceN(f64),
    /// Pushed in by a given approach \[mm\].
    ApproachMm(f64),
}

/// The shape of a rigid indenter: its initial gap h(x) to the flat surface.
#[derive(Clone, Copy, Debug, Deserialize, Serialize)]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum Indenter {
    /// A sphere (on a half-plane: a cylinder across the plane), h = r²/(2R).
    Sphere {
        /// Radius R \[mm\].
        radius_mm: f64,
    },
    /// A roller along x: h = y²/(2R) on a grid, with the contact strip |x| ≤ length/2.
    Cylinder {
        /// Radius R \[mm\].
        radius_mm: f64,
    },
    /// A flat punch of radius (half-width) a: h = 0 for r ≤ a, open beyond.
    FlatPunch {
        /// Radius a \[mm\].
        radius_mm: f64,
    },
}

/// The bodies and the contact zone.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Problem {
    /// Two finite-element bodies: a punch on a base (the paper's Fig. 1), in contact over the
    /// punch's face with zero initial gap.
    PunchOnBase(PunchOnBaseSpec),
    /// A rigid indenter on an elastic half-space: a grid of `cells` cells of `cell_mm`,
    /// centred on the origin.
    RigidOnHalfSpace {
        /// The half-space's material.
        material: MaterialSpec,
        /// Cells along x and y.
        cells: [usize; 2],
        /// Cell size along x and y \[mm\].
        cell_mm: [f64; 2],
        /// The indenter.
        indenter: Indenter,
        /// The load.
        load: RigidLoad,
    },
    /// A rigid indenter on an elastic half-space, axisymmetric: `rings` rings out to
    /// `radius_mm`, narrowing towards the rim (r = a·sin(πk/2n)).
    RigidOnAxisymmetricHalfSpace {
        /// The half-space's material.
        material: MaterialSpec,
        /// Number of rings.
        rings: usize,
        /// Outer radius of the contact zone \[mm\].
        radius_mm: f64,
        /// The indenter.
        indenter: Indenter,
        /// The load.
        load: RigidLoad,
    },
    /// A rigid indenter on an elastic half-plane: `strips` strips across |x| ≤ half_width,
    /// narrowing towards the ends.
    RigidOnHalfPlane {
        /// The half-plane's material.
        material: MaterialSpec,
        /// `{ plane_stress = { thickness_mm } }` or `{ plane_strain = { thickness_mm } }`.
        analysis: Analysis,
        /// Number of strips.
        strips: usize,
        /// Half-width of the contact zone \[mm\].
        half_width_mm: f64,
        /// Depth at which a point load's deflection vanishes \[mm\] (default 100).
        #[serde(default = "datum")]
        datum_mm: f64,
        /// The indenter.
        indenter: Indenter,
        /// The load.
        load: RigidLoad,
    },
    /// A bearing roller on its raceway, both elastic half-spaces (the roller floats under its
    /// load): a grid of `cells` over the effective length and ±`reach_b`·b across it.
    Roller {
        /// Roller diameter D \[mm\].
        diameter_mm: f64,
        /// Effective length l \[mm\].
        length_mm: f64,
        /// Raceway diameter \[mm\]: positive for an inner ring, negative for an outer ring;
        /// default a flat raceway.
        #[serde(default)]
        raceway_diameter_mm: Option<f64>,
        /// The roller's material.
        roller: MaterialSpec,
        /// The raceway's material.
        raceway: MaterialSpec,
        /// Load Q \[N\].
        load_n: f64,
        /// Misalignment γ \[arc-minutes\]: an extra gap γ·x along the axis (default 0).
        #[serde(default)]
        tilt_arcmin: f64,
        /// Cells along the axis and across (odd: the centre row lies on y = 0).
        cells: [usize; 2],
        /// How far the grid reaches across, in Hertz half-widths b (default 2.6).
        #[serde(default = "reach")]
        reach_b: f64,
        /// The crown.
        profile: ProfileSpec,
    },
    /// A rigid indenter on a large axisymmetric finite-element block clamped at its bottom.
    RigidOnBlock {
        /// The block's material.
        material: MaterialSpec,
        /// Radius of the contact zone \[mm\].
        zone_mm: f64,
        /// Elements across the zone.
        elements: usize,
        /// Radius and depth of the block \[mm\].
        size_mm: f64,
        /// The indenter.
        indenter: Indenter,
        /// The load.
        load: RigidLoad,
    },
}

fn datum() -> f64 {
    100.0
}

fn reach() -> f64 {
    2.6
}

/// A roller's crown.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum ProfileSpec {
    /// No crown.
    Straight,
    /// ISO/TS 16281: 0.00035·D·ln[1/(1 − (2x/l)²)].
    Iso,
    /// Lundberg: Q/(π l E*)·ln[1/(1 − (2x/l)²)].
    Lundberg,
    /// Johns–Gohar: Q/(π l E*)·ln[1/(1 − (1 − (2b/l)²)(2x/l)²)].
    JohnsGohar,
    /// Fujiwara–Kawase: load coefficient K1, crowned fraction K2, end drop z_m.
    FujiwaraKawase {
        /// K1.
        k1: f64,
        /// K2, in (0, 1].
        k2: f64,
        /// z_m \[mm\].
        z_m_mm: f64,
    },
    /// A CSV file of `x_mm, drop_mm` rows (|x| increasing; one header line allowed), relative
    /// to the scene file.
    Table {
        /// The file.
        file: String,
    },
    /// The crown the `[optimisation]` finds: Ω_v the centre row, the profile along the axis.
    Optimised,
    /// The symmetric crown the `[optimisation]` (mode `load_split`) finds for the whole
    /// `[envelope]`: the least worst-case p_max, max over the cases of p ≤ v·p_max.
    Robust,
    /// Fujiwara–Kawase with K1, K2 and z_m tuned by a Nelder–Mead search to the least
    /// worst-case p_max over the `[envelope]` (or at the scene's load without one), ends that
    /// carry more than 10 % over mid-length penalised; from K1 = 1, K2 = ½ and z_m = 5 Q/(π l E*).
    FujiwaraKawaseTuned,
}

/// The contact solver.
#[derive(Clone, Copy, Debug, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum SolverSpec {
    /// The QP (2.14) by clarabel.
    Qp,
    /// Kalker's active set with exact dense solves.
    ActiveSet,
    /// The penalty method.
    Penalty {
        /// Penalty parameter c \[MPa/mm\].
        c_mpa_per_mm: f64,
    },
    /// The augmented Lagrangian with Uzawa updates.
    AugmentedLagrangian {
        /// Penalty parameter c \[MPa/mm\].
        c_mpa_per_mm: f64,
        /// Relative pressure change at which Uzawa stops (default 1e-10).
        #[serde(default)]
        tolerance: Option<f64>,
        /// Largest number of Uzawa steps (default 2000).
        #[serde(default)]
        max_steps: Option<usize>,
    },
    /// Polonsky–Keer's constrained conjugate gradients through the bodies' operators (FFT
    /// products on half-space grids): no dense matrix, for large grids.
    PolonskyKeer {
        /// Relative tolerance (default 1e-12).
        #[serde(default)]
        tolerance: Option<f64>,
        /// Largest number of steps (default 10 000).
        #[serde(default)]
        max_steps: Option<usize>,
    },
}

/// The optimisation of the initial gap.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Optimise {
    /// How p_max is found.
    pub mode: ModeSpec,
    /// The controller v(x).
    pub controller: ControllerSpec,
    /// TOLH criterion (4.2) \[mm²\] (default the paper's 0.5e-6).
    #[serde(default = "tolh")]
    pub tolh_mm2: f64,
    /// Largest number of outer iterations (default 100).
    #[serde(default = "hundred")]
    pub max_iterations: usize,
    /// `load_split`: stop when each column's Ω_v pressure is within this fraction of p_max of
    /// v·p_max (default 1e-8).
    #[serde(default = "split_tolerance")]
    pub tolerance: f64,
    /// Ω_v as a region of the contact surface (the rest of the zone is Ω_nv); default: all of
    /// it (a roller: its centre row).
    #[serde(default)]
    pub omega_v: Option<OmegaVSpec>,
    /// Change the profile along this axis only (0, 1, 2; the roller's eq. 3.3); default: at
    /// the finite-element face nodes, or at every point.
    #[serde(default)]
    pub profile_axis: Option<usize>,
}

fn tolh() -> f64 {
    0.5e-6
}

fn hundred() -> usize {
    100
}

fn split_tolerance() -> f64 {
    1e-8
}

/// Ω_v, the part of the zone where the pressure is prescribed (d = 0, p = v·p_max; §3.1), as
/// a region of the contact surface; the zone's other points are Ω_nv. A point is placed by its
/// surface coordinates: its position less its component along its normal (a grid's (x, y); a
/// finite-element face's or a half-plane's x, or r, with the second coordinate 0).
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq)]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum OmegaVSpec {
    /// The points whose surface coordinate `axis` (0 or 1) lies in [from, to].
    Strip {
        /// The coordinate: 0 (x or r) or 1 (y).
        axis: usize,
        /// Lower end \[mm\].
        from_mm: f64,
        /// Upper end \[mm\].
        to_mm: f64,
    },
    /// The points within `radius_mm` of `centre_mm` on the surface.
    Disc {
        /// Centre (x, y) \[mm\].
        centre_mm: [f64; 2],
        /// Radius \[mm\].
        radius_mm: f64,
    },
    /// The points whose surface coordinates lie in [from, to] along both axes.
    Box {
        /// Lower corner (x, y) \[mm\].
        from_mm: [f64; 2],
        /// Upper corner (x, y) \[mm\].
        to_mm: [f64; 2],
    },
}

impl OmegaVSpec {
    /// Refuses a region that is not one: ends out of order, a radius not positive, an axis
    /// off the surface, a coordinate not finite.
    pub fn check(&self) -> Result<()> {
        let finite = |field: &str, v: f64| {
            if v.is_finite() {
                Ok(())
            } else {
                Err(Error::invalid(field, v, "must be finite"))
            }
        };
        let ordered = |field: &str, from: f64, to: f64| {
            finite(field, from)?;
            finite(field, to)?;
            if from <= to {
                Ok(())
            } else {
                Err(Error::invalid(
                    field,
                    to,
                    format!("must be at least from_mm = {from}"),
                ))
            }
        };
        match *self {
            OmegaVSpec::Strip {
                axis,
                from_mm,
                to_mm,
            } => {
                if axis > 1 {
                    return Err(Error::invalid(
                        "omega_v.axis",
                        axis,
                        "a surface coordinate: 0 (x or r) or 1 (y)",
                    ));
                }
                ordered("omega_v.to_mm", from_mm, to_mm)
            }
            OmegaVSpec::Disc {
                centre_mm,
                radius_mm,
            } => {
                centre_mm
                    .iter()
                    .try_for_each(|&c| finite("omega_v.centre_mm", c))?;
                if radius_mm > 0.0 && radius_mm.is_finite() {
                    Ok(())
                } else {
                    Err(Error::invalid(
                        "omega_v.radius_mm",
                        radius_mm,
                        "must be positive and finite",
                    ))
                }
            }
            OmegaVSpec::Box { from_mm, to_mm } => {
                (0..2).try_for_each(|k| ordered("omega_v.to_mm", from_mm[k], to_mm[k]))
            }
        }
    }

    /// Whether a point at `x` with unit normal `normal` lies in the region.
    pub fn contains(&self, x: [f64; 3], normal: [f64; 3]) -> bool {
        let along: f64 = (0..3).map(|k| x[k] * normal[k]).sum();
        let s: [f64; 3] = std::array::from_fn(|k| x[k] - along * normal[k]);
        let within = |v: f64, from: f64, to: f64| from <= v && v <= to;
        match *self {
            OmegaVSpec::Strip {
                axis,
                from_mm,
                to_mm,
            } => within(s[axis.min(1)], from_mm, to_mm),
            OmegaVSpec::Disc {
                centre_mm,
                radius_mm,
            } => (s[0] - centre_mm[0]).hypot(s[1] - centre_mm[1]).hypot(s[2]) <= radius_mm,
            OmegaVSpec::Box { from_mm, to_mm } => {
                (0..2).all(|k| within(s[k], from_mm[k], to_mm[k]))
            }
        }
    }
}

/// The optimisation modes.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum ModeSpec {
    /// The iteration of §3.2 with p_max from the floating body's equilibrium (Tables 1, 3).
    GivenLoad,
    /// The iteration of §3.2 with p_max from the contact pressure (Table 2).
    GivenDisplacement,
    /// The restricted linear programme (3.5) on the dense influence matrix (small problems).
    LinearProgramme,
    /// The optimum of (3.5) without a dense matrix: the load carried by each design column,
    /// one contact solve per update (given load; pointwise or extruded profiles).
    LoadSplit,
}

/// A controller v(x).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum ControllerSpec {
    /// v = level.
    Constant {
        /// The level, in (0, 1].
        level: f64,
    },
    /// 1 up to L1, falling linearly to 0 at L2, in the coordinate `axis` (absolute value).
    Trapezoid {
        /// L1 \[mm\].
        l1_mm: f64,
        /// L2 \[mm\].
        l2_mm: f64,
        /// The coordinate (default 0: r or x).
        #[serde(default)]
        axis: usize,
    },
    /// 1 up to L1, then 1 − 3s² + 2s³ to 0 at L2 (Tables 1–3).
    Cubic {
        /// L1 \[mm\].
        l1_mm: f64,
        /// L2 \[mm\].
        l2_mm: f64,
        /// The coordinate (default 0).
        #[serde(default)]
        axis: usize,
    },
    /// The product of two controllers, v(x1)·v(x2).
    Product {
        /// First factor.
        a: Box<ControllerSpec>,
        /// Second factor.
        b: Box<ControllerSpec>,
    },
}
