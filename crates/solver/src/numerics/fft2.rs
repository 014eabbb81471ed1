//! Row-pruned 2-D real FFT: transforms only the rows that hold the droplet window.
//!
//! Forward: `r2c` along x on the rows `lo..=hi` (all other rows are taken as zero), then
//! complex FFTs along y on the `N/2 + 1` columns, stored contiguously (kx-major).
//! Inverse: complex inverse FFTs along y on every column, then `c2r` along x only on the rows
//! `lo..=hi`. Both are exact: skipping a zero row, or a row nobody reads, changes nothing.
//! Plans and scratch buffers are made once; nothing is allocated per transform.
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// Rows transposed together in the forward transform.
const BLOCK: usize = 8;

/// Columns whose derivatives are formed and transformed together in
/// [`PrunedFft2::inverse_gradient`].
const COLUMNS: usize = 8;

/// Plans plus the scratch buffers of one worker.
pub struct PrunedFft2 {
    n: usize,
    /// Row spectra of up to `BLOCK` rows, transposed into the output together.
    block: Vec<Complex64>,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    col_fwd: Arc<dyn Fft<f64>>,
    col_inv: Arc<dyn Fft<f64>>,
    row_real: Vec<f64>,
    row_scratch: Vec<Complex64>,
    col_scratch: Vec<Complex64>,
    /// [`Self::inverse_gradient`]'s buffers (empty until its first call): the derivatives'
    /// columns transformed along y, and a block of columns being transformed.
    grad_cols: [Vec<Complex64>; 2],
    grad_block: [Vec<Complex64>; 2],
}

impl PrunedFft2 {
    /// Plans the transforms for an `n x n` grid.
    pub fn new(n: usize) -> Self {
        let mut real_planner = RealFftPlanner::<f64>::new();
        let r2c = real_planner.plan_fft_forward(n);
        let c2r = real_planner.plan_fft_inverse(n);
        let mut planner = FftPlanner::<f64>::new();
        let col_fwd = planner.plan_fft_forward(n);
        let col_inv = planner.plan_fft_inverse(n);
        let row_scratch_len = r2c.get_scratch_len().max(c2r.get_scratch_len());
        let col_scratch_len = col_fwd
            .get_inplace_scratch_len()
            .max(col_inv.get_inplace_scratch_len());
        Self {
            n,
            block: vec![Complex64::default(); BLOCK * (n / 2 + 1)],
            row_real: vec![0.0; n],
            row_scratch: vec![Complex64::default(); row_scratch_len],
            col_scratch: vec![Complex64::default(); col_scratch_len],
            grad_cols: Default::default(),
            grad_block: Default::default(),
            r2c,
            c2r,
            col_fwd,
            col_inv,
        }
    }

    /// Unnormalised forward transform of `real` (row-major `N x N`), whose rows outside
    /// `lo..=hi` are zero, into `spec` (`[kx][ky]`); `real` is left as it was (each row is
    /// copied into a row buffer the real transform may overwrite).
    pub fn forward(&mut self, real: &[f64], spec: &mut [Complex64], lo: usize, hi: usize) {
        let n = self.n;
        let nc = n / 2 + 1;
        debug_assert_eq!(real.len(), n * n);
        debug_assert_eq!(spec.len(), nc * n);
        for col in spec.chunks_exact_mut(n) {
            col[..lo].fill(Complex64::default());
            col[hi + 1..].fill(Complex64::default());
        }
        // Rows in blocks: each block's spectra are written column by column, so every
        // column receives BLOCK consecutive values (a cache-friendly transposition).
        let mut b0 = lo;
        while b0 <= hi {
            let rows = (hi + 1 - b0).min(BLOCK);
            for r in 0..rows {
                let iy = b0 + r;
                self.row_real.copy_from_slice(&real[iy * n..(iy + 1) * n]);
                self.r2c
                    .process_with_scratch(
                        &mut self.row_real,
                        &mut self.block[r * nc..(r + 1) * nc],
                        &mut self.row_scratch,
                    )
                    .expect("r2c lengths are planned");
            }
            for jx in 0..nc {
                let col = &mut spec[jx * n + b0..jx * n + b0 + rows];
                for (r, c) in col.iter_mut().enumerate() {
                    *c = self.block[r * nc + jx];
                }
            }
            b0 += rows;
        }
        self.col_fwd
            .process_with_scratch(spec, &mut self.col_scratch);
    }

