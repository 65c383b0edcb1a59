//! Zero-padded FFT convolution with a translation-invariant, even kernel on an nx × ny grid:
//! the influence product of a half-space grid in O(N log N) time and O(N) memory (N = nx·ny),
//! exact (not periodic) because the grid is padded to 2nx × 2ny.

use std::sync::{Arc, Mutex};

use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

/// Buffers reused by every product (the hot loop of iterative solvers allocates nothing).
struct Work {
    row: Vec<f64>,
    row_spectrum: Vec<Complex<f64>>,
    columns: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
}

pub(crate) struct Convolution {
    nx: usize,
    ny: usize,
    py: usize,
    /// Spectrum of the padded kernel, column-major: [i·py + j] for x-frequency i; real,
    /// because the kernel is even.
    spectrum: Vec<f64>,
    /// Its reciprocal: the circulant approximation of the inverse operator (the padded
    /// spectrum of a positive kernel such as Love's is positive).
    inverse: Vec<f64>,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    forward_y: Arc<dyn Fft<f64>>,
    inverse_y: Arc<dyn Fft<f64>>,
    work: Mutex<Work>,
}

impl std::fmt::Debug for Convolution {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "Convolution {{ {} x {} padded to {} x {} }}",
            self.nx,
            self.ny,
            2 * self.nx,
            self.py
        )
    }
}

impl Convolution {
    /// The convolution with `kernel(|Δi|, |Δj|)` (|Δi| < nx, |Δj| < ny).
    pub fn new(nx: usize, ny: usize, kernel: impl Fn(usize, usize) -> f64) -> Self {
        let (px, py) = (2 * nx, 2 * ny);
        let mut real = RealFftPlanner::<f64>::new();
        let mut complex = FftPlanner::<f64>::new();
        let r2c = real.plan_fft_forward(px);
        let c2r = real.plan_fft_inverse(px);
        let forward_y = complex.plan_fft_forward(py);
        let inverse_y = complex.plan_fft_inverse(py);
        let cx = px / 2 + 1;
        let scratch_len = [
            r2c.get_scratch_len(),
            c2r.get_scratch_len(),
            forward_y.get_inplace_scratch_len(),
            inverse_y.get_inplace_scratch_len(),
        ]
        .into_iter()
        .max()
        .unwrap_or(0);
        let work = Work {
            row: vec![0.0; px],
            row_spectrum: vec![Complex::new(0.0, 0.0); cx],
            columns: vec![Complex::new(0.0, 0.0); cx * py],
            scratch: vec![Complex::new(0.0, 0.0); scratch_len],
        };
        let mut conv = Self {
            nx,
            ny,
            py,
            spectrum: vec![],
            inverse: vec![],
            r2c,
            c2r,
            forward_y,
            inverse_y,
            work: Mutex::new(work),
        };
        // Distance along an axis on the padded (circular) grid; the middle entry is never used.
        let distance = |i: usize, n: usize| {
            if i < n {
                Some(i)
            } else if i > n {
                Some(2 * n - i)
            } else {
                None
            }
        };
        let padded: Vec<f64> = (0..py)
            .flat_map(|j| (0..px).map(move |i| (i, j)))
            .map(|(i, j)| match (distance(i, nx), distance(j, ny)) {
                (Some(a), Some(b)) => kernel(a, b),
                _ => 0.0,
            })
            .collect();
        let mut work = conv.work.lock().expect("fresh lock");
        conv.forward(&mut work, &padded, px, py);
        let spectrum: Vec<f64> = work.columns.iter().map(|c| c.re).collect();
        drop(work);
        conv.inverse = spectrum
            .iter()
            .map(|&s| if s > 0.0 { 1.0 / s } else { 0.0 })
            .collect();
        conv.spectrum = spectrum;
        conv
    }

    /// Transforms a real field of `width` × `rows` (x fastest, zero beyond) into
    /// `work.columns`.
    fn forward(&self, work: &mut Work, field: &[f64], width: usize, rows: usize) {
        let (px, py) = (2 * self.nx, self.py);
        let cx = px / 2 + 1;
        for c in work.columns.iter_mut() {
            *c = Complex::new(0.0, 0.0);
        }
        for j in 0..rows {
            work.row[..width].copy_from_slice(&field[j * width..(j + 1) * width]);
            work.row[width..].fill(0.0);
            self.r2c
                .process_with_scratch(&mut work.row, &mut work.row_spectrum, &mut work.scratch)
                .expect("buffer lengths match the plan");
            for i in 0..cx {
                work.columns[i * py + j] = work.row_spectrum[i];
            }
        }
        self.forward_y
            .process_with_scratch(&mut work.columns, &mut work.scratch);
    }

    /// output = kernel ∗ input on the nx × ny grid (x fastest).
    pub fn apply(&self, input: &[f64], output: &mut [f64]) {
        self.convolve(&self.spectrum, input, output);
    }

    /// The circulant approximate inverse: output = kernel⁻¹ ∗ input, for preconditioning.
    pub fn apply_inverse(&self, input: &[f64], output: &mut [f64]) {
        self.convolve(&self.inverse, input, output);
    }

    fn convolve(&self, spectrum: &[f64], input: &[f64], output: &mut [f64]) {
        let (nx, ny, px, py) = (self.nx, self.ny, 2 * self.nx, self.py);
        let cx = px / 2 + 1;
        let mut work = self
            .work
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        self.forward(&mut work, input, nx, ny);
        for (c, s) in work.columns.iter_mut().zip(spectrum) {
            *c *= s;
        }
        let Work {
            row,
            row_spectrum,
            columns,
            scratch,
        } = &mut *work;
        self.inverse_y.process_with_scratch(columns, scratch);
        let scale = 1.0 / (px * py) as f64;
        for j in 0..ny {
            for i in 0..cx {
                row_spectrum[i] = columns[i * py + j];
            }
            // The input of a real inverse transform has real end points.
            row_spectrum[0].im = 0.0;
            row_spectrum[cx - 1].im = 0.0;
            self.c2r
                .process_with_scratch(row_spectrum, row, scratch)
                .expect("buffer lengths match the plan");
            for i in 0..nx {
                output[j * nx + i] = row[i] * scale;
            }
        }
    }
}
