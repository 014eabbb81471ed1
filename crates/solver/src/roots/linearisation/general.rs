//! Linear stability of a steady state of the model with shape modes `2..K`, field included:
//! the construction of [`crate::roots::linearisation`] for the state
//! `z = (vx, vy, a_2..a_K, b_2..b_K)` (`2K` unknowns). In the co-moving frame
//!
//! `du_t = D du + B dz`,  `M dz_t = E dz + C du`,  `M = diag(m, m, eta_k.., eta_k..)`
//! (`eta_k` of [`SteadySolver::eta`]: `eta2` for every mode unless a friction law is set),
//!
//! with `D = -(1 + k^2) + i k.v`, `B`'s columns `i k_x u0`, `i k_y u0` and the shape
//! derivatives of the source `Theta / A`, `C du` the forces of a field at the frozen shape and
//! `E` the rest (`-eta_t`, `-kappa_k`, and the shape derivatives of the forces at the frozen
//! field). Every eigenvalue with `Re lambda > -1` solves `det T(lambda) = 0`,
//! `T(lambda) = lambda M - E - C (lambda - D)^(-1) B`, a `2K x 2K` matrix of single sums over
//! the modes. The roots are found by Newton on `det T` divided by the roots already found
//! (its logarithmic derivative `tr(T^(-1) T')`, exact), started from the eigenvalues of the
//! `lambda = 0` problem `M^(-1) (E + C (-D)^(-1) B)`.
//!
//! The sums run over every stored mode (`N (N/2 + 1)`, 18 624 at N = 192), for each of the
//! some hundred `lambda` Newton visits. Only the slow modes need it: where `|d_k| >=`
//! [`FAR`], `1 / (lambda - d_k) = -Sum_p lambda^p / d_k^(p+1)`, so the fast modes' part of
//! the sums is `-Sum_p lambda^p M_p` with the moments `M_p = Sum_far c_k b_k^T / d_k^(p+1)`,
//! made once per state ([`FarField`]); for `|lambda| <=` [`SERIES_RADIUS`] the first
//! [`TERMS`] of them leave `(SERIES_RADIUS / FAR)^TERMS = 4e-15` of each fast mode's term. The
//! slow modes (a few hundred at every N) are summed as they are.
use crate::model::forces::quadrature::fill_operator;
use crate::model::modes::Modes;
use crate::roots::steady_solver::SteadySolver;
use crate::roots::verdict::{assess, Spectrum, Verdict};
use nalgebra::DMatrix;
use rustfft::num_complex::Complex64;

type C64 = Complex64;

/// Step of the central differences in the shape.
const SHAPE_STEP: f64 = 1e-6;

/// Smallest `|d_k|` of a mode whose part of the response is taken from the moments.
pub const FAR: f64 = 256.0;

/// Largest `|lambda|` at which the response is summed with the moments (else every mode is
/// summed as it is).
pub const SERIES_RADIUS: f64 = 4.0;

/// Moments kept: `(SERIES_RADIUS / FAR)^TERMS = 3.5e-15`.
pub const TERMS: usize = 8;

/// The fast modes' part of the response, as moments ([`Linearization`]'s module notes).
struct FarField {
    /// The stored modes with `|d_k| <` [`FAR`].
    near: Vec<usize>,
    /// `M_p[j][i] = Sum_far c_ik b_jk / d_k^(p+1)` for `p < TERMS`.
    moments: Vec<Vec<Vec<C64>>>,
}

impl FarField {
    /// The moments of the modes with `|d_k| >= far`.
    fn new(d: &[C64], b: &[Vec<C64>], c: &[C64], far: f64) -> Self {
        let dim = b.len();
        let zero = C64::default();
        let mut moments = vec![vec![vec![zero; dim]; dim]; TERMS];
        let mut near = Vec::new();
        for (k, d) in d.iter().enumerate() {
            if d.norm() < far {
                near.push(k);
                continue;
            }
            let w = d.inv();
            let ck = &c[k * dim..(k + 1) * dim];
            for (j, b) in b.iter().enumerate() {
                let mut t = b[k] * w;
                for m in moments.iter_mut() {
                    for (acc, c) in m[j].iter_mut().zip(ck) {
                        *acc += t * c;
                    }
                    t *= w;
                }
            }
        }
        Self { near, moments }
    }

