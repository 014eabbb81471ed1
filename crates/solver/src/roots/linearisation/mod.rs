//! Linear stability of a steady or steadily moving state, field included (docs/model.md,
//! "Steady states as roots"). In the co-moving frame the linearisation about `(u0, z0)`,
//! `z = (vx, vy, a_2..a_K, b_2..b_K)`, is
//!
//! `du_t = D du + B dz`,  `M dz_t = E dz + C du`,  `M = diag(m, m, eta_k.., eta_k..)`,
//!
//! with `D = -(1 + k^2) + i k.v` diagonal in Fourier space (`Re D <= -1`), `B`'s columns the
//! field equation's sensitivity to `z` (`i k_x u0`, `i k_y u0` and the shape derivatives of
//! the source `Theta / A`), `C du` the forces of a field `du` at the frozen shape (real-linear
//! functionals of its half spectrum, `F_i(u) = Sum_k Re(c_ik u_k)`), and `E` the rest
//! (`-eta_t` on the velocity, `-kappa_k` on the shape, the forces' shape derivatives at fixed
//! `u0`). Every eigenvalue with `Re lambda > -1` solves the `2K x 2K` nonlinear eigenproblem
//! `T(lambda) dz = 0`, `T(lambda) = lambda M - E - C (lambda - D)^(-1) B`, whose entries are
//! single sums over the modes: the field's own modes decay at rate >= 1 and cannot
//! destabilise anything.
//!
//! One [`Linearization`] for every `K`, with two constructions of its parts: [`general`], the
//! forces by quadrature on a droplet of any shape ([`crate::roots::steady_solver::SteadySolver`]),
//! and [`two_mode`], the fast path of `K = 2` (the point-symmetric droplet's forces by
//! Parseval, [`crate::roots::steady_solver::TwoModeSolver`]); they give the same eigenvalues
//! (tested). The sums over the fast modes come from their moments ([`far_field`]); the
//! eigenvalues are the roots of `det T` ([`eigenvalues`]).
pub mod eigenvalues;
pub mod far_field;
pub mod general;
pub mod two_mode;

use crate::model::forces::quadrature::fill_operator;
use crate::model::grid::Grid;
use crate::roots::verdict::{assess, Spectrum, Verdict};
use far_field::{FarField, FAR, SERIES_RADIUS};
use nalgebra::DMatrix;
use rustfft::num_complex::Complex64;
use std::sync::OnceLock;

type C64 = Complex64;

/// Step of the central differences in the shape (both constructions).
const SHAPE_STEP: f64 = 1e-6;

/// Largest `|Im lambda|` of an eigenvalue taken to be real: Newton in the complex plane leaves
/// a real root of `det T` with an imaginary part of round-off (`1e-24` measured at K = 4),
/// and a verdict tells the rotation mode, and a continuation a real crossing from a complex
/// one, by `Im lambda == 0`.
pub const REAL_EIGENVALUE: f64 = 1e-10;

/// `lambda`, its imaginary part set to 0 where it is round-off ([`REAL_EIGENVALUE`]).
pub fn real_if_round_off(lambda: Complex64) -> Complex64 {
    if lambda.im.abs() < REAL_EIGENVALUE {
        Complex64::new(lambda.re, 0.0)
    } else {
        lambda
    }
}

/// The linearisation of one state `z0 = (vx, vy, a_2..a_K, b_2..b_K)`.
pub struct Linearization {
    z0: Vec<f64>,
    /// `d(k)` for every stored mode.
    d: Vec<C64>,
    /// The columns of `B` (half spectra, normalised like the steady field).
    b: Vec<Vec<C64>>,
    e: Vec<Vec<f64>>,
    m: Vec<f64>,
    /// The forces on the frozen shape as functionals of a field's half spectrum, `[k][i]`:
    /// `dim` values per stored mode.
    c: Vec<C64>,
    /// The fast modes' moments, made when a response within [`SERIES_RADIUS`] first asks.
    far: OnceLock<FarField>,
    /// The split between slow and fast modes ([`FAR`]; tests sum every mode).
    far_from: f64,
}

