//! Stresses below a half-space grid under a computed pressure field.
//!
//! Each stress component at depth z is a convolution of the cell pressures with one kernel:
//! the stress of a uniformly loaded rectangle (Love 1929; Johnson, *Contact Mechanics*,
//! eqs. 3.9–3.10 through the potentials ψ = ∬ p/ρ and ψ₁ = ∬ p ln(ρ + z)). A free grid
//! zero-pads the product to at least 2nx × 2ny (along x to a length of factors 2, 3, 5 and 7,
//! and further when the fields are read beyond the grid for a free end's images) so the
//! circular FFT product is the exact linear one; a periodic grid multiplies the pressure's
//! spectrum by the half-space's response to a sinusoid. Depths are taken one at a time, so
//! memory is linear in the grid, whatever the number of depths.

use std::f64::consts::PI;
use std::sync::Arc;

use contopt_core::{
    Result, Section, SectionAxis, SectionField, StressPeaks, StressTensor, Subsurface,
    SubsurfaceRequest,
};
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealToComplex};
use rustfft::Fft;

use crate::fft::{Convolution, Plans};
use crate::subsurface_2d::{check_pressure, not_finite};
use crate::HalfSpace;

/// Stress components in [`StressTensor`] order: xx, yy, zz, xy, xz, yz.
const COMPONENTS: usize = 6;

/// Whether a kernel component is even (+1) or odd (−1) in Δx and in Δy: the normal stresses
/// are even in both, τ_xy odd in both, τ_xz odd in x, τ_yz odd in y.
const PARITY: [[f64; 2]; COMPONENTS] = [
    [1.0, 1.0],
    [1.0, 1.0],
    [1.0, 1.0],
    [-1.0, -1.0],
    [-1.0, 1.0],
    [1.0, -1.0],
];

/// The corner functions of a uniformly loaded rectangle at X, Y > 0, depth z > 0: the stress
/// at (x, y, z) under unit pressure on [ξ₁, ξ₂] × [η₁, η₂] is G(X₁, Y₁) − G(X₁, Y₂) −
/// G(X₂, Y₁) + G(X₂, Y₂) with Xₖ = x − ξₖ, Yₖ = y − ηₖ. From Johnson eq. (3.10):
///
/// σ_xx = [2ν ψ_z − z ψ_xx − (1 − 2ν) ψ₁_xx]/2π, σ_zz = [ψ_z − z ψ_zz]/2π,
/// τ_xy = −[(1 − 2ν) ψ₁_xy + z ψ_xy]/2π, τ_xz = −z ψ_xz/2π (and y for x),
///
/// with each second derivative of a potential replaced by its corner function (written so
/// that no term cancels catastrophically). Values at negative X or Y follow from the
/// parity of each function ([`Corners::at`]).
fn corner(x: f64, y: f64, z: f64, nu: f64) -> [f64; COMPONENTS] {
    let rho = (x * x + y * y + z * z).sqrt();
    let (xz2, yz2) = (x * x + z * z, y * y + z * z);
    let psi_z = -(x * y / (z * rho)).atan();
    let psi_zz = x * y * (rho * rho + z * z) / (rho * xz2 * yz2);
    let psi_xx = -x * y / (xz2 * rho);
    let psi_yy = -x * y / (yz2 * rho);
    let psi_xy = 1.0 / rho;
    let psi_xz = -y * z / (xz2 * rho);
    let psi_yz = -x * z / (yz2 * rho);
    // ρ − z without cancellation.
    let rho_minus_z = (x * x + y * y) / (rho + z);
    let psi1_xx = (x * y * rho_minus_z / (x * x * rho + z * y * y)).atan();
    let psi1_yy = (x * y * rho_minus_z / (y * y * rho + z * x * x)).atan();
    let psi1_xy = (rho + z).ln();
    let c = 1.0 / (2.0 * PI);
    [
        c * (2.0 * nu * psi_z - z * psi_xx - (1.0 - 2.0 * nu) * psi1_xx),
        c * (2.0 * nu * psi_z - z * psi_yy - (1.0 - 2.0 * nu) * psi1_yy),
        c * (psi_z - z * psi_zz),
        -c * ((1.0 - 2.0 * nu) * psi1_xy + z * psi_xy),
        -c * z * psi_xz,
        -c * z * psi_yz,
    ]
}

/// The stress \[xx, yy, zz, xy, xz, yz\] at (`x`, `y`, `z`), z > 0, under unit pressure on the
/// rectangle `xs` × `ys` of the surface: the corner sum G(X₁, Y₁) − G(X₁, Y₂) − G(X₂, Y₁) +
/// G(X₂, Y₂) of [`corner`], each corner at |X|, |Y| with its parity (a Green's body's single
/// evaluation, where the grids take a whole lattice: [`Corners`]).
pub(crate) fn rectangle_stress(
    x: f64,
    y: f64,
    z: f64,
    xs: [f64; 2],
    ys: [f64; 2],
    nu: f64,
) -> [f64; COMPONENTS] {
    let signed = |cx: f64, cy: f64| -> [f64; COMPONENTS] {
        let g = corner(cx.abs(), cy.abs(), z, nu);
        std::array::from_fn(|c| {
            let sx = if cx < 0.0 { -PARITY[c][0] } else { 1.0 };
            let sy = if cy < 0.0 { -PARITY[c][1] } else { 1.0 };
            sx * sy * g[c]
        })
    };
    let (a, b) = (signed(x - xs[0], y - ys[0]), signed(x - xs[0], y - ys[1]));
    let (c, d) = (signed(x - xs[1], y - ys[0]), signed(x - xs[1], y - ys[1]));
    std::array::from_fn(|k| a[k] - b[k] - c[k] + d[k])
}

