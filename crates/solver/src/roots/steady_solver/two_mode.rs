//! The fast path of `K = 2` for the exact co-moving steady state (docs/model.md, "Steady states as roots": in the droplet's
//! frame a steadily moving state is a fixed point, so it can be computed directly): for given `(v, a2, b2)` the field
//! `u_hat = Theta_hat / (A (1 + k^2 - i k.v))` solves `0 = Lap u - u + v.grad u + Theta / A`
//! (paper eq. S13), and the force balance `-eta_t v + F = 0`, `Ga - kappa2 a2 = 0`,
//! `Gb - kappa2 b2 = 0` is solved by Newton. Same grid, `Theta` and force quadrature as
//! [`crate::stepping::comoving_etd::TwoModeEtd`], so its fixed points coincide with the solver's.
use crate::error::SolverError;
use crate::model::dynamics;
use crate::model::forces::parseval::{spectral_forces, Forces};
use crate::model::grid::Grid;
use crate::model::mirror::MirrorLine;
use crate::model::params::ModelParams;
use crate::model::shape_transform::ShapeTransform;
use crate::numerics::fft2::PrunedFft2;
use crate::numerics::newton::{self, NewtonOptions};
use crate::roots::forces_memo::ForcesMemo;
use crate::roots::kept_jacobians::KeptJacobians;
use rustfft::num_complex::Complex64;

/// Evaluates steady fields and force-balance residuals on an `N x N` co-moving grid.
pub struct TwoModeSolver {
    params: ModelParams,
    grid: Grid,
    fft: PrunedFft2,
    shapes: ShapeTransform,
    /// The transforms of the last shapes, the newest first: a residual at a new velocity
    /// or new `(eta_t, kappa2)` and a shape seen just before (most columns of a nested
    /// difference Jacobian) transforms nothing.
    transformed: Vec<Transformed>,
    w: Vec<Complex64>,
    /// The forces of the last droplets `(vx, vy, a2, b2)` asked for.
    memo: ForcesMemo<[f64; 4], Forces>,
}

/// The packed transforms `ph`, `yh` of the shape `(a2, b2)` and its area.
struct Transformed {
    a2: f64,
    b2: f64,
    area: f64,
    ph: Vec<Complex64>,
    yh: Vec<Complex64>,
}

/// Shapes whose transforms a solver keeps: a state and its two neighbours in one amplitude
/// (a central difference), and one more.
const SHAPES_KEPT: usize = 4;

/// A steady state found by [`TwoModeSolver::newton`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyState {
    /// Speed along the axis (+x for [`TwoModeSolver::newton`]).
    pub v: f64,
    /// Shape amplitude on the axis: `a2` for [`MirrorLine::X`] (`b2 = 0`; `a2 < 0` is a
    /// droplet elongated across the motion), `b2` for [`MirrorLine::Diagonal`] (`a2 = 0`).
    pub a2: f64,
    /// Max norm of the residual at the solution.
    pub residual: f64,
    pub iterations: usize,
}

/// `x / d` for a real `x`, as `Complex64::new(x, 0.0) / d` computes it (the same operations in
/// the same order, so the same bits), written out so that a loop of them is vectorised: the
/// steady field, `Theta_hat / (A N^2 (1 + k^2 - i k.v))`, took a tenth of a 2-mode map's run
/// time with one scalar division after another.
#[inline(always)]
fn real_over(x: f64, d: Complex64) -> Complex64 {
    let norm_sqr = d.re * d.re + d.im * d.im;
    let re = x * d.re + 0.0 * d.im;
    let im = 0.0 * d.re - x * d.im;
    Complex64::new(re / norm_sqr, im / norm_sqr)
}

impl TwoModeSolver {
    pub fn new(params: ModelParams, n: usize) -> Result<Self, SolverError> {
        params.validate()?;
        let grid = Grid::new(n, params.box_len)?;
        crate::contract::limits::check_resolved(&params, n)?;
        let shape = params.shape();
        let len = grid.spectral_len();
        let z = Complex64::default();
        Ok(Self {
            params,
            fft: PrunedFft2::new(n),
            shapes: ShapeTransform::new(&grid, shape),
            transformed: Vec::with_capacity(SHAPES_KEPT),
            w: vec![z; len],
            memo: ForcesMemo::default(),
            grid,
        })
    }

