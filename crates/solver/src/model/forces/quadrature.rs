//! The forces on a droplet of any shape (modes `2..K`, [`crate::model::modes::Modes`]) by
//! quadrature over the grid: `F = -dx^2 Sum grad(u) Theta` and
//! `G_k = -dx^2 Sum w_k . grad(u) Theta` (the smoothed eqs. 35, dakdt_dl, dbkdt_dl), with the
//! same samples of `Theta` and the same spectral gradient (Nyquist mode zeroed) as the
//! point-symmetric fast path ([`super::parseval`]), the sums taken in real space over the
//! droplet's rows (equal to the Parseval sums to round-off for `K = 2`, tested in the steady
//! solver). No symmetry of the shape is assumed: odd modes break the point symmetry.
//!
//! [`ForceQuadrature`] owns the plans and buffers (made once): `Theta` sampled on the rows that
//! can hold it, its transform, the field's gradient on those rows. A steady solve, a time step
//! and the linearisation use it in their own order ([`ForceQuadrature::sample`],
//! [`ForceQuadrature::theta_spectrum`], [`ForceQuadrature::gradient`],
//! [`ForceQuadrature::sums`]).
use crate::model::forces::polar::PolarTable;
use crate::model::grid::Grid;
use crate::model::modes::{Modes, MAX_MODES};
use crate::model::shape::ShapeParams;
use crate::numerics::fft2::PrunedFft2;
use rustfft::num_complex::Complex64;

/// The forces on a droplet with shape modes `2..=K`.
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeForces {
    pub fx: f64,
    pub fy: f64,
    /// `G_k^(a)`, `G_k^(b)` for `k = 2..=K` (index `k - 2`).
    pub ga: Vec<f64>,
    pub gb: Vec<f64>,
    /// `A = Sum(Theta) dx^2`.
    pub area: f64,
}

impl ShapeForces {
    /// The forces as one vector `(Fx, Fy, G^(a)_2.., G^(b)_2..)`, ordered like a state.
    pub fn to_vec(&self) -> Vec<f64> {
        [self.fx, self.fy]
            .into_iter()
            .chain(self.ga.iter().copied())
            .chain(self.gb.iter().copied())
            .collect()
    }
}

/// `D = -(1 + k^2) + i k.v`, the co-moving field operator, at one mode: wavenumbers
/// `(kx, ky)`, derivative wavenumbers `(kxd, kyd)` (Nyquist zeroed), velocity `(vx, vy)`.
#[inline(always)]
pub fn operator((kx, ky): (f64, f64), (kxd, kyd): (f64, f64), (vx, vy): (f64, f64)) -> Complex64 {
    Complex64::new(-(1.0 + kx * kx + ky * ky), kxd * vx + kyd * vy)
}

/// [`operator`] for every stored mode of `grid` (`[kx][ky]`), into `out`.
pub fn fill_operator(grid: &Grid, vx: f64, vy: f64, out: &mut [Complex64]) {
    let n = grid.n;
    for jx in 0..=n / 2 {
        let (kx, kxd) = (grid.kx[jx], grid.kx_d[jx]);
        for jy in 0..n {
            let (ky, kyd) = (grid.ky[jy], grid.ky_d[jy]);
            out[jx * n + jy] = operator((kx, ky), (kxd, kyd), (vx, vy));
        }
    }
}

/// One sampled droplet: `Theta` on the rows and columns `lo..=hi` of the grid (row-major
/// `N x N`; nothing outside that window is read), its raw transform (`[kx][ky]`, not divided
/// by `A N^2`) and its area. A time step keeps the last two states' ([`ForceQuadrature::exchange`])
/// to extrapolate its predictor's ([`ForceQuadrature::extrapolate`]).
pub struct SampledShape {
    pub theta: Vec<f64>,
    pub spec: Vec<Complex64>,
    pub area: f64,
    pub lo: usize,
    pub hi: usize,
}

