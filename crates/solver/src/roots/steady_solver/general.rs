//! Steady states of the paper's general model with shape modes `k = 2..K`, every `K`.
//!
//! For a droplet of shape `{a_k, b_k}` moving at `v` the co-moving field solves
//! `0 = Lap u - u + v . grad u + Theta / A` (paper eq. S13, `Theta` of
//! [`crate::model::modes::Modes`]), `u_hat = Theta_hat / (A (1 + k^2 - i k.v))`, and the forces are
//! the paper's general ones: `F = -Int grad u Theta` (eq. 35) and
//! `G_k^(a) = -Int w_k^(a) . grad u Theta`, `G_k^(b) = -Int w_k^(b) . grad u Theta` (the
//! smoothed form of eqs. dakdt_dl, dbkdt_dl). A steady state balances
//! `-eta_t v + F = 0`, `G_k - kappa_k (a_k, b_k) = 0` with `kappa_k = (k^2 / 4) kappa2` (eq.
//! for `kappa_k`: `pi k^2 tau R`); `eta_k` sets only how fast the shape moves, not where it
//! rests.
//!
//! The discretisation is the 2-mode fast path's ([`crate::roots::steady_solver::TwoModeSolver`]):
//! the same samples of `Theta`, the same spectral gradient (Nyquist mode zeroed), the sums over
//! the grid taken in real space instead of by Parseval
//! ([`crate::model::forces::quadrature`]; equal to round-off for `K = 2`, tested). No
//! symmetry of the shape is assumed (odd modes break the point symmetry the fast path uses).
use crate::error::SolverError;
use crate::model::forces::quadrature::{operator, ForceQuadrature, PassBuffers, ShapeForces};
use crate::model::grid::Grid;
use crate::model::modes::Modes;
use crate::model::params::ModelParams;
use crate::model::state::turned;
use crate::numerics::newton::{self, NewtonOptions};
use crate::roots::forces_memo::ForcesMemo;
use rustfft::num_complex::Complex64;

/// A steady state on the x mirror line: moving along `x` (or at rest), its shape symmetric
/// about the x axis (`b_k = 0`).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct MirrorState {
    pub v: f64,
    /// `a_k` for `k = 2..=K`.
    pub a: Vec<f64>,
    pub residual: f64,
}

/// The unknowns `(vx, vy, a_2..a_K, b_2..b_K)` of a state moving along +x at speed `v` with the
/// shape `a = a_2..a_K` symmetric about the x axis (`vy = 0`, `b_k = 0`).
pub fn on_x_axis(v: f64, a: &[f64]) -> Vec<f64> {
    let mut z = vec![v, 0.0];
    z.extend(a.iter().copied());
    z.extend(std::iter::repeat_n(0.0, a.len()));
    z
}

/// Evaluates steady fields and force balances of `K`-mode droplets on an `N x N` grid.
pub struct SteadySolver {
    params: ModelParams,
    /// `Theta`, its transform and the forces of a field on it.
    quad: ForceQuadrature,
    /// The last field's coefficients (normalised, `[kx][ky]`).
    u_spec: Vec<Complex64>,
    /// The angle of the axis [`Self::residual_x`] works on (0: the x axis).
    axis: f64,
    /// The forces of the last droplets the residuals asked for.
    memo: ForcesMemo<(f64, f64, Modes), ShapeForces>,
    /// The shape whose source `quad` holds, with its area and rows: a droplet of the same
    /// shape at another velocity (the velocity columns of a difference Jacobian) samples and
    /// transforms nothing.
    sourced: Option<(Modes, (f64, usize, usize))>,
}

impl SteadySolver {
    pub fn new(params: ModelParams, n: usize) -> Result<Self, SolverError> {
        params.validate()?;
        let grid = Grid::new(n, params.box_len)?;
        crate::contract::limits::check_resolved(&params, n)?;
        let shape = params.shape();
        let len = grid.spectral_len();
        Ok(Self {
            params,
            quad: ForceQuadrature::new(grid, shape),
            u_spec: vec![Complex64::default(); len],
            axis: 0.0,
            memo: ForcesMemo::default(),
            sourced: None,
        })
    }

    pub fn params(&self) -> &ModelParams {
        &self.params
    }

    /// Grid points per side.
    pub fn n(&self) -> usize {
        self.quad.grid().n
    }

    pub fn set_control(&mut self, eta_t: f64, kappa2: f64) {
        self.params.eta_t = eta_t;
        self.params.kappa2 = kappa2;
    }