/// The corner functions of one depth on the lattice of cell edges X = (k + ½)dx,
/// Y = (l + ½)dy, k < nx, l < ny, one table per component: [c][l·nx + k].
struct Corners {
    nx: usize,
    tables: [Vec<f64>; COMPONENTS],
}

impl Corners {
    fn new(nx: usize, ny: usize, dx: f64, dy: f64, z: f64, nu: f64) -> Self {
        let mut tables: [Vec<f64>; COMPONENTS] = Default::default();
        for t in &mut tables {
            t.reserve_exact(nx * ny);
        }
        for l in 0..ny {
            for k in 0..nx {
                let g = corner((k as f64 + 0.5) * dx, (l as f64 + 0.5) * dy, z, nu);
                for (t, v) in tables.iter_mut().zip(g) {
                    t.push(v);
                }
            }
        }
        Self { nx, tables }
    }

    /// G_c at the signed edge indices (k, l), X = (k + ½)dx: the corner function's parity
    /// along an axis is the opposite of the kernel's (a difference across a cell turns odd
    /// into even).
    fn at(&self, c: usize, k: isize, l: isize) -> f64 {
        let fold = |m: isize, kernel_parity: f64| {
            if m >= 0 {
                (m as usize, 1.0)
            } else {
                ((-m - 1) as usize, -kernel_parity)
            }
        };
        let (i, si) = fold(k, PARITY[c][0]);
        let (j, sj) = fold(l, PARITY[c][1]);
        si * sj * self.tables[c][j * self.nx + i]
    }

    /// The kernel of component `c` at the cell offset (Δi, Δj): the corner sum over the
    /// edges Δi ± ½, Δj ± ½.
    fn kernel_value(&self, c: usize, di: isize, dj: isize) -> f64 {
        self.at(c, di, dj) - self.at(c, di, dj - 1) - self.at(c, di - 1, dj)
            + self.at(c, di - 1, dj - 1)
    }
}

/// Two-dimensional real FFTs on a `px` × `py` grid, spectra stored column by column:
/// [i·py + j] for x-frequency i < px/2 + 1.
struct Transform {
    px: usize,
    py: usize,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    forward_y: Arc<dyn Fft<f64>>,
    inverse_y: Arc<dyn Fft<f64>>,
    row: Vec<f64>,
    rows: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
}

impl Transform {
    fn new(px: usize, py: usize) -> Self {
        let Plans {
            r2c,
            c2r,
            forward_y,
            inverse_y,
            scratch,
        } = Plans::new(px, py);
        let cx = px / 2 + 1;
        let zero = Complex::new(0.0, 0.0);
        Self {
            px,
            py,
            r2c,
            c2r,
            forward_y,
            inverse_y,
            row: vec![0.0; px],
            rows: vec![zero; cx * py],
            scratch: vec![zero; scratch],
        }
    }

    fn spectrum_len(&self) -> usize {
        (self.px / 2 + 1) * self.py
    }

    /// The spectrum of the `nx` × `ny` field `input` (x fastest), zero beyond it.
    fn forward(&mut self, input: &[f64], nx: usize, ny: usize, out: &mut [Complex<f64>]) {
        let cx = self.px / 2 + 1;
        for j in 0..ny {
            self.row[..nx].copy_from_slice(&input[j * nx..(j + 1) * nx]);
            self.row[nx..].fill(0.0);
            self.r2c
                .process_with_scratch(
                    &mut self.row,
                    &mut self.rows[j * cx..(j + 1) * cx],
                    &mut self.scratch,
                )
                .expect("buffer lengths match the plan");
        }
        for (i, out) in out.chunks_exact_mut(self.py).enumerate() {
            for (j, v) in out[..ny].iter_mut().enumerate() {
                *v = self.rows[j * cx + i];
            }
            out[ny..].fill(Complex::new(0.0, 0.0));
            self.forward_y.process_with_scratch(out, &mut self.scratch);
        }
    }

    /// The first `ny` rows of the field whose spectrum is `spectrum` (consumed), columns
    /// −`reach` to nx + `reach` − 1 (circular), written to `out` (x fastest).
    fn inverse(
        &mut self,
        spectrum: &mut [Complex<f64>],
        [nx, ny, reach]: [usize; 3],
        out: &mut [f64],
    ) {
        let cx = self.px / 2 + 1;
        for (i, column) in spectrum.chunks_exact_mut(self.py).enumerate() {
            self.inverse_y
                .process_with_scratch(column, &mut self.scratch);
            for (j, v) in column[..ny].iter().enumerate() {
                self.rows[j * cx + i] = *v;
            }
        }
        let scale = 1.0 / (self.px * self.py) as f64;
        for j in 0..ny {
            let spectrum = &mut self.rows[j * cx..(j + 1) * cx];
            // A real inverse transform needs real end points (the last one at even length).
            spectrum[0].im = 0.0;
            if self.px.is_multiple_of(2) {
                spectrum[cx - 1].im = 0.0;
            }
            self.c2r
                .process_with_scratch(spectrum, &mut self.row, &mut self.scratch)
                .expect("buffer lengths match the plan");
            let width = nx + 2 * reach;
            let (before, rest) = out[j * width..(j + 1) * width].split_at_mut(reach);
            for (o, r) in before.iter_mut().zip(&self.row[self.px - reach..]) {
                *o = r * scale;
            }
            for (o, r) in rest.iter_mut().zip(&self.row) {
                *o = r * scale;
            }
        }
    }
}

