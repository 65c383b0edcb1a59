use std::f64::consts::PI;
use std::sync::{Arc, OnceLock};

use contopt_core::{
    check, memory, ElasticBody, Error, Geometry, InfluenceShape, Interface, Material, Result,
    RigidMode, Subsurface, SubsurfaceRequest,
};
use faer::Mat;

use crate::fft::Convolution;

/// An elastic half-space z ≤ 0 whose surface is divided into a regular grid of
/// `nx` × `ny` rectangular cells of size `dx` × `dy`; the contact points are the cell
/// centres, each cell a rectangle of uniform pressure.
///
/// Love's solution for a uniformly loaded rectangle (Johnson, *Contact Mechanics*, eq. 3.25)
/// gives the deflection at any point; the grid is translation-invariant, so the influence
/// coefficients form one kernel K(Δi, Δj), computed once (O(nx·ny) memory), and the
/// collocated matrix is symmetric because each cell is symmetric about its centre.
/// [`ElasticBody::apply_influence`] is a zero-padded FFT convolution with that kernel,
/// O(N log N) for N cells; the dense matrix is built only when asked for.
///
/// [`HalfSpace::periodic`] repeats the grid in both directions instead (rough surfaces, a
/// representative patch of a larger contact): the product is the circular convolution with
/// the spectral kernel 2/(E*·|q|), no padding, and a uniform pressure moves the surface by an
/// undetermined constant, which the approach absorbs.
#[derive(Clone, Debug)]
pub struct HalfSpace {
    pub(crate) name: String,
    pub(crate) interface: Interface,
    pub(crate) nx: usize,
    pub(crate) ny: usize,
    pub(crate) periodic: bool,
    /// K[(Δi, Δj)]: deflection at a cell centre per unit force on a cell Δi, Δj away; the
    /// index is |Δ| ≤ n on a free grid (n itself for the FFT's padding) and Δ mod n on a
    /// periodic one. Shared by the grid's sub-grids ([`ElasticBody::restrict`]).
    kernel: Arc<Mat<f64>>,
    convolution: Arc<Convolution>,
    /// A free grid's preconditioner, the circulant on its own grid ([`Convolution::folded`]),
    /// planned by the first call: the whole grid of a solve that runs on its parts never
    /// needs its own.
    folded: Arc<OnceLock<Convolution>>,
    /// The free translation of a pressed body ([`HalfSpace::pressed`]), or none.
    modes: Vec<RigidMode>,
    /// (1 − ν²)/E: the kernel is this times one of the grid's geometry alone.
    pub(crate) compliance: f64,
    pub(crate) material: Material,
    /// Cell sizes \[mm\].
    pub(crate) dx: f64,
    pub(crate) dy: f64,
    /// Poisson's ratio: the stresses below the surface depend on it alone, not on E.
    pub(crate) nu: f64,
}

/// Deflection at (x, y) under unit pressure on the rectangle |x| < a, |y| < b, divided by
/// (1 − ν²)/(πE) (Love 1929; Johnson, *Contact Mechanics*, eq. 3.25): the sum over the four
/// corners of t·ln[(s₁ + √(s₁² + t²))/(s₂ + √(s₂² + t²))] ([`love_log`]).
fn love(x: f64, y: f64, a: f64, b: f64) -> f64 {
    let term = |t: f64, s1: f64, s2: f64| {
        if t == 0.0 {
            0.0
        } else {
            t * love_log(t, s1, s2)
        }
    };
    term(x + a, y + b, y - b)
        + term(y + b, x + a, x - a)
        + term(x - a, y - b, y + b)
        + term(y - b, x - a, x + a)
}

/// ln[(s₁ + √(s₁² + t²))/(s₂ + √(s₂² + t²))] for t ≠ 0, without cancellation: for s < 0,
/// s + √(s² + t²) cancels (to 0 when |s| ≫ |t|, a cell 10⁸ times longer than wide), and equals
/// t²/(√(s² + t²) − s). Both s of one sign: the ratio, the negative ones in that form (t²
/// cancels). Signs differ: ln[(s + √(s² + t²))/|t|] = asinh(s/|t|) for either sign, so the
/// log is asinh(s₁/|t|) − asinh(s₂/|t|), two terms of one sign (no t², which may underflow).
fn love_log(t: f64, s1: f64, s2: f64) -> f64 {
    let (r1, r2) = (s1.hypot(t), s2.hypot(t));
    match (s1 >= 0.0, s2 >= 0.0) {
        (true, true) => ((s1 + r1) / (s2 + r2)).ln(),
        (false, false) => ((r2 - s2) / (r1 - s1)).ln(),
        _ => (s1 / t.abs()).asinh() - (s2 / t.abs()).asinh(),
    }
}

