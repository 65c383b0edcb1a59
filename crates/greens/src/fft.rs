//! FFT convolution with a translation-invariant, even kernel on an nx × ny grid: the influence
//! product of a half-space grid in O(N log N) time and O(N) memory (N = nx·ny). A free
//! (non-periodic) grid is padded to 2nx × 2ny so the circular product is the exact linear
//! one; a periodic grid is transformed as it is.

use std::sync::Arc;

use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

use contopt_core::Spares;

/// Buffers reused by every product (the hot loop of iterative solvers allocates nothing); a
/// set per product running at once ([`Spares`]). Only the ny rows of the field are held in the x-transformed form, not the py rows of the
/// padded grid: the columns are padded, transformed, multiplied and transformed back a block
/// at a time, which halves the largest buffer of a free grid.
struct Work {
    row: Vec<f64>,
    /// The x-spectra of the ny rows, row after row: [j·cx + i].
    rows: Vec<Complex<f64>>,
    /// A block of [`BLOCK`] columns, each of py values, one after another.
    block: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
}

/// Columns transformed together: a block is gathered from the rows in runs of this many
/// neighbouring values (a run fills whole cache lines), and its transforms share one call.
const BLOCK: usize = 16;

/// The transforms of a `px` × `py` grid: real rows along x, complex columns along y, and the
/// scratch length that serves all four.
pub(crate) struct Plans {
    pub r2c: Arc<dyn RealToComplex<f64>>,
    pub c2r: Arc<dyn ComplexToReal<f64>>,
    pub forward_y: Arc<dyn Fft<f64>>,
    pub inverse_y: Arc<dyn Fft<f64>>,
    pub scratch: usize,
}

impl Plans {
    pub fn new(px: usize, py: usize) -> Self {
        let (mut real, mut complex) = (RealFftPlanner::new(), FftPlanner::new());
        let (r2c, c2r) = (real.plan_fft_forward(px), real.plan_fft_inverse(px));
        let (forward_y, inverse_y) = (complex.plan_fft_forward(py), complex.plan_fft_inverse(py));
        let scratch = [
            r2c.get_scratch_len(),
            c2r.get_scratch_len(),
            forward_y.get_inplace_scratch_len(),
            inverse_y.get_inplace_scratch_len(),
        ]
        .into_iter()
        .max()
        .unwrap_or(0);
        Self {
            r2c,
            c2r,
            forward_y,
            inverse_y,
            scratch,
        }
    }
}

pub(crate) struct Convolution {
    nx: usize,
    ny: usize,
    /// Transformed lengths: 2nx × 2ny (free) or nx × ny (periodic).
    px: usize,
    py: usize,
    /// Columns of the output beyond the field's each side ([`Convolution::wide`]; 0 else).
    reach: usize,
    /// Spectrum of the (padded) kernel, column-major: [i·(py/2 + 1) + j] for x-frequency i
    /// and y-frequency j ≤ py/2; real and even in j (the kernel is even), so that frequency
    /// py − j is j's. Its reciprocal, where positive, is the circulant approximation of the
    /// inverse operator used for preconditioning.
    spectrum: Vec<f64>,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    forward_y: Arc<dyn Fft<f64>>,
    inverse_y: Arc<dyn Fft<f64>>,
    /// The scratch length of the four transforms.
    scratch: usize,
    work: Spares<Work>,
}

impl std::fmt::Debug for Convolution {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "Convolution {{ {} x {} transformed as {} x {} }}",
            self.nx, self.ny, self.px, self.py
        )
    }
}

