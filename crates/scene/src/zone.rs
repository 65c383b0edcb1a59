//! The contact zone Ω (`contact.zone`): where the bodies may touch and how finely, shared by
//! both bodies, so that their points pair one to one. A grid of cells on a half-space
//! surface, rings of an axisymmetric surface, strips of a plane one, the element faces of
//! finite-element bodies along r (or x), or the contact faces of imported meshes
//! ([`MeshSurface`]). Each kind is a type that implements [`ZoneKind`], registered by its name
//! in a [`crate::Registry`] ([`crate::Registry::with_zone`]).

use std::f64::consts::PI;
use std::sync::Arc;

use contopt_core::{check, Error, Interface, Result};
use contopt_fem::{Analysis, ElementKind, Spacing, MAX_AXIS_ELEMENTS};
use contopt_greens::{AxisymmetricHalfSpace, HalfPlane, HalfSpace};

use crate::chosen::Chosen;
use crate::mesh_surface::MeshSurface;
use serde::{Deserialize, Serialize};

/// The most rings or strips of a zone: their dense surface matrix grows with the square.
pub const MAX_LINE_CELLS: usize = 100_000;

/// What a zone kind says of itself: its layout with every size known, the analysis of the
/// bodies on it and what it says of a gap's surface coordinates. Its name is the one it is
/// registered under ([`crate::Registry::with_zone`]); a body that needs a particular zone asks
/// for it by type ([`crate::Chosen::downcast`]).
pub trait ZoneKind: Send + Sync {
    /// The zone with its sizes resolved; `natural` gives the cell size of a grid of so many
    /// cells that the gap spans by itself (for a grid without `cell_mm`); `surveyed` is a mesh
    /// zone's survey of its bodies' meshes ([`MeshSurface`]), which the caller makes first.
    fn layout(&self, natural: &Natural, surveyed: Option<MeshSurface>) -> Result<Layout>;

    /// The analysis of the bodies on it: `None` on a grid (3-D), axisymmetric on rings.
    fn analysis(&self) -> Option<Analysis>;

    /// What it says of a gap's surface coordinates: a grid without an analysis, else as its
    /// analysis.
    fn surface(&self) -> Surface {
        match self.analysis() {
            None => Surface::Grid,
            Some(Analysis::Axisymmetric) => Surface::Axisymmetric,
            Some(_) => Surface::Plane,
        }
    }
}

/// The cell size of a grid of so many cells that the gap spans by itself, if it does.
pub type Natural<'a> = dyn Fn([usize; 2]) -> Result<Option<[f64; 2]>> + 'a;

/// A zone of imported meshes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshZone {
    /// `"axisymmetric"` (x = r, y = z), `{ plane_stress = { thickness_mm } }` or
    /// `{ plane_strain = { thickness_mm } }`: the analysis of both bodies.
    pub analysis: Analysis,
    /// How far along its normal a point of the first body's contact faces looks for the
    /// second body's \[mm\] (default: half the smaller of the two contact groups' extents);
    /// a point that finds none cannot touch.
    #[serde(default)]
    pub search_mm: Option<f64>,
}

/// A grid zone.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridZone {
    /// Cells along x and y.
    pub cells: [usize; 2],
    /// Cell size along x and y \[mm\]; default: the gap's own extent over the cells (a
    /// roller's length, and ±`reach_b`·b to the outer cell centres across; 1.5 Hertz radii of
    /// a sphere both ways).
    #[serde(default)]
    pub cell_mm: Option<[f64; 2]>,
    /// The bodies' planes of symmetry through the axis, `["x"]` for the plane x = 0, `["x",
    /// "y"]` for both (default none): the grid then starts at the plane and covers x ≥ 0 (y ≥
    /// 0), a half or a quarter of the contact, which the bodies model with symmetry planes of
    /// their own (solids, with a measured gap); contact at the plane is no limit of the zone,
    /// and the forces and figures are the part's.
    #[serde(default)]
    pub symmetry: Vec<GridSymmetry>,
}