impl SampledShape {
    /// Empty buffers for `grid`.
    pub fn new(grid: &Grid) -> Self {
        let n = grid.n;
        Self {
            theta: vec![0.0; n * n],
            spec: vec![Complex64::default(); grid.spectral_len()],
            area: 0.0,
            lo: n / 2,
            hi: n / 2,
        }
    }

    /// `Theta` at the flat index `i` of row `iy`, column `ix` (0 outside the window).
    #[inline(always)]
    fn at(&self, iy: usize, ix: usize, i: usize) -> f64 {
        if (self.lo..=self.hi).contains(&iy) && (self.lo..=self.hi).contains(&ix) {
            self.theta[i]
        } else {
            0.0
        }
    }
}

/// A field's gradient `(u_x, u_y)` on the rows `lo..=hi` of the grid (row-major `N x N`;
/// the forces read its rows and columns `lo..=hi` only). A time step keeps the last two
/// states' ([`ForceQuadrature::exchange_gradient`]) to extrapolate its predictor's
/// ([`ForceQuadrature::extrapolate_gradient`]).
pub struct GradientRows {
    pub ux: Vec<f64>,
    pub uy: Vec<f64>,
    pub lo: usize,
    pub hi: usize,
}

impl GradientRows {
    /// Empty buffers for `grid`.
    pub fn new(grid: &Grid) -> Self {
        let n = grid.n;
        Self {
            ux: vec![0.0; n * n],
            uy: vec![0.0; n * n],
            lo: n / 2,
            hi: n / 2,
        }
    }
}

/// [`ForceQuadrature::pass_buffers`]: the grid and `Theta`'s last transform to read.
pub struct PassBuffers<'a> {
    pub grid: &'a Grid,
    pub source: &'a [Complex64],
}

/// `Theta` of a droplet of any shape on an `N x N` grid, its transform and the forces of a
/// field on it.
pub struct ForceQuadrature {
    grid: Grid,
    shape: ShapeParams,
    fft: PrunedFft2,
    /// `Theta` and its transform.
    sampled: SampledShape,
    /// The field's gradient on the droplet's rows.
    grad: GradientRows,
    /// The window's radii, harmonics and powers.
    polar: PolarTable,
}