/// The parts both constructions share: `D = -(1 + k^2) + i k.v` for every stored mode of
/// `grid`, and `B`'s velocity columns `i k_x u0`, `i k_y u0` for the steady field `u0`
/// (normalised half spectrum, `[kx][ky]`).
fn field_parts(grid: &Grid, vx: f64, vy: f64, u0: &[C64]) -> (Vec<C64>, Vec<Vec<C64>>) {
    let n = grid.n;
    let mut d = vec![C64::default(); u0.len()];
    fill_operator(grid, vx, vy, &mut d);
    let advect = |use_x: bool| -> Vec<C64> {
        let mut out = Vec::with_capacity(u0.len());
        for jx in 0..=n / 2 {
            for jy in 0..n {
                let k = if use_x { grid.kx_d[jx] } else { grid.ky_d[jy] };
                out.push(C64::new(0.0, k) * u0[jx * n + jy]);
            }
        }
        out
    };
    (d, vec![advect(true), advect(false)])
}

impl Linearization {
    /// The linearisation of its parts (both constructions end here).
    fn of_parts(
        z0: Vec<f64>,
        d: Vec<C64>,
        b: Vec<Vec<C64>>,
        e: Vec<Vec<f64>>,
        m: Vec<f64>,
        c: Vec<C64>,
    ) -> Self {
        Self {
            z0,
            d,
            b,
            e,
            m,
            c,
            far: OnceLock::new(),
            far_from: FAR,
        }
    }

    /// The state's dimension `2K`.
    fn dim(&self) -> usize {
        self.z0.len()
    }

    /// `R(lambda) = C (lambda - D)^(-1) B` and its first `order` derivatives
    /// (`R' = -C (lambda - D)^(-2) B`, `R'' = 2 C (lambda - D)^(-3) B`): the forces of the
    /// response fields. The field `(lambda - D)^(-1) b` of a real perturbation is not real;
    /// its real and imaginary parts are the half spectra `(g1 + g2) b / 2` and
    /// `-i (g1 - g2) b / 2` (`g1 = (lambda - d)^(-1)`, `g2 = (conj lambda - d)^(-1)`), so with
    /// the functionals `c` this is `(S(lambda) + conj S(conj lambda)) / 2`,
    /// `S_ij(l) = Sum_k c_ik b_jk / (l - d_k)`, and likewise for the derivatives: one pass
    /// over the spectrum per column, no transform. Within [`SERIES_RADIUS`] the fast modes'
    /// part comes from their moments ([`FarField`]); `all`: every mode summed as it is.
    fn response(&self, lambda: C64, order: usize, all: bool) -> Vec<Vec<Vec<C64>>> {
        let series = !all && lambda.norm() <= SERIES_RADIUS;
        let every: Vec<usize>;
        let far = series.then(|| {
            self.far
                .get_or_init(|| FarField::new(&self.d, &self.b, &self.c, self.far_from))
        });
        let modes = match far {
            Some(far) => &far.near,
            None => {
                every = (0..self.d.len()).collect();
                &every
            }
        };
        if lambda.im == 0.0 {
            self.real_response(lambda.re, order, modes, far)
        } else {
            self.complex_response(lambda, order, modes, far)
        }
    }