/// A plane of symmetry of a grid zone's bodies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GridSymmetry {
    /// The plane x = 0.
    X,
    /// The plane y = 0.
    Y,
}

/// A zone of rings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RingsZone {
    /// Number of rings (r = a·sin(πk/2n)).
    pub rings: usize,
    /// Outer radius a \[mm\].
    pub radius_mm: f64,
}

/// A zone of strips.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StripsZone {
    /// Number of strips (x = −a·cos(πk/n)).
    pub strips: usize,
    /// Half-width a \[mm\].
    pub half_width_mm: f64,
    /// `{ plane_stress = { thickness_mm } }` or `{ plane_strain = { thickness_mm } }`.
    pub analysis: Analysis,
}

/// A zone of finite-element faces.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FacesZone {
    /// `"axisymmetric"`, `{ plane_stress = { thickness_mm } }` or
    /// `{ plane_strain = { thickness_mm } }`: the analysis of both bodies (a plane model is the
    /// half x ≥ 0 of a body symmetric about x = 0).
    pub analysis: Analysis,
    /// The zone's radius (plane: half-width) \[mm\].
    pub radius_mm: f64,
    /// Quadratic elements across it.
    pub elements: usize,
    /// Size ratio innermost / outermost element (1, the default: uniform).
    #[serde(default = "FacesZone::uniform")]
    pub grading: f64,
    /// The element, `"q8"` (default) or `"q9"`.
    #[serde(default = "FacesZone::serendipity")]
    pub element: ElementKind,
}

impl FacesZone {
    fn uniform() -> f64 {
        1.0
    }

    fn serendipity() -> ElementKind {
        ElementKind::Q8
    }

    /// The element boundaries across the zone, after checking the counts and the grading; a
    /// grading whose element sizes f64 cannot hold across the radius (a ratio of 10³⁰⁰ over
    /// a few elements) is refused as the zone's `grading`, not as the spacing's coordinates.
    pub fn spacing(&self) -> Result<Spacing> {
        check::count("elements", self.elements, 1, MAX_AXIS_ELEMENTS)?;
        check::positive("grading", self.grading)?;
        check::positive("radius_mm", self.radius_mm)?;
        Spacing::geometric(0.0, self.radius_mm, self.elements, 1.0 / self.grading).map_err(|_| {
            Error::invalid(
                "grading",
                self.grading,
                format!(
                    "is a size ratio innermost / outermost that f64 cannot lay out over {} \
                     elements on {} mm (element boundaries coincide): use a milder one",
                    self.elements, self.radius_mm
                ),
            )
        })
    }

    /// The size of the outermost element, at the zone's rim \[mm\].
    pub fn edge_size(&self) -> Result<f64> {
        let s = self.spacing()?;
        let c = s.coords();
        Ok(c[c.len() - 1] - c[c.len() - 2])
    }
}

/// What a zone says of the surface coordinates a gap is given: on a grid (x, y), on an
/// axisymmetric line r = x, on a plane line x.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Surface {
    /// A 3-D grid: (x, y).
    Grid,
    /// An axisymmetric line: r = x.
    Axisymmetric,
    /// A plane line: x.
    Plane,
}

impl Surface {
    /// The distance of `x` from the gap's axis: √(x² + y²) on a grid, |x| on a line.
    pub fn radius(self, x: [f64; 3]) -> f64 {
        match self {
            Surface::Grid => x[0].hypot(x[1]),
            Surface::Axisymmetric | Surface::Plane => x[0].abs(),
        }
    }
}

/// A zone with every size known: a grid's cell size resolved from the gap when not given.
#[derive(Clone, Debug, PartialEq)]
pub enum Layout {
    /// `nx` × `ny` cells of `dx` × `dy`, the first cell's centre at `origin`; `symmetric`
    /// along x (y) when it starts at the bodies' plane of symmetry x = 0 (y = 0).
    Grid {
        nx: usize,
        ny: usize,
        dx: f64,
        dy: f64,
        origin: [f64; 2],
        symmetric: [bool; 2],
    },
    /// Ring radii from 0 to the rim.
    Rings(Vec<f64>),
    /// Strip edges from −a to a, in a plane body of `thickness`.
    Strips { edges: Vec<f64>, thickness: f64 },
    /// Finite-element faces.
    Faces(FacesZone),
    /// The contact faces of imported meshes, surveyed.
    Mesh(MeshSurface),
}

