//! The transforms of the droplet's shape fields, using their point symmetry.
//!
//! A mode-2 droplet is point-symmetric about its centre, the grid point `(N/2, N/2)`:
//! `Theta` is even, `X Theta` and `Y Theta` are odd under `(ix, iy) -> (N - ix, N - iy)`.
//! So the row transforms of the lower half are those of the upper half conjugated
//! (`R(N - iy) = conj R(iy)` for `Theta`, `-conj R(iy)` for the odd fields), and only the
//! rows `N/2..=hi` are transformed. Along `y`:
//! - `Theta + X Theta` (packed, see [`crate::model::forces`]) takes one complex transform per
//!   column: `Theta_hat = Re`, `(X Theta)_hat = i Im`;
//! - `Y Theta`'s column is anti-Hermitian in `iy`, so `-i` times it is Hermitian and its
//!   transform is real: one complex-to-real transform of half the length per column.
//!
//! Against the plain row-pruned transform of both packed fields ([`crate::numerics::fft2::PrunedFft2`]):
//! 3 x (hi - N/2 + 1) row transforms instead of 2 x (hi - lo + 1), and 1.5 instead of 2
//! column transforms' worth. The output is the same (to round-off): `p` of `Theta + X Theta`
//! and `y` of `Y Theta`, raw, `[kx][ky]`. Plans and buffers are made once.
use crate::model::forces::parseval::ShapeSampler;
use crate::model::grid::Grid;
use crate::model::shape::ShapeParams;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// Samples and transforms droplet shapes on one grid (one per worker).
pub struct ShapeTransform {
    sampler: ShapeSampler,
    n: usize,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    col_fwd: Arc<dyn Fft<f64>>,
    /// Sampled rows `N/2..=hi` of `Theta`, `X Theta`, `Y Theta` (`[row][ix]`).
    th: Vec<f64>,
    x: Vec<f64>,
    y: Vec<f64>,
    /// Their row spectra (`[row][kx]`).
    r_th: Vec<Complex64>,
    r_x: Vec<Complex64>,
    r_y: Vec<Complex64>,
    /// One column of `Y Theta` as a half spectrum, and its real transform.
    half: Vec<Complex64>,
    real: Vec<f64>,
    row_scratch: Vec<Complex64>,
    col_scratch: Vec<Complex64>,
}

impl ShapeTransform {
    pub fn new(grid: &Grid, shape: ShapeParams) -> Self {
        let n = grid.n;
        let nc = n / 2 + 1;
        let mut real_planner = RealFftPlanner::<f64>::new();
        let r2c = real_planner.plan_fft_forward(n);
        let c2r = real_planner.plan_fft_inverse(n);
        let col_fwd = FftPlanner::<f64>::new().plan_fft_forward(n);
        let z = Complex64::default();
        // At most the rows N/2..N - 1.
        let rows = n / 2;
        Self {
            sampler: ShapeSampler::new(grid, shape),
            n,
            th: vec![0.0; rows * n],
            x: vec![0.0; rows * n],
            y: vec![0.0; rows * n],
            r_th: vec![z; rows * nc],
            r_x: vec![z; rows * nc],
            r_y: vec![z; rows * nc],
            half: vec![z; nc],
            real: vec![0.0; n],
            row_scratch: vec![z; r2c.get_scratch_len().max(c2r.get_scratch_len())],
            col_scratch: vec![z; col_fwd.get_inplace_scratch_len()],
            r2c,
            c2r,
            col_fwd,
        }
    }

    /// The sampler of this grid.
    pub fn sampler(&self) -> &ShapeSampler {
        &self.sampler
    }