    /// Unnormalised inverse transform of `spec` (`[kx][ky]`, consumed) into the rows
    /// `lo..=hi` of `real` (row-major `N x N`); other rows of `real` are left untouched.
    pub fn inverse(&mut self, spec: &mut [Complex64], real: &mut [f64], lo: usize, hi: usize) {
        self.col_inv
            .process_with_scratch(spec, &mut self.col_scratch);
        self.inverse_rows(spec, real, lo, hi);
    }

    /// The gradient `(u_x, u_y)`, on the rows `lo..=hi` of `ux` and `uy` (row-major `N x N`),
    /// of the real field whose unnormalised half spectrum is `u` (`[kx][ky]`, left as it is):
    /// the inverse transforms of `i kx u` and `i ky u` with the derivative wavenumbers `kx`
    /// (per column) and `ky` (per row of a column). The derivatives are formed a few columns
    /// at a time into a block that is transformed along y while it is in the cache, and only
    /// the rows `lo..=hi` are kept; then the rows as in [`Self::inverse`]. The same numbers
    /// as forming both derivative spectra and transforming each with [`Self::inverse`].
    pub fn inverse_gradient(
        &mut self,
        u: &[Complex64],
        (kx, ky): (&[f64], &[f64]),
        (ux, uy): (&mut [f64], &mut [f64]),
        lo: usize,
        hi: usize,
    ) {
        let n = self.n;
        let nc = n / 2 + 1;
        let mut cols = std::mem::take(&mut self.grad_cols);
        let [bx, by] = &mut self.grad_block;
        for c in cols.iter_mut() {
            c.resize(nc * n, Complex64::default());
        }
        bx.resize(COLUMNS * n, Complex64::default());
        by.resize(COLUMNS * n, Complex64::default());
        let mut c0 = 0;
        while c0 < nc {
            let width = (nc - c0).min(COLUMNS);
            for (j, jx) in (c0..c0 + width).enumerate() {
                let column = &u[jx * n..(jx + 1) * n];
                let (x, y) = (&mut bx[j * n..(j + 1) * n], &mut by[j * n..(j + 1) * n]);
                for (((x, y), u), k) in x.iter_mut().zip(y.iter_mut()).zip(column).zip(ky) {
                    *x = Complex64::new(-u.im * kx[jx], u.re * kx[jx]);
                    *y = Complex64::new(-u.im * k, u.re * k);
                }
            }
            let [cx, cy] = &mut cols;
            for (block, cols) in [(&mut *bx, cx), (&mut *by, cy)] {
                let block = &mut block[..width * n];
                self.col_inv
                    .process_with_scratch(block, &mut self.col_scratch);
                for (j, jx) in (c0..c0 + width).enumerate() {
                    cols[jx * n + lo..=jx * n + hi]
                        .copy_from_slice(&block[j * n + lo..=j * n + hi]);
                }
            }
            c0 += width;
        }
        self.inverse_rows(&cols[0], ux, lo, hi);
        self.inverse_rows(&cols[1], uy, lo, hi);
        self.grad_cols = cols;
    }

