//! A half-space grid whose surface ends at free faces across its x axis: a roller's ends, by
//! the image (mirror) pressure.
//!
//! Near a free face the half-space misjudges the surface: the material beyond the face that
//! the half-space assumes is not there to carry the load, and the surface sinks further. The
//! classical correction superposes half-spaces (M. Hetényi, *A general solution for the
//! elastic quarter space*, J. Appl. Mech. 37 (1970) 70–76): the pressure p on x < x_f and its
//! image p(2x_f − x, y) beyond the face load one half-space; by symmetry the plane x = x_f
//! then carries no shear and does not move along x. That is the exact quarter-space whose end
//! face slides without friction against a rigid wall; the free face also carries the image's
//! normal stress σ_xx, which Hetényi removes by further superposed half-spaces
//! ([`crate::hetenyi_load`]). J. B. de Mul, J. J. Kalker and B. Fredriksson (*The contact
//! between arbitrarily curved bodies of finite dimensions*, J. Tribol. 108 (1986) 140–148) use
//! the image alone for finite bodies in contact; R. Guilbault (*A fast correction for elastic
//! quarter-space applied to 3D modeling of edge contact problems*, J. Tribol. 133 (2011)
//! 031402) weights the image by a correction factor. Here the image carries a weight w:
//! u = C·(p + w·M p), C Love's half-space operator, M the reflection about each face (the two
//! faces' images are taken apart: the reflection of one image in the other face, a roller's
//! length away, is left out). With w = 1 it is the sliding end; the weight that matches
//! Hetényi's free face is measured in [`crate::hetenyi_load`]'s tests.
//!
//! The images lie on the grid's own lattice when each face is a whole number of half-cells
//! beyond the grid's edge: a face is moved to the nearest such place (at most a quarter of a
//! cell; [`FreeEnds::faces`] says where it is). Love's kernel is even, so the product of the
//! image is the reflection of the own pressure's product, C·M p = M·C p: the product is one
//! FFT convolution of the own pressure alone, read beyond the grid as far as the images reach
//! (a padded length of about 2(2nx + m) cells for faces m half-cells out, where the
//! pressure and its images written out on one long grid took 2(3nx + 2m)), and each cell
//! adds its images' values.

use contopt_core::{
    check, ElasticBody, Error, Interface, Material, Result, RigidMode, Subsurface,
    SubsurfaceRequest,
};

use crate::fft::Convolution;
use crate::subsurface::Images;
use crate::HalfSpace;
use contopt_core::{InfluenceShape, Spares};

/// A half-space grid ending at free faces x = x₋ below its first column and x = x₊ beyond its
/// last, each loaded by the image pressure with a weight (see the module's account).
#[derive(Debug)]
pub struct FreeEnds {
    /// The grid itself: its points, modes and name.
    own: HalfSpace,
    /// The own grid's product read `reach` columns beyond it each side, as far as the images
    /// lie (own column i at column `reach + i` of a row).
    wide: Convolution,
    reach: usize,
    /// The column of a `wide` row holding own column 0's image about each face; own column
    /// i's is `mirror − i`.
    mirrors: Vec<usize>,
    /// The faces as placed \[mm\]: below, beyond.
    faces: [Option<f64>; 2],
    weight: f64,
    /// Work: a `wide` product, one per product running at once.
    work: Spares<Vec<f64>>,
}

/// The whole number of half-cells `dx/2` from a grid's edge to a face `distance` \[mm\] away
/// (≥ 0).
fn half_cells(distance: f64, dx: f64, field: &str) -> Result<usize> {
    let m = (2.0 * distance / dx).round();
    if !(m >= 0.0 && m.is_finite() && m < 1e9) {
        return Err(Error::invalid(
            field,
            distance,
            "a free face lies at or beyond the grid's edge, within a billion cells",
        ));
    }
    Ok(m as usize)
}

