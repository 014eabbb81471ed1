//! The fast path of `K = 2` for the linear stability of a steady or steadily moving state,
//! field included (docs/model.md,
//! "Steady states as roots"). In the co-moving frame the linearisation about `(u0, z0)`, `z = (vx, vy, a2, b2)`,
//! is
//!
//! `du_t = D du + B dz`,  `M dz_t = E dz + C du`,  `M = diag(m, m, eta2, eta2)`,
//!
//! with `D = -(1 + k^2) + i k.v` diagonal in Fourier space (`Re D <= -1`), `B`'s columns the
//! field equation's sensitivity to `z` (`i k_x u0`, `i k_y u0`, `d(Theta/A)/da2`,
//! `d(Theta/A)/db2`), `C du` the forces `(F, Ga, Gb)` of a field `du` at the frozen shape, and
//! `E` the rest (`-eta_t` on the velocity, `-kappa2` on the shape, and the forces' shape
//! derivatives at fixed `u0`). Every eigenvalue with `Re lambda > -1` solves the 4 x 4
//! nonlinear eigenproblem
//!
//! `T(lambda) dz = 0`,  `T(lambda) = lambda M - E - C (lambda - D)^(-1) B`,
//!
//! whose entries are single sums over the modes: the field's own modes decay at rate >= 1 and
//! cannot destabilise anything. The eigenvalues are found as fixed points
//! `lambda = mu(lambda)` of the eigenvalues `mu` of `M^(-1) (E + C (lambda - D)^(-1) B)`,
//! started from `lambda = 0`.
use crate::model::dynamics;
use crate::model::forces::parseval::{spectral_forces, ColumnSums, ForceSums, Forces};
use crate::roots::steady_solver::TwoModeSolver;
use rustfft::num_complex::Complex64;

type C64 = Complex64;

/// The linearisation of one state.
pub struct TwoModeLinearization {
    /// `d(k)` for every stored mode.
    d: Vec<C64>,
    /// The columns of `B` (half spectra of real fields, normalised like the steady field).
    b: [Vec<C64>; 4],
    /// The frozen shape's transforms, for `C`.
    ph: Vec<C64>,
    yh: Vec<C64>,
    area: f64,
    e: [[f64; 4]; 4],
    m: [f64; 4],
    grid: crate::model::grid::Grid,
}

fn as_array(f: &Forces) -> [f64; 4] {
    [f.fx, f.fy, f.ga, f.gb]
}

/// Step of the central differences in the shape.
const SHAPE_STEP: f64 = 1e-6;

impl TwoModeLinearization {
    /// Linearises the steady state `z0 = (vx, vy, a2, b2)` of `solver`'s parameters (a root of
    /// the force balance; the linearisation is taken wherever `z0` is). Needs inertia `m > 0`.
    pub fn at(solver: &mut TwoModeSolver, z0: [f64; 4]) -> Self {
        let p = *solver.params();
        let [vx, vy, a2, b2] = z0;
        let grid = solver.grid().clone();
        let n = grid.n;
        let (w0, _) = solver.field_and_forces(vx, vy, a2, b2);
        let w0 = w0.to_vec();
        let (ph, yh, area) = solver.shape_spectra(a2, b2);
        let mut d = Vec::with_capacity(grid.spectral_len());
        for jx in 0..=n / 2 {
            for jy in 0..n {
                let (kx, ky) = (grid.kx[jx], grid.ky[jy]);
                let kv = grid.kx_d[jx] * vx + grid.ky_d[jy] * vy;
                d.push(C64::new(-(1.0 + kx * kx + ky * ky), kv));
            }
        }
        let advect = |use_x: bool| -> Vec<C64> {
            let mut out = Vec::with_capacity(w0.len());
            for jx in 0..=n / 2 {
                for jy in 0..n {
                    let k = if use_x { grid.kx_d[jx] } else { grid.ky_d[jy] };
                    out.push(C64::new(0.0, k) * w0[jx * n + jy]);
                }
            }
            out
        };
        // The source Theta_hat / A (normalised as the steady field) of a shape.
        let norm = 1.0 / (n * n) as f64;
        let mut source = |a: f64, b: f64| -> (Vec<C64>, [f64; 4]) {
            let (p2, y2, ar) = solver.shape_spectra(a, b);
            let s: Vec<C64> = p2.iter().map(|q| C64::new(q.re * norm / ar, 0.0)).collect();
            // Forces of the frozen field w0 on this shape.
            let f = spectral_forces(&grid, &w0, &p2, &y2, ar);
            (s, as_array(&f))
        };
        let h = SHAPE_STEP;
        let (sa_p, fa_p) = source(a2 + h, b2);
        let (sa_m, fa_m) = source(a2 - h, b2);
        let (sb_p, fb_p) = source(a2, b2 + h);
        let (sb_m, fb_m) = source(a2, b2 - h);
        let diff = |p: &[C64], m: &[C64]| -> Vec<C64> {
            p.iter().zip(m).map(|(a, b)| (a - b) / (2.0 * h)).collect()
        };
        let b = [
            advect(true),
            advect(false),
            diff(&sa_p, &sa_m),
            diff(&sb_p, &sb_m),
        ];
        // E: the force balance's derivatives at the frozen field.
        let zero = Forces::default();
        let mut e = [[0.0; 4]; 4];
        for (j, col) in [(0usize, [1.0, 0.0, 0.0, 0.0]), (1, [0.0, 1.0, 0.0, 0.0])] {
            let fb = dynamics::force_balance(&p, col, &zero);
            for i in 0..4 {
                e[i][j] = fb[i];
            }
        }
        for (j, (fp, fm), unit) in [
            (2usize, (fa_p, fa_m), [0.0, 0.0, 1.0, 0.0]),
            (3, (fb_p, fb_m), [0.0, 0.0, 0.0, 1.0]),
        ] {
            let linear = dynamics::force_balance(&p, unit, &zero);
            for i in 0..4 {
                e[i][j] = (fp[i] - fm[i]) / (2.0 * h) + linear[i];
            }
        }
        Self {
            d,
            b,
            ph,
            yh,
            area,
            e,
            m: [p.mass, p.mass, p.eta2, p.eta2],
            grid,
        }
    }