/// The stress fields of one grid under one pressure, depth after depth, read `reach` columns
/// beyond the grid each side (a free grid's; [`crate::FreeEnds`]' images).
struct StressSolver<'a> {
    body: &'a HalfSpace,
    reach: usize,
    transform: Transform,
    /// The pressure's spectrum.
    pressure: Vec<Complex<f64>>,
    /// Work: a padded kernel and a product spectrum.
    kernel: Vec<f64>,
    product: Vec<Complex<f64>>,
}

impl<'a> StressSolver<'a> {
    /// The solver of `body` under `pressure`, read `reach` columns beyond a free grid: the
    /// padding along x is [`Convolution::wide_length`] (at least 2(nx + reach), factors 2, 3,
    /// 5 and 7), so every column read is the linear product (distances below half the period).
    fn new(body: &'a HalfSpace, pressure: &[f64], reach: usize) -> Self {
        let (nx, ny) = (body.nx, body.ny);
        let (px, py) = if body.periodic {
            (nx, ny)
        } else {
            (Convolution::wide_length(nx, reach), 2 * ny)
        };
        let mut transform = Transform::new(px, py);
        let mut spectrum = vec![Complex::new(0.0, 0.0); transform.spectrum_len()];
        transform.forward(pressure, nx, ny, &mut spectrum);
        let product = spectrum.clone();
        Self {
            body,
            reach: if body.periodic { 0 } else { reach },
            transform,
            pressure: spectrum,
            kernel: if body.periodic {
                vec![]
            } else {
                vec![0.0; px * py]
            },
            product,
        }
    }

    /// The six components at depth `z` at every cell and `reach` beyond each side:
    /// `fields[c][j·(nx + 2·reach) + reach + i]`.
    fn depth(&mut self, z: f64, fields: &mut [Vec<f64>; COMPONENTS]) {
        let (nx, ny) = (self.body.nx, self.body.ny);
        // The padded period's offsets reach (px − 1)/2 cells along x: the table holds their
        // edges.
        let kx = self.transform.px.div_ceil(2);
        let corners = (!self.body.periodic)
            .then(|| Corners::new(kx, ny, self.body.dx, self.body.dy, z, self.body.nu));
        for (c, field) in fields.iter_mut().enumerate() {
            match &corners {
                Some(corners) => self.free_product(corners, c),
                None => self.periodic_product(z, c),
            }
            let window = [nx, ny, self.reach];
            self.transform.inverse(&mut self.product, window, field);
        }
    }

    /// product = FFT(kernel_c) · FFT(p) on the zero-padded grid.
    fn free_product(&mut self, corners: &Corners, c: usize) {
        let (px, py) = (self.transform.px, self.transform.py);
        // Offsets on the padded (circular) period; the middle entry (even period) is never
        // used.
        let offset = |a: usize, period: usize| match (2 * a).cmp(&period) {
            std::cmp::Ordering::Less => Some(a as isize),
            std::cmp::Ordering::Greater => Some(a as isize - period as isize),
            std::cmp::Ordering::Equal => None,
        };
        for b in 0..py {
            for a in 0..px {
                self.kernel[b * px + a] = match (offset(a, px), offset(b, py)) {
                    (Some(di), Some(dj)) => corners.kernel_value(c, di, dj),
                    _ => 0.0,
                };
            }
        }
        self.transform
            .forward(&self.kernel, px, py, &mut self.product);
        for (k, p) in self.product.iter_mut().zip(&self.pressure) {
            *k *= p;
        }
    }