impl ForceQuadrature {
    /// Plans and buffers for `grid` and droplets of radius and interface width `shape`.
    pub fn new(grid: Grid, shape: ShapeParams) -> Self {
        let n = grid.n;
        Self {
            shape,
            fft: PrunedFft2::new(n),
            sampled: SampledShape::new(&grid),
            grad: GradientRows::new(&grid),
            polar: PolarTable::default(),
            grid,
        }
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The rows (and columns) `lo..=hi` that can hold `Theta > 0` (droplet at the centre).
    pub fn span(&self, m: &Modes) -> (usize, usize) {
        let c = self.grid.n / 2;
        let w = ((m.outer_radius(&self.shape) / self.grid.dx).ceil() as usize).min(c - 1);
        (c - w, c + w)
    }

    /// Samples `Theta` of `m` into the rows `lo..=hi` (returned) of the grid buffer; the area.
    pub fn sample(&mut self, m: &Modes) -> (f64, usize, usize) {
        let n = self.grid.n;
        let shape = self.shape;
        let (lo, hi) = self.span(m);
        self.polar.ensure(&self.grid, lo, hi, m.k_max());
        let (r_in, r_out) = (m.inner_radius(&shape), m.outer_radius(&shape));
        // Squared radii: no square root outside the interface band.
        let (r_in2, r_out2) = (r_in * r_in, r_out * r_out);
        let mut count = 0.0;
        let stride = self.polar.stride();
        for iy in lo..=hi {
            let y = self.grid.coord(iy);
            let row = &mut self.sampled.theta[iy * n..(iy + 1) * n];
            row[..lo].fill(0.0);
            row[hi + 1..].fill(0.0);
            let (radii, harmonics, _) = self.polar.row(iy, lo, hi);
            let points = row[lo..=hi]
                .iter_mut()
                .zip(radii)
                .zip(harmonics.chunks_exact(stride));
            for (ix, ((t, r), h)) in (lo..=hi).zip(points) {
                let x = self.grid.coord(ix);
                let r2 = x * x + y * y;
                *t = if r2 < r_in2 {
                    1.0
                } else if r2 > r_out2 {
                    0.0
                } else {
                    m.theta_on(&shape, *r, h)
                };
                count += *t;
            }
        }
        let area = count * self.grid.dx * self.grid.dx;
        (self.sampled.area, self.sampled.lo, self.sampled.hi) = (area, lo, hi);
        (area, lo, hi)
    }

    /// Transforms the source `Theta / A` of `m` into a normalised half spectrum (`[kx][ky]`,
    /// like the field's; [`Self::source_spectrum`]), leaving `Theta` sampled: the area and the
    /// rows `lo..=hi` that hold it.
    pub fn source(&mut self, m: &Modes) -> (f64, usize, usize) {
        let (area, lo, hi) = self.theta_spectrum(m);
        let norm = self.source_scale(area);
        for c in self.sampled.spec.iter_mut() {
            *c *= norm;
        }
        (area, lo, hi)
    }

    /// Like [`Self::source`], but leaves the raw transform of `Theta` (not divided by
    /// `A N^2`, [`Self::source_scale`]) in [`Self::source_spectrum`]: a time step folds the
    /// scale into its own pass over the spectrum.
    pub fn theta_spectrum(&mut self, m: &Modes) -> (f64, usize, usize) {
        let (area, lo, hi) = self.sample(m);
        self.fft
            .forward(&self.sampled.theta, &mut self.sampled.spec, lo, hi);
        (area, lo, hi)
    }

    /// The factor `1 / (A N^2)` from the raw transform of `Theta` to the normalised source.
    pub fn source_scale(&self, area: f64) -> f64 {
        1.0 / (area * (self.grid.n * self.grid.n) as f64)
    }

    /// `Theta` of the last [`Self::sample`] (row-major `N x N`, rows `lo..=hi`).
    pub fn theta(&self) -> &[f64] {
        &self.sampled.theta
    }

    /// Exchanges the last sampled droplet (`Theta`, its transform after
    /// [`Self::theta_spectrum`], area and window) with `other`, without copying.
    pub fn exchange(&mut self, other: &mut SampledShape) {
        std::mem::swap(&mut self.sampled, other);
    }

    /// Makes `Theta` the extrapolation `base + alpha (base - back)` of two sampled droplets
    /// on the union of their windows, and the area likewise: `(area, lo, hi)` as
    /// [`Self::sample`] returns them. The transform is not formed (a time step forms it on the
    /// fly, [`crate::stepping::comoving_etd`]); [`Self::source_spectrum`] is stale after it.
    pub fn extrapolate(
        &mut self,
        base: &SampledShape,
        back: &SampledShape,
        alpha: f64,
    ) -> (f64, usize, usize) {
        let n = self.grid.n;
        let (lo, hi) = (base.lo.min(back.lo), base.hi.max(back.hi));
        if (base.lo, base.hi) == (back.lo, back.hi) {
            // One window (the usual case): no point outside either.
            for iy in lo..=hi {
                let row = iy * n + lo..=iy * n + hi;
                let out = self.sampled.theta[row.clone()].iter_mut();
                for ((t, b), q) in out.zip(&base.theta[row.clone()]).zip(&back.theta[row]) {
                    *t = b + alpha * (b - q);
                }
            }
        } else {
            for iy in lo..=hi {
                for ix in lo..=hi {
                    let i = iy * n + ix;
                    let b = base.at(iy, ix, i);
                    self.sampled.theta[i] = b + alpha * (b - back.at(iy, ix, i));
                }
            }
        }
        let area = base.area + alpha * (base.area - back.area);
        (self.sampled.area, self.sampled.lo, self.sampled.hi) = (area, lo, hi);
        (area, lo, hi)
    }

    /// The unnormalised transform (`[kx][ky]`) of a real field whose rows outside `lo..=hi`
    /// are zero.
    pub fn transform(&mut self, real: &[f64], lo: usize, hi: usize) -> Vec<Complex64> {
        let mut spec = vec![Complex64::default(); self.grid.spectral_len()];
        self.fft.forward(real, &mut spec, lo, hi);
        spec
    }

    /// The last [`Self::source`]'s normalised half spectrum (raw after
    /// [`Self::theta_spectrum`]).
    pub fn source_spectrum(&self) -> &[Complex64] {
        &self.sampled.spec
    }

    /// The gradient of the real field with the normalised half spectrum `u` on the rows
    /// `lo..=hi` (spectral derivatives, Nyquist mode zeroed; [`PrunedFft2::inverse_gradient`]).
    pub fn gradient(&mut self, u: &[Complex64], lo: usize, hi: usize) {
        let wavenumbers = (&self.grid.kx_d[..], &self.grid.ky_d[..]);
        let rows = (&mut self.grad.ux[..], &mut self.grad.uy[..]);
        self.fft.inverse_gradient(u, wavenumbers, rows, lo, hi);
        (self.grad.lo, self.grad.hi) = (lo, hi);
    }

    /// Exchanges the last gradient (its buffers and rows) with `other`, without copying.
    pub fn exchange_gradient(&mut self, other: &mut GradientRows) {
        std::mem::swap(&mut self.grad, other);
    }

    /// Makes the gradient the extrapolation `base + beta (base - back)` of two gradients on
    /// the rows and columns `lo..=hi`, which both must hold (what the forces read).
    pub fn extrapolate_gradient(
        &mut self,
        base: &GradientRows,
        back: &GradientRows,
        beta: f64,
        (lo, hi): (usize, usize),
    ) {
        debug_assert!(base.lo <= lo && hi <= base.hi && back.lo <= lo && hi <= back.hi);
        let n = self.grid.n;
        let pairs = [
            (&mut self.grad.ux, &base.ux, &back.ux),
            (&mut self.grad.uy, &base.uy, &back.uy),
        ];
        for (out, base, back) in pairs {
            for iy in lo..=hi {
                let row = iy * n + lo..=iy * n + hi;
                let points = out[row.clone()].iter_mut().zip(&base[row.clone()]);
                for ((o, b), q) in points.zip(&back[row]) {
                    *o = b + beta * (b - q);
                }
            }
        }
        (self.grad.lo, self.grad.hi) = (lo, hi);
    }

    /// What a pass over a field's spectrum reads here: the grid and the last transform of
    /// `Theta` ([`Self::source_spectrum`]).
    pub fn pass_buffers(&self) -> PassBuffers<'_> {
        PassBuffers {
            grid: &self.grid,
            source: &self.sampled.spec,
        }
    }