    /// `C (lambda - D)^(-1) B` (complex `lambda`: the response field is split into the real
    /// fields of its real and imaginary parts, each a half spectrum).
    fn response(&self, lambda: C64) -> [[C64; 4]; 4] {
        self.response_derivatives(lambda, 0)[0]
    }

    /// `R(lambda) = C (lambda - D)^(-1) B` and its first `order` derivatives in `lambda`
    /// (`R' = -C (lambda - D)^(-2) B`, `R'' = 2 C (lambda - D)^(-3) B`), in one pass over the
    /// modes: `(lambda - d)^(-1)` once per mode for all four columns, and the forces of the
    /// response fields accumulated on the fly (no field is stored).
    ///
    /// With `g1 = (lambda - d)^(-1)`, `g2 = (conj(lambda) - d)^(-1)`, the real and imaginary
    /// parts of the response to column `b` have the half spectra `(g1 + g2) b / 2` and
    /// `-i (g1 - g2) b / 2` (the field at `-k` has `d(-k) = conj(d(k))`); the derivatives
    /// replace `g` by `-g^2` and `2 g^3` in both.
    fn response_derivatives(&self, lambda: C64, order: usize) -> [[[C64; 4]; 4]; 3] {
        let grid = &self.grid;
        let n = grid.n;
        let conj = lambda.conj();
        let half_i = C64::new(0.0, -0.5);
        // [column][derivative][re, im]
        let mut sums = [[[ForceSums::default(); 2]; 3]; 4];
        for jx in 0..=n / 2 {
            let mut cols = [[[ColumnSums::default(); 2]; 3]; 4];
            let row = jx * n..(jx + 1) * n;
            let modes = grid
                .ky_d
                .iter()
                .zip(&self.d[row.clone()])
                .zip(self.ph[row.clone()].iter().zip(&self.yh[row.clone()]));
            for (k, ((ky, d), (p, y))) in row.clone().zip(modes) {
                let (g1, g2) = ((lambda - d).inv(), (conj - d).inv());
                let mut g = [(g1, g2); 3];
                if order >= 1 {
                    g[1] = (-g1 * g1, -g2 * g2);
                }
                if order >= 2 {
                    g[2] = (-2.0 * g[1].0 * g1, -2.0 * g[1].1 * g2);
                }
                for (o, (h1, h2)) in g.iter().enumerate().take(order + 1) {
                    let (he, ho) = (0.5 * (h1 + h2), half_i * (h1 - h2));
                    for (col, b) in cols.iter_mut().zip(&self.b) {
                        let b = b[k];
                        col[o][0].add(*ky, he * b, *p, *y);
                        col[o][1].add(*ky, ho * b, *p, *y);
                    }
                }
            }
            let (wt, kx) = (grid.column_weight(jx), grid.kx_d[jx]);
            for (s, c) in sums.iter_mut().zip(&cols) {
                for (s, c) in s.iter_mut().zip(c).take(order + 1) {
                    s[0].column(wt, kx, &c[0]);
                    s[1].column(wt, kx, &c[1]);
                }
            }
        }
        let da = grid.dx * grid.dx;
        let mut out = [[[C64::default(); 4]; 4]; 3];
        for (j, s) in sums.iter().enumerate() {
            for (o, [re, im]) in s.iter().enumerate().take(order + 1) {
                let (fr, fi) = (
                    as_array(&re.finish(da, self.area)),
                    as_array(&im.finish(da, self.area)),
                );
                for i in 0..4 {
                    out[o][i][j] = C64::new(fr[i], fi[i]);
                }
            }
        }
        out
    }