    /// `-Sum_p l^p M_p[j]` and, with `slope`, `-Sum_p p l^(p-1) M_p[j]`, added to `s` and `ds`.
    fn add(&self, j: usize, l: C64, s: &mut [C64], ds: Option<&mut [C64]>) {
        let mut power = C64::new(1.0, 0.0);
        for m in &self.moments {
            for (s, m) in s.iter_mut().zip(&m[j]) {
                *s -= power * m;
            }
            power *= l;
        }
        if let Some(ds) = ds {
            let mut power = C64::new(1.0, 0.0);
            for (p, m) in self.moments.iter().enumerate().skip(1) {
                for (s, m) in ds.iter_mut().zip(&m[j]) {
                    *s -= power * m * p as f64;
                }
                power *= l;
            }
        }
    }
}

/// The linearisation of one `K`-mode state.
pub struct Linearization {
    z0: Vec<f64>,
    d: Vec<C64>,
    b: Vec<Vec<C64>>,
    e: Vec<Vec<f64>>,
    m: Vec<f64>,
    /// The forces on the frozen shape as functionals of a field's half spectrum
    /// ([`force_functionals`]), `[k][i]`: `dim` values per stored mode.
    c: Vec<C64>,
    far: FarField,
}

impl Linearization {
    /// Linearises `solver`'s model about `z0 = (vx, vy, a_2..a_K, b_2..b_K)` (a root of the
    /// force balance; taken wherever `z0` is). Needs inertia `m > 0`.
    pub fn at(solver: &mut SteadySolver, z0: &[f64]) -> Self {
        let p = *solver.params();
        let dim = z0.len();
        let m0 = Modes::of_state(z0);
        let k_max = m0.k_max();
        solver.forces(z0[0], z0[1], &m0);
        let u0 = solver.field_spectrum().to_vec();
        let mut d = vec![C64::default(); u0.len()];
        fill_operator(solver.grid(), z0[0], z0[1], &mut d);
        let grid = solver.grid().clone();
        let n = grid.n;
        let mut b: Vec<Vec<C64>> = Vec::with_capacity(dim);
        for use_x in [true, false] {
            let mut col = Vec::with_capacity(u0.len());
            for jx in 0..=n / 2 {
                for jy in 0..n {
                    let k = if use_x { grid.kx_d[jx] } else { grid.ky_d[jy] };
                    col.push(C64::new(0.0, k) * u0[jx * n + jy]);
                }
            }
            b.push(col);
        }
        let mut e = vec![vec![0.0; dim]; dim];
        e[0][0] = -p.eta_t;
        e[1][1] = -p.eta_t;
        let h = SHAPE_STEP;
        for j in 2..dim {
            let shifted = |sign: f64| {
                let mut z = z0.to_vec();
                z[j] += sign * h;
                Modes::of_state(&z)
            };
            solver.quadrature_mut().source(&shifted(1.0));
            let sp = solver.quadrature_mut().source_spectrum().to_vec();
            solver.quadrature_mut().source(&shifted(-1.0));
            let sm = solver.quadrature_mut().source_spectrum();
            b.push(
                sp.iter()
                    .zip(sm)
                    .map(|(a, c)| (a - c) / (2.0 * h))
                    .collect(),
            );
            // The frozen field's forces on the shifted shape.
            let mut forces = |sign: f64| {
                let (area, lo, hi) = solver.quadrature_mut().sample(&shifted(sign));
                solver.quadrature_mut().gradient(&u0, lo, hi);
                solver.quadrature_mut().sums(k_max, lo, hi, area).to_vec()
            };
            let (fp, fm) = (forces(1.0), forces(-1.0));
            for i in 0..dim {
                e[i][j] = (fp[i] - fm[i]) / (2.0 * h);
            }
            let k = 2 + (j - 2) % (k_max - 1);
            e[j][j] -= (k * k) as f64 / 4.0 * p.kappa2;
        }
        let mut m = vec![p.mass, p.mass];
        m.extend((2..=k_max).chain(2..=k_max).map(|k| solver.eta(k)));
        let c = force_functionals(solver, &m0);
        let far = FarField::new(&d, &b, &c, FAR);
        Self {
            z0: z0.to_vec(),
            d,
            b,
            e,
            m,
            c,
            far,
        }
    }