    /// [`Self::response`] at a real `lambda`, where it is real, `Re S(lambda)`: only the real
    /// parts summed, the same numbers as the real parts of the complex sums (half the
    /// products).
    fn real_response(
        &self,
        lambda: f64,
        order: usize,
        modes: &[usize],
        far: Option<&FarField>,
    ) -> Vec<Vec<Vec<C64>>> {
        let dim = self.dim();
        let g: Vec<C64> = modes
            .iter()
            .map(|&k| (C64::new(lambda, 0.0) - self.d[k]).inv())
            .collect();
        let mut out = vec![vec![vec![C64::default(); dim]; dim]; order + 1];
        let mut p = vec![vec![0.0; dim]; order + 1];
        for (j, b) in self.b.iter().enumerate() {
            p.iter_mut().for_each(|s| s.fill(0.0));
            if let Some(far) = far {
                let mut ps: Vec<&mut [f64]> = p.iter_mut().map(|s| s.as_mut_slice()).collect();
                far.add(j, lambda, order, &mut ps);
            }
            for (g, &k) in g.iter().zip(modes) {
                let (b, c) = (&b[k], &self.c[k * dim..(k + 1) * dim]);
                // The o-th derivative of 1 / (l - d) is (-1)^o o! g^(o+1).
                let mut t = g * b;
                for (o, s) in p.iter_mut().enumerate() {
                    for (p, c) in s.iter_mut().zip(c) {
                        *p += t.re * c.re - t.im * c.im;
                    }
                    t = t * g * -((o + 1) as f64);
                }
            }
            for (out, p) in out.iter_mut().zip(&p) {
                for (row, p) in out.iter_mut().zip(p) {
                    row[j] = C64::new(*p, 0.0);
                }
            }
        }
        out
    }

    /// [`Self::response`] at a complex `lambda`: `(S(lambda) + conj S(conj lambda)) / 2`.
    fn complex_response(
        &self,
        lambda: C64,
        order: usize,
        modes: &[usize],
        far: Option<&FarField>,
    ) -> Vec<Vec<Vec<C64>>> {
        let dim = self.dim();
        let zero = C64::default();
        let g: Vec<(C64, C64)> = modes
            .iter()
            .map(|&k| {
                let d = self.d[k];
                ((lambda - d).inv(), (lambda.conj() - d).inv())
            })
            .collect();
        let mut out = vec![vec![vec![zero; dim]; dim]; order + 1];
        // `p[o]`: S^(o)(lambda), `q[o]`: S^(o)(conj lambda), for one column.
        let mut p = vec![vec![zero; dim]; order + 1];
        let mut q = vec![vec![zero; dim]; order + 1];
        for (j, b) in self.b.iter().enumerate() {
            p.iter_mut().chain(q.iter_mut()).for_each(|s| s.fill(zero));
            if let Some(far) = far {
                let mut ps: Vec<&mut [C64]> = p.iter_mut().map(|s| s.as_mut_slice()).collect();
                far.add(j, lambda, order, &mut ps);
                let mut qs: Vec<&mut [C64]> = q.iter_mut().map(|s| s.as_mut_slice()).collect();
                far.add(j, lambda.conj(), order, &mut qs);
            }
            for ((g1, g2), &k) in g.iter().zip(modes) {
                let (b, c) = (&b[k], &self.c[k * dim..(k + 1) * dim]);
                let (mut t1, mut t2) = (g1 * b, g2 * b);
                for o in 0..=order {
                    for ((p, q), c) in p[o].iter_mut().zip(q[o].iter_mut()).zip(c) {
                        *p += t1 * c;
                        *q += t2 * c;
                    }
                    let f = -((o + 1) as f64);
                    (t1, t2) = (t1 * g1 * f, t2 * g2 * f);
                }
            }
            for o in 0..=order {
                for i in 0..dim {
                    out[o][i][j] = 0.5 * (p[o][i] + q[o][i].conj());
                }
            }
        }
        out
    }

    /// `T(lambda) = lambda M - E - R(lambda)` and its first `order` derivatives
    /// (`T' = M - R'`, `T'' = -R''`).
    fn t_derivatives(&self, lambda: C64, order: usize, all: bool) -> Vec<DMatrix<C64>> {
        let r = self.response(lambda, order, all);
        let dim = self.dim();
        let one = C64::new(1.0, 0.0);
        (0..=order)
            .map(|o| {
                DMatrix::from_fn(dim, dim, |i, j| {
                    let diag = match (i == j, o) {
                        (true, 0) => lambda * self.m[i],
                        (true, 1) => one * self.m[i],
                        _ => C64::default(),
                    };
                    let e = if o == 0 { self.e[i][j] } else { 0.0 };
                    diag - e - r[o][i][j]
                })
            })
            .collect()
    }

    /// `T(lambda) = lambda M - E - C (lambda - D)^(-1) B`.
    pub fn t_matrix(&self, lambda: C64) -> DMatrix<C64> {
        self.t_derivatives(lambda, 0, false).remove(0)
    }

