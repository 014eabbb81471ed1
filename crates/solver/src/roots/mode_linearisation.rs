//! Linear stability of a steady state of the `K`-mode model, field included: the 2-mode
//! construction of [`crate::roots::linearisation`] for the state
//! `z = (vx, vy, a_2..a_K, b_2..b_K)` (`2K` unknowns). In the co-moving frame
//!
//! `du_t = D du + B dz`,  `M dz_t = E dz + C du`,  `M = diag(m, m, eta_k.., eta_k..)`
//! (`eta_k` of [`ModeSolver::eta`]: `eta2` for every mode unless a friction law is set),
//!
//! with `D = -(1 + k^2) + i k.v`, `B`'s columns `i k_x u0`, `i k_y u0` and the shape
//! derivatives of the source `Theta / A`, `C du` the forces of a field at the frozen shape and
//! `E` the rest (`-eta_t`, `-kappa_k`, and the shape derivatives of the forces at the frozen
//! field). Every eigenvalue with `Re lambda > -1` solves `det T(lambda) = 0`,
//! `T(lambda) = lambda M - E - C (lambda - D)^(-1) B`, a `2K x 2K` matrix of single sums over
//! the modes. The roots are found by Newton on `det T` divided by the roots already found
//! (its logarithmic derivative by central differences), started from the eigenvalues of the
//! `lambda = 0` problem `M^(-1) (E + C (-D)^(-1) B)`.
use crate::model::modes::Modes;
use crate::roots::mode_solver::{fill_operator, ModeSolver};
use nalgebra::DMatrix;
use rustfft::num_complex::Complex64;

type C64 = Complex64;

/// Step of the central differences in the shape.
const SHAPE_STEP: f64 = 1e-6;

/// The linearisation of one `K`-mode state.
pub struct ModeLinearization {
    z0: Vec<f64>,
    d: Vec<C64>,
    b: Vec<Vec<C64>>,
    e: Vec<Vec<f64>>,
    m: Vec<f64>,
}

