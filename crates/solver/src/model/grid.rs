//! Periodic square grid of the co-moving frame and its wavenumbers.
//!
//! Real-space sample `(ix, iy)` sits at `X = (ix - N/2) dx`, `Y = (iy - N/2) dx`, so the droplet
//! centre is the grid point `(N/2, N/2)`. Spectra are stored kx-major (`[kx][ky]`, `N/2 + 1`
//! rows of length `N`), the layout of [`crate::numerics::fft2::PrunedFft2`].
use crate::error::{require, SolverError};
use rustfft::num_complex::Complex64;

/// Grid geometry and wavenumber tables.
#[derive(Debug, Clone)]
pub struct Grid {
    /// Points per side (even).
    pub n: usize,
    /// Box side `L`.
    pub len: f64,
    /// Spacing `L / N`.
    pub dx: f64,
    /// `kx` for the `N/2 + 1` stored columns.
    pub kx: Vec<f64>,
    /// `ky` for the `N` rows, in FFT order.
    pub ky: Vec<f64>,
    /// `kx` for first derivatives: the Nyquist mode set to zero.
    pub kx_d: Vec<f64>,
    /// `ky` for first derivatives: the Nyquist mode set to zero.
    pub ky_d: Vec<f64>,
}

/// Most grid points per side any command accepts (runs, roots, audits alike): at `N = 4096`
/// one field is 128 MiB, and the droplet's interface is resolved from `N = 192` on.
pub const MAX_N: usize = 4096;

/// The one check of a grid size: an even integer from 16 to [`MAX_N`].
pub fn check_n(n: usize) -> Result<(), SolverError> {
    require(
        (16..=MAX_N).contains(&n) && n.is_multiple_of(2),
        "n",
        n as f64,
        format!("an even integer from 16 to {MAX_N}"),
    )
}

impl Grid {
    /// A grid of `n x n` points on a box of side `len`.
    pub fn new(n: usize, len: f64) -> Result<Self, SolverError> {
        check_n(n)?;
        require(len > 0.0, "box_len", len, "a finite number > 0")?;
        let dk = 2.0 * std::f64::consts::PI / len;
        let signed = |j: usize| -> f64 {
            if j <= n / 2 {
                j as f64
            } else {
                j as f64 - n as f64
            }
        };
        let kx: Vec<f64> = (0..=n / 2).map(|j| dk * j as f64).collect();
        let ky: Vec<f64> = (0..n).map(|j| dk * signed(j)).collect();
        let zero_nyquist = |k: &[f64]| -> Vec<f64> {
            k.iter()
                .enumerate()
                .map(|(j, &v)| if j == n / 2 { 0.0 } else { v })
                .collect()
        };
        Ok(Self {
            n,
            len,
            dx: len / n as f64,
            kx_d: zero_nyquist(&kx),
            ky_d: zero_nyquist(&ky),
            kx,
            ky,
        })
    }

    /// Number of stored spectral coefficients (`(N/2 + 1) N`).
    pub fn spectral_len(&self) -> usize {
        (self.n / 2 + 1) * self.n
    }

    /// `1 / c` per stored coefficient (`[kx][ky]`), `c = -(1 + kx^2 + ky^2)`: the field's
    /// diffusion and decay, the exact part of the exponential steps.
    pub fn inverse_rates(&self) -> Vec<f64> {
        let n = self.n;
        (0..self.spectral_len())
            .map(|i| {
                let (kx, ky) = (self.kx[i / n], self.ky[i % n]);
                -1.0 / (1.0 + kx * kx + ky * ky)
            })
            .collect()
    }

    /// Coordinate of grid index `i` relative to the centre.
    pub fn coord(&self, i: usize) -> f64 {
        (i as f64 - (self.n / 2) as f64) * self.dx
    }

    /// Index range `[lo, hi]` of the points with `|coordinate| <= radius`, clamped to the grid.
    pub fn index_span(&self, radius: f64) -> (usize, usize) {
        let half = (self.n / 2) as isize;
        let w = (radius / self.dx).ceil() as isize;
        let lo = (half - w).max(0) as usize;
        let hi = ((half + w) as usize).min(self.n - 1);
        (lo, hi)
    }

    /// Weight of a stored column in a full-spectrum sum (Parseval): columns `0` and `N/2`
    /// appear once, the others stand for themselves and their conjugates.
    pub fn column_weight(&self, jx: usize) -> f64 {
        if jx == 0 || jx == self.n / 2 {
            1.0
        } else {
            2.0
        }
    }

    /// Moves the field whose half spectrum is `spec` (row-major, `N/2 + 1` columns of `N`) by
    /// `(x, y)`: `u(r) -> u(r - (x, y))`, the exact phase shift `e^{-i k . (x, y)}` with the
    /// derivative wavenumbers (the Nyquist modes dropped).
    pub fn shift_spectrum(&self, spec: &mut [Complex64], x: f64, y: f64) {
        let n = self.n;
        for jx in 0..=n / 2 {
            let kx = self.kx_d[jx];
            for jy in 0..n {
                let phase = -(kx * x + self.ky_d[jy] * y);
                spec[jx * n + jy] *= Complex64::from_polar(1.0, phase);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wavenumbers_and_coordinates() {
        let g = Grid::new(16, 8.0).unwrap();
        assert_eq!(g.dx, 0.5);
        assert_eq!(g.coord(8), 0.0);
        assert!((g.ky[15] + 2.0 * std::f64::consts::PI / 8.0).abs() < 1e-15);
        assert_eq!(g.kx_d[8], 0.0);
        assert_eq!(g.ky_d[8], 0.0);
        assert!(g.kx[8] > 0.0);
        assert_eq!(g.index_span(1.0), (6, 10));
        assert!(Grid::new(15, 1.0).is_err());
    }
}