    /// Moves the solver to another value of one parameter, as
    /// [`crate::roots::steady_solver::TwoModeSolver::set_param`] does: `eta_t`, `kappa2`,
    /// `eta2` and `mass` are set (they enter the force balance or the eigenvalues only);
    /// `radius`, `sigma` and `box_len` sample the droplet (and for `box_len` the grid) again.
    /// Refused, leaving the solver as it was, where the parameters would be invalid or the grid
    /// would not resolve the droplet ([`crate::contract::limits::check_resolved`]).
    pub fn set_param(
        &mut self,
        param: crate::model::param::ModelParam,
        x: f64,
    ) -> Result<(), SolverError> {
        let Some((params, sampled)) = super::moved(&self.params, self.n(), param, x)? else {
            return Ok(());
        };
        if let Some((grid, shape)) = sampled {
            self.quad = ForceQuadrature::new(grid, shape);
            self.memo.clear();
            self.sourced = None;
        }
        self.params = params;
        Ok(())
    }

    /// Makes [`Self::residual_x`] work on the mirror line at angle `phi` to the x axis (the
    /// diagonal: `pi / 4`): its unknowns and balances are those of the state turned back by
    /// `phi`. Every x-axis computation on this solver (Newton, thresholds, folds) then holds
    /// on that line; the box tells the lines apart.
    pub fn set_axis(&mut self, phi: f64) {
        self.axis = phi;
    }

    /// [`Self::forces`] for a residual: a droplet asked for before is not solved again (and
    /// then the solver's field is not its field).
    fn kept_forces(&mut self, vx: f64, vy: f64, m: &Modes) -> ShapeForces {
        let droplet = (vx, vy, m.clone());
        if let Some(f) = self.memo.get(&droplet) {
            return f;
        }
        let f = self.forces(vx, vy, m);
        self.memo.keep(&droplet, &f);
        f
    }

    /// The forces of the steady field of the droplet `m` moving at `(vx, vy)`.
    pub fn forces(&mut self, vx: f64, vy: f64, m: &Modes) -> ShapeForces {
        crate::contract::profile::field_solve();
        let (area, lo, hi) = match &self.sourced {
            Some((held, window)) if held == m => *window,
            _ => {
                let window = self.quad.source(m);
                self.sourced = Some((m.clone(), window));
                window
            }
        };
        // u_hat = source / (1 + k^2 - i k.v) = -source / D.
        let PassBuffers { grid, source } = self.quad.pass_buffers();
        let n = grid.n;
        for (jx, (kx, kxd)) in grid.kx.iter().zip(&grid.kx_d).enumerate().take(n / 2 + 1) {
            let row = jx * n..(jx + 1) * n;
            let modes = grid.ky.iter().zip(&grid.ky_d);
            let fields = self.u_spec[row.clone()]
                .iter_mut()
                .zip(&source[row.clone()]);
            for ((ky, kyd), (u, s)) in modes.zip(fields) {
                *u = -s / operator((*kx, *ky), (*kxd, *kyd), (vx, vy));
            }
        }
        self.quad.gradient(&self.u_spec, lo, hi);
        self.quad.sums(m.k_max(), lo, hi, area)
    }

    /// The last steady field's normalised half spectrum.
    pub(crate) fn field_spectrum(&self) -> &[Complex64] {
        &self.u_spec
    }

    /// The grid.
    pub(crate) fn grid(&self) -> &Grid {
        self.quad.grid()
    }

    /// The quadrature of the forces, for computations that take its steps in their own order
    /// (the linearisation); the solver's last field stays.
    pub(crate) fn quadrature_mut(&mut self) -> &mut ForceQuadrature {
        self.sourced = None;
        &mut self.quad
    }

    /// The force balance of the state `z = (vx, vy, a_2..a_K, b_2..b_K)` (`K = z.len() / 2`):
    /// `-eta_t v + F`, `G_k^(a) - kappa_k a_k`, `G_k^(b) - kappa_k b_k`, in that order.
    pub fn residual(&mut self, z: &[f64]) -> Vec<f64> {
        let m = Modes::of_state(z);
        let f = self.kept_forces(z[0], z[1], &m);
        let mut r = vec![
            -self.params.eta_t * z[0] + f.fx,
            -self.params.eta_t * z[1] + f.fy,
        ];
        for (j, (g, a)) in f.ga.iter().zip(&m.a).enumerate() {
            r.push(g - self.kappa(j + 2) * a);
        }
        for (j, (g, b)) in f.gb.iter().zip(&m.b).enumerate() {
            r.push(g - self.kappa(j + 2) * b);
        }
        r
    }