impl ModeLinearization {
    /// Linearises `solver`'s model about `z0 = (vx, vy, a_2..a_K, b_2..b_K)` (a root of the
    /// force balance; taken wherever `z0` is). Needs inertia `m > 0`.
    pub fn at(solver: &mut ModeSolver, z0: &[f64]) -> Self {
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
            solver.source(&shifted(1.0));
            let sp = solver.source_spectrum().to_vec();
            solver.source(&shifted(-1.0));
            let sm = solver.source_spectrum();
            b.push(
                sp.iter()
                    .zip(sm)
                    .map(|(a, c)| (a - c) / (2.0 * h))
                    .collect(),
            );
            // The frozen field's forces on the shifted shape.
            let mut forces = |sign: f64| {
                let (area, lo, hi) = solver.sample(&shifted(sign));
                solver.gradient(&u0, lo, hi);
                solver.sums(k_max, lo, hi, area).to_vec()
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
        Self {
            z0: z0.to_vec(),
            d,
            b,
            e,
            m,
        }
    }

    /// `C (lambda - D)^(-1) B`: the forces of the response fields (the real and imaginary
    /// parts of each, half spectra `(g1 + g2) b / 2` and `-i (g1 - g2) b / 2` with
    /// `g1 = (lambda - d)^(-1)`, `g2 = (conj lambda - d)^(-1)`).
    fn response(&self, solver: &mut ModeSolver, lambda: C64) -> Vec<Vec<C64>> {
        let dim = self.z0.len();
        let m0 = Modes::of_state(&self.z0);
        let k_max = m0.k_max();
        let (area, lo, hi) = solver.sample(&m0);
        let mut r = vec![vec![C64::default(); dim]; dim];
        let half_i = C64::new(0.0, -0.5);
        let mut re = vec![C64::default(); self.d.len()];
        let mut im = vec![C64::default(); self.d.len()];
        for (j, b) in self.b.iter().enumerate() {
            for (((d, b), re), im) in self.d.iter().zip(b).zip(&mut re).zip(&mut im) {
                let (g1, g2) = ((lambda - d).inv(), (lambda.conj() - d).inv());
                *re = 0.5 * (g1 + g2) * b;
                *im = half_i * (g1 - g2) * b;
            }
            solver.gradient(&re, lo, hi);
            let fr = solver.sums(k_max, lo, hi, area).to_vec();
            solver.gradient(&im, lo, hi);
            let fi = solver.sums(k_max, lo, hi, area).to_vec();
            for i in 0..dim {
                r[i][j] = C64::new(fr[i], fi[i]);
            }
        }
        r
    }

    /// `T(lambda) = lambda M - E - C (lambda - D)^(-1) B`.
    pub fn t_matrix(&self, solver: &mut ModeSolver, lambda: C64) -> DMatrix<C64> {
        let r = self.response(solver, lambda);
        let dim = self.z0.len();
        DMatrix::from_fn(dim, dim, |i, j| {
            let diag = if i == j {
                lambda * self.m[i]
            } else {
                C64::default()
            };
            diag - self.e[i][j] - r[i][j]
        })
    }

    /// `-T(0)`: the Jacobian of the steady force balance with the steady field following `z`.
    pub fn jacobian0(&self, solver: &mut ModeSolver) -> Vec<Vec<f64>> {
        let t = self.t_matrix(solver, C64::default());
        let dim = self.z0.len();
        (0..dim)
            .map(|i| (0..dim).map(|j| -t[(i, j)].re).collect())
            .collect()
    }

    /// The eigenvalues with `Re lambda > -1`, sorted by decreasing real part; one `NaN` when
    /// the state or its response is not finite (counted as growing by [`Self::verdict`]).
    pub fn eigenvalues(&self, solver: &mut ModeSolver) -> Vec<C64> {
        let dim = self.z0.len();
        let r0 = self.response(solver, C64::default());
        let k0 = DMatrix::from_fn(dim, dim, |i, j| (self.e[i][j] + r0[i][j].re) / self.m[i]);
        let Some(guesses) = crate::numerics::eigen::complex_eigenvalues(&k0) else {
            return vec![C64::new(f64::NAN, 0.0)];
        };
        let det = |s: &mut ModeSolver, l: C64| self.t_matrix(s, l).determinant();
        let mut found: Vec<C64> = Vec::new();
        for guess in guesses.iter().chain(&guesses) {
            if found.len() == dim {
                break;
            }
            let mut lambda = C64::new(guess.re.max(-0.99), guess.im);
            let mut converged = false;
            for _ in 0..60 {
                let h = 1e-6;
                let f0 = det(solver, lambda);
                if f0.norm() == 0.0 {
                    converged = true;
                    break;
                }
                let slope = (det(solver, lambda + h) - det(solver, lambda - h)) / (2.0 * h);
                let log_d = slope / f0 - found.iter().map(|r| (lambda - r).inv()).sum::<C64>();
                let mut step = log_d.inv();
                if !step.is_finite() {
                    break;
                }
                if step.norm() > 0.2 {
                    step *= 0.2 / step.norm();
                }
                lambda -= step;
                lambda.re = lambda.re.max(-0.999);
                if step.norm() < 1e-11 {
                    converged = true;
                    break;
                }
            }
            if converged && lambda.re > -0.999 {
                found.push(lambda);
            }
        }
        found.sort_by(|a, b| b.re.total_cmp(&a.re));
        found
    }
}

/// The stability of a `K`-mode state: its eigenvalues, the rotation mode set aside.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ModeVerdict {
    /// `[re, im]`, by decreasing real part.
    pub eigenvalues: Vec<[f64; 2]>,
    /// The near-neutral rotation mode's eigenvalue (a moving or deformed state), if found.
    pub rotation: Option<f64>,
    /// Eigenvalues with a positive real part, the rotation mode excluded.
    pub unstable: usize,
}

impl ModeVerdict {
    pub fn stable(&self) -> bool {
        self.unstable == 0
    }

    /// The largest real part, the rotation mode excluded (`-1` when none is above it).
    pub fn leading(&self) -> f64 {
        let mut skipped = false;
        self.eigenvalues
            .iter()
            .filter(|l| {
                let rotation = !skipped && Some(l[0]) == self.rotation && l[1].abs() < 1e-9;
                skipped |= rotation;
                !rotation
            })
            .map(|l| l[0])
            .fold(-1.0, f64::max)
    }
}