    /// `T(lambda)`, `T'(lambda) = M - R'(lambda)` and `T''(lambda) = -R''(lambda)`.
    fn t_derivatives(&self, lambda: C64) -> [[[C64; 4]; 4]; 3] {
        let r = self.response_derivatives(lambda, 2);
        let mut t = [[[C64::default(); 4]; 4]; 3];
        for i in 0..4 {
            for j in 0..4 {
                let (diag, ddiag) = if i == j {
                    (lambda * self.m[i], C64::new(self.m[i], 0.0))
                } else {
                    (C64::default(), C64::default())
                };
                t[0][i][j] = diag - self.e[i][j] - r[0][i][j];
                t[1][i][j] = ddiag - r[1][i][j];
                t[2][i][j] = -r[2][i][j];
            }
        }
        t
    }

    /// `T(lambda) = lambda M - E - C (lambda - D)^(-1) B`.
    pub fn t_matrix(&self, lambda: C64) -> [[C64; 4]; 4] {
        let r = self.response(lambda);
        let mut t = [[C64::default(); 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                let diag = if i == j {
                    lambda * self.m[i]
                } else {
                    C64::default()
                };
                t[i][j] = diag - self.e[i][j] - r[i][j];
            }
        }
        t
    }

    /// `-T(0)`: the Jacobian of the steady force balance `R(z)` (with the steady field
    /// following `z`), the `lambda = 0` limit.
    pub fn jacobian0(&self) -> [[f64; 4]; 4] {
        let t = self.t_matrix(C64::default());
        let mut j = [[0.0; 4]; 4];
        for r in 0..4 {
            for c in 0..4 {
                j[r][c] = -t[r][c].re;
            }
        }
        j
    }

    /// `M^(-1) (E + C (lambda - D)^(-1) B)`, whose eigenvalues equal `lambda` at a solution.
    fn k_matrix(&self, lambda: C64) -> [[C64; 4]; 4] {
        let r = self.response(lambda);
        let mut k = [[C64::default(); 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                k[i][j] = (self.e[i][j] + r[i][j]) / self.m[i];
            }
        }
        k
    }

    /// `det T(lambda)`.
    pub fn det(&self, lambda: C64) -> C64 {
        det4(self.t_matrix(lambda))
    }

    /// The mode `dz` of an eigenvalue `lambda` (`T(lambda) dz = 0`), unit length, its largest
    /// component real and positive (a real eigenvalue's mode is then real).
    pub fn mode(&self, lambda: C64) -> [C64; 4] {
        let v = null_vector(&self.t_matrix(lambda));
        let big = v
            .iter()
            .copied()
            .max_by(|a, b| a.norm().total_cmp(&b.norm()))
            .expect("four");
        let phase = if big.norm() > 0.0 {
            big.conj() / big.norm()
        } else {
            C64::new(1.0, 0.0)
        };
        v.map(|c| c * phase)
    }

