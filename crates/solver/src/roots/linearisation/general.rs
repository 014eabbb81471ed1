//! The construction of a [`Linearization`] ([`crate::roots::linearisation`]) for a droplet of
//! any shape, `z = (vx, vy, a_2..a_K, b_2..b_K)` (`2K` unknowns), from the general steady
//! solver: `M = diag(m, m, eta_k.., eta_k..)` (`eta_k` of [`SteadySolver::eta`]: `eta2` for
//! every mode unless a friction law is set), `B`'s shape columns and `E`'s shape derivatives
//! by central differences of the sampled droplet, and the forces' functionals `C` by the
//! adjoint of the quadrature's inverse transform ([`force_functionals`]).
use super::{field_parts, Linearization, SHAPE_STEP};
use crate::model::modes::Modes;
use crate::roots::steady_solver::SteadySolver;
use rustfft::num_complex::Complex64;

type C64 = Complex64;

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
        let (d, mut b) = field_parts(solver.grid(), z0[0], z0[1], &u0);
        let mut e = vec![vec![0.0; dim]; dim];
        e[0][0] = -p.eta_t;
        e[1][1] = -p.eta_t;
        let h = SHAPE_STEP;
        let shifted = |j: usize, sign: f64| {
            let mut z = z0.to_vec();
            z[j] += sign * h;
            Modes::of_state(&z)
        };
        // The frozen field's gradient, once, on the rows of every shifted shape.
        let (lo, hi) = (2..dim)
            .flat_map(|j| [shifted(j, 1.0), shifted(j, -1.0)])
            .map(|m| solver.quadrature_mut().span(&m))
            .fold((usize::MAX, 0), |(lo, hi), (l, u)| (lo.min(l), hi.max(u)));
        solver.quadrature_mut().gradient(&u0, lo, hi);
        for j in 2..dim {
            // Each shifted shape sampled once: its source's transform, and the frozen
            // field's forces on it.
            let mut side = |sign: f64| {
                let quad = solver.quadrature_mut();
                let (area, lo, hi) = quad.source(&shifted(j, sign));
                let forces = quad.sums(k_max, lo, hi, area).to_vec();
                (quad.source_spectrum().to_vec(), forces)
            };
            let ((sp, fp), (sm, fm)) = (side(1.0), side(-1.0));
            b.push(
                sp.iter()
                    .zip(&sm)
                    .map(|(a, c)| (a - c) / (2.0 * h))
                    .collect(),
            );
            for (row, (fp, fm)) in e.iter_mut().zip(fp.iter().zip(&fm)) {
                row[j] = (fp - fm) / (2.0 * h);
            }
            let k = 2 + (j - 2) % (k_max - 1);
            e[j][j] -= (k * k) as f64 / 4.0 * p.kappa2;
        }
        let mut m = vec![p.mass, p.mass];
        m.extend((2..=k_max).chain(2..=k_max).map(|k| solver.eta(k)));
        let c = force_functionals(solver, &m0);
        Self::of_parts(z0.to_vec(), d, b, e, m, c)
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
    // The weights' distinct fields: `t = -dx^2 Theta`, then `(Re, Im)` of
    // `t R^(2-k) (x + i y)^(k-1)` for each mode; `w_k^(b)` is `w_k^(a)` turned by 90 degrees,
    // so its transforms are the same two (the transform of `-w` is minus that of `w`, to the
    // last bit).
    let mut fields = vec![vec![0.0; n * n]; 2 * k_max - 1];
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
            fields[0][i] = t;
            // `(Re, Im)` of `(x + i y)^(k-1)`, as in the sums.
            let (mut re, mut im) = (x, y);
            for j in 0..k_max - 1 {
                let s = t * r0.powi(-(j as i32));
                (fields[1 + 2 * j][i], fields[2 + 2 * j][i]) = (s * re, s * im);
                (re, im) = (re * x - im * y, re * y + im * x);
            }
        }
    }
    let spectra: Vec<Vec<C64>> = fields
        .iter()
        .map(|f| solver.quadrature_mut().transform(f, lo, hi))
        .collect();
    // Per force, the transforms of its weights on `u_x` and `u_y` (`None`: the weight 0).
    type Pair<'a> = (Option<(&'a [C64], f64)>, Option<(&'a [C64], f64)>);
    let mut pairs: Vec<Pair> = vec![
        (Some((&spectra[0], 1.0)), None),
        (None, Some((&spectra[0], 1.0))),
    ];
    let re = |j: usize| &spectra[1 + 2 * j][..];
    let im = |j: usize| &spectra[2 + 2 * j][..];
    pairs.extend((0..k_max - 1).map(|j| (Some((re(j), 1.0)), Some((im(j), -1.0)))));
    pairs.extend((0..k_max - 1).map(|j| (Some((im(j), 1.0)), Some((re(j), 1.0)))));
    let zero = C64::default();
    let at = |w: Option<(&[C64], f64)>, k: usize| w.map_or(zero, |(s, sign)| sign * s[k]);
    let mut c = vec![C64::default(); grid.spectral_len() * dim];
    for (i, (wx, wy)) in pairs.into_iter().enumerate() {
        for jx in 0..=n / 2 {
            let weight = if jx == 0 || 2 * jx == n { 1.0 } else { 2.0 };
            for jy in 0..n {
                let k = jx * n + jy;
                let g = grid.kx_d[jx] * at(wx, k).conj() + grid.ky_d[jy] * at(wy, k).conj();
                c[k * dim + i] = C64::new(0.0, weight) * g;
            }
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::ModelParams;
    use crate::numerics::newton::fd_jacobian;
    use crate::roots::steady_solver::TwoModeSolver;

    impl Linearization {
        /// The same linearisation with every mode summed as it is (no moments).
        fn summing_every_mode(mut self) -> Self {
            self.far_from = f64::INFINITY;
            self
        }
    }

    #[test]
    fn the_fast_modes_moments_give_the_full_sums() {
        // Modes 2..4, the x-axis MD at (0.085, 0.112), N = 96 (4704 stored modes, 1280 of
        // them slow): T(lambda), T'(lambda) and T''(lambda) with the moments against every
        // mode summed, inside the series' radius and at its edge; the eigenvalues both ways.
        let p = ModelParams::at(0.085, 0.112);
        let mut solver = SteadySolver::new(p, 96).unwrap();
        let st = crate::roots::named_state::md_state(&mut solver, 4).unwrap();
        let z = [st.v, 0.0, st.a[0], st.a[1], st.a[2], 0.0, 0.0, 0.0];
        let fast = Linearization::at(&mut solver, &z);
        fast.t_matrix(C64::default());
        let near = fast.far.get().expect("made by the response").near.len();
        assert!(near < fast.d.len() / 3, "{near}");
        let full = Linearization::at(&mut solver, &z).summing_every_mode();
        for l in [
            C64::new(0.0, 0.0),
            C64::new(-0.3, 0.2),
            C64::new(0.01, -0.5),
            C64::new(-2.8, 2.8),
        ] {
            let t = fast.t_derivatives(l, 2, false);
            let u = full.t_derivatives(l, 2, false);
            let scale = u[0].iter().fold(0.0f64, |m, x| m.max(x.norm()));
            for (t, u) in t.iter().zip(&u) {
                assert!((t - u).iter().all(|x| x.norm() < 1e-13 * scale), "{l}");
            }
        }
        let (a, b) = (fast.eigenvalues(), full.eigenvalues());
        assert_eq!(a.len(), b.len(), "{a:?} {b:?}");
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).norm() < 1e-10, "{a:?} {b:?}");
        }
    }

    /// At the Fig. 1c point and grid size `n`: the 2-mode solver, the K-mode one and the
    /// 2-mode MD state `(v, 0, a2, 0)` (which both describe).
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
        let want = Linearization::of_two_modes(&mut two, z).eigenvalues();
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
        let want = crate::roots::verdict::assess(&Linearization::of_two_modes(&mut two, z), &z);
        let got = Linearization::at(&mut solver, &z).verdict();
        assert_eq!(got.stable(), want.stable(), "{got:?} {want:?}");
        match (got.rotation, want.rotation) {
            (Some(a), Some(b)) => assert!((a - b).abs() < 1e-8, "{got:?} {want:?}"),
            other => panic!("{other:?}: {got:?} {want:?}"),
        }
    }
}