impl FreeEnds {
    /// The grid of [`HalfSpace::grid`] (`nx` × `ny` cells of `dx` × `dy`, first centre at
    /// `origin`) ending at free faces x = `faces`\[0\] (at or below the grid's first edge)
    /// and x = `faces`\[1\] (at or beyond its last), either left out (`None`: the surface goes
    /// on), whose images carry `weight` ∈ \[0, 2\] (1: the sliding end; 0: the half-space).
    #[allow(clippy::too_many_arguments)]
    pub fn grid(
        name: impl Into<String>,
        material: Material,
        nx: usize,
        ny: usize,
        dx: f64,
        dy: f64,
        origin: [f64; 2],
        faces: [Option<f64>; 2],
        weight: f64,
    ) -> Result<Self> {
        let own = HalfSpace::grid(name, material, nx, ny, dx, dy, origin)?;
        Self::around(own, faces, weight)
    }

    /// The free faces and images of [`FreeEnds::grid`] around the grid `own` as it is (its
    /// load and side kept).
    fn around(own: HalfSpace, faces: [Option<f64>; 2], weight: f64) -> Result<Self> {
        check::between(
            "free_ends.weight",
            weight,
            -f64::EPSILON,
            2.0 + f64::EPSILON,
        )?;
        let ((nx, ny), dx) = (own.cells(), own.dx);
        let first = own.interface().points()[0][0];
        let (lo, hi) = (first - 0.5 * dx, first + (nx as f64 - 0.5) * dx);
        let below = faces[0]
            .map(|f| {
                half_cells(
                    lo - check::finite("free_ends.faces[0]", f)?,
                    dx,
                    "free_ends.faces[0]",
                )
            })
            .transpose()?;
        let beyond = faces[1]
            .map(|f| {
                half_cells(
                    check::finite("free_ends.faces[1]", f)? - hi,
                    dx,
                    "free_ends.faces[1]",
                )
            })
            .transpose()?;
        let placed = [
            below.map(|m| lo - m as f64 * 0.5 * dx),
            beyond.map(|m| hi + m as f64 * 0.5 * dx),
        ];
        // Own column i lies at lattice index i; its image about the lower face at
        // −m₋ − 1 − i, about the upper at 2nx + m₊ − 1 − i: at most m + nx columns beyond the
        // grid's edge.
        let reach = [below, beyond].into_iter().flatten().map(|m| m + nx).max();
        let reach = reach.unwrap_or(0);
        let mirrors = [
            below.map(|m| reach - m - 1),
            beyond.map(|m| reach + 2 * nx + m - 1),
        ]
        .into_iter()
        .flatten()
        .collect();
        let wide = own.wide_convolution(reach)?;
        Ok(Self {
            own,
            wide,
            reach,
            mirrors,
            faces: placed,
            weight,
            work: Spares::new(vec![0.0; (nx + 2 * reach) * ny]),
        })
    }

    /// The memory of an `nx` × `ny` grid with its images \[bytes\]: its own grid's and, for the
    /// product read beyond it (kernel, spectrum and buffers), a grid's five times as long (an
    /// upper bound); `None` when the count overflows.
    pub fn grid_bytes(nx: usize, ny: usize) -> Option<u64> {
        let own = HalfSpace::grid_bytes(nx, ny)?;
        let wide = HalfSpace::grid_bytes(nx.checked_mul(5)?, ny)?;
        own.checked_add(wide)
    }

    /// The faces as placed on the lattice \[mm\]: below the first column, beyond the last.
    pub fn faces(&self) -> [Option<f64>; 2] {
        self.faces
    }

    /// The images' weight.
    pub fn weight(&self) -> f64 {
        self.weight
    }

    /// The same grid as the surface of the body above the plane ([`HalfSpace::upper`]).
    pub fn upper(mut self) -> Self {
        self.own = self.own.upper();
        self
    }

    /// The body pressed by `force` \[N\] ([`HalfSpace::pressed`]).
    pub fn pressed(mut self, force: f64) -> Result<Self> {
        self.own = self.own.pressed(force)?;
        Ok(self)
    }
}

impl ElasticBody for FreeEnds {
    fn name(&self) -> &str {
        self.own.name()
    }

    fn interface(&self) -> &Interface {
        self.own.interface()
    }

    /// u = C·(p + w·M p) = C p + w·M(C p): the own pressure's product read at each cell and,
    /// weighted, at its images.
    fn apply_influence(&self, force: &[f64], displacement: &mut [f64]) {
        self.apply_influence_adding(force, 0.0, displacement);
    }

    /// The own grid's half-space ([`HalfSpace`]'s shape and scale (1 − ν²)/E): a raceway on
    /// the same grid adds its product to this one's.
    fn base_shape(&self) -> Option<(InfluenceShape, f64)> {
        self.own.influence_shape()
    }