impl Layout {
    /// The surface of the body below, when the zone alone defines it (a grid, rings, strips);
    /// `None` for finite-element faces, whose body meshes them.
    pub fn surface(&self) -> Option<Result<Interface>> {
        Some(match self {
            Layout::Grid {
                nx,
                ny,
                dx,
                dy,
                origin,
                ..
            } => HalfSpace::cells_interface(*nx, *ny, *dx, *dy, *origin),
            Layout::Rings(edges) => AxisymmetricHalfSpace::rings_interface(edges),
            Layout::Strips { edges, thickness } => HalfPlane::strips_interface(edges, *thickness),
            Layout::Faces(_) | Layout::Mesh(_) => return None,
        })
    }

    /// The number of interface points, `None` when it overflows (a finite-element face
    /// holds three Gauss points; imported meshes, as surveyed).
    pub fn points(&self) -> Option<usize> {
        match self {
            Layout::Grid { nx, ny, .. } => nx.checked_mul(*ny),
            Layout::Rings(edges) | Layout::Strips { edges, .. } => {
                Some(edges.len().saturating_sub(1))
            }
            Layout::Faces(f) => f.elements.checked_mul(3),
            Layout::Mesh(m) => Some(m.points.len()),
        }
    }

    /// How far the zone reaches from its centre along each surface axis \[mm\] (x or r, y);
    /// a grid that starts at a plane of symmetry, from the plane.
    pub fn half_extent(&self) -> [f64; 2] {
        match self {
            Layout::Grid {
                nx,
                ny,
                dx,
                dy,
                symmetric,
                ..
            } => {
                let reach = |n: usize, d: f64, from_plane: bool| match from_plane {
                    true => n as f64 * d,
                    false => 0.5 * n as f64 * d,
                };
                [reach(*nx, *dx, symmetric[0]), reach(*ny, *dy, symmetric[1])]
            }
            Layout::Rings(edges) => [edges.last().copied().unwrap_or(0.0), 0.0],
            Layout::Strips { edges, .. } => [edges.last().copied().unwrap_or(0.0), 0.0],
            Layout::Faces(f) => [f.radius_mm, 0.0],
            Layout::Mesh(m) => m.half_extent,
        }
    }

    /// The size of a cell at the zone's edge along each surface axis \[mm\] (0 along an axis
    /// the zone does not extend in).
    pub fn edge_cell(&self) -> [f64; 2] {
        let last = |e: &[f64]| e[e.len() - 1] - e[e.len() - 2];
        match self {
            Layout::Grid { dx, dy, .. } => [*dx, *dy],
            Layout::Rings(edges) | Layout::Strips { edges, .. } => [last(edges), 0.0],
            Layout::Faces(f) => [f.edge_size().unwrap_or(f.radius_mm), 0.0],
            Layout::Mesh(m) => [m.cell, m.cell],
        }
    }

    /// The length a line load spreads over \[mm\]: a grid's length along x, a strips zone's
    /// thickness, and half the thickness of a plane faces zone, whose bodies are the half x ≥ 0
    /// of bodies symmetric about x = 0: a force on the half is half the whole contact's, so the
    /// whole line load is 2F/t. `None` elsewhere, and on a mesh zone, whose meshes may be whole
    /// or halves (nothing says which).
    pub fn line_length(&self) -> Option<f64> {
        match self {
            Layout::Grid { nx, dx, .. } => Some(*nx as f64 * dx),
            Layout::Strips { thickness, .. } => Some(*thickness),
            Layout::Faces(_) => self.thickness().map(|t| 0.5 * t),
            Layout::Mesh(_) | Layout::Rings(_) => None,
        }
    }