    /// `C (lambda - D)^(-1) B`: the forces of the response fields. The field `(lambda - D)^(-1)
    /// b` of a real perturbation is not real; its real and imaginary parts are the half
    /// spectra `(g1 + g2) b / 2` and `-i (g1 - g2) b / 2` (`g1 = (lambda - d)^(-1)`,
    /// `g2 = (conj lambda - d)^(-1)`), and with the forces' functionals `c` this is
    /// `(S(lambda) + conj S(conj lambda)) / 2`, `S_ij(l) = Sum_k c_ik b_jk / (l - d_k)`: one
    /// pass over the spectrum per column, no transform.
    /// With `slope`, its derivative in `lambda` too, `-C (lambda - D)^(-2) B` (the same
    /// reflection: `(S'(lambda) + conj S'(conj lambda)) / 2`).
    /// With `lambda` within [`SERIES_RADIUS`], the fast modes' part comes from the moments
    /// ([`FarField`]).
    fn response(&self, lambda: C64, slope: bool) -> (Vec<Vec<C64>>, Vec<Vec<C64>>) {
        let dim = self.z0.len();
        let zero = C64::default();
        let series = lambda.norm() <= SERIES_RADIUS;
        let all: Vec<usize>;
        let modes = if series {
            &self.far.near
        } else {
            all = (0..self.d.len()).collect();
            &all
        };
        let g: Vec<(C64, C64)> = modes
            .iter()
            .map(|&k| {
                (
                    (lambda - self.d[k]).inv(),
                    (lambda.conj() - self.d[k]).inv(),
                )
            })
            .collect();
        let mut r = vec![vec![zero; dim]; dim];
        let mut dr = vec![vec![zero; if slope { dim } else { 0 }]; dim];
        let mut acc = vec![zero; 4 * dim];
        for (j, b) in self.b.iter().enumerate() {
            acc.fill(zero);
            let (pq, dpq) = acc.split_at_mut(2 * dim);
            let (p, q) = pq.split_at_mut(dim);
            let (dp, dq) = dpq.split_at_mut(dim);
            if series {
                self.far.add(j, lambda, p, slope.then_some(&mut *dp));
                self.far.add(j, lambda.conj(), q, slope.then_some(&mut *dq));
            }
            for ((g1, g2), &k) in g.iter().zip(modes) {
                let (b, c) = (&b[k], &self.c[k * dim..(k + 1) * dim]);
                let (t1, t2) = (g1 * b, g2 * b);
                for ((p, q), c) in p.iter_mut().zip(q.iter_mut()).zip(c) {
                    *p += t1 * c;
                    *q += t2 * c;
                }
                if slope {
                    let (u1, u2) = (t1 * g1, t2 * g2);
                    for ((p, q), c) in dp.iter_mut().zip(dq.iter_mut()).zip(c) {
                        *p -= u1 * c;
                        *q -= u2 * c;
                    }
                }
            }
            for i in 0..dim {
                r[i][j] = 0.5 * (p[i] + q[i].conj());
                if slope {
                    dr[i][j] = 0.5 * (dp[i] + dq[i].conj());
                }
            }
        }
        (r, dr)
    }

    /// `T(lambda) = lambda M - E - C (lambda - D)^(-1) B`.
    pub fn t_matrix(&self, lambda: C64) -> DMatrix<C64> {
        self.t_and_slope(lambda, false).0
    }

    /// `T(lambda)` and, with `slope`, `T'(lambda) = M + C (lambda - D)^(-2) B` (else empty).
    fn t_and_slope(&self, lambda: C64, slope: bool) -> (DMatrix<C64>, DMatrix<C64>) {
        let (r, dr) = self.response(lambda, slope);
        let dim = self.z0.len();
        let diag = |i: usize, j: usize, x: C64| {
            if i == j {
                x * self.m[i]
            } else {
                C64::default()
            }
        };
        let t = DMatrix::from_fn(dim, dim, |i, j| diag(i, j, lambda) - self.e[i][j] - r[i][j]);
        let dt = match slope {
            true => DMatrix::from_fn(dim, dim, |i, j| diag(i, j, C64::new(1.0, 0.0)) - dr[i][j]),
            false => DMatrix::zeros(0, 0),
        };
        (t, dt)
    }

    /// `-T(0)`: the Jacobian of the steady force balance with the steady field following `z`.
    pub fn jacobian0(&self) -> Vec<Vec<f64>> {
        let t = self.t_matrix(C64::default());
        let dim = self.z0.len();
        (0..dim)
            .map(|i| (0..dim).map(|j| -t[(i, j)].re).collect())
            .collect()
    }