/// The memory of a grid per cell \[bytes\]: 57 for the interface (point, weight, normal,
/// region), 8 for the kernel, 64 for the padded spectrum and 64 for the FFT's work rows, with
/// a margin.
const GRID_BYTES_PER_CELL: u64 = 200;

/// The free grid's kernel: the deflection (1 − ν²)/(πE)·love(i·dx, j·dy, dx/2, dy/2)/(dx·dy)
/// at cell (i, j) per unit force on cell 0. Love's deflection is of degree 1 in its lengths,
/// so it is taken in units of the larger cell side h and divided by the smaller one alone:
/// dx·dy is never formed (it underflows for cells of 10⁻¹⁶⁰ mm), and the lengths stay near 1.
fn love_kernel(material: Material, nx: usize, ny: usize, dx: f64, dy: f64) -> Mat<f64> {
    let scale = (1.0 - material.nu().powi(2)) / (PI * material.e());
    let h = dx.max(dy);
    let (rx, ry, small) = (dx / h, dy / h, dx.min(dy));
    Mat::from_fn(nx, ny, |i, j| {
        let (x, y) = (i as f64 * rx, j as f64 * ry);
        scale * (love(x, y, 0.5 * rx, 0.5 * ry) / small)
    })
}

/// The FFT product's bound for forces of at most 1 N: its transforms scale last, so their
/// intermediates stay below the `padded` cells times Σ|K| over the (up to four times
/// mirrored) kernel. Finite, else a kernel whose entries are finite is still too large for
/// f64 to convolve (E near 10⁻³⁰⁸ MPa): an error naming the cells, as [`check::derived`].
fn check_fft_bound(kernel: &Mat<f64>, padded: usize, dx: f64, what: &str) -> Result<()> {
    let total: f64 = (0..kernel.ncols())
        .flat_map(|j| kernel.col(j).iter().map(|v| v.abs()))
        .sum();
    let bound = 4.0 * padded as f64 * total;
    check::derived(
        "half_space.dx",
        dx,
        &format!("{what}: its FFT product"),
        bound,
    )
    .map(|_| ())
}

impl HalfSpace {
    /// A half-space of `material` under an `nx` × `ny` grid of `dx` × `dy` \[mm\] cells whose
    /// first centre is at `origin` (x, y) \[mm\]; points are listed x fastest.
    pub fn grid(
        name: impl Into<String>,
        material: Material,
        nx: usize,
        ny: usize,
        dx: f64,
        dy: f64,
        origin: [f64; 2],
    ) -> Result<Self> {
        let interface = Self::cells_interface(nx, ny, dx, dy, origin)?;
        let [kx, ky] = Self::kernel_size(nx, ny);
        let kernel = love_kernel(material, kx, ky, dx, dy);
        Self::with_kernel(name.into(), material, interface, [nx, ny], [dx, dy], kernel)
    }

    /// The kernel values a free `nx` × `ny` grid holds: the cell offsets up to half its
    /// padded lengths ([`Convolution::free_lengths`]), which its products and preconditioner
    /// read, and which the parts and coarser grids derived from it read too (their padded
    /// lengths are no longer).
    fn kernel_size(nx: usize, ny: usize) -> [usize; 2] {
        Convolution::free_lengths(nx, ny).map(|p| p / 2 + 1)
    }

    /// The free grid of [`HalfSpace::grid`] on `interface`, with its `kernel` (at least
    /// [`HalfSpace::kernel_size`] values: Love's, or a finer grid's scaled) checked.
    fn with_kernel(
        name: String,
        material: Material,
        interface: Interface,
        [nx, ny]: [usize; 2],
        [dx, dy]: [f64; 2],
        kernel: Mat<f64>,
    ) -> Result<Self> {
        let what = format!(
            "the kernel (1 − ν²)/(πE)·Love/(dx·dy) with dy = {dy} mm, E = {}",
            material.e()
        );
        crate::check_matrix("half_space.dx", dx, &what, &kernel)?;
        let [px, py] = Convolution::free_lengths(nx, ny);
        check_fft_bound(&kernel, px * py, dx, &what)?;
        let convolution = Arc::new(Convolution::free_fast(nx, ny, |i, j| kernel[(i, j)]));
        Ok(Self {
            name,
            interface,
            nx,
            ny,
            periodic: false,
            kernel: Arc::new(kernel),
            convolution,
            folded: Default::default(),
            modes: vec![],
            compliance: (1.0 - material.nu().powi(2)) / material.e(),
            material,
            dx,
            dy,
            nu: material.nu(),
        })
    }