    /// The eigenvalues with `Re lambda > -1` (the only ones the field's decay leaves), with
    /// multiplicity, sorted by decreasing real part: roots of `det T(lambda)` by Schroeder's
    /// method (Newton on `det / det'`, exact derivatives from `T'`, `T''`; quadratic at
    /// multiple roots), each one divided out before the next is sought, started from the eigenvalues of
    /// the `lambda = 0` problem `M^(-1) (E + C (-D)^(-1) B)` (real states: their real and
    /// imaginary parts, so complex pairs are found as pairs).
    pub fn eigenvalues(&self) -> Vec<C64> {
        let guesses = eig4(&self.k_matrix(C64::default()));
        let mut found: Vec<C64> = Vec::new();
        for guess in guesses.iter().chain(&guesses) {
            if found.len() == 4 {
                break;
            }
            let mut lambda = C64::new(guess.re.max(-0.99), guess.im);
            for _ in 0..100 {
                // Newton on f / f' with f = det T / prod (lambda - r) (Schroeder's method,
                // quadratic at the IC state's double roots too): with L = f'/f =
                // tr(T^(-1) T') - sum 1 / (lambda - r) and
                // L' = tr(T^(-1) T'') - tr((T^(-1) T')^2) + sum 1 / (lambda - r)^2,
                // the step is -L / L'.
                let [t, dt, ddt] = self.t_derivatives(lambda).map(|m| matrix4(&m));
                let lu = t.lu();
                let (Some(x1), Some(x2)) = (lu.solve(&dt), lu.solve(&ddt)) else {
                    break; // T singular: lambda is a root
                };
                let poles = found.iter().map(|r| (lambda - r).inv());
                let l1 = x1.trace() - poles.clone().sum::<C64>();
                let l1_slope = x2.trace() - (x1 * x1).trace() + poles.map(|p| p * p).sum::<C64>();
                let mut step = -l1 / l1_slope;
                if !step.is_finite() {
                    break;
                }
                // Damped: never more than 0.2 at once, never into the field's spectrum.
                if step.norm() > 0.2 {
                    step *= 0.2 / step.norm();
                }
                lambda -= step;
                if lambda.re < -0.999 {
                    lambda.re = -0.999;
                }
                if step.norm() < 1e-12 {
                    break;
                }
            }
            let root_ok = self.det(lambda).norm() <= 1e-9 * self.det(lambda + 0.1).norm();
            if lambda.re > -0.999 && root_ok {
                found.push(super::real_if_round_off(lambda));
            }
        }
        found.sort_by(|a, b| b.re.total_cmp(&a.re));
        found
    }
}

fn matrix4(a: &[[C64; 4]; 4]) -> nalgebra::Matrix4<C64> {
    nalgebra::Matrix4::from_fn(|i, j| a[i][j])
}

/// The determinant of a complex 4 x 4 matrix (LU with partial pivoting).
fn det4(a: [[C64; 4]; 4]) -> C64 {
    matrix4(&a).lu().determinant()
}

/// The eigenvalues of a complex 4 x 4 matrix (complex Schur form).
fn eig4(a: &[[C64; 4]; 4]) -> Vec<C64> {
    let m = matrix4(a);
    let schur = m
        .iter()
        .all(|x| x.re.is_finite() && x.im.is_finite())
        .then(|| m.try_schur(1e-15, 1000))
        .flatten();
    match schur.and_then(|sch| sch.eigenvalues()) {
        Some(e) => e.iter().copied().collect(),
        // Not finite, or the Schur iteration did not converge: start from the diagonal.
        None => (0..4).map(|i| a[i][i]).collect(),
    }
}

/// A unit null vector of a (numerically) singular complex 4 x 4 matrix: the right singular
/// vector of its smallest singular value.
fn null_vector(a: &[[C64; 4]; 4]) -> [C64; 4] {
    let Some(svd) = matrix4(a).try_svd(false, true, 1e-15, 1000) else {
        return [C64::default(); 4];
    };
    let Some(v_t) = svd.v_t else {
        return [C64::default(); 4];
    };
    let k = (0..4)
        .min_by(|&i, &j| svd.singular_values[i].total_cmp(&svd.singular_values[j]))
        .expect("four values");
    std::array::from_fn(|j| v_t[(k, j)].conj())
}

impl crate::roots::verdict::Spectrum for TwoModeLinearization {
    fn eigenvalues(&self) -> Vec<C64> {
        TwoModeLinearization::eigenvalues(self)
    }