    /// The thickness of a plane zone (strips, plane faces or meshes) \[mm\].
    pub fn thickness(&self) -> Option<f64> {
        let of = |a: Analysis| match a {
            Analysis::PlaneStress { thickness } | Analysis::PlaneStrain { thickness } => {
                Some(thickness)
            }
            Analysis::Axisymmetric => None,
        };
        match self {
            Layout::Strips { thickness, .. } => Some(*thickness),
            Layout::Faces(f) => of(f.analysis),
            Layout::Mesh(m) => of(m.analysis),
            Layout::Grid { .. } | Layout::Rings(_) => None,
        }
    }

    /// Whether the zone starts at the bodies' plane of symmetry x = 0, y = 0 (a grid's
    /// `symmetry`): contact there is no limit of the zone.
    pub fn symmetric(&self) -> [bool; 2] {
        match self {
            Layout::Grid { symmetric, .. } => *symmetric,
            _ => [false; 2],
        }
    }

    /// The zone as a grid, when it is one.
    pub fn grid(&self) -> Option<(usize, usize, f64, f64, [f64; 2])> {
        match *self {
            Layout::Grid {
                nx,
                ny,
                dx,
                dy,
                origin,
                ..
            } => Some((nx, ny, dx, dy, origin)),
            _ => None,
        }
    }
}

impl ZoneKind for GridZone {
    /// The cell size given, or the gap's own extent over the cells.
    fn layout(&self, natural: &Natural, _surveyed: Option<MeshSurface>) -> Result<Layout> {
        let [nx, ny] = self.cells;
        check::count("cells[0]", nx, 1, usize::MAX)?;
        check::count("cells[1]", ny, 1, usize::MAX)?;
        let cell = match self.cell_mm {
            Some([dx, dy]) => [
                check::positive("cell_mm[0]", dx)?,
                check::positive("cell_mm[1]", dy)?,
            ],
            None => natural([nx, ny])?.ok_or_else(|| {
                Error::invalid(
                    "cell_mm",
                    "missing",
                    "give the cell size: this gap has no extent of its own to span",
                )
            })?,
        };
        let symmetric = [GridSymmetry::X, GridSymmetry::Y].map(|p| self.symmetry.contains(&p));
        let first = |n: usize, d: f64, from_plane: bool| match from_plane {
            true => 0.5 * d,
            false => -0.5 * (n as f64 - 1.0) * d,
        };
        Ok(Layout::Grid {
            nx,
            ny,
            dx: cell[0],
            dy: cell[1],
            origin: [
                first(nx, cell[0], symmetric[0]),
                first(ny, cell[1], symmetric[1]),
            ],
            symmetric,
        })
    }

    /// A 3-D grid.
    fn analysis(&self) -> Option<Analysis> {
        None
    }
}

impl ZoneKind for RingsZone {
    /// `rings` + 1 radii a·sin(πk/2n), narrowing towards the rim.
    fn layout(&self, _natural: &Natural, _surveyed: Option<MeshSurface>) -> Result<Layout> {
        check::positive("radius_mm", self.radius_mm)?;
        let count = check::count("rings", self.rings, 1, MAX_LINE_CELLS)?;
        Ok(Layout::Rings(clustered(
            count,
            self.radius_mm,
            |t| t.sin(),
            0.5,
        )))
    }

    fn analysis(&self) -> Option<Analysis> {
        Some(Analysis::Axisymmetric)
    }
}

impl ZoneKind for StripsZone {
    /// `strips` + 1 edges −a·cos(πk/n), narrowing towards both ends.
    fn layout(&self, _natural: &Natural, _surveyed: Option<MeshSurface>) -> Result<Layout> {
        check::positive("half_width_mm", self.half_width_mm)?;
        let count = check::count("strips", self.strips, 1, MAX_LINE_CELLS)?;
        let thickness = plane_thickness(&self.analysis)?;
        Ok(Layout::Strips {
            edges: clustered(count, self.half_width_mm, |t| -t.cos(), 1.0),
            thickness,
        })
    }