    /// The steady co-moving field (normalised Fourier coefficients, `[kx][ky]`) of a droplet
    /// of shape `(a2, b2)` moving at `(vx, vy)`, and the forces it exerts.
    pub fn field_and_forces(
        &mut self,
        vx: f64,
        vy: f64,
        a2: f64,
        b2: f64,
    ) -> (&[Complex64], Forces) {
        crate::contract::profile::field_solve();
        let n = self.grid.n;
        let area = self.transform(a2, b2);
        let norm = 1.0 / (area * (n * n) as f64);
        let t = &self.transformed[0];
        let grid = &self.grid;
        let columns = self.w.chunks_exact_mut(n).zip(t.ph.chunks_exact(n));
        for ((w_col, ph_col), (kx, kxd)) in columns.zip(grid.kx.iter().zip(&grid.kx_d)) {
            let kx2 = 1.0 + kx * kx;
            let modes = grid.ky.iter().zip(&grid.ky_d);
            for ((w, ph), (ky, kyd)) in w_col.iter_mut().zip(ph_col).zip(modes) {
                let kv = kxd * vx + kyd * vy;
                // Theta_hat = Re of the packed transform.
                *w = real_over(ph.re * norm, Complex64::new(kx2 + ky * ky, -kv));
            }
        }
        let f = spectral_forces(&self.grid, &self.w, &t.ph, &t.yh, area);
        (&self.w, f)
    }

    /// The packed shape transforms of a droplet `(a2, b2)` (of `Theta + X Theta` and of
    /// `Y Theta`, raw, `[kx][ky]`; see [`crate::model::forces`]) and its area `A`.
    pub fn shape_spectra(&mut self, a2: f64, b2: f64) -> (Vec<Complex64>, Vec<Complex64>, f64) {
        let area = self.transform(a2, b2);
        let t = &self.transformed[0];
        (t.ph.clone(), t.yh.clone(), area)
    }

    pub fn params(&self) -> &ModelParams {
        &self.params
    }

    /// Moves the solver to another value of one parameter: `eta_t`, `kappa2`, `eta2` and
    /// `mass` are set (they enter the force balance or the eigenvalues only); `radius`,
    /// `sigma` and `box_len` sample the droplet (and for `box_len` the grid) again. Refused,
    /// leaving the solver as it was, where the parameters would be invalid or the grid would
    /// not resolve the droplet ([`crate::contract::limits::check_resolved`]).
    pub fn set_param(
        &mut self,
        param: crate::model::param::ModelParam,
        x: f64,
    ) -> Result<(), SolverError> {
        let Some((params, sampled)) = super::moved(&self.params, self.grid.n, param, x)? else {
            return Ok(());
        };
        if let Some((grid, shape)) = sampled {
            self.shapes = ShapeTransform::new(&grid, shape);
            self.grid = grid;
            self.transformed.clear();
            self.memo.clear();
        }
        self.params = params;
        Ok(())
    }

    /// Moves the solver to another `(eta_t, kappa2)`: they enter only the force balance, so
    /// nothing sampled or planned changes (the continuation's parameters).
    pub fn set_control(&mut self, eta_t: f64, kappa2: f64) {
        self.params.eta_t = eta_t;
        self.params.kappa2 = kappa2;
    }

    /// Makes the transforms of the shape `(a2, b2)` the newest of [`Self::transformed`],
    /// computing them unless they are kept; its area.
    fn transform(&mut self, a2: f64, b2: f64) -> f64 {
        let kept = &mut self.transformed;
        match kept.iter().position(|t| t.a2 == a2 && t.b2 == b2) {
            Some(i) => kept[..=i].rotate_right(1),
            None => {
                let mut t = if kept.len() == SHAPES_KEPT {
                    kept.pop().expect("full")
                } else {
                    let len = self.grid.spectral_len();
                    Transformed {
                        a2,
                        b2,
                        area: 0.0,
                        ph: vec![Complex64::default(); len],
                        yh: vec![Complex64::default(); len],
                    }
                };
                t.area = self.shapes.transform(a2, b2, &mut t.ph, &mut t.yh);
                (t.a2, t.b2) = (a2, b2);
                kept.insert(0, t);
            }
        }
        kept[0].area
    }

    /// The steady field in real space (co-moving, droplet at the grid centre; row-major,
    /// `values[iy * n + ix]` at `((ix - n/2) dx, (iy - n/2) dx)`).
    pub fn field(&mut self, vx: f64, vy: f64, a2: f64, b2: f64) -> Vec<f64> {
        let n = self.grid.n;
        self.field_and_forces(vx, vy, a2, b2);
        let mut spec = self.w.clone();
        let mut out = vec![0.0; n * n];
        self.fft.inverse(&mut spec, &mut out, 0, n - 1);
        out
    }

    /// Forces exerted by the steady field of a droplet `(a2, b2)` moving at `(vx, vy)` (a
    /// droplet asked for shortly before is not solved again).
    pub fn forces(&mut self, vx: f64, vy: f64, a2: f64, b2: f64) -> Forces {
        let droplet = [vx, vy, a2, b2];
        if let Some(f) = self.memo.get(&droplet) {
            return f;
        }
        let f = self.field_and_forces(vx, vy, a2, b2).1;
        self.memo.keep(&droplet, &f);
        f
    }