    /// product = σ̂_c(q, z) · p̂ on the periodic grid: the response to a sinusoid of wave
    /// vector q = |q|·n, a plane-strain state along n (Johnson §2.6 for cos qx):
    /// σ_nn = −(1 − qz)e^{−qz}, σ_zz = −(1 + qz)e^{−qz}, τ_nz = i·qz·e^{−qz}, and across n
    /// σ_tt = ν(σ_nn + σ_zz) = −2ν e^{−qz}. The mean pressure acts as a uniform load on a wide
    /// disc (no direction preferred): σ_xx = σ_yy = −(1 + 2ν)/2·p̄, σ_zz = −p̄.
    fn periodic_product(&mut self, z: f64, c: usize) {
        let b = self.body;
        let (nx, ny, nu) = (b.nx, b.ny, b.nu);
        let (lx, ly) = (nx as f64 * b.dx, ny as f64 * b.dy);
        // Signed frequency index; odd (imaginary) multipliers vanish at the Nyquist index,
        // where a real field cannot carry them.
        let signed = |k: usize, n: usize| -> (f64, f64) {
            let s = if 2 * k <= n {
                k as f64
            } else {
                k as f64 - n as f64
            };
            (s, if 2 * k == n { 0.0 } else { s })
        };
        for (i, column) in self.product.chunks_exact_mut(ny).enumerate() {
            let (fx, odd_x) = signed(i, nx);
            for (j, value) in column.iter_mut().enumerate() {
                let (fy, odd_y) = signed(j, ny);
                let (qx, qy) = (2.0 * PI * fx / lx, 2.0 * PI * fy / ly);
                let q = qx.hypot(qy);
                let multiplier = if q == 0.0 {
                    let lateral = -0.5 * (1.0 + 2.0 * nu);
                    [lateral, lateral, -1.0, 0.0, 0.0, 0.0][c]
                } else {
                    let decay = (-q * z).exp();
                    let (n_x, n_y) = (qx / q, qy / q);
                    let normal = -(1.0 - q * z) * decay;
                    let across = -2.0 * nu * decay;
                    let shear = q * z * decay;
                    match c {
                        0 => n_x * n_x * normal + n_y * n_y * across,
                        1 => n_y * n_y * normal + n_x * n_x * across,
                        2 => -(1.0 + q * z) * decay,
                        3 => n_x * n_y * (normal - across),
                        4 => 2.0 * PI * odd_x / lx / q * shear,
                        _ => 2.0 * PI * odd_y / ly / q * shear,
                    }
                };
                let p = self.pressure[i * ny + j];
                *value = if c >= 4 {
                    Complex::new(0.0, multiplier) * p
                } else {
                    p * multiplier
                };
            }
        }
    }
}

/// A grid's pressure mirrored beyond free faces, with a weight ([`crate::FreeEnds`]): own
/// column i's image about a face is column `mirror − i` of a row read `reach` columns beyond
/// the grid each side. Love's kernels are even or odd in x, so the stresses of the image
/// pressure are the pressure's own, read there, times the component's parity.
pub(crate) struct Images<'a> {
    pub reach: usize,
    pub mirrors: &'a [usize],
    pub weight: f64,
}

impl Images<'_> {
    /// The stress at own cell `k` (x fastest, `nx` columns) of the pressure and its images,
    /// from the `fields` read `reach` beyond the grid.
    fn tensor(&self, fields: &[Vec<f64>; COMPONENTS], nx: usize, k: usize) -> StressTensor {
        let (i, row) = (k % nx, (k / nx) * (nx + 2 * self.reach));
        let component = |c: usize| {
            let f = &fields[c];
            let images: f64 = self.mirrors.iter().map(|&m| f[row + m - i]).sum();
            f[row + self.reach + i] + self.weight * PARITY[c][0] * images
        };
        StressTensor {
            xx: component(0),
            yy: component(1),
            zz: component(2),
            xy: component(3),
            xz: component(4),
            yz: component(5),
        }
    }
}

/// Six zero fields of `n` cells.
fn zero_fields(n: usize) -> [Vec<f64>; COMPONENTS] {
    std::array::from_fn(|_| vec![0.0; n])
}

fn tensor(fields: &[Vec<f64>; COMPONENTS], k: usize) -> StressTensor {
    StressTensor {
        xx: fields[0][k],
        yy: fields[1][k],
        zz: fields[2][k],
        xy: fields[3][k],
        xz: fields[4][k],
        yz: fields[5][k],
    }
}

impl HalfSpace {
    /// The stress tensor at depth `depth` \[mm\] below every cell centre (x fastest) under
    /// the cell pressures `pressure` \[MPa\]. For the whole field, call it once per depth:
    /// each call holds one depth, O(nx·ny) memory and O(nx·ny·log(nx·ny)) time.
    pub fn stress_field(&self, pressure: &[f64], depth: f64) -> Result<Vec<StressTensor>> {
        check_pressure(&self.name, pressure, self.nx * self.ny)?;
        let request = SubsurfaceRequest {
            depths: vec![depth],
            sections: vec![],
        };
        request.check()?;
        let mut fields = zero_fields(self.nx * self.ny);
        StressSolver::new(self, pressure, 0).depth(depth, &mut fields);
        let field: Vec<StressTensor> = (0..self.nx * self.ny).map(|k| tensor(&fields, k)).collect();
        match field.iter().position(|s| !s.is_finite()) {
            None => Ok(field),
            Some(k) => Err(not_finite(
                &self.name,
                format!("{:?} at cell {k}", field[k]),
            )),
        }
    }

    /// [`contopt_core::ElasticBody::subsurface`] for the grid: every cell centre at every
    /// requested depth for the peaks, and the row (or column) of cells nearest each section.
    pub fn stresses_below(
        &self,
        pressure: &[f64],
        request: &SubsurfaceRequest,
    ) -> Result<Subsurface> {
        let none = Images {
            reach: 0,
            mirrors: &[],
            weight: 0.0,
        };
        self.stresses_imaged(pressure, request, &none)
    }