impl Convolution {
    /// Plans the transforms of a `px` × `py` grid holding an `nx` × `ny` field, read `reach`
    /// columns beyond it each side; with a set of work buffers when `work`, else the first
    /// product that finds none free makes one ([`Spares::with`]).
    fn plan(nx: usize, ny: usize, [px, py]: [usize; 2], reach: usize, work: bool) -> Self {
        let Plans {
            r2c,
            c2r,
            forward_y,
            inverse_y,
            scratch: scratch_len,
        } = Plans::new(px, py);
        let mut conv = Self {
            nx,
            ny,
            px,
            py,
            reach,
            spectrum: vec![],
            r2c,
            c2r,
            forward_y,
            inverse_y,
            scratch: scratch_len,
            work: Spares::default(),
        };
        if work {
            conv.work = Spares::new(conv.new_work());
        }
        conv
    }

    /// A set of work buffers for one product.
    fn new_work(&self) -> Work {
        let cx = self.px / 2 + 1;
        Work {
            row: vec![0.0; self.px],
            rows: vec![Complex::new(0.0, 0.0); cx * self.ny],
            block: vec![Complex::new(0.0, 0.0); BLOCK * self.py],
            scratch: vec![Complex::new(0.0, 0.0); self.scratch],
        }
    }

    /// The exact (linear, non-periodic) convolution with `kernel(|Δi|, |Δj|)` (|Δi| < nx,
    /// |Δj| < ny), by zero padding to 2nx × 2ny.
    ///
    /// The padded grid is a period of the kernel at the circular distance, `kernel(a, b)` with
    /// a = min(i, 2nx − i) ≤ nx and b ≤ ny: the distances nx and ny never reach the field's
    /// cells, so the product is the same for any value there, but the value decides whether
    /// the circulant is positive. With the kernel's own values it is the kernel's periodic
    /// repetition, positive like the kernel; with zeros there (a gap in the period) its spectrum
    /// turns negative at some frequencies (anisotropic cells, odd sides), and its inverse would
    /// be no approximation of the operator's there (the preconditioner of a free grid is the
    /// circulant on its own grid, [`Convolution::folded`], with the kernel's own values). (The
    /// grids use [`Convolution::free_fast`]; this one's padding is the tests' reference.)
    #[cfg(test)]
    pub fn free(nx: usize, ny: usize, kernel: impl Fn(usize, usize) -> f64) -> Self {
        Self::padded(nx, ny, [2 * nx, 2 * ny], 0, kernel)
    }

    /// The circulant on the field's own grid, each side only lengthened to a fast length
    /// ([`fast_length`]), with `kernel` at the circular distances: the kernel's periodic
    /// repetition over about the field's size, positive like the kernel (test
    /// `padded_circulant_is_positive`). Its product wraps, so it is no influence product; its
    /// inverse ([`Convolution::apply_inverse`]) preconditions a free grid at about a quarter
    /// of the padded grid's transforms. Measured on the flat punch (`halfspace_peers --one-row
    /// punch N`, CPU): 14, 16, 17 steps at 256², 1024², 2048² against 13, 15, 17 with the
    /// padded circulant's inverse, 0.47 against 0.53 s at 1024², 2.28 against 2.52 s at 2048².
    ///
    /// It holds no work buffers of its own: its products borrow a lender's
    /// ([`Convolution::apply_inverse_in`]), so that it adds only its spectrum, a quarter of
    /// the field's values, to the grid's memory.
    pub fn folded(nx: usize, ny: usize, kernel: impl Fn(usize, usize) -> f64) -> Self {
        Self::padded_with(nx, ny, [fast_length(nx), fast_length(ny)], 0, false, kernel)
    }

    /// The padded lengths of [`Convolution::free_fast`]: [`fast_length`] of 2nx and of 2ny.
    pub fn free_lengths(nx: usize, ny: usize) -> [usize; 2] {
        [fast_length(2 * nx), fast_length(2 * ny)]
    }

    /// As [`Convolution::free`], padded to the faster lengths [`Convolution::free_lengths`]
    /// (`kernel` asked for distances up to half of each): the same exact product, whatever the
    /// padding beyond 2n, since no distance between two cells of the field reaches n; the
    /// circulant preconditioner is the kernel's repetition over the longer period, positive
    /// as over 2n.
    pub fn free_fast(nx: usize, ny: usize, kernel: impl Fn(usize, usize) -> f64) -> Self {
        Self::padded(nx, ny, Self::free_lengths(nx, ny), 0, kernel)
    }