    /// A half-space whose surface repeats the `nx` × `ny` grid of `dx` × `dy` \[mm\] cells in
    /// both directions (period nx·dx × ny·dy), first centre at `origin`: the influence is the
    /// spectral kernel û(q) = 2/(E*·|q|)·p̂(q), E* = E/(1 − ν²), on the grid's frequencies, with
    /// the mean (q = 0) left out. Exact for band-limited pressures (a sinusoid gives its
    /// Westergaard deflection to round-off); it cannot be restricted, since a part of a
    /// periodic surface is not periodic.
    pub fn periodic(
        name: impl Into<String>,
        material: Material,
        nx: usize,
        ny: usize,
        dx: f64,
        dy: f64,
        origin: [f64; 2],
    ) -> Result<Self> {
        let interface = Self::cells_interface(nx, ny, dx, dy, origin)?;
        let estar = material.e() / (1.0 - material.nu().powi(2));
        let (lx, ly) = (nx as f64 * dx, ny as f64 * dy);
        let convolution = Arc::new(Convolution::periodic(nx, ny, |i, j| {
            let q = 2.0 * PI * (i as f64 / lx).hypot(j as f64 / ly);
            if q > 0.0 {
                2.0 / (estar * q * dx * dy)
            } else {
                0.0
            }
        }));
        // The kernel in space, for the dense matrix: the response to a unit force on cell 0.
        let mut impulse = vec![0.0; nx * ny];
        impulse[0] = 1.0;
        let mut response = vec![0.0; nx * ny];
        convolution.apply(&impulse, &mut response);
        let what = format!("the spectral kernel 2/(E*·|q|·dx·dy) with dy = {dy} mm, E* = {estar}");
        check::all_derived("half_space.dx", dx, &what, &response)?;
        let kernel = Mat::from_fn(nx, ny, |i, j| response[j * nx + i]);
        check_fft_bound(&kernel, nx * ny, dx, &what)?;
        Ok(Self {
            name: name.into(),
            interface,
            nx,
            ny,
            periodic: true,
            kernel: Arc::new(kernel),
            convolution,
            folded: Default::default(),
            modes: vec![],
            compliance: (1.0 - material.nu().powi(2)) / material.e(),
            material,
            dx,
            dy,
            nu: material.nu(),
        })
    }

    /// The memory an `nx` × `ny` grid takes \[bytes\]: its points, its kernel and the FFT's
    /// zero-padded 2nx × 2ny spectra and buffers (200 bytes per cell); `None`
    /// when the count overflows.
    pub fn grid_bytes(nx: usize, ny: usize) -> Option<u64> {
        memory::bytes(&[nx, ny], GRID_BYTES_PER_CELL)
    }

    /// The surface of an `nx` × `ny` grid of cells of `dx` × `dy` \[mm\] whose first cell's
    /// centre is at `origin`: the cell centres, x fastest, each weighted by its area, with
    /// the outward normal +z of the half-space below. A rigid body or a bed facing a grid
    /// takes this surface (mirrored); the memory estimate of the grid's body is checked first.
    pub fn cells_interface(
        nx: usize,
        ny: usize,
        dx: f64,
        dy: f64,
        origin: [f64; 2],
    ) -> Result<Interface> {
        if nx == 0 || ny == 0 {
            return Err(Error::invalid(
                "half_space.cells",
                format!("{nx} x {ny}"),
                "at least one cell each way",
            ));
        }
        check::positive("half_space.dx", dx)?;
        check::positive("half_space.dy", dy)?;
        memory::require(
            format!("a half-space grid of {nx} × {ny} cells"),
            Self::grid_bytes(nx, ny),
            memory::BODY_LIMIT_BYTES,
            "use fewer cells",
        )?;
        let area = format!("the cell area dx·dy with dy = {dy} mm");
        check::derived_positive("half_space.dx", dx, &area, dx * dy)?;
        let n = nx * ny;
        let points = (0..n)
            .map(|k| {
                [
                    origin[0] + (k % nx) as f64 * dx,
                    origin[1] + (k / nx) as f64 * dy,
                    0.0,
                ]
            })
            .collect();
        Interface::new(
            Geometry::Surface,
            points,
            vec![dx * dy; n],
            vec![[0.0, 0.0, 1.0]; n],
        )
    }

    /// The product of this free grid read `reach` columns beyond it each side
    /// ([`Convolution::wide`]): its kernel evaluated to the wider padding's half length.
    pub(crate) fn wide_convolution(&self, reach: usize) -> Result<Convolution> {
        let (nx, ny) = (self.nx, self.ny);
        let px = Convolution::wide_length(nx, reach);
        let kernel = love_kernel(self.material, px / 2 + 1, ny + 1, self.dx, self.dy);
        let what = format!(
            "the kernel (1 − ν²)/(πE)·Love/(dx·dy) with dy = {} mm, E = {}, read {reach} cells \
             beyond the grid",
            self.dy,
            self.material.e()
        );
        crate::check_matrix("half_space.dx", self.dx, &what, &kernel)?;
        check_fft_bound(&kernel, 2 * px * ny, self.dx, &what)?;
        Ok(Convolution::wide(nx, ny, reach, |i, j| kernel[(i, j)]))
    }