    /// u = C p + w·M(C p) + added·C₀ p = (1 + added/c)·C p + w·M(C p), C = c·C₀ the own grid's
    /// operator: a partner on the grid costs no product of its own.
    fn apply_influence_adding(&self, force: &[f64], added: f64, displacement: &mut [f64]) {
        let (nx, ny) = self.own.cells();
        let width = nx + 2 * self.reach;
        let own = 1.0 + added / self.own.compliance;
        self.work.with(
            || vec![0.0; width * ny],
            |wide| {
                self.wide.apply(force, wide);
                let rows = wide
                    .chunks_exact(width)
                    .zip(displacement.chunks_exact_mut(nx));
                for (row, out) in rows {
                    for (i, d) in out.iter_mut().enumerate() {
                        let images: f64 = self.mirrors.iter().map(|&m| row[m - i]).sum();
                        *d = own * row[self.reach + i] + self.weight * images;
                    }
                }
            },
        );
    }

    /// The half-space's circulant inverse: the images change the operator near the faces
    /// only, which a preconditioner may ignore.
    fn precondition(&self, displacement: &[f64], force: &mut [f64]) -> bool {
        self.own.precondition(displacement, force)
    }

    fn load_displacement(&self) -> Result<Vec<f64>> {
        self.own.load_displacement()
    }

    fn rigid_modes(&self) -> &[RigidMode] {
        self.own.rigid_modes()
    }

    /// The own grid coarsened as a half-space grid's ([`HalfSpace`]'s: cells twice as large
    /// each way), ending at the same faces (each moved to the coarse lattice, at most a quarter
    /// of a coarse cell) with images of the same weight: the nested start of a solver.
    fn coarsen(&self) -> Option<(Box<dyn ElasticBody>, Vec<usize>)> {
        let (own, parent) = self.own.coarse_grid()?;
        let coarse = FreeEnds::around(own, self.faces, self.weight).ok()?;
        Some((Box::new(coarse), parent))
    }