    /// The padded length along x of [`Convolution::wide`]: the smallest with prime factors 2,
    /// 3, 5 and 7 (fast transforms) of at least 2(nx + reach).
    pub fn wide_length(nx: usize, reach: usize) -> usize {
        smooth_at_least(2 * (nx + reach), usize::MAX)
    }

    /// As [`Convolution::free`], with the product also read `reach` columns beyond the field
    /// each side (an output nx + 2·reach wide, its column `reach` the field's first): the
    /// padded length along x is [`Convolution::wide_length`], and `kernel` is asked for
    /// distances |Δi| up to half of it. Every output column is the exact linear product: its
    /// distances to the field's cells are below nx + reach, at most half the period, so the
    /// circular kernel min(a, px − a) is the kernel there, and no column wraps onto another.
    /// A grid's images beyond its free faces are read so from one product of the field alone
    /// ([`crate::FreeEnds`]).
    pub fn wide(nx: usize, ny: usize, reach: usize, kernel: impl Fn(usize, usize) -> f64) -> Self {
        Self::padded(
            nx,
            ny,
            [Self::wide_length(nx, reach), 2 * ny],
            reach,
            kernel,
        )
    }

    /// The free product on a grid padded to `px` × `py`, the kernel at the circular distances.
    fn padded(
        nx: usize,
        ny: usize,
        [px, py]: [usize; 2],
        reach: usize,
        kernel: impl Fn(usize, usize) -> f64,
    ) -> Self {
        Self::padded_with(nx, ny, [px, py], reach, true, kernel)
    }

    /// [`Convolution::padded`], with a set of work buffers of its own when `work`.
    fn padded_with(
        nx: usize,
        ny: usize,
        [px, py]: [usize; 2],
        reach: usize,
        work: bool,
        kernel: impl Fn(usize, usize) -> f64,
    ) -> Self {
        let mut conv = Self::plan(nx, ny, [px, py], reach, work);
        let distance = |i: usize, period: usize| i.min(period - i);
        // The padded kernel fills all py rows, row py − j the same as row j: its rows up to
        // py/2 transformed along x, once; the columns read the others' mirror images.
        let cx = px / 2 + 1;
        let hy = py / 2 + 1;
        let mut spectra = vec![Complex::new(0.0, 0.0); cx * hy];
        let (mut row, mut block) = (vec![0.0; px], vec![Complex::new(0.0, 0.0); py]);
        let mut scratch = vec![Complex::new(0.0, 0.0); conv.scratch];
        for j in 0..hy {
            for (i, v) in row.iter_mut().enumerate() {
                *v = kernel(distance(i, px), distance(j, py));
            }
            conv.r2c
                .process_with_scratch(&mut row, &mut spectra[j * cx..(j + 1) * cx], &mut scratch)
                .expect("buffer lengths match the plan");
        }
        let mut spectrum = vec![0.0; cx * hy];
        let column = &mut block[..];
        for i in 0..cx {
            for (j, c) in column.iter_mut().enumerate() {
                *c = spectra[distance(j, py) * cx + i];
            }
            conv.forward_y.process_with_scratch(column, &mut scratch);
            for (s, c) in spectrum[i * hy..(i + 1) * hy].iter_mut().zip(column.iter()) {
                *s = c.re;
            }
        }
        conv.spectrum = spectrum;
        conv
    }

    /// The periodic (circular) convolution on the nx × ny grid whose spectrum at the signed
    /// frequency indices (i, j) is `spectrum(i, j)` (even in each index).
    pub fn periodic(nx: usize, ny: usize, spectrum: impl Fn(isize, isize) -> f64) -> Self {
        let mut conv = Self::plan(nx, ny, [nx, ny], 0, true);
        let signed = |k: usize, n: usize| {
            if 2 * k <= n {
                k as isize
            } else {
                k as isize - n as isize
            }
        };
        let (cx, hy) = (nx / 2 + 1, ny / 2 + 1);
        conv.spectrum = (0..cx)
            .flat_map(|i| (0..hy).map(move |j| (i, j)))
            .map(|(i, j)| spectrum(signed(i, nx), signed(j, ny)))
            .collect();
        conv
    }