    /// The sub-grid of `cx` × `cy` cells starting at cell (`i0`, `j0`): the same kernel, a
    /// smaller FFT (its padded lengths no longer than this grid's, so the kernel holds the
    /// offsets it reads).
    fn sub_grid(&self, i0: usize, j0: usize, cx: usize, cy: usize) -> Result<(Self, Vec<usize>)> {
        let index: Vec<usize> = (0..cx * cy)
            .map(|k| (j0 + k / cx) * self.nx + i0 + k % cx)
            .collect();
        let points = index.iter().map(|&k| self.interface.points()[k]).collect();
        let weights = index.iter().map(|&k| self.interface.weights()[k]).collect();
        let interface = Interface::new(
            Geometry::Surface,
            points,
            weights,
            vec![self.interface.normals()[0]; cx * cy],
        )?;
        let kernel = &self.kernel;
        let convolution = Arc::new(Convolution::free_fast(cx, cy, |i, j| kernel[(i, j)]));
        Ok((
            Self {
                name: self.name.clone(),
                interface,
                nx: cx,
                ny: cy,
                periodic: false,
                kernel: self.kernel.clone(),
                convolution,
                folded: Default::default(),
                modes: self
                    .modes
                    .iter()
                    .map(|m| RigidMode {
                        interface_displacement: vec![1.0; cx * cy],
                        ..m.clone()
                    })
                    .collect(),
                compliance: self.compliance,
                material: self.material,
                dx: self.dx,
                dy: self.dy,
                nu: self.nu,
            },
            index,
        ))
    }

    fn coefficient(&self, k: usize, l: usize) -> f64 {
        let (ik, jk, il, jl) = (k % self.nx, k / self.nx, l % self.nx, l / self.nx);
        if self.periodic {
            self.kernel[((ik + self.nx - il) % self.nx, (jk + self.ny - jl) % self.ny)]
        } else {
            self.kernel[(ik.abs_diff(il), jk.abs_diff(jl))]
        }
    }

    /// The grid coarsened ([`ElasticBody::coarsen`]), as a half-space grid of its own.
    pub(crate) fn coarse_grid(&self) -> Option<(HalfSpace, Vec<usize>)> {
        let (nx, ny) = (self.nx, self.ny);
        let (fx, fy) = (if nx > 1 { 2 } else { 1 }, if ny > 1 { 2 } else { 1 });
        if fx * fy == 1 || (self.periodic && (nx % fx != 0 || ny % fy != 0)) {
            return None;
        }
        let (cx, cy) = (nx.div_ceil(fx), ny.div_ceil(fy));
        let (dx, dy) = (fx as f64 * self.dx, fy as f64 * self.dy);
        let first = self.interface.points()[0];
        let origin = [
            first[0] + 0.5 * (fx - 1) as f64 * self.dx,
            first[1] + 0.5 * (fy - 1) as f64 * self.dy,
        ];
        let mut coarse = if self.periodic {
            HalfSpace::periodic(&self.name, self.material, cx, cy, dx, dy, origin).ok()?
        } else {
            let interface = Self::cells_interface(cx, cy, dx, dy, origin).ok()?;
            let kernel = self.coarse_kernel(fx, fy, cx, cy);
            let (name, material) = (self.name.clone(), self.material);
            Self::with_kernel(name, material, interface, [cx, cy], [dx, dy], kernel).ok()?
        };
        if let Some(mode) = self.modes.first() {
            coarse = coarse.pressed(-mode.load).ok()?;
        }
        if self.interface.normals()[0][2] < 0.0 {
            coarse = coarse.upper();
        }
        let parent = (0..nx * ny)
            .map(|k| (k / nx / fy) * cx + (k % nx) / fx)
            .collect();
        Some((coarse, parent))
    }

    /// The free kernel of the `cx` × `cy` grid of cells `fx` × `fy` times this one's. Love's
    /// deflection is of degree 1 in its lengths, so when both sides double the coarse kernel
    /// is this one's halved, at the same cell offsets (no Love evaluation: at 1024² cells those
    /// take a few FFT pairs' time; the coarse grid's padded lengths are no longer than this
    /// one's, so this kernel holds its offsets); else Love's, evaluated.
    fn coarse_kernel(&self, fx: usize, fy: usize, cx: usize, cy: usize) -> Mat<f64> {
        let [kx, ky] = Self::kernel_size(cx, cy);
        if fx == fy {
            let scale = 1.0 / fx as f64;
            Mat::from_fn(kx, ky, |i, j| scale * self.kernel[(i, j)])
        } else {
            let (dx, dy) = (fx as f64 * self.dx, fy as f64 * self.dy);
            love_kernel(self.material, kx, ky, dx, dy)
        }
    }