    fn mode(&self, lambda: C64) -> Vec<C64> {
        TwoModeLinearization::mode(self, lambda).to_vec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contract::settings::SolverSettings;
    use crate::model::params::ModelParams;

    fn eigs(p: ModelParams, z: [f64; 4]) -> Vec<C64> {
        let mut s = TwoModeSolver::new(p, 192).unwrap();
        TwoModeLinearization::at(&mut s, z).eigenvalues()
    }

    #[test]
    fn lambda_zero_is_the_jacobian_of_the_steady_equations() {
        // The MD state of Fig. 1c, on the x axis.
        let p = ModelParams::at(0.085, 0.112);
        let mut s = TwoModeSolver::new(p, 192).unwrap();
        let st = s.newton(0.59, -0.27, 1e-12).unwrap();
        let z0 = [st.v, 0.0, st.a2, 0.0];
        let lin = TwoModeLinearization::at(&mut s, z0);
        let j0 = lin.jacobian0();
        let mut residual = |z: &[f64]| {
            let f = s.forces(z[0], z[1], z[2], z[3]);
            dynamics::force_balance(&p, [z[0], z[1], z[2], z[3]], &f).to_vec()
        };
        let fd = crate::numerics::newton::fd_jacobian(&mut residual, &z0, 1e-6);
        let scale = fd.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in 0..4 {
            for j in 0..4 {
                assert!(
                    (j0[i][j] - fd[i][j]).abs() < 1e-6 * scale,
                    "({i}, {j}): {} vs {}",
                    j0[i][j],
                    fd[i][j]
                );
            }
        }
    }

    fn assert_close(got: &[C64], want: &[f64], tol: f64) {
        assert_eq!(got.len(), want.len(), "{got:?}");
        for (g, w) in got.iter().zip(want) {
            assert!(
                g.im.abs() < 1e-9 && (g.re - w).abs() < tol,
                "{got:?} vs {want:?}"
            );
        }
    }

    /// The leading eigenvalues of docs/model.md's reference values, from an independent numpy
    /// implementation at N = 192 (IC: drift pair and the shape pair split by the square box;
    /// MD: the rotation-like mode first).
    #[test]
    fn eigenvalues_match_the_independent_computation() {
        let ic = |e, k| eigs(ModelParams::at(e, k), [0.0; 4]);
        assert_close(
            &ic(0.085, 0.13),
            &[-0.066267, -0.066267, -0.146358, -0.152733],
            2e-6,
        );
        // Just past the onset of motion: the drift pair is unstable.
        let onset = ic(0.0763, 0.16);
        assert_close(&onset[..2], &[0.001445, 0.001445], 2e-6);
        assert_close(
            &ic(0.085, 0.112),
            &[0.087228, 0.082111, -0.066267, -0.066267],
            2e-6,
        );
        let p = ModelParams::at(0.085, 0.112);
        let mut s = TwoModeSolver::new(p, 192).unwrap();
        let st = s.newton(0.59, -0.27, 1e-12).unwrap();
        let md = TwoModeLinearization::at(&mut s, [st.v, 0.0, st.a2, 0.0]).eigenvalues();
        assert_close(&md, &[-0.008436, -0.052054, -0.361618, -0.434750], 2e-6);
    }

    /// Against time stepping (N = 128, the same discretisation on both sides): small `a2` and
    /// `b2` deformations of the resting droplet decay at the shape eigenvalues (mirror symmetry
    /// keeps `v = 0`); the rate is measured between t = 6 and 12, when the field's own
    /// transients (rate >= 1) have died out.
    #[test]
    fn shape_eigenvalues_are_the_time_steppers_decay_rates() {
        let p = ModelParams::at(0.0763, 0.16);
        let n = 128;
        let lambda = {
            let mut s = TwoModeSolver::new(p, n).unwrap();
            TwoModeLinearization::at(&mut s, [0.0; 4]).eigenvalues()
        };
        let settings = |t_max| SolverSettings {
            n,
            dt: 0.005,
            tol: 0.0,
            t_max,
            steady_tol: 1e-30,
            // Plain time stepping to exactly t_max.
            landing: false,
            run_on: false,
            ..SolverSettings::default()
        };
        let mut rates = Vec::new();
        for ic in ["custom:0,0,0.001,0", "custom:0,0,0,0.001"] {
            let ic = crate::model::initial::InitialCondition::parse(ic).unwrap();
            let s = |t| {
                crate::runs::driver::simulate(&p, &ic, &settings(t))
                    .unwrap()
                    .s
            };
            rates.push((s(12.0) / s(6.0)).ln() / 6.0);
        }
        // Each rate is one of the two shape eigenvalues (the square box and the grid split
        // them by about 5e-3), and they are different ones.
        let shape: Vec<f64> = lambda[2..].iter().map(|l| l.re).collect();
        let nearest = |r: f64| {
            (0..2)
                .min_by(|&i, &j| (shape[i] - r).abs().total_cmp(&(shape[j] - r).abs()))
                .unwrap()
        };
        let (i, j) = (nearest(rates[0]), nearest(rates[1]));
        assert_ne!(i, j, "{rates:?} vs {lambda:?}");
        assert!(
            (rates[0] - shape[i]).abs() < 1e-3,
            "{rates:?} vs {lambda:?}"
        );
        assert!(
            (rates[1] - shape[j]).abs() < 1e-3,
            "{rates:?} vs {lambda:?}"
        );
        // The drift pair is the unstable one here, as at N = 192.
        assert!(lambda[0].re > 0.0 && lambda[1].re > 0.0);
    }
}