    /// [`HalfSpace::stresses_below`] with the weighted `images` of the pressure added: the
    /// pressure's transform is taken once for every component and depth, and each depth's
    /// fields are read beyond the grid as far as the images reach.
    pub(crate) fn stresses_imaged(
        &self,
        pressure: &[f64],
        request: &SubsurfaceRequest,
        images: &Images,
    ) -> Result<Subsurface> {
        check_pressure(&self.name, pressure, self.nx * self.ny)?;
        request.check()?;
        let (nx, ny) = (self.nx, self.ny);
        let origin = self.interface.points()[0];
        let lines: Vec<(Section, Vec<usize>, Vec<f64>)> = request
            .sections
            .iter()
            .map(|s| self.section_cells(*s, origin))
            .collect();
        let mut fields = zero_fields((nx + 2 * images.reach) * ny);
        let mut solver = StressSolver::new(self, pressure, images.reach);
        let mut peaks = StressPeaks::default();
        let mut sections: Vec<SectionField> = lines
            .iter()
            .map(|(section, _, positions)| SectionField {
                section: *section,
                positions: positions.clone(),
                depths: request.depths.clone(),
                tensors: Vec::with_capacity(positions.len() * request.depths.len()),
            })
            .collect();
        for &z in &request.depths {
            solver.depth(z, &mut fields);
            let at = |k: usize| images.tensor(&fields, nx, k);
            for k in 0..nx * ny {
                let p = self.interface.points()[k];
                peaks.record(&at(k), p[0], p[1], z);
            }
            for (field, (_, cells, _)) in sections.iter_mut().zip(&lines) {
                field.tensors.extend(cells.iter().map(|&k| at(k)));
            }
        }
        Ok(Subsurface {
            peaks: peaks.finite(&self.name)?,
            sections,
        })
    }