    /// The second half of [`Self::inverse`]: the rows `lo..=hi` of `real` from `spec`, whose
    /// columns are transformed along y.
    fn inverse_rows(&mut self, spec: &[Complex64], real: &mut [f64], lo: usize, hi: usize) {
        let n = self.n;
        let nc = n / 2 + 1;
        // Rows in blocks, as in the forward transform: every column gives BLOCK consecutive
        // values to the block's row spectra.
        let mut b0 = lo;
        while b0 <= hi {
            let rows = (hi + 1 - b0).min(BLOCK);
            for jx in 0..nc {
                let col = &spec[jx * n + b0..jx * n + b0 + rows];
                for (r, c) in col.iter().enumerate() {
                    self.block[r * nc + jx] = *c;
                }
            }
            for r in 0..rows {
                let iy = b0 + r;
                let row_spec = &mut self.block[r * nc..(r + 1) * nc];
                // A real field's kx = 0 and kx = N/2 columns are real after the y transform;
                // drop the round-off imaginary parts that c2r would reject.
                row_spec[0].im = 0.0;
                row_spec[nc - 1].im = 0.0;
                self.c2r
                    .process_with_scratch(
                        row_spec,
                        &mut real[iy * n..(iy + 1) * n],
                        &mut self.row_scratch,
                    )
                    .expect("c2r lengths are planned");
            }
            b0 += rows;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gradient_is_the_inverse_transform_of_the_derivative_spectra_to_the_last_bit() {
        // A field with every coefficient set (the kx = 0 and N/2 columns real, as a real
        // field's are after the y transform), N = 24: three column blocks, the last partial.
        let n = 24;
        let nc = n / 2 + 1;
        let u: Vec<Complex64> = (0..nc * n)
            .map(|i| Complex64::new((i as f64 * 0.37).sin(), (i as f64 * 0.11).cos()))
            .collect();
        let kx: Vec<f64> = (0..nc)
            .map(|j| if j == n / 2 { 0.0 } else { j as f64 * 0.9 })
            .collect();
        let ky: Vec<f64> = (0..n)
            .map(|j| match j {
                _ if j == n / 2 => 0.0,
                _ if j > n / 2 => (j as f64 - n as f64) * 0.9,
                _ => j as f64 * 0.9,
            })
            .collect();
        let (lo, hi) = (5, 17);
        let mut fft = PrunedFft2::new(n);
        let (mut ux, mut uy) = (vec![0.0; n * n], vec![0.0; n * n]);
        fft.inverse_gradient(&u, (&kx, &ky), (&mut ux, &mut uy), lo, hi);
        let (mut dx, mut dy) = (u.clone(), u.clone());
        for jx in 0..nc {
            for jy in 0..n {
                let (w, i) = (u[jx * n + jy], jx * n + jy);
                dx[i] = Complex64::new(-w.im * kx[jx], w.re * kx[jx]);
                dy[i] = Complex64::new(-w.im * ky[jy], w.re * ky[jy]);
            }
        }
        let (mut ex, mut ey) = (vec![0.0; n * n], vec![0.0; n * n]);
        fft.inverse(&mut dx, &mut ex, lo, hi);
        fft.inverse(&mut dy, &mut ey, lo, hi);
        assert_eq!(ux, ex);
        assert_eq!(uy, ey);
        assert!(ux[lo * n..(hi + 1) * n].iter().any(|v| v.abs() > 1.0));
    }

    #[test]
    fn pruned_round_trip_is_exact() {
        let n = 32;
        let mut fft = PrunedFft2::new(n);
        let mut real = vec![0.0; n * n];
        let (lo, hi) = (10, 20);
        for iy in lo..=hi {
            for ix in 0..n {
                real[iy * n + ix] = ((ix * 7 + iy * 3) % 11) as f64 - 5.0;
            }
        }
        let orig = real.clone();
        let mut spec = vec![Complex64::default(); (n / 2 + 1) * n];
        fft.forward(&real, &mut spec, lo, hi);
        // DC coefficient = sum of samples.
        let sum: f64 = orig.iter().sum();
        assert!((spec[0].re - sum).abs() < 1e-9);
        let mut back = vec![0.0; n * n];
        fft.inverse(&mut spec, &mut back, 0, n - 1);
        for (a, b) in orig.iter().zip(&back) {
            assert!((a - b / (n * n) as f64).abs() < 1e-12);
        }
    }
}
