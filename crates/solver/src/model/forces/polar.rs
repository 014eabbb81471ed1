//! The droplet's window in polar form, tabulated once per run. In its own frame the droplet
//! sits at the grid's centre, so at each grid point of a square around it the radius `r`, the
//! harmonics `(cos k theta, sin k theta)` for `k = 2..K` (what `Theta`'s boundary `f(theta)`
//! needs) and the powers `(x + i y)^(k-1)` (what the modes' forces weigh the field's gradient
//! by) are the same at every step. Sampling `Theta` ([`super::quadrature`]) and summing the
//! forces read them instead of taking a square root, a division and two recurrences at every
//! point. They are the values those recurrences give, in the same order, so `Theta` and the
//! forces are unchanged to the last bit (tested).
use crate::model::grid::Grid;

/// Points beyond the window asked for that a table covers, so that a window growing by a
/// few points from step to step does not rebuild it.
const MARGIN: usize = 4;

/// The tabulated square: rows and columns `c - half ..= c + half` (`c = N / 2`), modes up to
/// `k_max`.
#[derive(Debug, Clone, Default)]
pub struct PolarTable {
    n: usize,
    half: usize,
    k_max: usize,
    /// Per point (row-major over the square): `r`.
    r: Vec<f64>,
    /// Per point: `cos k theta, sin k theta` for `k = 2..=K`, `2 (K - 1)` values.
    harmonics: Vec<f64>,
    /// Per point: `Re, Im` of `(x + i y)^(k - 1)` for `k = 2..=K`, `2 (K - 1)` values.
    powers: Vec<f64>,
}

impl PolarTable {
    /// Whether the table of `grid` covers the rows and columns `lo..=hi` and the modes up to
    /// `k_max`.
    pub fn covers(&self, grid: &Grid, lo: usize, hi: usize, k_max: usize) -> bool {
        let c = grid.n / 2;
        self.n == grid.n && self.k_max >= k_max && lo + self.half >= c && hi <= c + self.half
    }

    /// Makes the table cover `lo..=hi` and the modes up to `k_max` (a margin beyond the window,
    /// at least the modes it had), unless it does.
    pub fn ensure(&mut self, grid: &Grid, lo: usize, hi: usize, k_max: usize) {
        if self.covers(grid, lo, hi, k_max) {
            return;
        }
        let c = grid.n / 2;
        let wanted = (c - lo.min(c)).max(hi.saturating_sub(c));
        let half = (wanted + MARGIN).min(c - 1).max(self.half.min(c - 1));
        *self = Self::build(grid, half, k_max.max(self.k_max).max(2));
    }

    fn build(grid: &Grid, half: usize, k_max: usize) -> Self {
        let c = grid.n / 2;
        let side = 2 * half + 1;
        let m = 2 * (k_max - 1);
        let mut t = Self {
            n: grid.n,
            half,
            k_max,
            r: Vec::with_capacity(side * side),
            harmonics: Vec::with_capacity(side * side * m),
            powers: Vec::with_capacity(side * side * m),
        };
        for iy in c - half..=c + half {
            let y = grid.coord(iy);
            for ix in c - half..=c + half {
                let x = grid.coord(ix);
                // As `Modes::theta` takes them: r, (cos, sin) = (x / r, y / r), and the
                // harmonics by `Modes::relative`'s recurrence.
                let r = (x * x + y * y).sqrt();
                t.r.push(r);
                let (cs, sn) = if r == 0.0 { (0.0, 0.0) } else { (x / r, y / r) };
                let (mut ck, mut sk) = (cs, sn);
                // As `ForceQuadrature::sums` took them: (x + i y)^(k-1) from (x, y).
                let (mut re, mut im) = (x, y);
                for _ in 2..=k_max {
                    (ck, sk) = (ck * cs - sk * sn, sk * cs + ck * sn);
                    t.harmonics.extend([ck, sk]);
                    t.powers.extend([re, im]);
                    (re, im) = (re * x - im * y, re * y + im * x);
                }
            }
        }
        t
    }