    /// `-T(0)`: the Jacobian of the steady force balance with the steady field following `z`
    /// (every mode summed: one evaluation needs no moments).
    pub fn jacobian0(&self) -> Vec<Vec<f64>> {
        let t = self.t_derivatives(C64::default(), 0, true).remove(0);
        let dim = self.dim();
        (0..dim)
            .map(|i| (0..dim).map(|j| -t[(i, j)].re).collect())
            .collect()
    }

    /// The unit null vector of `T(lambda)` (its smallest singular vector).
    pub fn eigenmode(&self, lambda: C64) -> Vec<C64> {
        let t = self.t_matrix(lambda);
        let svd = t.svd(false, true);
        let v_t = svd.v_t.expect("asked for");
        let (i, _) = svd
            .singular_values
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1))
            .expect("a singular value");
        v_t.row(i).iter().map(|c| c.conj()).collect()
    }

    /// The verdict ([`assess`]): the rotation mode told apart by its shape, the others decide.
    pub fn verdict(&self) -> Verdict {
        assess(self, &self.z0)
    }
}

impl Spectrum for Linearization {
    fn eigenvalues(&self) -> Vec<C64> {
        Linearization::eigenvalues(self)
    }

    fn eigenmode(&self, lambda: C64) -> Vec<C64> {
        Linearization::eigenmode(self, lambda)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::ModelParams;
    use crate::roots::steady_solver::TwoModeSolver;

    #[test]
    fn at_a_real_lambda_the_real_sums_are_the_complex_sums_real_parts() {
        // Modes 2..3 on a droplet off every mirror line (no root: the sums do not care), N =
        // 64: the response and its two derivatives summed in real arithmetic equal, to the
        // last bit, the complex sums at the same lambda, with the moments and without.
        let p = ModelParams::at(0.085, 0.112).with_modes(3);
        let mut s = crate::roots::steady_solver::SteadySolver::new(p, 64).unwrap();
        let lin = Linearization::at(&mut s, &[0.3, 0.05, -0.18, -0.04, 0.02, 0.01]);
        let far = lin
            .far
            .get_or_init(|| FarField::new(&lin.d, &lin.b, &lin.c, lin.far_from));
        let every: Vec<usize> = (0..lin.d.len()).collect();
        for l in [0.0, -0.37, 1.5] {
            for (modes, far) in [(&far.near, Some(far)), (&every, None)] {
                let real = lin.real_response(l, 2, modes, far);
                let complex = lin.complex_response(C64::new(l, 0.0), 2, modes, far);
                assert_eq!(real, complex, "{l}");
                assert!(real[0].iter().flatten().any(|x| x.re != 0.0));
            }
        }
    }

    #[test]
    fn t_prime_and_t_second_are_the_derivatives_of_t() {
        // The Fig. 1c MD at N = 64, at a complex lambda inside the moments' radius and one
        // outside it: central differences of T and T' against the exact T' and T''.
        let p = ModelParams::at(0.085, 0.112);
        let mut s = TwoModeSolver::new(p, 64).unwrap();
        let st = s.newton(0.59, -0.27, 1e-12).unwrap();
        let lin = Linearization::of_two_modes(&mut s, [st.v, 0.0, st.a2, 0.0]);
        let h = 1e-5;
        for l in [C64::new(-0.2, 0.3), C64::new(3.0, 4.0)] {
            let at = |x: C64| lin.t_derivatives(x, 2, false);
            let (t, up, down) = (at(l), at(l + h), at(l - h));
            for o in 0..2 {
                let fd = (&up[o] - &down[o]) / C64::new(2.0 * h, 0.0);
                let scale = t[o + 1].iter().fold(1.0f64, |m, x| m.max(x.norm()));
                let err = (fd - &t[o + 1]).iter().fold(0.0f64, |m, x| m.max(x.norm()));
                assert!(err < 1e-6 * scale, "{l}, order {}: {err:e}", o + 1);
            }
        }
    }
}