    /// The eigenvalues with `Re lambda > -1`, sorted by decreasing real part; one `NaN` when
    /// the state or its response is not finite (counted as growing by [`Self::verdict`]).
    pub fn eigenvalues(&self) -> Vec<C64> {
        let dim = self.z0.len();
        let (r0, _) = self.response(C64::default(), false);
        let k0 = DMatrix::from_fn(dim, dim, |i, j| (self.e[i][j] + r0[i][j].re) / self.m[i]);
        let Some(guesses) = crate::numerics::eigen::complex_eigenvalues(&k0) else {
            return vec![C64::new(f64::NAN, 0.0)];
        };
        // `(det T)' / det T = tr(T^(-1) T')`; `None` where `T` is singular (a root).
        let log_slope = |l: C64| {
            let (t, dt) = self.t_and_slope(l, true);
            t.lu().solve(&dt).map(|x| x.trace())
        };
        let mut found: Vec<C64> = Vec::new();
        for guess in guesses.iter().chain(&guesses) {
            if found.len() == dim {
                break;
            }
            let mut lambda = C64::new(guess.re.max(-0.99), guess.im);
            let mut converged = false;
            // Iterations in a row that Newton pushed out to `Re lambda <= -1`, where no root
            // is sought: after three the guess is given up (its root lies there).
            let mut pushed_out = 0;
            for _ in 0..60 {
                let Some(slope) = log_slope(lambda) else {
                    converged = true;
                    break;
                };
                let log_d = slope - found.iter().map(|r| (lambda - r).inv()).sum::<C64>();
                let mut step = log_d.inv();
                if !step.is_finite() {
                    break;
                }
                if step.norm() > 0.2 {
                    step *= 0.2 / step.norm();
                }
                lambda -= step;
                if lambda.re < -0.999 {
                    lambda.re = -0.999;
                    pushed_out += 1;
                    if pushed_out == 3 {
                        break;
                    }
                } else {
                    pushed_out = 0;
                }
                if step.norm() < 1e-11 {
                    converged = true;
                    break;
                }
            }
            if converged && lambda.re > -0.999 {
                found.push(super::real_if_round_off(lambda));
            }
        }
        found.sort_by(|a, b| b.re.total_cmp(&a.re));
        found
    }
}

/// The forces of [`SteadySolver::sums`] on the shape `m` (`(Fx, Fy, G^(a)_k.., G^(b)_k..)`, `dim
/// = 2K`) as real-linear functionals of a field's normalised half spectrum `u`:
/// `F_i(u) = Sum_k Re(c_ik u_k)`, returned `[k][i]`. Each force is `Sum_x wx_i ux + wy_i uy`
/// over the grid, with weights `Theta` times the modes' `w_k`; for a real weight field `w`,
/// `Sum_x w IFFT(X) = Sum_k m_k Re(X_k conj(W_k))` over the half spectrum (`W` its transform,
/// `m_k = 1` on the columns `kx = 0` and `N/2`, 2 elsewhere), and `X = i k u` for a
/// derivative.
fn force_functionals(solver: &mut SteadySolver, m: &Modes) -> Vec<C64> {
    let (_, lo, hi) = solver.quadrature_mut().sample(m);
    let grid = solver.grid().clone();
    let (n, k_max) = (grid.n, m.k_max());
    let dim = 2 * k_max;
    let (da, r0) = (-grid.dx * grid.dx, solver.params().radius);
    let (mut wx, mut wy) = (vec![vec![0.0; n * n]; dim], vec![vec![0.0; n * n]; dim]);
    let theta = solver.quadrature_mut().theta();
    for iy in lo..=hi {
        let y = grid.coord(iy);
        for ix in lo..=hi {
            let i = iy * n + ix;
            let t = da * theta[i];
            if t == 0.0 {
                continue;
            }
            let x = grid.coord(ix);
            wx[0][i] = t;
            wy[1][i] = t;
            // `(Re, Im)` of `(x + i y)^(k-1)`, as in the sums.
            let (mut re, mut im) = (x, y);
            for j in 0..k_max - 1 {
                let s = t * r0.powi(-(j as i32));
                (wx[2 + j][i], wy[2 + j][i]) = (s * re, -s * im);
                (wx[k_max + 1 + j][i], wy[k_max + 1 + j][i]) = (s * im, s * re);
                (re, im) = (re * x - im * y, re * y + im * x);
            }
        }
    }
    let mut c = vec![C64::default(); grid.spectral_len() * dim];
    for (i, (wx, wy)) in wx.iter_mut().zip(&mut wy).enumerate() {
        let (tx, ty) = (
            solver.quadrature_mut().transform(wx, lo, hi),
            solver.quadrature_mut().transform(wy, lo, hi),
        );
        for jx in 0..=n / 2 {
            let weight = if jx == 0 || 2 * jx == n { 1.0 } else { 2.0 };
            for jy in 0..n {
                let k = jx * n + jy;
                let g = grid.kx_d[jx] * tx[k].conj() + grid.ky_d[jy] * ty[k].conj();
                c[k * dim + i] = C64::new(0.0, weight) * g;
            }
        }
    }
    c
}