    /// The cells of the row (or column) nearest a section, the section moved onto it, and
    /// the positions along it.
    pub(crate) fn section_cells(
        &self,
        section: Section,
        origin: [f64; 3],
    ) -> (Section, Vec<usize>, Vec<f64>) {
        let (nx, ny) = (self.nx, self.ny);
        let nearest = |at: f64, start: f64, step: f64, n: usize| {
            (((at - start) / step).round().max(0.0) as usize).min(n - 1)
        };
        match section.axis {
            SectionAxis::X => {
                let j = nearest(section.at, origin[1], self.dy, ny);
                let cells: Vec<usize> = (0..nx).map(|i| j * nx + i).collect();
                let positions = cells
                    .iter()
                    .map(|&k| self.interface.points()[k][0])
                    .collect();
                let at = origin[1] + j as f64 * self.dy;
                (Section { at, ..section }, cells, positions)
            }
            SectionAxis::Y => {
                let i = nearest(section.at, origin[0], self.dx, nx);
                let cells: Vec<usize> = (0..ny).map(|j| j * nx + i).collect();
                let positions = cells
                    .iter()
                    .map(|&k| self.interface.points()[k][1])
                    .collect();
                let at = origin[0] + i as f64 * self.dx;
                (Section { at, ..section }, cells, positions)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use contopt_core::{ElasticBody, Material};

    const NU: f64 = 0.3;

    fn steel() -> Material {
        Material::new(2e5, NU).unwrap()
    }

    /// Boussinesq's point force P = 1 at the origin (Johnson eqs. 3.21), stresses at
    /// (x, y, z) in Cartesian components: σ_r, σ_θ, σ_z, τ_rz rotated about z.
    fn boussinesq(x: f64, y: f64, z: f64) -> [f64; COMPONENTS] {
        let r2 = x * x + y * y;
        let rho = (r2 + z * z).sqrt();
        let c = 1.0 / (2.0 * PI);
        let s_r = c * ((1.0 - 2.0 * NU) / r2 * (1.0 - z / rho) - 3.0 * z * r2 / rho.powi(5));
        let s_t = -c * (1.0 - 2.0 * NU) * ((1.0 - z / rho) / r2 - z / rho.powi(3));
        let s_z = -3.0 * c * z.powi(3) / rho.powi(5);
        let t_rz = -3.0 * c * r2.sqrt() * z * z / rho.powi(5);
        let (cos, sin) = (x / r2.sqrt(), y / r2.sqrt());
        [
            s_r * cos * cos + s_t * sin * sin,
            s_r * sin * sin + s_t * cos * cos,
            s_z,
            (s_r - s_t) * sin * cos,
            t_rz * cos,
            t_rz * sin,
        ]
    }

    /// Abscissae and weights of the n-point Gauss–Legendre rule on [−1, 1] (Newton on Pₙ).
    fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
        (0..n)
            .map(|i| {
                let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
                loop {
                    let (mut p0, mut p1) = (1.0, x);
                    for k in 2..=n {
                        let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                        p0 = p1;
                        p1 = p2;
                    }
                    let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                    let step = p1 / dp;
                    x -= step;
                    if step.abs() < 1e-15 {
                        return (x, 2.0 / ((1.0 - x * x) * dp * dp));
                    }
                }
            })
            .collect()
    }

    /// Every component of the closed-form cell kernel equals Boussinesq's point force
    /// integrated over the cell by Gauss quadrature, at offsets near and far, above and
    /// beside the cell, at two depths: the corner functions and their parities are right.
    #[test]
    fn cell_kernel_is_the_integrated_point_force() {
        let (dx, dy) = (0.4, 0.25);
        let rule = gauss_legendre(24);
        for z in [0.3, 1.1] {
            let corners = Corners::new(6, 6, dx, dy, z, NU);
            for (di, dj) in [(0, 0), (1, 0), (0, -2), (-3, 2), (5, -4), (-1, -1)] {
                let (x, y) = (di as f64 * dx, dj as f64 * dy);
                let mut quad = [0.0; COMPONENTS];
                for &(u, wu) in &rule {
                    for &(v, wv) in &rule {
                        let w = wu * wv * 0.25 * dx * dy;
                        let s = boussinesq(x - 0.5 * dx * u, y - 0.5 * dy * v, z);
                        for c in 0..COMPONENTS {
                            quad[c] += w * s[c];
                        }
                    }
                }
                for (c, q) in quad.iter().enumerate() {
                    let k = corners.kernel_value(c, di, dj);
                    assert!(
                        (k - q).abs() < 1e-9,
                        "component {c} at ({di}, {dj}), z {z}: closed form {k}, quadrature {q}"
                    );
                }
            }
        }
    }

    /// An odd-sized grid centred on the origin with cell size `h`, loaded by
    /// `pressure(x, y)` at the cell centres, and the index of the centre cell.
    fn centred(
        nx: usize,
        ny: usize,
        h: [f64; 2],
        pressure: impl Fn(f64, f64) -> f64,
        periodic: bool,
    ) -> (HalfSpace, Vec<f64>, usize) {
        let origin = [
            -((nx - 1) as f64) / 2.0 * h[0],
            -((ny - 1) as f64) / 2.0 * h[1],
        ];
        let body = if periodic {
            HalfSpace::periodic("hs", steel(), nx, ny, h[0], h[1], origin)
        } else {
            HalfSpace::grid("hs", steel(), nx, ny, h[0], h[1], origin)
        }
        .unwrap();
        let p = body
            .interface()
            .points()
            .iter()
            .map(|x| pressure(x[0], x[1]))
            .collect();
        (body, p, (ny / 2) * nx + nx / 2)
    }

    /// The largest `criterion` along the axis and its depth, from the section through the
    /// centre cell.
    fn axis_peak(
        body: &HalfSpace,
        p: &[f64],
        depths: Vec<f64>,
        criterion: impl Fn(&StressTensor) -> f64,
    ) -> (f64, f64) {
        let request = SubsurfaceRequest {
            depths,
            sections: vec![Section {
                axis: SectionAxis::X,
                at: 0.0,
            }],
        };
        let sub = body.stresses_below(p, &request).unwrap();
        let section = &sub.sections[0];
        let centre = section.positions.len() / 2;
        assert!(section.positions[centre].abs() < 1e-12 && section.section.at.abs() < 1e-12);
        (0..section.depths.len())
            .map(|k| (criterion(section.at(k, centre)), section.depths[k]))
            .fold((f64::MIN, 0.0), |m, v| if v.0 > m.0 { v } else { m })
    }

    fn depths(from: f64, to: f64, step: f64) -> Vec<f64> {
        let n = ((to - from) / step).round() as usize;
        (0..=n).map(|k| from + k as f64 * step).collect()
    }

    /// Hertz line contact, ν = 0.3, as a strip 20 100 b long (cells 100 b along it, where
    /// the pressure does not change; the missing ends would shift σ_xx by (1 − 2ν)b/L):
    /// below its middle the largest shear is 0.3003 p₀ at 0.786 b and von Mises 0.5575 p₀
    /// at 0.704 b (McEwen's closed form on the axis, Johnson eq. 4.45), and the stresses
    /// follow that form at every depth.
    #[test]
    fn hertz_line_contact_below_the_axis() {
        let b = 1.0;
        let hertz = |x: f64, _: f64| (1.0 - (x / b).powi(2)).max(0.0).sqrt();
        let (body, p, centre) = centred(161, 201, [b / 64.0, 100.0 * b], hertz, false);
        let (tresca, z_t) = axis_peak(&body, &p, depths(0.70, 0.90, 0.004), |s| s.tresca());
        let (mises, z_m) = axis_peak(&body, &p, depths(0.60, 0.80, 0.004), |s| s.von_mises());
        assert!((tresca - 0.3003).abs() < 3e-4, "Tresca {tresca}");
        assert!((z_t - 0.786).abs() < 0.01, "Tresca at {z_t}");
        assert!((mises - 0.5575).abs() < 5e-4, "von Mises {mises}");
        assert!((z_m - 0.704).abs() < 0.01, "von Mises at {z_m}");
        let zs = [0.25, 0.5, 1.0, 2.0];
        let field: Vec<Vec<StressTensor>> = zs
            .iter()
            .map(|&z| body.stress_field(&p, z).unwrap())
            .collect();
        for (z, f) in zs.iter().zip(&field) {
            let root = (1.0 + z * z).sqrt();
            let xx = -((1.0 + 2.0 * z * z) / root - 2.0 * z);
            let zz = -1.0 / root;
            let s = f[centre];
            for (got, want, name) in [
                (s.xx, xx, "σ_xx"),
                (s.zz, zz, "σ_zz"),
                (s.yy, NU * (xx + zz), "σ_yy (plane strain)"),
            ] {
                assert!(
                    (got - want).abs() < 3e-4,
                    "{name} at z = {z}: {got} vs {want}"
                );
            }
            assert!(s.xz.abs() < 1e-12 && s.xy.abs() < 1e-12 && s.yz.abs() < 1e-9);
        }
    }

    /// The orthogonal shear of a line contact rolling across it: the largest |τ_xz| is
    /// 0.25·p₀ at z = 0.5·b, x = ±0.87·b (Johnson, *Contact Mechanics*, §4.2), and the peaks
    /// say so (to 2e-3 of p₀, a depth step, a cell and a half); |τ_yz| vanishes along the
    /// contact (below 1e-3 of p₀ at the cells' centres, 50 b from the strip's ends).
    #[test]
    fn orthogonal_shear_of_a_line_contact() {
        let b = 1.0;
        let hertz = |x: f64, _: f64| (1.0 - (x / b).powi(2)).max(0.0).sqrt();
        let (body, p, _) = centred(161, 201, [b / 64.0, 100.0 * b], hertz, false);
        let request = SubsurfaceRequest {
            depths: depths(0.40, 0.60, 0.01),
            sections: vec![],
        };
        let peaks = body.stresses_below(&p, &request).unwrap().peaks;
        let s = peaks.shear_xz;
        assert!((s.value - 0.25).abs() < 2e-3, "{s:?}");
        assert!((s.depth - 0.5).abs() < 0.011, "{s:?}");
        assert!((s.x.abs() - 0.866).abs() < 1.5 / 64.0, "{s:?}");
        assert!(peaks.shear_yz.value < 1e-3, "{:?}", peaks.shear_yz);
    }

    /// Hertz contact of a sphere, ν = 0.3: below the centre the largest shear is 0.310 p₀ at
    /// 0.481 a, von Mises 0.620 p₀ there (Johnson eq. 3.45 on the axis).
    #[test]
    fn hertz_sphere_below_the_axis() {
        let a = 1.0;
        let hertz = |x: f64, y: f64| (1.0 - (x * x + y * y) / (a * a)).max(0.0).sqrt();
        let (body, p, centre) = centred(81, 81, [a / 32.0; 2], hertz, false);
        let (tresca, z_t) = axis_peak(&body, &p, depths(0.40, 0.56, 0.004), |s| s.tresca());
        let (mises, z_m) = axis_peak(&body, &p, depths(0.40, 0.56, 0.004), |s| s.von_mises());
        assert!((tresca - 0.310).abs() < 2e-3, "Tresca {tresca}");
        assert!((z_t - 0.481).abs() < 0.012, "Tresca at {z_t}");
        assert!((mises - 0.620).abs() < 4e-3, "von Mises {mises}");
        assert!((z_m - 0.481).abs() < 0.012, "von Mises at {z_m}");
        for z in [0.3, 0.6, 1.5] {
            let s = body.stress_field(&p, z).unwrap()[centre];
            let zs = z / a;
            let zz = -1.0 / (1.0 + zs * zs);
            let rr = -((1.0 + NU) * (1.0 - zs * (1.0 / zs).atan()) - 0.5 / (1.0 + zs * zs));
            assert!((s.zz - zz).abs() < 3e-3, "σ_zz at {z}: {} vs {zz}", s.zz);
            assert!(
                (s.xx - rr).abs() < 3e-3 && (s.yy - rr).abs() < 3e-3,
                "σ_r at {z}"
            );
        }
    }

    /// A uniform pressure on a circle of radius a (cells whose centre lies inside): on the
    /// axis, Love's closed form (Johnson eqs. 3.37–3.38) at several depths, to the
    /// staircase's error; and on a rectangle of cells, Newmark's σ_zz under its centre
    /// exactly.
    #[test]
    fn uniform_circle_and_rectangle() {
        let a = 1.0;
        let disc = |x: f64, y: f64| if x * x + y * y < a * a { 1.0 } else { 0.0 };
        let (body, p, centre) = centred(101, 101, [a / 40.0; 2], disc, false);
        for z in [0.2, 0.5, 1.0, 3.0] {
            let s = body.stress_field(&p, z).unwrap()[centre];
            let c = z / (a * a + z * z).sqrt();
            let zz = -(1.0 - c.powi(3));
            let rr = -0.5 * ((1.0 + 2.0 * NU) - 2.0 * (1.0 + NU) * c + c.powi(3));
            assert!((s.zz - zz).abs() < 2e-3, "σ_zz at {z}: {} vs {zz}", s.zz);
            assert!((s.xx - rr).abs() < 2e-3, "σ_r at {z}: {} vs {rr}", s.xx);
            assert!((s.yy - s.xx).abs() < 1e-9, "σ_θ = σ_r on the axis");
        }
        // Cells |i| ≤ 3, |j| ≤ 2 of a 0.2 × 0.3 grid: the rectangle 1.4 × 1.5.
        let (half_a, half_b) = (0.7, 0.75);
        let block = |x: f64, y: f64| {
            if x.abs() < half_a && y.abs() < half_b {
                2.0
            } else {
                0.0
            }
        };
        let (body, p, centre) = centred(15, 11, [0.2, 0.3], block, false);
        for z in [0.1, 0.7, 2.5] {
            let s = body.stress_field(&p, z).unwrap()[centre];
            let r = (half_a * half_a + half_b * half_b + z * z).sqrt();
            let corner = ((half_a * half_b / (z * r)).atan()
                + half_a * half_b * z / r
                    * (1.0 / (half_a * half_a + z * z) + 1.0 / (half_b * half_b + z * z)))
                / (2.0 * PI);
            assert!((s.zz + 2.0 * 4.0 * corner).abs() < 1e-10, "Newmark at {z}");
        }
    }

    /// A sinusoidal pressure on a periodic grid, oblique to the axes: the plane-strain
    /// sinusoid of Johnson §2.6 along its wave vector, to round-off.
    #[test]
    fn periodic_sinusoid_exactly() {
        let (nx, ny, h) = (24, 20, [0.1, 0.15]);
        let (lx, ly) = (nx as f64 * h[0], ny as f64 * h[1]);
        let (qx, qy) = (2.0 * PI * 2.0 / lx, 2.0 * PI / ly);
        let q = qx.hypot(qy);
        let wave = |x: f64, y: f64| (qx * x + qy * y).cos();
        let (body, p, _) = centred(nx, ny, h, wave, true);
        let z = 0.4;
        let field = body.stress_field(&p, z).unwrap();
        let (n_x, n_y, e) = (qx / q, qy / q, (-q * z).exp());
        for (x, s) in body.interface().points().iter().zip(&field) {
            let (cos, sin) = ((qx * x[0] + qy * x[1]).cos(), (qx * x[0] + qy * x[1]).sin());
            let nn = -(1.0 - q * z) * e * cos;
            let tt = -2.0 * NU * e * cos;
            let nz = -q * z * e * sin;
            let want = [
                n_x * n_x * nn + n_y * n_y * tt,
                n_y * n_y * nn + n_x * n_x * tt,
                -(1.0 + q * z) * e * cos,
                n_x * n_y * (nn - tt),
                n_x * nz,
                n_y * nz,
            ];
            let got = [s.xx, s.yy, s.zz, s.xy, s.xz, s.yz];
            for c in 0..COMPONENTS {
                assert!((got[c] - want[c]).abs() < 1e-12, "component {c}");
            }
        }
    }

    /// A uniform pressure on a periodic grid: σ_zz = −p at every depth, and the lateral
    /// stresses of a uniform load on a wide disc, −(1 + 2ν)/2·p (the convention for the
    /// mean, which a periodic surface leaves open).
    #[test]
    fn periodic_mean_pressure() {
        let (body, p, _) = centred(9, 7, [0.1, 0.1], |_, _| 3.0, true);
        for s in body.stress_field(&p, 0.35).unwrap() {
            assert!((s.zz + 3.0).abs() < 1e-12);
            assert!((s.xx + 1.5 * (1.0 + 2.0 * NU)).abs() < 1e-12 && (s.yy - s.xx).abs() < 1e-12);
            assert!(s.xy.abs() + s.xz.abs() + s.yz.abs() < 1e-12);
        }
    }

    /// Peaks, sections and the errors of a request.
    #[test]
    fn request_peaks_sections_and_errors() {
        let hertz = |x: f64, y: f64| 1000.0 * (1.0 - x * x - y * y).max(0.0).sqrt();
        let (body, p, _) = centred(41, 31, [0.1, 0.1], hertz, false);
        let request = SubsurfaceRequest {
            depths: depths(0.1, 1.0, 0.05),
            sections: vec![
                Section {
                    axis: SectionAxis::X,
                    at: 0.52,
                },
                Section {
                    axis: SectionAxis::Y,
                    at: -0.03,
                },
            ],
        };
        let sub = body.stresses_below(&p, &request).unwrap();
        let peaks = sub.peaks;
        assert!((peaks.tresca.depth - 0.5).abs() < 0.051, "{peaks:?}");
        assert!(peaks.tresca.x.abs() < 1e-9 && peaks.tresca.y.abs() < 1e-9);
        assert!(peaks.min_principal.value < -900.0 && peaks.min_principal.depth == 0.1);
        assert!((sub.sections[0].section.at - 0.5).abs() < 1e-12);
        assert_eq!(sub.sections[0].positions.len(), 41);
        assert_eq!(sub.sections[1].positions.len(), 31);
        assert!(sub.sections[1].section.at.abs() < 1e-12);
        assert_eq!(sub.sections[1].tensors.len(), 31 * request.depths.len());
        let bad_depth = SubsurfaceRequest {
            depths: vec![0.5, -1.0],
            sections: vec![],
        };
        let e = body.stresses_below(&p, &bad_depth).unwrap_err().to_string();
        assert!(e.contains("depths[1]") && e.contains("-1"), "{e}");
        let e = body
            .stresses_below(&p[1..], &request)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("hs.subsurface.pressure") && e.contains("1270"),
            "{e}"
        );
        let mut nan = p.clone();
        nan[3] = f64::NAN;
        let e = body.stress_field(&nan, 0.5).unwrap_err().to_string();
        assert!(e.contains("pressure[3]"), "{e}");
        // Finite pressures whose stresses overflow f64: an error, not infinities.
        let e = body
            .stress_field(&vec![1e308; p.len()], 0.5)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("hs.subsurface") && e.contains("not finite"),
            "{e}"
        );
    }
}