    /// Number of cells (nx, ny).
    pub fn cells(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// Whether the grid repeats ([`HalfSpace::periodic`]).
    pub fn is_periodic(&self) -> bool {
        self.periodic
    }

    /// The body free to translate along its normal, pressed into its partner by `force` \[N\] >
    /// 0 (a roller under its load, both as half-spaces): one rigid mode that moves every point by
    /// one unit into the body, loaded by −force.
    pub fn pressed(mut self, force: f64) -> Result<Self> {
        check::positive("half_space.force", force)?;
        self.modes = vec![RigidMode {
            name: "translation".into(),
            interface_displacement: vec![1.0; self.interface.len()],
            load: -force,
        }];
        Ok(self)
    }

    /// The same grid as the surface of the half-space z ≥ 0 above the plane, whose outward
    /// normal is −z: the second of two elastic bodies pressed together (a roller on its
    /// raceway, both as half-spaces). The influence is unchanged.
    pub fn upper(mut self) -> Self {
        self.interface = self.interface.mirrored();
        self
    }
}

impl ElasticBody for HalfSpace {
    fn name(&self) -> &str {
        &self.name
    }

    fn interface(&self) -> &Interface {
        &self.interface
    }

    fn apply_influence(&self, force: &[f64], displacement: &mut [f64]) {
        self.convolution.apply(force, displacement);
    }

    /// The bounding box of the kept cells, two cells wider each way; `None` when that box
    /// would hold more than three quarters of the grid (too little to gain), and always on a
    /// periodic grid.
    fn restrict(&self, keep: &[bool]) -> Option<(Box<dyn ElasticBody>, Vec<usize>)> {
        if self.periodic {
            return None;
        }
        let kept = (0..keep.len()).filter(|&k| keep[k]);
        let (mut lo, mut hi) = ([usize::MAX; 2], [0usize; 2]);
        for k in kept {
            let (i, j) = (k % self.nx, k / self.nx);
            lo = [lo[0].min(i), lo[1].min(j)];
            hi = [hi[0].max(i), hi[1].max(j)];
        }
        if lo[0] == usize::MAX {
            return None;
        }
        // Two cells of margin, the box shifted to stay on the grid (its product pads each
        // side to a fast FFT length, [`Convolution::free_lengths`]).
        let side = |lo: usize, hi: usize, n: usize| {
            let len = (hi - lo + 5).min(n);
            let start = lo.saturating_sub(2).min(n - len);
            (start, len)
        };
        let ((i0, cx), (j0, cy)) = (side(lo[0], hi[0], self.nx), side(lo[1], hi[1], self.ny));
        if 4 * cx * cy > 3 * self.nx * self.ny {
            return None;
        }
        let (sub, index) = self.sub_grid(i0, j0, cx, cy).ok()?;
        Some((Box::new(sub), index))
    }

    /// A grid of cells twice as large each way (a side of one cell stays), ⌈nx/2⌉ × ⌈ny/2⌉
    /// over the same surface, each coarse cell the parent of the cells it covers (an odd
    /// side's last coarse cell reaches half a coarse cell past the grid); pressed by the same
    /// force, facing the same way. A periodic grid coarsens only when its sides are even.
    fn coarsen(&self) -> Option<(Box<dyn ElasticBody>, Vec<usize>)> {
        let (coarse, parent) = self.coarse_grid()?;
        Some((Box::new(coarse), parent))
    }

    /// The grid's cells, spacing and kind; the kernel is (1 − ν²)/E times one of those alone.
    fn influence_shape(&self) -> Option<(InfluenceShape, f64)> {
        let p = &self.interface.points();
        let dx = if self.nx > 1 { p[1][0] - p[0][0] } else { 0.0 };
        let dy = if self.ny > 1 {
            p[self.nx][1] - p[0][1]
        } else {
            0.0
        };
        let w = self.interface.weights()[0];
        let shape = InfluenceShape::CellGrid {
            cells: [self.nx, self.ny],
            spacing: [dx, dy],
            cell_area: w,
            periodic: self.periodic,
        };
        Some((shape, self.compliance))
    }

    fn precondition(&self, displacement: &[f64], force: &mut [f64]) -> bool {
        if self.periodic {
            self.convolution.apply_inverse(displacement, force);
        } else {
            let kernel = &self.kernel;
            self.folded
                .get_or_init(|| Convolution::folded(self.nx, self.ny, |i, j| kernel[(i, j)]))
                .apply_inverse_in(&self.convolution, displacement, force);
        }
        true
    }

    fn influence_matrix(&self) -> Mat<f64> {
        let n = self.interface.len();
        Mat::from_fn(n, n, |k, l| self.coefficient(k, l))
    }