    /// The smallest value of the kernel's spectrum (the circulant's smallest eigenvalue).
    #[cfg(test)]
    pub fn smallest_eigenvalue(&self) -> f64 {
        self.spectrum.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// output = kernel ∗ input on the nx × ny grid (x fastest); on a [`Convolution::wide`]
    /// one the output rows are nx + 2·reach long.
    pub fn apply(&self, input: &[f64], output: &mut [f64]) {
        self.convolve(|s| s, input, output);
    }

    /// The circulant approximate inverse: output = kernel⁻¹ ∗ input, for preconditioning
    /// (modes the kernel does not resist, such as the mean of a periodic grid, are dropped).
    pub fn apply_inverse(&self, input: &[f64], output: &mut [f64]) {
        self.convolve(inverse, input, output);
    }

    /// [`Convolution::apply_inverse`] in the work buffers of `lender`, a convolution of the
    /// same field whose transforms are at least as long (a grid's padded product lending to
    /// its [`Convolution::folded`] preconditioner); in buffers of its own otherwise.
    pub fn apply_inverse_in(&self, lender: &Convolution, input: &[f64], output: &mut [f64]) {
        let fits = (self.nx, self.ny) == (lender.nx, lender.ny)
            && self.px <= lender.px
            && self.py <= lender.py
            && self.scratch <= lender.scratch;
        if fits {
            lender.work.with(
                || lender.new_work(),
                |work| self.convolve_on(work, inverse, input, output),
            );
        } else {
            self.apply_inverse(input, output);
        }
    }

    fn convolve(&self, multiplier: impl Fn(f64) -> f64, input: &[f64], output: &mut [f64]) {
        self.work.with(
            || self.new_work(),
            |work| self.convolve_on(work, multiplier, input, output),
        );
    }

    /// [`Convolution::convolve`] on one set of work buffers.
    fn convolve_on(
        &self,
        work: &mut Work,
        multiplier: impl Fn(f64) -> f64,
        input: &[f64],
        output: &mut [f64],
    ) {
        let (nx, ny, px, py) = (self.nx, self.ny, self.px, self.py);
        let (cx, hy) = (px / 2 + 1, py / 2 + 1);
        // A lender's buffers may be longer ([`Convolution::apply_inverse_in`]): each is cut to
        // this grid's lengths.
        let row = &mut work.row[..px];
        let rows = &mut work.rows[..cx * ny];
        let block = &mut work.block[..BLOCK * py];
        let scratch = &mut work.scratch[..self.scratch];
        for (j, spectrum) in rows.chunks_exact_mut(cx).enumerate() {
            row[..nx].copy_from_slice(&input[j * nx..(j + 1) * nx]);
            row[nx..].fill(0.0);
            self.r2c
                .process_with_scratch(row, spectrum, scratch)
                .expect("buffer lengths match the plan");
        }
        for i0 in (0..cx).step_by(BLOCK) {
            let width = BLOCK.min(cx - i0);
            let columns = &mut block[..width * py];
            for j in 0..ny {
                for (b, &c) in rows[j * cx + i0..j * cx + i0 + width].iter().enumerate() {
                    columns[b * py + j] = c;
                }
            }
            for column in columns.chunks_exact_mut(py) {
                column[ny..].fill(Complex::new(0.0, 0.0));
            }
            self.forward_y.process_with_scratch(columns, scratch);
            for (b, column) in columns.chunks_exact_mut(py).enumerate() {
                let kernel = &self.spectrum[(i0 + b) * hy..(i0 + b + 1) * hy];
                for (j, c) in column.iter_mut().enumerate() {
                    *c *= multiplier(kernel[j.min(py - j)]);
                }
            }
            self.inverse_y.process_with_scratch(columns, scratch);
            for j in 0..ny {
                for (b, c) in rows[j * cx + i0..j * cx + i0 + width]
                    .iter_mut()
                    .enumerate()
                {
                    *c = columns[b * py + j];
                }
            }
        }
        let scale = 1.0 / (px * py) as f64;
        let width = nx + 2 * self.reach;
        for (j, spectrum) in rows.chunks_exact_mut(cx).enumerate() {
            // The input of a real inverse transform has real end points (the last one only
            // when the length is even).
            spectrum[0].im = 0.0;
            if px % 2 == 0 {
                spectrum[cx - 1].im = 0.0;
            }
            self.c2r
                .process_with_scratch(spectrum, row, scratch)
                .expect("buffer lengths match the plan");
            // Column −reach + o of the field is the row's (o − reach) mod px.
            let (before, rest) = output[j * width..(j + 1) * width].split_at_mut(self.reach);
            for (o, r) in before.iter_mut().zip(&row[px - self.reach..]) {
                *o = r * scale;
            }
            for (o, r) in rest.iter_mut().zip(row.iter()) {
                *o = r * scale;
            }
        }
    }
}

/// The circulant inverse's multiplier of a spectrum value: its reciprocal where positive,
/// 0 for modes the kernel does not resist (the mean of a periodic grid).
fn inverse(s: f64) -> f64 {
    if s > 0.0 {
        1.0 / s
    } else {
        0.0
    }
}

/// The smallest length ≥ `n` (at most `max`) whose prime factors are 2, 3, 5 and 7, for
/// which FFTs are fast.
pub(crate) fn smooth_at_least(n: usize, max: usize) -> usize {
    let smooth = |mut m: usize| {
        for f in [2, 3, 5, 7] {
            while m.is_multiple_of(f) {
                m /= f;
            }
        }
        m == 1
    };
    (n.min(max)..=max).find(|&m| smooth(m)).unwrap_or(max)
}

/// The smallest even length ≥ `n` whose prime factors are 2 and 3 with at most one 5: the FFT
/// lengths rustfft transforms fastest per point. One padded FFT pair (rows and columns, as
/// [`Convolution::apply`] does it, one core, CPU time) on a 525² field took 7.5 ms at 1050
/// (2·3·5²·7), 6.3 at 1080 (2³·3³·5), 6.4 at 1152, 6.5 at 1120 (2⁵·5·7) and 7.5 at 1176
/// (2³·3·7²); on a 1029² field 34 ms at 2058 (2·3·7³), 26 at 2160 (2⁴·3³·5), 30 at 2240,
/// 34 at 2304; on a 417² field 16.5 ms at 834 (2·3·139), 4.1 at 840 and 4.4 at 864. Even,
/// since a real transform of an odd length is a complex one of the whole length: on a 200²
/// field 1.02 ms at 405 = 3⁴·5, 0.75 at 400 and 0.70 at 432.
pub(crate) fn fast_length(n: usize) -> usize {
    let fast = |m: usize| {
        let mut odd = m / 2;
        while odd.is_multiple_of(2) {
            odd /= 2;
        }
        while odd.is_multiple_of(3) {
            odd /= 3;
        }
        odd == 1 || odd == 5
    };
    let first = n.max(2).next_multiple_of(2);
    (first..).step_by(2).find(|&m| fast(m)).unwrap_or(first)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fast lengths: even, 2ᵃ·3ᵇ with at most one 5, the least at or above n.
    #[test]
    fn fast_lengths() {
        for (n, fast) in [
            (1, 2),
            (7, 8),
            (14, 16),
            (400, 432),
            (1034, 1080),
            (1050, 1080),
            (2058, 2160),
            (834, 864),
            (4096, 4096),
        ] {
            assert_eq!(fast_length(n), fast, "{n}");
        }
    }
}