    /// The last field of [`Self::forces`] at `(x, y)` relative to the droplet's centre, summed
    /// from its Fourier series (for checks: `N^2` terms per point).
    pub fn field_at(&self, x: f64, y: f64) -> f64 {
        let grid = self.quad.grid();
        let n = grid.n;
        let (x, y) = (x - grid.coord(0), y - grid.coord(0));
        let mut sum = 0.0;
        for jx in 0..=n / 2 {
            let (c, s) = (grid.kx[jx] * x).sin_cos();
            let wt = grid.column_weight(jx);
            for jy in 0..n {
                let u = self.u_spec[jx * n + jy];
                let phase = Complex64::new(s, c) * Complex64::from_polar(1.0, grid.ky[jy] * y);
                sum += wt * (u * phase).re;
            }
        }
        sum
    }

    /// The friction `eta_k` of mode `k` (the model's friction law,
    /// [`crate::model::friction`]: `eta2` for every mode by default); the time stepping and
    /// the eigenvalues use it, no steady state depends on it.
    pub fn eta(&self, k: usize) -> f64 {
        crate::model::friction::eta_k(self.params.eta2, k, self.params.eta_k_exponent)
    }

    /// `kappa_k = (k^2 / 4) kappa2`.
    pub fn kappa(&self, k: usize) -> f64 {
        crate::model::modes::kappa_k(self.params.kappa2, k)
    }

    /// The force balance along x for a droplet moving along x with `a_k = y[k - 1]`
    /// (`b_k = 0`): `(-eta_t v + Fx, G_k^(a) - kappa_k a_k for k = 2..=K)`, `K = y.len()`.
    ///
    /// With [`Self::set_axis`] `phi`: the same in the frame turned by `phi`, the state
    /// [`turned`] by `phi` and its balances (which turn as the state does) turned back.
    pub fn residual_x(&mut self, y: &[f64]) -> Vec<f64> {
        if self.axis != 0.0 {
            let k_max = y.len();
            let z = turned(&on_x_axis(y[0], &y[1..]), self.axis);
            let r = turned(&self.residual(&z), -self.axis);
            return std::iter::once(r[0])
                .chain(r[2..k_max + 1].iter().copied())
                .collect();
        }
        let m = Modes {
            a: y[1..].to_vec(),
            b: vec![0.0; y.len() - 1],
        };
        let f = self.kept_forces(y[0], 0.0, &m);
        let mut r = vec![-self.params.eta_t * y[0] + f.fx];
        for (j, (g, a)) in f.ga.iter().zip(&m.a).enumerate() {
            r.push(g - self.kappa(j + 2) * a);
        }
        r
    }