impl ModeLinearization {
    /// The unit null vector of `T(lambda)` (its smallest singular vector).
    pub fn mode(&self, solver: &mut ModeSolver, lambda: C64) -> Vec<C64> {
        let t = self.t_matrix(solver, lambda);
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

    /// The verdict: the rotation mode is the real eigenvalue, within 0.05 of zero, whose mode
    /// is the state's infinitesimal rotation `(-vy, vx, -k b_k, k a_k)` (overlap above 0.9); the
    /// others decide.
    pub fn verdict(&self, solver: &mut ModeSolver) -> ModeVerdict {
        let eig = self.eigenvalues(solver);
        let z = &self.z0;
        let k_max = (z.len() - 2) / 2 + 1;
        let mut g = vec![-z[1], z[0]];
        g.extend((2..=k_max).map(|k| -(k as f64) * z[k_max - 1 + k]));
        g.extend((2..=k_max).map(|k| k as f64 * z[k]));
        let gn = g.iter().map(|x| x * x).sum::<f64>().sqrt();
        let mut rotation = None;
        if gn > 1e-9 {
            let overlap = |s: &mut ModeSolver, l: C64| {
                let v = self.mode(s, l);
                let dot: C64 = v.iter().zip(&g).map(|(a, b)| a * b).sum();
                let vn = v.iter().map(|c| c.norm_sqr()).sum::<f64>().sqrt();
                dot.norm() / (vn * gn)
            };
            rotation = eig
                .iter()
                .filter(|l| l.im.abs() < 1e-9 && l.re.abs() < 0.05)
                .map(|l| (*l, overlap(solver, *l)))
                .filter(|(_, o)| *o > 0.9)
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(l, _)| l.re);
        }
        let mut skipped = false;
        let unstable = eig
            .iter()
            .filter(|l| {
                if !skipped && Some(l.re) == rotation && l.im.abs() < 1e-9 {
                    skipped = true;
                    return false;
                }
                l.re > 0.0 || !l.re.is_finite()
            })
            .count();
        ModeVerdict {
            eigenvalues: eig.iter().map(|l| [l.re, l.im]).collect(),
            rotation,
            unstable,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::ModelParams;
    use crate::numerics::newton::fd_jacobian;
    use crate::roots::linearisation::Linearization;
    use crate::roots::steady_solver::SteadySolver;

    /// At the Fig. 1c point and grid size `n`: the 2-mode solver, the K-mode one and the
    /// 2-mode MD state `(v, 0, a2, 0)` (which both describe).
    fn fig1c_two_mode_md(n: usize) -> (SteadySolver, ModeSolver, [f64; 4]) {
        let p = ModelParams::at(0.085, 0.112);
        let mut two = SteadySolver::new(p, n).unwrap();
        let st = two.newton(0.59, -0.27, 1e-12).unwrap();
        (two, ModeSolver::new(p, n).unwrap(), [st.v, 0.0, st.a2, 0.0])
    }

    #[test]
    fn with_two_modes_the_eigenvalues_are_the_two_mode_ones() {
        let (mut two, mut solver, z) = fig1c_two_mode_md(64);
        let want = Linearization::at(&mut two, z).eigenvalues();
        let lin = ModeLinearization::at(&mut solver, &z);
        let got = lin.eigenvalues(&mut solver);
        assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
        for (g, w) in got.iter().zip(&want) {
            // Measured: 1e-10.
            assert!((g - w).norm() < 1e-8, "{got:?} vs {want:?}");
        }
    }

    #[test]
    fn t_at_zero_is_the_finite_difference_jacobian() {
        // K = 3, a moving deformed state (not a root: T(0) is defined anywhere).
        let p = ModelParams::at(0.085, 0.112);
        let mut solver = ModeSolver::new(p, 64).unwrap();
        let z = [0.3, 0.05, -0.15, 0.03, 0.02, -0.01];
        let lin = ModeLinearization::at(&mut solver, &z);
        let j0 = lin.jacobian0(&mut solver);
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
    fn the_verdict_finds_the_rotation_mode_and_agrees_with_two_modes() {
        let (mut two, mut solver, z) = fig1c_two_mode_md(96);
        let want = crate::roots::verdict::assess(&Linearization::at(&mut two, z), z);
        let got = ModeLinearization::at(&mut solver, &z).verdict(&mut solver);
        assert_eq!(got.stable(), want.stable(), "{got:?} {want:?}");
        match (got.rotation, want.rotation) {
            (Some(a), Some(b)) => assert!((a - b).abs() < 1e-8, "{got:?} {want:?}"),
            other => panic!("{other:?}: {got:?} {want:?}"),
        }
    }
}
