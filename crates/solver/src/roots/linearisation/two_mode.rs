//! The construction of a [`Linearization`] ([`crate::roots::linearisation`]) for the 2-mode
//! droplet `z = (vx, vy, a2, b2)` from the 2-mode steady solver, the fast path of `K = 2`: the
//! point-symmetric droplet's shape transforms (`Theta + X Theta` and `Y Theta`,
//! [`crate::model::forces::parseval`]) give the forces' functionals `C` directly, by
//! Parseval, and `B`'s shape columns and `E`'s shape derivatives by central differences of
//! those transforms; no inverse transform. The same eigenvalues as the general construction
//! at `K = 2` (tested there).
use super::{field_parts, Linearization, SHAPE_STEP};
use crate::model::dynamics;
use crate::model::forces::parseval::{spectral_forces, Forces};
use crate::model::grid::Grid;
use crate::roots::steady_solver::TwoModeSolver;
use rustfft::num_complex::Complex64;

type C64 = Complex64;

fn as_array(f: &Forces) -> [f64; 4] {
    [f.fx, f.fy, f.ga, f.gb]
}

/// The forces `(Fx, Fy, Ga, Gb)` on the point-symmetric droplet of the packed transforms `p`
/// (of `Theta + X Theta`) and `y` (of `Y Theta`) as real-linear functionals of a field's
/// normalised half spectrum, `F_i(u) = Sum_k Re(c_ik u_k)`, returned `[k][i]`: the
/// Parseval sums of [`spectral_forces`] term by term.
fn force_functionals(grid: &Grid, p: &[C64], y: &[C64]) -> Vec<C64> {
    let n = grid.n;
    let da = grid.dx * grid.dx;
    let mut c = Vec::with_capacity(4 * p.len());
    for jx in 0..=n / 2 {
        let (w, kx) = (da * grid.column_weight(jx), grid.kx_d[jx]);
        for (jy, ky) in grid.ky_d.iter().enumerate() {
            let (p, y) = (p[jx * n + jy], y[jx * n + jy]);
            c.extend([
                C64::new(0.0, -w * kx * p.re),
                C64::new(0.0, -w * ky * p.re),
                C64::new(-w * (kx * p.im - ky * y.im), 0.0),
                C64::new(-w * (kx * y.im + ky * p.im), 0.0),
            ]);
        }
    }
    c
}

impl Linearization {
    /// Linearises the steady state `z0 = (vx, vy, a2, b2)` of `solver`'s parameters (a root of
    /// the force balance; the linearisation is taken wherever `z0` is). Needs inertia `m > 0`.
    pub fn of_two_modes(solver: &mut TwoModeSolver, z0: [f64; 4]) -> Self {
        let p = *solver.params();
        let [vx, vy, a2, b2] = z0;
        let grid = solver.grid().clone();
        let n = grid.n;
        let (w0, _) = solver.field_and_forces(vx, vy, a2, b2);
        let w0 = w0.to_vec();
        let (ph, yh, _) = solver.shape_spectra(a2, b2);
        let (d, mut b) = field_parts(&grid, vx, vy, &w0);
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
        b.extend([diff(&sa_p, &sa_m), diff(&sb_p, &sb_m)]);
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
        let c = force_functionals(&grid, &ph, &yh);
        Self::of_parts(
            z0.to_vec(),
            d,
            b,
            e.iter().map(|row| row.to_vec()).collect(),
            vec![p.mass, p.mass, p.eta2, p.eta2],
            c,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contract::settings::SolverSettings;
    use crate::model::params::ModelParams;

    #[test]
    fn the_force_functionals_are_the_parseval_forces() {
        // The Fig. 1c MD's steady field on a shape off both mirror lines, N = 64:
        // `Sum_k Re(c_ik w_k)` against the Parseval sums of the forces.
        let mut s = TwoModeSolver::new(ModelParams::at(0.085, 0.112), 64).unwrap();
        let (w, _) = s.field_and_forces(0.5, 0.1, -0.2, 0.05);
        let w = w.to_vec();
        let (ph, yh, area) = s.shape_spectra(-0.15, 0.08);
        let want = as_array(&spectral_forces(s.grid(), &w, &ph, &yh, area));
        let c = force_functionals(s.grid(), &ph, &yh);
        for (i, want) in want.iter().enumerate() {
            let got: f64 = w
                .iter()
                .enumerate()
                .map(|(k, u)| (c[4 * k + i] * u).re)
                .sum();
            assert!(
                (got - want).abs() < 1e-12 * want.abs().max(1e-3),
                "{i}: {got} vs {want}"
            );
        }
    }

    fn eigs(p: ModelParams, z: [f64; 4]) -> Vec<C64> {
        let mut s = TwoModeSolver::new(p, 192).unwrap();
        Linearization::of_two_modes(&mut s, z).eigenvalues()
    }

    #[test]
    fn lambda_zero_is_the_jacobian_of_the_steady_equations() {
        // The MD state of Fig. 1c, on the x axis.
        let p = ModelParams::at(0.085, 0.112);
        let mut s = TwoModeSolver::new(p, 192).unwrap();
        let st = s.newton(0.59, -0.27, 1e-12).unwrap();
        let z0 = [st.v, 0.0, st.a2, 0.0];
        let lin = Linearization::of_two_modes(&mut s, z0);
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
        let md = Linearization::of_two_modes(&mut s, [st.v, 0.0, st.a2, 0.0]).eigenvalues();
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
            Linearization::of_two_modes(&mut s, [0.0; 4]).eigenvalues()
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