    /// `Sum grad u Theta` and, interleaved, `Sum (x + i y)^(k-1) (u_x + i u_y) Theta` for
    /// `k = 2..=M / 2 + 1` over the last [`Self::sample`]d shape (rows and columns `lo..=hi`).
    #[inline(always)]
    fn moments<const M: usize>(&mut self, lo: usize, hi: usize) -> (f64, f64, Vec<f64>) {
        let n = self.grid.n;
        self.polar.ensure(&self.grid, lo, hi, M / 2 + 1);
        let (mut fx, mut fy) = (0.0, 0.0);
        let mut g = [0.0; M];
        let stride = self.polar.stride();
        for iy in lo..=hi {
            let row = iy * n + lo..=iy * n + hi;
            let (_, _, powers) = self.polar.row(iy, lo, hi);
            let points = self.sampled.theta[row.clone()]
                .iter()
                .zip(&self.grad.ux[row.clone()])
                .zip(&self.grad.uy[row])
                .zip(powers.chunks_exact(stride));
            for (((&t, ux), uy), powers) in points {
                if t == 0.0 {
                    continue;
                }
                let (gx, gy) = (ux * t, uy * t);
                fx += gx;
                fy += gy;
                // w_k^(a) . g and w_k^(b) . g without their factor R^(2-k)
                // ([`crate::model::modes::w_fields`]), with (Re, Im) of (x + i y)^(k-1).
                let powers = &powers[..M];
                for j in 0..M / 2 {
                    let (re, im) = (powers[2 * j], powers[2 * j + 1]);
                    g[2 * j] += re * gx - im * gy;
                    g[2 * j + 1] += im * gx + re * gy;
                }
            }
        }
        (fx, fy, g.to_vec())
    }