    /// Newton on [`Self::residual_x`] from `(v, a_2..a_K)`.
    pub fn newton_x(&mut self, guess: &[f64], tol: f64) -> Result<MirrorState, SolverError> {
        let opts = NewtonOptions {
            tol,
            max_iter: 40,
            fd_step: 1e-7,
            max_step: vec![0.1; guess.len()],
            one_sided: false,
            backtrack: false,
        };
        let sol = newton::solve(|y| self.residual_x(y), guess, &opts)?;
        Ok(MirrorState {
            v: sol.x[0],
            a: sol.x[1..].to_vec(),
            residual: sol.residual,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::modes::w_fields;
    use crate::model::shape::ShapeParams;
    use crate::model::state::turned;

    #[test]
    fn on_the_diagonal_axis_newton_finds_the_turned_state_of_all_2k_balances() {
        // Fig. 1c with modes 2..3 at N = 96: Newton on the x-axis unknowns with the axis at
        // 45 degrees, against Newton on all 2K balances from the x-axis state turned by 45
        // degrees (independent: no frame turned back). They agree, the off-line balances
        // vanish there, and the box makes the diagonal state differ from the axis one.
        let p = ModelParams::at(0.085, 0.112);
        let mut solver = SteadySolver::new(p, 96).unwrap();
        let axis = crate::roots::named_state::md_state(&mut solver, 3).unwrap();
        let phi = std::f64::consts::FRAC_PI_4;
        let guess: Vec<f64> = std::iter::once(axis.v).chain(axis.a.clone()).collect();
        solver.set_axis(phi);
        let diag = solver.newton_x(&guess, 1e-12).unwrap();
        solver.set_axis(0.0);
        let opts = NewtonOptions {
            tol: 1e-12,
            max_iter: 30,
            fd_step: 1e-7,
            max_step: vec![0.2; 6],
            one_sided: false,
            backtrack: false,
        };
        let full = newton::solve(
            |y| solver.residual(y),
            &turned(&on_x_axis(axis.v, &axis.a), phi),
            &opts,
        )
        .unwrap()
        .x;
        let mine = turned(&on_x_axis(diag.v, &diag.a), phi);
        for (a, b) in mine.iter().zip(&full) {
            assert!((a - b).abs() < 1e-9, "{mine:?} vs {full:?}");
        }
        assert!(solver.residual(&mine).iter().all(|r| r.abs() < 1e-10));
        assert!((diag.v - axis.v).abs() > 1e-7, "{diag:?} {axis:?}");
    }

    use crate::roots::steady_solver::TwoModeSolver;

    #[test]
    fn two_modes_give_the_two_mode_solvers_forces() {
        let p = ModelParams::at(0.085, 0.112);
        let mut modes = SteadySolver::new(p, 96).unwrap();
        let mut two = TwoModeSolver::new(p, 96).unwrap();
        for (vx, vy, a2, b2) in [
            (0.3, 0.1, -0.2, 0.05),
            (0.0, 0.0, 0.1, 0.0),
            (0.6, 0.0, -0.27, 0.0),
        ] {
            let f = modes.forces(
                vx,
                vy,
                &Modes {
                    a: vec![a2],
                    b: vec![b2],
                },
            );
            let g = two.forces(vx, vy, a2, b2);
            for (x, y) in [
                (f.fx, g.fx),
                (f.fy, g.fy),
                (f.ga[0], g.ga),
                (f.gb[0], g.gb),
                (f.area, g.area),
            ] {
                assert!((x - y).abs() < 1e-12 * (1.0 + y.abs()), "{x} vs {y}");
            }
        }
    }

    #[test]
    fn forces_are_the_papers_boundary_integrals_for_k_3_and_4_shapes() {
        // G_k^(a) = -oint u w_k^(a) . e_n dl (eq. dakdt_dl) on the sharp boundary, by a
        // 1000-point quadrature of the solver's own field (the trapezoidal rule of a smooth
        // periodic integrand: 4000 points change no digit that matters), against the solver's
        // smoothed area sums: equal to the smoothing's O(sigma^2).
        let p = ModelParams {
            sigma: 0.01,
            ..ModelParams::at(0.085, 0.112)
        };
        let mut s = SteadySolver::new(p, 384).unwrap();
        let m = Modes {
            a: vec![-0.1, 0.06, 0.03],
            b: vec![0.02, -0.04, 0.01],
        };
        let f = s.forces(0.3, -0.1, &m);
        let shape = ShapeParams {
            radius: 1.0,
            sigma: 0.01,
        };
        let q = 1000;
        let (mut fx, mut ga, mut gb) = (0.0, vec![0.0; 3], vec![0.0; 3]);
        for i in 0..q {
            let th = 2.0 * std::f64::consts::PI * (i as f64 + 0.5) / q as f64;
            let (c, sn) = (th.cos(), th.sin());
            let r = m.boundary(&shape, c, sn);
            // dr/dtheta, by the derivative of the series.
            let dr: f64 = (2..=4)
                .map(|k| {
                    let kf = k as f64;
                    kf * (-m.a[k - 2] * (kf * th).sin() + m.b[k - 2] * (kf * th).cos())
                })
                .sum();
            let (x, y) = (r * c, r * sn);
            // Outward normal times dl: (dy/dtheta, -dx/dtheta) dtheta.
            let (tx, ty) = (dr * c - r * sn, dr * sn + r * c);
            let (nx, ny) = (ty, -tx);
            let u = s.field_at(x, y);
            let dth = 2.0 * std::f64::consts::PI / q as f64;
            fx -= u * nx * dth;
            for k in 2..=4 {
                let (wa, wb) = w_fields(k, 1.0, x, y);
                ga[k - 2] -= u * (wa[0] * nx + wa[1] * ny) * dth;
                gb[k - 2] -= u * (wb[0] * nx + wb[1] * ny) * dth;
            }
        }
        let scale =
            f.ga.iter()
                .chain(&f.gb)
                .fold(f.fx.abs(), |m, g| m.max(g.abs()));
        for (a, b) in std::iter::once((f.fx, fx))
            .chain(f.ga.iter().copied().zip(ga))
            .chain(f.gb.iter().copied().zip(gb))
        {
            // Measured: 2e-5 to 5.3e-4 of the largest force.
            assert!((a - b).abs() < 1e-3 * scale, "{a} vs {b} (scale {scale})");
        }
    }

    #[test]
    fn a_shape_at_rest_feels_no_net_force_and_mirrors_flip_odd_modes() {
        let p = ModelParams::at(0.085, 0.112);
        let mut s = SteadySolver::new(p, 192).unwrap();
        let mut m = Modes::circle(4);
        m.a[1] = 0.08;
        let f = s.forces(0.0, 0.0, &m);
        // At rest no shape feels a net force: its own steady field pulls it symmetrically (the
        // kernel of the field is even), to round-off on the grid too.
        assert!(f.fx.hypot(f.fy) < 1e-15, "{f:?}");
        // Three-fold symmetric: its own mode feels a force of order a3, modes 2 and 4 none
        // but for the square box and grid (measured 4e-5 and 1e-3 of it).
        assert!(f.ga[1].abs() > 1e-2, "{f:?}");
        assert!(
            f.ga[0].abs().max(f.ga[2].abs()) < 2e-3 * f.ga[1].abs(),
            "{f:?}"
        );
        // The mirror x -> -x maps a3 to -a3: the grid's own symmetry, so exactly.
        m.a[1] = -0.08;
        let g = s.forces(0.0, 0.0, &m);
        assert!(
            (g.ga[1] + f.ga[1]).abs() < 1e-14 && (g.fx + f.fx).abs() < 1e-14,
            "{f:?} {g:?}"
        );
        assert!((g.ga[0] - f.ga[0]).abs() < 1e-14, "{f:?} {g:?}");
    }

    #[test]
    fn a_moving_droplet_has_a_mode_3_deformation_along_its_motion() {
        // Fig. 1c (eta_t = 0.085, kappa2 = 0.112): the 2-mode MD state, then with modes up
        // to 3: a3 != 0 (front-back asymmetry), the speed changes.
        let mut s = SteadySolver::new(ModelParams::at(0.085, 0.112), 192).unwrap();
        let two = s.newton_x(&[0.59, -0.27], 1e-11).unwrap();
        assert!(
            (two.v - 0.592462).abs() < 1e-6 && (two.a[0] + 0.270056).abs() < 1e-6,
            "{two:?}"
        );
        let three = s.newton_x(&[two.v, two.a[0], 0.0], 1e-11).unwrap();
        assert!(three.a[1].abs() > 1e-2, "{three:?}");
        assert!((three.v - two.v).abs() > 1e-2, "{three:?}");
        // Moving the other way mirrors it: -v, the same a2, -a3.
        let back = s
            .newton_x(&[-three.v, three.a[0], -three.a[1]], 1e-11)
            .unwrap();
        assert!((back.v + three.v).abs() < 1e-9 && (back.a[1] + three.a[1]).abs() < 1e-9);
    }

    #[test]
    fn the_three_mode_state_continues_the_two_mode_one() {
        // Mode 3's stiffness scaled by lam from 1000 (a3 ~ 0: the 2-mode state) down to 1:
        // Newton from each state to the next follows one branch, with no fold on the way, to
        // the 3-mode root Newton finds directly (not another root).
        let mut s = SteadySolver::new(ModelParams::at(0.085, 0.112), 96).unwrap();
        let two = s.newton_x(&[0.59, -0.27], 1e-11).unwrap();
        let direct = s.newton_x(&[two.v, two.a[0], 0.0], 1e-11).unwrap();
        let k3 = s.kappa(3);
        let opts = NewtonOptions {
            tol: 1e-11,
            max_iter: 40,
            fd_step: 1e-7,
            max_step: vec![0.05; 3],
            one_sided: false,
            backtrack: false,
        };
        let mut y = vec![two.v, two.a[0], 0.0];
        let mut last_v = f64::INFINITY;
        // 1000 down to 4 geometrically, then to 1 in steps of 0.05 (v falls steeply there:
        // from 0.53 at lam = 3 to 0.27 at 1, at N = 192).
        let lams = (0..12)
            .map(|i| 1000f64.powf(1.0 - i as f64 / 12.0) * 4f64.powf(i as f64 / 12.0))
            .chain((0..=60).map(|i| 4.0 - 0.05 * i as f64));
        for lam in lams {
            let sol = newton::solve(
                |u| {
                    let mut r = s.residual_x(u);
                    r[2] -= (lam - 1.0) * k3 * u[2];
                    r
                },
                &y,
                &opts,
            )
            .unwrap();
            // The speed falls steadily as mode 3 softens.
            assert!(
                sol.x[0] < last_v && (sol.x[0] - y[0]).abs() < 0.05,
                "{lam}: {sol:?}"
            );
            last_v = sol.x[0];
            y = sol.x;
        }
        assert!(
            (y[0] - direct.v).abs() < 1e-7 && (y[2] - direct.a[1]).abs() < 1e-7,
            "{y:?} {direct:?}"
        );
    }
}