    /// The stresses of the image model, σ(p + w·M p) = σ(p) + w·M σ(p) (each component with
    /// its parity in x), from the own pressure's fields read beyond the grid, one transform of
    /// the pressure for every depth.
    fn subsurface(
        &self,
        pressure: &[f64],
        request: &SubsurfaceRequest,
    ) -> Result<Option<Subsurface>> {
        let images = Images {
            reach: self.reach,
            mirrors: &self.mirrors,
            weight: self.weight,
        };
        self.own
            .stresses_imaged(pressure, request, &images)
            .map(Some)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steel() -> Material {
        Material::new(2.1e5, 0.3).unwrap()
    }

    /// A steel grid of `nx` × `ny` cells of `cell` from `origin` with end faces `faces` and
    /// image weight `weight`.
    fn steel_ends(
        nx: usize,
        ny: usize,
        cell: [f64; 2],
        origin: [f64; 2],
        faces: [Option<f64>; 2],
        weight: f64,
    ) -> FreeEnds {
        FreeEnds::grid(
            "f",
            steel(),
            nx,
            ny,
            cell[0],
            cell[1],
            origin,
            faces,
            weight,
        )
        .unwrap()
    }

    fn pressure(n: usize) -> Vec<f64> {
        (0..n)
            .map(|k| 1.0 + ((k * 37 % 101) as f64).sin())
            .collect()
    }

    /// Weight 0 is the half-space; the operator is symmetric (reciprocity) for any weight;
    /// with weight 1 and a face at the grid's edge, each image column is the reflected one:
    /// the product equals the half-space's product of the reflected extension, written out
    /// here on a grid three times as long.
    #[test]
    fn images_are_reflections() {
        let (nx, ny, dx, dy) = (9, 5, 0.1, 0.07);
        let origin = [-0.4, -0.14];
        let (lo, hi) = (-0.45, 0.45);
        let p = pressure(nx * ny);
        let plain = HalfSpace::grid("h", steel(), nx, ny, dx, dy, origin).unwrap();
        let mut want = vec![0.0; nx * ny];
        plain.apply_influence(&p, &mut want);
        let none = steel_ends(nx, ny, [dx, dy], origin, [Some(lo), Some(hi)], 0.0);
        let mut got = vec![0.0; nx * ny];
        none.apply_influence(&p, &mut got);
        for (a, b) in got.iter().zip(&want) {
            assert!((a - b).abs() < 1e-12 * want[0].abs(), "{a} vs {b}");
        }
        let ends = steel_ends(nx, ny, [dx, dy], origin, [Some(lo), Some(hi)], 1.0);
        for (got, want) in ends.faces().into_iter().zip([lo, hi]) {
            assert!((got.unwrap() - want).abs() < 1e-12 * want.abs());
        }
        let long = HalfSpace::grid(
            "l",
            steel(),
            3 * nx,
            ny,
            dx,
            dy,
            [origin[0] - 0.9, origin[1]],
        )
        .unwrap();
        let mut ext = vec![0.0; 3 * nx * ny];
        for j in 0..ny {
            for i in 0..nx {
                let v = p[j * nx + i];
                ext[j * 3 * nx + nx + i] = v;
                ext[j * 3 * nx + nx - 1 - i] = v;
                ext[j * 3 * nx + 3 * nx - 1 - i] = v;
            }
        }
        let mut out = vec![0.0; 3 * nx * ny];
        long.apply_influence(&ext, &mut out);
        ends.apply_influence(&p, &mut got);
        for j in 0..ny {
            for i in 0..nx {
                let (a, b) = (got[j * nx + i], out[j * 3 * nx + nx + i]);
                assert!((a - b).abs() < 1e-12 * b.abs(), "{i} {j}: {a} vs {b}");
            }
        }
        let half = steel_ends(nx, ny, [dx, dy], origin, [None, Some(0.53)], 0.7);
        assert!(
            (half.faces()[1].unwrap() - 0.55).abs() < 1e-12,
            "{:?}",
            half.faces()
        );
        let a = half.influence_matrix();
        for i in 0..nx * ny {
            for j in 0..i {
                assert!((a[(i, j)] - a[(j, i)]).abs() < 1e-12 * a[(0, 0)], "{i} {j}");
            }
        }
    }

    /// The pressure and its weighted images written out on a grid `reach` columns wider each
    /// side, as the product and the stresses were computed before they were read beyond the
    /// grid: that grid, the written-out pressure, and each own cell's index on it.
    fn written_out(ends: &FreeEnds, p: &[f64]) -> (HalfSpace, Vec<f64>, Vec<usize>) {
        let ((nx, ny), r, (dx, dy)) = (ends.own.cells(), ends.reach, (ends.own.dx, ends.own.dy));
        let width = nx + 2 * r;
        let first = ends.own.interface().points()[0];
        let origin = [first[0] - r as f64 * dx, first[1]];
        let long = HalfSpace::grid("long", steel(), width, ny, dx, dy, origin).unwrap();
        let (mut ext, mut index) = (vec![0.0; width * ny], vec![0; nx * ny]);
        for j in 0..ny {
            for i in 0..nx {
                let (k, row) = (j * nx + i, j * width);
                index[k] = row + r + i;
                ext[row + r + i] += p[k];
                for &m in &ends.mirrors {
                    ext[row + m - i] += ends.weight * p[k];
                }
            }
        }
        (long, ext, index)
    }

    /// The rows and the cell (dx, dy) \[mm\] of the grids of [`variety`].
    const VARIETY_CELLS: (usize, f64, f64) = (7, 0.12, 0.03);

    /// One grid of [`variety`]: its width, faces and first cell's centre, the body and a
    /// pressure on it.
    struct Variant {
        nx: usize,
        faces: [Option<f64>; 2],
        origin: [f64; 2],
        ends: FreeEnds,
        p: Vec<f64>,
    }

    /// Free ends of two faces, one either side, none, on odd, FFT-unfriendly widths, on
    /// [`VARIETY_CELLS`].
    fn variety() -> Vec<Variant> {
        let (ny, dx, dy) = VARIETY_CELLS;
        [
            (41, [Some(-2.6), Some(2.55)], 1.0),
            (20, [None, Some(1.3)], 1.4),
            (23, [Some(-1.5), None], 0.6),
            (16, [None, None], 1.0),
        ]
        .into_iter()
        .map(|(nx, faces, weight)| {
            let origin = [-0.5 * (nx - 1) as f64 * dx, -0.09];
            Variant {
                nx,
                faces,
                origin,
                ends: steel_ends(nx, ny, [dx, dy], origin, faces, weight),
                p: pressure(nx * ny),
            }
        })
        .collect()
    }

    /// The product read beyond the grid (C p + w·M C p) is the product of the pressure and its
    /// weighted images written out on a longer grid (C (p + w·M p), as it was computed
    /// before), to round-off of the largest value: an image column one off is a change of a
    /// few per cent at the ends.
    #[test]
    fn wide_product_equals_the_written_out_one() {
        let ny = VARIETY_CELLS.0;
        for Variant {
            nx, faces, ends, p, ..
        } in variety()
        {
            let mut got = vec![0.0; nx * ny];
            ends.apply_influence(&p, &mut got);
            let (long, ext, index) = written_out(&ends, &p);
            let mut out = vec![0.0; ext.len()];
            long.apply_influence(&ext, &mut out);
            let scale = out.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (k, a) in got.iter().enumerate() {
                let b = out[index[k]];
                assert!(
                    (a - b).abs() < 1e-12 * scale,
                    "{nx} {faces:?}, cell {k}: {a} vs {b}"
                );
            }
        }
    }

    /// The stresses read beyond the grid (σ(p) + w·M σ(p), each component with its parity in
    /// x) are the stresses of the pressure and its images written out on a longer grid, to
    /// round-off of the largest stress, along a row and along the end column at two depths: a
    /// shear component of the wrong parity is off by its image's share at the end.
    #[test]
    fn wide_stresses_equal_the_written_out_ones() {
        let (ny, _, dy) = VARIETY_CELLS;
        for Variant {
            nx,
            faces,
            origin,
            ends,
            p,
        } in variety()
        {
            let request = SubsurfaceRequest {
                depths: vec![0.02, 0.1],
                sections: vec![
                    contopt_core::Section {
                        axis: contopt_core::SectionAxis::X,
                        at: origin[1] + 4.0 * dy,
                    },
                    contopt_core::Section {
                        axis: contopt_core::SectionAxis::Y,
                        at: origin[0],
                    },
                ],
            };
            let sub = ends.subsurface(&p, &request).unwrap().unwrap();
            let (long, ext, index) = written_out(&ends, &p);
            let cells = [
                (0..nx).map(|i| 4 * nx + i).collect::<Vec<_>>(),
                (0..ny).map(|j| j * nx).collect(),
            ];
            for (section, cells) in sub.sections.iter().zip(&cells) {
                for (d, &z) in request.depths.iter().enumerate() {
                    let want = long.stress_field(&ext, z).unwrap();
                    let scale = want.iter().fold(0.0f64, |m, s| {
                        [s.xx, s.yy, s.zz, s.xy, s.xz, s.yz]
                            .iter()
                            .fold(m, |m, v| m.max(v.abs()))
                    });
                    for (c, &k) in cells.iter().enumerate() {
                        let (a, b) = (section.tensors[d * cells.len() + c], want[index[k]]);
                        let pairs = [
                            (a.xx, b.xx),
                            (a.yy, b.yy),
                            (a.zz, b.zz),
                            (a.xy, b.xy),
                            (a.xz, b.xz),
                            (a.yz, b.yz),
                        ];
                        for (u, v) in pairs {
                            assert!(
                                (u - v).abs() < 1e-12 * scale,
                                "{nx} {faces:?}, z {z}, cell {k}: {a:?} vs {b:?}"
                            );
                        }
                    }
                }
            }
        }
    }

    /// Coarsened, the grid keeps its faces (within a quarter of a coarse cell), its images'
    /// weight, load and normal: under a uniform pressure the coarse end cells sink as the mean
    /// of their fine children to 1 % (0.1 % measured), and their images' share of it (the
    /// sinking beyond a plain coarse half-space's, 38 % of it) is the fine grid's to 5 % (2 %
    /// measured; a coarse grid without images, or with its faces a cell off, fails).
    #[test]
    fn coarsen_keeps_the_faces() {
        let (nx, ny, dx, dy) = (40, 10, 0.1, 0.02);
        let origin = [-1.95, -0.09];
        let fine = steel_ends(nx, ny, [dx, dy], origin, [Some(-2.0), Some(2.0)], 1.0)
            .pressed(30.0)
            .unwrap()
            .upper();
        let (coarse, parent) = fine.coarsen().unwrap();
        let plain = fine.own.coarse_grid().unwrap().0;
        let m = coarse.interface().len();
        assert_eq!(m, 20 * 5);
        assert_eq!(
            coarse.interface().weights()[0],
            4.0 * fine.interface().weights()[0]
        );
        assert_eq!(coarse.rigid_modes()[0].load, fine.rigid_modes()[0].load);
        assert!(coarse.interface().normals()[0][2] < 0.0);
        // A uniform pressure: each cell's force its area.
        let deflect = |body: &dyn ElasticBody, n: usize| {
            let mut u = vec![0.0; n];
            body.apply_influence(body.interface().weights(), &mut u);
            u
        };
        let (u, uc, up) = (
            deflect(&fine, nx * ny),
            deflect(coarse.as_ref(), m),
            deflect(&plain, m),
        );
        let plain_fine = deflect(&fine.own, nx * ny);
        let mean = |v: &[f64], c: usize| {
            let children: Vec<f64> = (0..nx * ny)
                .filter(|&k| parent[k] == c)
                .map(|k| v[k])
                .collect();
            children.iter().sum::<f64>() / children.len() as f64
        };
        let end = (5 / 2) * 20;
        let (fine_end, fine_plain) = (mean(&u, end), mean(&plain_fine, end));
        assert!(
            (uc[end] - fine_end).abs() < 0.01 * fine_end,
            "{} {fine_end}",
            uc[end]
        );
        let (images, fine_images) = (uc[end] - up[end], fine_end - fine_plain);
        assert!(
            (images - fine_images).abs() < 0.05 * fine_images,
            "{images} {fine_images}"
        );
    }

    /// The free ends make the surface softer near them and nowhere stiffer, most at the face:
    /// a uniform strip along the whole grid sinks its end cells deeper than the half-space's,
    /// by less than the image's full column (the image never exceeds its own load).
    #[test]
    fn the_ends_sink_deeper() {
        let (nx, ny, dx, dy) = (40, 9, 0.1, 0.02);
        let origin = [-1.95, -0.08];
        let p = vec![1.0; nx * ny];
        let plain = HalfSpace::grid("h", steel(), nx, ny, dx, dy, origin).unwrap();
        let ends = steel_ends(nx, ny, [dx, dy], origin, [Some(-2.0), Some(2.0)], 1.0);
        let (mut a, mut b) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        plain.apply_influence(&p, &mut a);
        ends.apply_influence(&p, &mut b);
        let centre = (ny / 2) * nx;
        let (end, mid) = (centre, centre + nx / 2);
        assert!(b.iter().zip(&a).all(|(b, a)| b >= a));
        assert!(
            b[end] - a[end] > 2.0 * (b[mid] - a[mid]),
            "{} {}",
            b[end] - a[end],
            b[mid] - a[mid]
        );
        // The end of a uniform strip on the half-space sinks about half as far as its middle
        // relative to far away; with the images it sinks as far as the middle (a uniform load
        // everywhere) up to the far image's share.
        assert!(
            a[end] < 0.8 * a[mid] && (b[end] / b[mid] - 1.0).abs() < 0.1,
            "{} {} {} {}",
            a[end],
            a[mid],
            b[end],
            b[mid]
        );
    }

    /// A face inside the grid, a weight outside [0, 2] and a face beyond f64's reach are
    /// named.
    #[test]
    fn bad_faces_are_named() {
        let make = |faces, w| FreeEnds::grid("f", steel(), 4, 3, 0.1, 0.1, [0.0, 0.0], faces, w);
        let e = make([Some(0.0), None], 1.0).unwrap_err().to_string();
        assert!(e.contains("free_ends.faces[0]"), "{e}");
        let e = make([None, Some(0.2)], 1.0).unwrap_err().to_string();
        assert!(e.contains("free_ends.faces[1]"), "{e}");
        let e = make([None, Some(1.0)], 2.5).unwrap_err().to_string();
        assert!(e.contains("free_ends.weight"), "{e}");
        let e = make([None, Some(f64::INFINITY)], 1.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("free_ends.faces[1]"), "{e}");
    }
}