    fn analysis(&self) -> Option<Analysis> {
        Some(self.analysis)
    }

    /// A plane line, whatever its analysis says (an axisymmetric one is refused by the
    /// layout).
    fn surface(&self) -> Surface {
        Surface::Plane
    }
}

impl ZoneKind for FacesZone {
    /// The faces themselves, their spacing and analysis checked.
    fn layout(&self, _natural: &Natural, _surveyed: Option<MeshSurface>) -> Result<Layout> {
        self.spacing()?;
        check_analysis(&self.analysis)?;
        Ok(Layout::Faces(self.clone()))
    }

    fn analysis(&self) -> Option<Analysis> {
        Some(self.analysis)
    }
}

impl ZoneKind for MeshZone {
    /// The survey of its bodies' meshes, which it needs.
    fn layout(&self, _natural: &Natural, surveyed: Option<MeshSurface>) -> Result<Layout> {
        check_analysis(&self.analysis)?;
        Ok(Layout::Mesh(surveyed.ok_or_else(|| {
            Error::invalid(
                "kind",
                "mesh",
                "a zone of imported meshes is laid out from its bodies' meshes: give an \
                 fe_mesh body",
            )
        })?))
    }

    fn analysis(&self) -> Option<Analysis> {
        Some(self.analysis)
    }
}

/// `count` + 1 edges a·f(π k / (2 count) · span), narrowing towards the rim.
fn clustered(count: usize, size: f64, f: impl Fn(f64) -> f64, span: f64) -> Vec<f64> {
    (0..=count)
        .map(|k| size * f(PI * span * k as f64 / count as f64))
        .collect()
}

/// The thickness of a plane analysis; an axisymmetric one is refused for strips.
fn plane_thickness(analysis: &Analysis) -> Result<f64> {
    match *analysis {
        Analysis::PlaneStress { thickness } | Analysis::PlaneStrain { thickness } => {
            check::positive("analysis.thickness_mm", thickness)
        }
        Analysis::Axisymmetric => Err(Error::invalid(
            "analysis",
            "axisymmetric",
            "strips lie in a plane: plane_stress or plane_strain (rings are the axisymmetric \
             zone)",
        )),
    }
}

/// An analysis whose thickness, if it has one, is positive and finite.
fn check_analysis(analysis: &Analysis) -> Result<()> {
    match analysis {
        Analysis::Axisymmetric => Ok(()),
        _ => plane_thickness(analysis).map(|_| ()),
    }
}