    /// Writes the raw transforms of `Theta + X Theta` into `p` and of `Y Theta` into `y`
    /// (`[kx][ky]`) for the shape `(a2, b2)`, and returns its area `A = Sum(Theta) dx^2`.
    pub fn transform(&mut self, a2: f64, b2: f64, p: &mut [Complex64], y: &mut [Complex64]) -> f64 {
        let n = self.n;
        let nc = n / 2 + 1;
        let c = n / 2;
        debug_assert_eq!(p.len(), nc * n);
        debug_assert_eq!(y.len(), nc * n);
        let (lo, hi) = self.sampler.span(a2, b2);
        let rows = hi - c + 1;
        let area = self.sampler.sample_upper(
            a2,
            b2,
            &mut self.th[..rows * n],
            &mut self.x[..rows * n],
            &mut self.y[..rows * n],
        );
        for (real, spec) in [
            (&mut self.th, &mut self.r_th),
            (&mut self.x, &mut self.r_x),
            (&mut self.y, &mut self.r_y),
        ] {
            for (row, out) in real
                .chunks_exact_mut(n)
                .zip(spec.chunks_exact_mut(nc))
                .take(rows)
            {
                self.r2c
                    .process_with_scratch(row, out, &mut self.row_scratch)
                    .expect("r2c lengths are planned");
            }
        }
        // Theta + X Theta: the upper rows as transformed, the lower ones mirrored.
        for (jx, col) in p.chunks_exact_mut(n).enumerate() {
            col[..lo].fill(Complex64::default());
            col[hi + 1..].fill(Complex64::default());
            for r in 0..rows {
                let (t, x) = (self.r_th[r * nc + jx], self.r_x[r * nc + jx]);
                col[c + r] = t + x;
                if r > 0 {
                    col[c - r] = t.conj() - x.conj();
                }
            }
        }
        self.col_fwd.process_with_scratch(p, &mut self.col_scratch);
        // Y Theta: -i times its column is Hermitian in iy; with X[c - r] = -i R(c + r) the
        // inverse real transform of X is the column's (real) forward transform / i.
        let minus_i = Complex64::new(0.0, -1.0);
        for (jx, col) in y.chunks_exact_mut(n).enumerate() {
            self.half.fill(Complex64::default());
            for r in 0..rows {
                self.half[c - r] = minus_i * self.r_y[r * nc + jx];
            }
            // Real in exact arithmetic (row N/2 of Y Theta is zero; row 0 is outside).
            self.half[0].im = 0.0;
            self.half[c].im = 0.0;
            self.c2r
                .process_with_scratch(&mut self.half, &mut self.real, &mut self.row_scratch)
                .expect("c2r lengths are planned");
            for (out, g) in col.iter_mut().zip(&self.real) {
                *out = Complex64::new(0.0, *g);
            }
        }
        area
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::fft2::PrunedFft2;

    #[test]
    fn symmetric_transform_equals_the_plain_one() {
        for (n, sigma) in [(64, 0.1), (96, 0.03)] {
            let grid = Grid::new(n, 7.0).unwrap();
            let shape = ShapeParams { radius: 1.0, sigma };
            let mut st = ShapeTransform::new(&grid, shape);
            let mut plain = PrunedFft2::new(n);
            let len = grid.spectral_len();
            for (a2, b2) in [(0.0, 0.0), (-0.15, 0.07), (0.3, -0.2), (-0.052, -0.032)] {
                // Direct samples of Theta, packed as the forces expect.
                let mut t = vec![0.0; n * n];
                st.sampler().theta(a2, b2, &mut t);
                let pr: Vec<f64> = (0..n * n)
                    .map(|i| t[i] * (1.0 + grid.coord(i % n)))
                    .collect();
                let yr: Vec<f64> = (0..n * n).map(|i| t[i] * grid.coord(i / n)).collect();
                let (mut p0, mut y0) = (
                    vec![Complex64::default(); len],
                    vec![Complex64::default(); len],
                );
                plain.forward(&pr, &mut p0, 0, n - 1);
                plain.forward(&yr, &mut y0, 0, n - 1);
                let (mut p1, mut y1) = (
                    vec![Complex64::default(); len],
                    vec![Complex64::default(); len],
                );
                let area = st.transform(a2, b2, &mut p1, &mut y1);
                let direct: f64 = t.iter().sum::<f64>() * grid.dx * grid.dx;
                assert!((area - direct).abs() < 1e-12, "area {area} vs {direct}");
                let scale = p0[0].norm();
                for i in 0..len {
                    assert!(
                        (p0[i] - p1[i]).norm() < 1e-12 * scale,
                        "p {i}: {} vs {}",
                        p0[i],
                        p1[i]
                    );
                    assert!(
                        (y0[i] - y1[i]).norm() < 1e-12 * scale,
                        "y {i}: {} vs {}",
                        y0[i],
                        y1[i]
                    );
                }
            }
        }
    }
}