    /// The index of the point at row `iy`, column `ix` (inside the square).
    #[inline(always)]
    fn index(&self, iy: usize, ix: usize) -> usize {
        let corner = self.n / 2 - self.half;
        (iy - corner) * (2 * self.half + 1) + (ix - corner)
    }

    /// The columns `lo..=hi` of row `iy` (inside the square): `r` per point, and the
    /// harmonics and powers of those points (each point's values [`Self::stride`] apart).
    #[inline(always)]
    pub fn row(&self, iy: usize, lo: usize, hi: usize) -> (&[f64], &[f64], &[f64]) {
        let (p, len, m) = (self.index(iy, lo), hi + 1 - lo, self.stride());
        (
            &self.r[p..p + len],
            &self.harmonics[p * m..(p + len) * m],
            &self.powers[p * m..(p + len) * m],
        )
    }

    /// How many values a point has in the harmonics and in the powers: `2 (K - 1)`, `K` the
    /// table's (at least the shape's).
    #[inline(always)]
    pub fn stride(&self) -> usize {
        2 * (self.k_max - 1)
    }
}

#[cfg(test)]
mod tests {
    use crate::model::forces::quadrature::ForceQuadrature;
    use crate::model::grid::Grid;
    use crate::model::modes::Modes;
    use crate::model::shape::ShapeParams;
    use rustfft::num_complex::Complex64;

    #[test]
    fn tabulated_theta_and_forces_equal_the_recurrences_to_the_last_bit() {
        let grid = Grid::new(64, 7.0).unwrap();
        let shape = ShapeParams {
            radius: 1.0,
            sigma: 0.03,
        };
        // K = 4 (the sums' accumulators held for it) and K = 9 (beyond them).
        for (a, b) in [
            (vec![0.12, -0.04, 0.01], vec![-0.05, 0.02, 0.003]),
            (
                vec![0.1, 0.02, -0.01, 4e-3, 2e-3, -1e-3, 5e-4, 2e-4],
                vec![-0.03; 8],
            ),
        ] {
            let k = a.len();
            let mut quad = ForceQuadrature::new(grid.clone(), shape);
            let m = Modes { a, b };
            let (area, lo, hi) = quad.sample(&m);
            let n = grid.n;
            for iy in lo..=hi {
                for ix in lo..=hi {
                    let (x, y) = (grid.coord(ix), grid.coord(iy));
                    let t = quad.theta()[iy * n + ix];
                    if t > 0.0 && t < 1.0 {
                        assert_eq!(t, m.theta(&shape, x, y), "({x}, {y})");
                    }
                }
            }
            // A field with a gradient everywhere: the sums against the recurrence's.
            let len = grid.spectral_len();
            let u: Vec<Complex64> = (0..len)
                .map(|i| Complex64::new((i as f64 * 0.37).sin(), (i as f64 * 0.11).cos()) * 1e-3)
                .collect();
            quad.gradient(&u, lo, hi);
            let f = quad.sums(k + 1, lo, hi, area);
            let (ux, uy) = quad.gradient_rows();
            let (mut fx, mut fy) = (0.0, 0.0);
            let (mut ga, mut gb) = (vec![0.0; k], vec![0.0; k]);
            for iy in lo..=hi {
                for ix in lo..=hi {
                    let i = iy * n + ix;
                    let t = quad.theta()[i];
                    if t == 0.0 {
                        continue;
                    }
                    let (x, y) = (grid.coord(ix), grid.coord(iy));
                    let (gx, gy) = (ux[i] * t, uy[i] * t);
                    fx += gx;
                    fy += gy;
                    let (mut re, mut im) = (x, y);
                    for (a, b) in ga.iter_mut().zip(gb.iter_mut()) {
                        *a += re * gx - im * gy;
                        *b += im * gx + re * gy;
                        (re, im) = (re * x - im * y, re * y + im * x);
                    }
                }
            }
            let da = -grid.dx * grid.dx;
            assert_eq!((f.fx, f.fy), (fx * da, fy * da));
            for j in 0..k {
                let scale = da * shape.radius.powi(-(j as i32));
                assert_eq!(
                    (f.ga[j], f.gb[j]),
                    (ga[j] * scale, gb[j] * scale),
                    "k = {}",
                    j + 2
                );
            }
        }
    }
}