impl Linearization {
    /// The unit null vector of `T(lambda)` (its smallest singular vector).
    pub fn mode(&self, lambda: C64) -> Vec<C64> {
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

    fn mode(&self, lambda: C64) -> Vec<C64> {
        Linearization::mode(self, lambda)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::ModelParams;
    use crate::numerics::newton::fd_jacobian;
    use crate::roots::linearisation::TwoModeLinearization;
    use crate::roots::steady_solver::TwoModeSolver;

    /// At the Fig. 1c point and grid size `n`: the 2-mode solver, the K-mode one and the
    /// 2-mode MD state `(v, 0, a2, 0)` (which both describe).
    impl Linearization {
        /// The same linearisation with every mode summed as it is (no moments).
        fn summing_every_mode(mut self) -> Self {
            self.far = FarField::new(&self.d, &self.b, &self.c, f64::INFINITY);
            self
        }
    }

    #[test]
    fn the_fast_modes_moments_give_the_full_sums() {
        // Modes 2..4, the x-axis MD at (0.085, 0.112), N = 96 (4704 stored modes, 1280 of
        // them slow): T(lambda) and T'(lambda) with the moments against every mode summed,
        // inside the series' radius and at its edge; the eigenvalues both ways.
        let p = ModelParams::at(0.085, 0.112);
        let mut solver = SteadySolver::new(p, 96).unwrap();
        let st = crate::roots::named_state::md_state(&mut solver, 4).unwrap();
        let z = [st.v, 0.0, st.a[0], st.a[1], st.a[2], 0.0, 0.0, 0.0];
        let fast = Linearization::at(&mut solver, &z);
        assert!(
            fast.far.near.len() < fast.d.len() / 3,
            "{}",
            fast.far.near.len()
        );
        let full = Linearization::at(&mut solver, &z).summing_every_mode();
        for l in [
            C64::new(0.0, 0.0),
            C64::new(-0.3, 0.2),
            C64::new(0.01, -0.5),
            C64::new(-2.8, 2.8),
        ] {
            let (t, dt) = fast.t_and_slope(l, true);
            let (u, du) = full.t_and_slope(l, true);
            let scale = u.iter().fold(0.0f64, |m, x| m.max(x.norm()));
            assert!((t - &u).iter().all(|x| x.norm() < 1e-13 * scale), "{l}");
            assert!((dt - du).iter().all(|x| x.norm() < 1e-13 * scale), "{l}");
        }
        let (a, b) = (fast.eigenvalues(), full.eigenvalues());
        assert_eq!(a.len(), b.len(), "{a:?} {b:?}");
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).norm() < 1e-10, "{a:?} {b:?}");
        }
    }

    fn fig1c_two_mode_md(n: usize) -> (TwoModeSolver, SteadySolver, [f64; 4]) {
        let p = ModelParams::at(0.085, 0.112);
        let mut two = TwoModeSolver::new(p, n).unwrap();
        let st = two.newton(0.59, -0.27, 1e-12).unwrap();
        (
            two,
            SteadySolver::new(p, n).unwrap(),
            [st.v, 0.0, st.a2, 0.0],
        )
    }

    #[test]
    fn with_two_modes_the_eigenvalues_are_the_two_mode_ones() {
        let (mut two, mut solver, z) = fig1c_two_mode_md(64);
        let want = TwoModeLinearization::at(&mut two, z).eigenvalues();
        let lin = Linearization::at(&mut solver, &z);
        let got = lin.eigenvalues();
        assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
        for (g, w) in got.iter().zip(&want) {
            // Measured: 1e-10.
            assert!((g - w).norm() < 1e-8, "{got:?} vs {want:?}");
        }
    }

    #[test]
    fn the_force_functionals_are_the_forces_of_the_fields_gradient() {
        // K = 3, a shape off every mirror line, and a field with every coefficient set:
        // `Sum_k Re(c_ik u_k)` against the sums over the grid of the field's gradient.
        let p = ModelParams::at(0.085, 0.112);
        let mut solver = SteadySolver::new(p, 64).unwrap();
        let m = Modes::of_state(&[0.3, 0.05, -0.15, 0.03, 0.02, -0.01]);
        let c = force_functionals(&mut solver, &m);
        let len = solver.grid().spectral_len();
        let u: Vec<C64> = (0..len)
            .map(|k| {
                C64::new(
                    ((k * 7919) % 101) as f64 - 50.0,
                    ((k * 104_729) % 89) as f64 - 44.0,
                )
            })
            .map(|x| x * 1e-3)
            .collect();
        let (area, lo, hi) = solver.quadrature_mut().sample(&m);
        solver.quadrature_mut().gradient(&u, lo, hi);
        let want = solver.quadrature_mut().sums(3, lo, hi, area).to_vec();
        for (i, w) in want.iter().enumerate() {
            let got: f64 = u
                .iter()
                .zip(c.chunks_exact(6))
                .map(|(u, c)| (u * c[i]).re)
                .sum();
            assert!(
                (got - w).abs() < 1e-10 * w.abs().max(1.0),
                "{i}: {got} vs {w}"
            );
        }
    }

    #[test]
    fn t_at_zero_is_the_finite_difference_jacobian() {
        // K = 3, a moving deformed state (not a root: T(0) is defined anywhere).
        let p = ModelParams::at(0.085, 0.112);
        let mut solver = SteadySolver::new(p, 64).unwrap();
        let z = [0.3, 0.05, -0.15, 0.03, 0.02, -0.01];
        let lin = Linearization::at(&mut solver, &z);
        let j0 = lin.jacobian0();
        let fd = fd_jacobian(&mut |y: &[f64]| solver.residual(y), &z, 1e-6);
        for i in 0..z.len() {
            for j in 0..z.len() {
                assert!(
                    (j0[i][j] - fd[i][j]).abs() < 1e-6,
                    "({i}, {j}): {} vs {}",
                    j0[i][j],
                    fd[i][j]
                );
            }
        }
    }

    #[test]
    fn real_eigenvalues_are_real_and_the_fast_mds_rotation_is_found() {
        // The x-axis MD with modes 2..4 at (0.0725, 0.13), N = 96: v = 0.979, its rotation
        // mode growing slowly (+0.0175). Newton in the complex plane left its eigenvalue an
        // imaginary part of round-off (-3.5e-24 at N = 192), so the verdict, which takes
        // only real eigenvalues for the rotation, counted it as a growing mode and the state
        // unstable. Every eigenvalue is now real or one of a conjugate pair.
        let p = ModelParams::at(0.0725, 0.13);
        let mut solver = SteadySolver::new(p, 96).unwrap();
        let st = crate::roots::named_state::md_state(&mut solver, 4).unwrap();
        let z = [st.v, 0.0, st.a[0], st.a[1], st.a[2], 0.0, 0.0, 0.0];
        let lin = Linearization::at(&mut solver, &z);
        let eigenvalues = lin.eigenvalues();
        for l in &eigenvalues {
            let paired = eigenvalues.iter().any(|m| (m - l.conj()).norm() < 1e-8);
            assert!(
                l.im == 0.0 || (l.im.abs() > 1e-8 && paired),
                "{eigenvalues:?}"
            );
        }
        let verdict = lin.verdict();
        let rotation = verdict.rotation.expect("the rotation mode");
        assert!(rotation > 0.0 && rotation < 0.05, "{verdict:?}");
        assert!(verdict.stable(), "{verdict:?}");
    }

    #[test]
    fn the_verdict_finds_the_rotation_mode_and_agrees_with_two_modes() {
        let (mut two, mut solver, z) = fig1c_two_mode_md(96);
        let want = crate::roots::verdict::assess(&TwoModeLinearization::at(&mut two, z), &z);
        let got = Linearization::at(&mut solver, &z).verdict();
        assert_eq!(got.stable(), want.stable(), "{got:?} {want:?}");
        match (got.rotation, want.rotation) {
            (Some(a), Some(b)) => assert!((a - b).abs() < 1e-8, "{got:?} {want:?}"),
            other => panic!("{other:?}: {got:?} {want:?}"),
        }
    }
}