    /// From the kernel of Love's cells, which the grid holds.
    fn influence_block(&self, points: &[usize]) -> Option<Mat<f64>> {
        let (m, n) = (points.len(), self.interface.len());
        let on = points.iter().all(|&i| i < n);
        on.then(|| Mat::from_fn(m, m, |a, b| self.coefficient(points[a], points[b])))
    }

    fn load_displacement(&self) -> Result<Vec<f64>> {
        Ok(vec![0.0; self.interface.len()])
    }

    fn rigid_modes(&self) -> &[RigidMode] {
        &self.modes
    }

    fn subsurface(
        &self,
        pressure: &[f64],
        request: &SubsurfaceRequest,
    ) -> Result<Option<Subsurface>> {
        self.stresses_below(pressure, request).map(Some)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The FFT product agrees with the dense matrix on an irregular grid, free and periodic.
    /// A 7 × 4 grid, pressed and facing down, coarsens to 4 × 2 cells twice as large: each
    /// cell lies inside its parent (a wrong parent index or origin puts cells a coarse cell
    /// away), every coarse cell has a child, and the coarse grid keeps the load and the
    /// normal; a periodic grid of an odd side offers none.
    #[test]
    fn coarsen_covers_the_grid() {
        let steel = Material::new(2e5, 0.3).unwrap();
        let fine = HalfSpace::grid("g", steel, 7, 4, 0.5, 0.25, [1.0, -2.0])
            .unwrap()
            .pressed(30.0)
            .unwrap()
            .upper();
        let (coarse, parent) = fine.coarsen().unwrap();
        let c = coarse.interface();
        assert_eq!(c.len(), 8);
        for (x, &k) in fine.interface().points().iter().zip(&parent) {
            let y = c.points()[k];
            assert!((x[0] - y[0]).abs() <= 0.5 + 1e-12, "{x:?} in {y:?}");
            assert!((x[1] - y[1]).abs() <= 0.25 + 1e-12, "{x:?} in {y:?}");
        }
        assert!((0..8).all(|k| parent.contains(&k)));
        assert!((c.weights()[0] - 0.5).abs() < 1e-12);
        assert_eq!(c.normals()[0], fine.interface().normals()[0]);
        assert_eq!(coarse.rigid_modes()[0].load, fine.rigid_modes()[0].load);
        let periodic = HalfSpace::periodic("p", steel, 7, 4, 0.5, 0.25, [0.0; 2]).unwrap();
        assert!(periodic.coarsen().is_none());
    }

    /// The coarse grid's kernel, the fine one's halved (Love's deflection is of degree 1 in its
    /// lengths), is Love's on the coarse cells to round-off; so is that of a grid one cell
    /// wide, which coarsens one way only and evaluates Love's.
    #[test]
    fn coarse_kernel_is_loves() {
        let steel = Material::new(2e5, 0.3).unwrap();
        for (nx, ny, dx, dy) in [(7, 4, 0.5, 0.25), (9, 1, 0.2, 0.7)] {
            let fine = HalfSpace::grid("g", steel, nx, ny, dx, dy, [0.0; 2]).unwrap();
            let (coarse, _) = fine.coarse_grid().unwrap();
            let (cx, cy) = coarse.cells();
            let [kx, ky] = HalfSpace::kernel_size(cx, cy);
            assert_eq!((coarse.kernel.nrows(), coarse.kernel.ncols()), (kx, ky));
            let love = love_kernel(steel, kx, ky, coarse.dx, coarse.dy);
            for i in 0..kx {
                for j in 0..ky {
                    let (k, l) = (coarse.kernel[(i, j)], love[(i, j)]);
                    assert!(
                        (k - l).abs() <= 1e-14 * l.abs(),
                        "({i}, {j}): {k} against {l}"
                    );
                }
            }
        }
    }

    #[test]
    fn fft_product_matches_dense() {
        let steel = Material::new(2e5, 0.3).unwrap();
        let (nx, ny) = (23, 17);
        for body in [
            HalfSpace::grid("hs", steel, nx, ny, 0.1, 0.15, [0.0, 0.0]).unwrap(),
            HalfSpace::periodic("hs", steel, nx, ny, 0.1, 0.15, [0.0, 0.0]).unwrap(),
        ] {
            let n = nx * ny;
            let force: Vec<f64> = (0..n)
                .map(|k| ((k * 37 % 101) as f64 - 40.0).sin() + 1.5)
                .collect();
            let mut fast = vec![0.0; n];
            body.apply_influence(&force, &mut fast);
            let dense = body.influence_matrix();
            let scale = fast.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for k in 0..n {
                let exact: f64 = (0..n).map(|l| dense[(k, l)] * force[l]).sum();
                assert!(
                    (fast[k] - exact).abs() < 1e-10 * scale,
                    "periodic {}, cell {k}: {} vs {exact}",
                    body.periodic,
                    fast[k]
                );
            }
        }
    }

    /// On a periodic grid a pressure cos(q·x) deflects the surface by 2/(E*q)·cos(q·x), the
    /// half-space's exact response to a sinusoid, to round-off; a uniform pressure does not
    /// move it.
    #[test]
    fn periodic_sinusoid_deflection() {
        let steel = Material::new(2e5, 0.3).unwrap();
        let estar = 2e5 / (1.0 - 0.09);
        let (nx, ny, dx, dy) = (30, 12, 0.05, 0.2);
        let body = HalfSpace::periodic("hs", steel, nx, ny, dx, dy, [0.0, 0.0]).unwrap();
        let (lx, ly) = (nx as f64 * dx, ny as f64 * dy);
        let (qx, qy) = (2.0 * PI * 3.0 / lx, 2.0 * PI * 2.0 / ly);
        let q = qx.hypot(qy);
        let pts = &body.interface().points();
        let force: Vec<f64> = pts
            .iter()
            .map(|x| (7.0 + (qx * x[0] + qy * x[1]).cos()) * dx * dy)
            .collect();
        let mut u = vec![0.0; nx * ny];
        body.apply_influence(&force, &mut u);
        for (x, u) in pts.iter().zip(&u) {
            let exact = 2.0 / (estar * q) * (qx * x[0] + qy * x[1]).cos();
            assert!(
                (u - exact).abs() < 1e-12 * 2.0 / (estar * q),
                "{u} vs {exact}"
            );
        }
    }

    /// Love's sum as it was written, s + √(s² + t²) for every s: it cancels for s < 0,
    /// |s| ≫ t.
    fn love_as_written(x: f64, y: f64, a: f64, b: f64) -> f64 {
        let term = |t: f64, s1: f64, s2: f64| {
            if t == 0.0 {
                0.0
            } else {
                t * ((s1 + s1.hypot(t)) / (s2 + s2.hypot(t))).ln()
            }
        };
        term(x + a, y + b, y - b)
            + term(y + b, x + a, x - a)
            + term(x - a, y - b, y + b)
            + term(y - b, x - a, x + a)
    }

    /// Round-off of Love's sum where the form as written is accurate (aspect ratios up to
    /// 10, points near and far): a few ε of the deflection under the cell. (At 167 the form as
    /// written is already 3·10⁻¹³ off the centre's closed form; this one is within ε.)
    const LOVE_ROUND_OFF: f64 = 1e-14;

    /// The cancellation-free sum agrees with the sum as written where that one is accurate,
    /// with the closed form at the centre of a 2a × 2b cell, 4a·asinh(b/a) + 4b·asinh(a/b),
    /// at any aspect, and stays finite and right for a cell 10¹⁰ times longer than wide,
    /// where the other is infinite: 4b(1 + ln(2a/b)) + O(b³/a²) there.
    #[test]
    fn love_without_cancellation() {
        for (a, b) in [
            (1.0, 1.0),
            (1.0, 0.1),
            (0.5, 3e-3),
            (2e-3, 1.0),
            (1.0, 1e-6),
        ] {
            let centre = love(0.0, 0.0, a, b);
            let closed = 4.0 * a * (b / a).asinh() + 4.0 * b * (a / b).asinh();
            assert!(
                (centre - closed).abs() <= 4.0 * f64::EPSILON * closed,
                "{a} {b}"
            );
        }
        for (a, b) in [(1.0, 1.0), (1.0, 0.1), (0.3, 1.0), (1.0, 0.5)] {
            let centre = love_as_written(0.0, 0.0, a, b);
            for (x, y) in [
                (0.0, 0.0),
                (2.0 * a, 0.0),
                (0.0, 2.0 * b),
                (7.0 * a, 3.0 * b),
            ]
            .into_iter()
            .chain([(100.0, 0.0), (3.0 * a, 50.0 * b), (-a, 0.5 * b)])
            {
                let (new, old) = (love(x, y, a, b), love_as_written(x, y, a, b));
                assert!(
                    (new - old).abs() <= LOVE_ROUND_OFF * centre,
                    "a {a}, b {b} at ({x}, {y}): {new} vs {old}"
                );
            }
        }
        let (a, b) = (1.0, 1e-10);
        assert!(!love_as_written(0.0, 0.0, a, b).is_finite());
        let centre = love(0.0, 0.0, a, b);
        let want = 4.0 * b * (1.0 + (2.0 * a / b).ln());
        assert!((centre - want).abs() <= 1e-14 * want, "{centre} vs {want}");
        // Across and along the strip, at its neighbours' centres: finite and below the centre.
        for (x, y) in [(2.0 * a, 0.0), (0.0, 2.0 * b), (2.0 * a, 2.0 * b)] {
            let w = love(x, y, a, b);
            assert!(w.is_finite() && w > 0.0 && w < centre, "({x}, {y}): {w}");
        }
    }

    /// A grid's kernel is the same whichever way its cells are long (to round-off), finite
    /// for cells of 1 × 10⁻³⁰⁰ mm, and an error naming the cells where it overflows f64.
    #[test]
    fn kernels_of_extreme_cells() {
        let steel = Material::new(2e5, 0.3).unwrap();
        let kernel = |dx: f64, dy: f64| love_kernel(steel, 3, 3, dx, dy);
        let (wide, long) = (kernel(0.2, 0.05), kernel(0.05, 0.2));
        for (i, j) in [(0, 0), (1, 0), (2, 1), (0, 2)] {
            let (u, v) = (wide[(i, j)], long[(j, i)]);
            assert!((u - v).abs() <= 1e-15 * wide[(0, 0)], "{u} vs {v}");
        }
        let thin = HalfSpace::grid("hs", steel, 2, 1, 1.0, 1e-300, [0.0, 0.0]).unwrap();
        assert!(thin.kernel.col(0).iter().all(|v| v.is_finite() && *v > 0.0));
        let soft = Material::new(1e-300, 0.3).unwrap();
        let e = HalfSpace::grid("hs", soft, 2, 1, 1e-10, 1e-10, [0.0, 0.0]).unwrap_err();
        assert!(
            e.to_string().contains("half_space.dx") && e.to_string().contains("kernel"),
            "{e}"
        );
        let e = HalfSpace::grid("hs", steel, 2, 1, 1e-300, 1e-300, [0.0, 0.0]).unwrap_err();
        assert!(e.to_string().contains("cell area"), "{e}");
        // Entries finite, but too large for the FFT to sum (the fuzz test's case).
        let soft = Material::new(2.2250738585072014e-308, -4.1e-15).unwrap();
        let e = HalfSpace::grid("hs", soft, 18, 16, 281.39, 1e-6, [0.0, 0.0]).unwrap_err();
        assert!(e.to_string().contains("FFT product"), "{e}");
    }

    /// The padded circulant of a free grid, and the one on its own grid, are positive (the
    /// latter's inverse preconditions), also for long cells and odd sides, where a period with
    /// zeros at the distances n (the padding's middle) has negative eigenvalues as large as its
    /// median ones; the product is the same.
    #[test]
    fn padded_circulant_is_positive() {
        let steel = Material::new(2e5, 0.3).unwrap();
        for (nx, ny, dx, dy) in [
            (100, 53, 0.1, 0.0173),
            (60, 30, 1.0, 1.0),
            (41, 40, 1.0, 1.0),
        ] {
            let kernel = love_kernel(steel, nx + 1, ny + 1, dx, dy);
            let periodic = Convolution::free(nx, ny, |i, j| kernel[(i, j)]);
            let gap = Convolution::free(nx, ny, |i, j| {
                if i == nx || j == ny {
                    0.0
                } else {
                    kernel[(i, j)]
                }
            });
            let k00 = kernel[(0, 0)];
            assert!(periodic.smallest_eigenvalue() > 0.05 * k00, "{nx} x {ny}");
            // The preconditioner's circulant on the field's own grid, too.
            let folded = Convolution::folded(nx, ny, |i, j| kernel[(i, j)]);
            assert!(folded.smallest_eigenvalue() > 0.05 * k00, "{nx} x {ny}");
            if (nx, ny) != (41, 40) {
                assert!(gap.smallest_eigenvalue() < 0.0, "{nx} x {ny}");
            }
            let force: Vec<f64> = (0..nx * ny).map(|k| ((k * 7 % 13) as f64).cos()).collect();
            let (mut a, mut b) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
            periodic.apply(&force, &mut a);
            gap.apply(&force, &mut b);
            let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(a.iter().zip(&b).all(|(a, b)| (a - b).abs() < 1e-12 * scale));
        }
    }

    /// Love's formula at the centre of a square 2a × 2a: (1 − ν²)pa/(πE) · 4 ln(1 + √2)·2
    /// = 8 ln(1 + √2) a (Johnson 3.26: w₀ = 2.24 p a (1 − ν²)/E for the square of side 2a).
    #[test]
    fn square_centre_deflection() {
        let w = love(0.0, 0.0, 1.0, 1.0) / PI;
        assert!((w - 8.0 * (1.0 + 2f64.sqrt()).ln() / PI).abs() < 1e-14);
        assert!((w - 2.24).abs() < 5e-3, "{w}");
        // Far away it is a point force 4ab/(πr) · (1 − ν²)/E·π.
        let far = love(1000.0, 0.0, 1.0, 1.0);
        assert!((far / (4.0 / 1000.0) - 1.0).abs() < 1e-5, "{far}");
    }
}