/// The zone of a `[contact]` before the registry has read it (serde's placeholder, replaced by
/// [`crate::CaseSpec::read`]): a grid of no cells, which no layout accepts.
pub(crate) fn unread() -> Chosen<dyn ZoneKind> {
    let grid = Arc::new(GridZone {
        cells: [0, 0],
        cell_mm: None,
        symmetry: vec![],
    });
    Chosen::new("none", serde_json::Value::Null, grid.clone(), grid)
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use contopt_input::{InputError, Node};

    use super::*;
    use crate::{Format, Registry};

    /// The zone of `text`'s `zone` key, read by `registry` at `contact.zone`.
    fn read_zone(
        registry: &Registry,
        text: &str,
    ) -> std::result::Result<Chosen<dyn ZoneKind>, InputError> {
        let node = Node::parse_toml(text).unwrap();
        registry.zone(node.get("zone").unwrap(), "contact.zone")
    }

    #[test]
    fn spellings_read_alike() {
        let standard = Registry::standard();
        let read = |text| read_zone(&standard, text).unwrap();
        let a = read("zone = { kind = \"rings\", rings = 4, radius_mm = 1.0 }");
        let b = read("zone = { rings = { rings = 4, radius_mm = 1.0 } }");
        assert_eq!(a, b);
        assert_eq!(a.name(), "rings");
        assert_eq!(
            a.written(),
            &serde_json::json!({ "rings": { "rings": 4, "radius_mm": 1.0 } })
        );
        let rings = RingsZone {
            rings: 4,
            radius_mm: 1.0,
        };
        assert_eq!(b.downcast::<RingsZone>(), Some(&rings));
        assert_eq!(b.surface(), Surface::Axisymmetric);
        let grid = read("zone = { kind = \"grid\", cells = [3, 5], cell_mm = [0.1, 0.2] }");
        assert_eq!(
            grid,
            read("zone.grid = { cells = [3, 5], cell_mm = [0.1, 0.2] }")
        );
        assert_eq!(grid.surface(), Surface::Grid);
    }

    #[test]
    fn an_unknown_zone_kind_lists_the_registered_ones() {
        let text = "zone = { kind = \"hexagons\", cells = 7 }";
        let e = read_zone(&Registry::standard(), text).unwrap_err();
        assert_eq!(e.path, "contact.zone.kind");
        assert_eq!(
            e.message,
            "unknown variant `hexagons`, expected one of `grid`, `rings`, `strips`, `faces`, \
             `mesh`"
        );
        let names: Vec<_> = Registry::standard().zone_kinds().collect();
        assert_eq!(names, ["grid", "rings", "strips", "faces", "mesh"]);
    }

    /// A zone of one's own: `strips` equal strips across −a…a of a plane body.
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct EvenStrips {
        strips: usize,
        half_width_mm: f64,
        analysis: Analysis,
    }

    impl ZoneKind for EvenStrips {
        fn layout(&self, _natural: &Natural, _surveyed: Option<MeshSurface>) -> Result<Layout> {
            let n = check::count("strips", self.strips, 1, MAX_LINE_CELLS)?;
            let a = check::positive("half_width_mm", self.half_width_mm)?;
            Ok(Layout::Strips {
                edges: (0..=n)
                    .map(|k| a * (2.0 * k as f64 / n as f64 - 1.0))
                    .collect(),
                thickness: plane_thickness(&self.analysis)?,
            })
        }

        fn analysis(&self) -> Option<Analysis> {
            Some(self.analysis)
        }
    }

    /// A rigid flat punch as wide as the zone (its rim the zone's edge) pressed by F into a
    /// Winkler bed of modulus k: p = k·δ uniform, F = p·2a·t.
    #[test]
    fn a_zone_of_ones_own_is_read_and_carries_the_contact() {
        let (k, force, a, t) = (50.0, 600.0, 2.0, 3.0);
        let text = format!(
            "name = \"even\"\n\
             [contact]\n\
             zone = {{ kind = \"even_strips\", strips = 10, half_width_mm = {a}, \
             analysis = {{ plane_strain = {{ thickness_mm = {t} }} }} }}\n\
             gap = {{ flat_punch = {{ radius_mm = {a} }} }}\n\
             load = {{ force_n = {force} }}\n\
             [[body]]\n\
             kind = \"winkler\"\n\
             modulus_mpa_per_mm = {k}\n\
             [[body]]\n\
             kind = \"rigid\"\n"
        );
        let registry = Registry::standard().with_zone::<EvenStrips>("even_strips");
        let scene = registry
            .parse(&text, Format::Toml, Path::new("even.toml"))
            .unwrap();
        let case = &scene.cases()[0];
        assert_eq!(case.spec.contact.zone.name(), "even_strips");
        let report = case.run().unwrap();
        assert!(report.is_solved(), "{:?}", report.termination);
        let p = force / (2.0 * a * t);
        assert_eq!(report.interface.len(), 10);
        for q in &report.interface {
            assert!((q.p_mpa - p).abs() < 1e-9 * p, "{} against {p}", q.p_mpa);
        }
        let delta_um = report.approach_um.unwrap();
        assert!(
            (delta_um - 1e3 * p / k).abs() < 1e-9 * delta_um,
            "δ = {delta_um} µm"
        );
        let unknown = Registry::standard().parse(&text, Format::Toml, Path::new("even.toml"));
        assert!(unknown
            .unwrap_err()
            .to_string()
            .contains("unknown variant `even_strips`"));
    }
}