    /// Force-balance residual `(-eta_t vx + Fx, Ga - kappa2 a2)` for motion along x, `b2 = 0`.
    pub fn residual(&mut self, v: f64, a2: f64) -> [f64; 2] {
        let f = self.forces(v, 0.0, a2, 0.0);
        let r = dynamics::force_balance(&self.params, [v, 0.0, a2, 0.0], &f);
        [r[0], r[2]]
    }

    /// The residual of [`Self::residual`] on a mirror axis: speed `v` along it, shape
    /// amplitude `c` on it.
    pub fn residual_on(&mut self, axis: MirrorLine, v: f64, c: f64) -> [f64; 2] {
        let p = self.params;
        match axis {
            MirrorLine::X => self.residual(v, c),
            MirrorLine::Diagonal => {
                let d = v * std::f64::consts::FRAC_1_SQRT_2;
                let f = self.forces(d, d, 0.0, c);
                let r = dynamics::force_balance(&p, [d, d, 0.0, c], &f);
                // The balance along the diagonal: its x and y parts projected on (1, 1)/sqrt 2.
                [(r[0] + r[1]) * std::f64::consts::FRAC_1_SQRT_2, r[3]]
            }
        }
    }

    /// Newton solve from `(v, a2)` on the x axis. With `v = 0` only `a2` is solved (ID and IC
    /// states, where `F = 0` by symmetry); otherwise `(v, a2)` (MD, MC states moving along x).
    pub fn newton(&mut self, v0: f64, a20: f64, tol: f64) -> Result<SteadyState, SolverError> {
        self.newton_on(MirrorLine::X, v0, a20, tol)
    }

    /// Newton on all four force balances from `z = (vx, vy, a2, b2)`, no mirror symmetry
    /// assumed: the root, or the error when Newton does not converge under `opts`.
    pub fn root_from(
        &mut self,
        z: [f64; 4],
        opts: &NewtonOptions,
    ) -> Result<[f64; 4], SolverError> {
        self.root_near(z, opts, &mut KeptJacobians::default())
    }

    /// [`Self::root_from`], first by the chord method with a Jacobian `kept` from an earlier
    /// solve near `z` ([`KeptJacobians::solve`]).
    pub fn root_near(
        &mut self,
        z: [f64; 4],
        opts: &NewtonOptions,
        kept: &mut KeptJacobians,
    ) -> Result<[f64; 4], SolverError> {
        let p = self.params;
        let balance = |x: &[f64]| {
            let f = self.forces(x[0], x[1], x[2], x[3]);
            dynamics::force_balance(&p, [x[0], x[1], x[2], x[3]], &f).to_vec()
        };
        let x = kept.solve(balance, &z, opts)?;
        Ok([x[0], x[1], x[2], x[3]])
    }

    /// [`Self::newton`] on either mirror axis ([`crate::numerics::newton::solve`]: central differences
    /// of step 1e-6, the shape step capped at 0.2 so that it never jumps past the
    /// small-deformation model, at most 50 iterations).
    pub fn newton_on(
        &mut self,
        axis: MirrorLine,
        v0: f64,
        a20: f64,
        tol: f64,
    ) -> Result<SteadyState, SolverError> {
        let moving = v0 != 0.0;
        let opts = NewtonOptions {
            tol,
            max_iter: 50,
            fd_step: 1e-6,
            max_step: if moving {
                vec![f64::INFINITY, 0.2]
            } else {
                vec![0.2]
            },
            one_sided: false,
            backtrack: false,
        };
        let sol = if moving {
            newton::solve(
                |x| self.residual_on(axis, x[0], x[1]).to_vec(),
                &[v0, a20],
                &opts,
            )?
        } else {
            newton::solve(
                |x| vec![self.residual_on(axis, 0.0, x[0])[1]],
                &[a20],
                &opts,
            )?
        };
        let (v, a2) = if moving {
            (sol.x[0], sol.x[1])
        } else {
            (0.0, sol.x[0])
        };
        Ok(SteadyState {
            v,
            a2,
            residual: sol.residual,
            iterations: sol.iterations,
        })
    }

    pub fn grid(&self) -> &Grid {
        &self.grid
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_real_over_a_complex_number_is_num_complexs_quotient_to_the_last_bit() {
        let xs = [0.0, -0.0, 1.0, -3.7e-5, 2.5e8, f64::MIN_POSITIVE];
        let ds = [
            Complex64::new(1.0, 0.0),
            Complex64::new(1.0, -0.0),
            Complex64::new(37.5, -0.8125),
            Complex64::new(1.0 + 1e-12, 4.2e3),
            Complex64::new(2.0, -1e-300),
        ];
        for x in xs {
            for d in ds {
                let (ours, theirs) = (real_over(x, d), Complex64::new(x, 0.0) / d);
                assert_eq!(ours.re.to_bits(), theirs.re.to_bits(), "{x} / {d}");
                assert_eq!(ours.im.to_bits(), theirs.im.to_bits(), "{x} / {d}");
            }
        }
    }
}