    /// The field's gradient `(u_x, u_y)` of the last [`Self::gradient`] (row-major `N x N`,
    /// the droplet's rows).
    pub fn gradient_rows(&self) -> (&[f64], &[f64]) {
        (&self.grad.ux, &self.grad.uy)
    }

    /// The forces `-Int grad u Theta` and `-Int w_k . grad u Theta` of the last
    /// [`Self::gradient`] on the last [`Self::sample`]d shape (`k_max` modes, rows `lo..=hi`).
    pub fn sums(&mut self, k_max: usize, lo: usize, hi: usize, area: f64) -> ShapeForces {
        let m = 2 * (k_max - 1);
        // The moments' accumulators held in registers for the usual K: the same sums, in the
        // same order, as for any other K.
        let (fx, fy, g) = match m {
            2 => self.moments::<2>(lo, hi),
            4 => self.moments::<4>(lo, hi),
            6 => self.moments::<6>(lo, hi),
            8 => self.moments::<8>(lo, hi),
            10 => self.moments::<10>(lo, hi),
            _ => self.moments::<{ 2 * (MAX_MODES - 1) }>(lo, hi),
        };
        let g = &g[..m];
        let mut f = ShapeForces {
            fx,
            fy,
            ga: g.iter().step_by(2).copied().collect(),
            gb: g.iter().skip(1).step_by(2).copied().collect(),
            area,
        };
        let da = -self.grid.dx * self.grid.dx;
        f.fx *= da;
        f.fy *= da;
        let r0 = self.shape.radius;
        for (k, (ga, gb)) in (2..).zip(f.ga.iter_mut().zip(f.gb.iter_mut())) {
            let scale = da * r0.powi(2 - k);
            *ga *= scale;
            *gb *= scale;
        }
        f
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_predictors_droplet_is_the_pointwise_extrapolation_whatever_the_windows() {
        let grid = Grid::new(64, 7.0).unwrap();
        let shape = ShapeParams {
            radius: 1.0,
            sigma: 0.03,
        };
        let mut quad = ForceQuadrature::new(grid.clone(), shape);
        let sampled = |quad: &mut ForceQuadrature, a2: f64| {
            quad.sample(&Modes {
                a: vec![a2, 0.02],
                b: vec![-0.02, 0.01],
            });
            let mut s = SampledShape::new(&grid);
            quad.exchange(&mut s);
            s
        };
        let n = grid.n;
        // One window (the row-by-row path), then a droplet behind with a wider one.
        for (back_a2, same_window) in [(0.1001, true), (0.3, false)] {
            let base = sampled(&mut quad, 0.1);
            let back = sampled(&mut quad, back_a2);
            assert_eq!((base.lo, base.hi) == (back.lo, back.hi), same_window);
            let alpha = 0.7;
            let (area, lo, hi) = quad.extrapolate(&base, &back, alpha);
            assert_eq!((lo, hi), (base.lo.min(back.lo), base.hi.max(back.hi)));
            assert_eq!(area, base.area + alpha * (base.area - back.area));
            for iy in lo..=hi {
                for ix in lo..=hi {
                    let i = iy * n + ix;
                    let (b, q) = (base.at(iy, ix, i), back.at(iy, ix, i));
                    assert_eq!(quad.theta()[i], b + alpha * (b - q));
                }
            }
        }
    }
}
