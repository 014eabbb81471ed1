//! The co-moving steady force balances of the model with shape modes `2..K`, one interface
//! over its two solvers: the 2-mode steady solver (the fast path, with the constrained solves
//! of the landing) and the general one ([`crate::roots::steady_solver::SteadySolver`]), both
//! solved by the chord method with kept Jacobians where one is near
//! ([`crate::roots::kept_jacobians`]). States are `(vx, vy, a_2..a_K, b_2..b_K)`,
//! for `K = 2` `(vx, vy, a2, b2)`. With them, the steady field of a droplet of any `K` in the
//! lab frame ([`lab_field`]).
use crate::error::SolverError;
use crate::model::dynamics;
use crate::model::mirror::MirrorLine;
use crate::model::modes::Modes;
use crate::model::param::ModelParam;
use crate::model::params::ModelParams;
use crate::model::state::{four, turned};
use crate::numerics::newton::NewtonOptions;
use crate::roots::kept_jacobians::KeptJacobians;
use crate::roots::linearisation::Linearization;
use crate::roots::steady_solver::SteadySolver;
use crate::roots::steady_solver::{on_x_axis, TwoModeSolver};
use crate::roots::verdict::Verdict;
use rustfft::num_complex::Complex64;

/// The steady force balances a finish solves: the 2-mode solver (with the constrained solves
/// of the landing and the orientation flow), or
/// the general one with shape modes `2..K`.
pub enum Balances {
    Two(TwoModeSolver),
    /// The general solver; the model's `K` is its parameters' (its states
    /// `(vx, vy, a_2..a_K, b_2..b_K)`).
    General(SteadySolver),
}

impl Balances {
    /// Newton on all the balances from `z`: `(vx, vy, a2, b2)`, or `(vx, vy, a_2..a_K,
    /// b_2..b_K)`; by the chord method where `jacobians` holds one near `z`.
    pub fn root_near(
        &mut self,
        z: &[f64],
        jacobians: &mut KeptJacobians,
    ) -> Result<Vec<f64>, SolverError> {
        match self {
            Balances::Two(solver) => {
                let opts = NewtonOptions {
                    tol: 1e-12,
                    // Converging solves from a run near its root take 3 to 8 iterations; a
                    // failing one (a run mid-turn, see `aligned_root`) is not worth 30.
                    max_iter: 12,
                    fd_step: 1e-6,
                    max_step: vec![f64::INFINITY, f64::INFINITY, 0.2, 0.2],
                    one_sided: false,
                    backtrack: false,
                };
                Ok(solver.root_near(four(z), &opts, jacobians)?.to_vec())
            }
            Balances::General(solver) => {
                // The settings K-mode runs have been finished with: to 1e-11, every
                // unknown's step limited; the Jacobian by forward differences (2K field solves
                // where central ones take 4K, the same roots: numerics modes-8); a step that
                // more than doubles the residual halved (numerics modes-16: the Fig. 1c run
                // from ii, modes 2..4, 0.18 degree off the x-axis MD, had Newton step 10
                // degrees along the MD's family and fail after 12 iterations).
                let opts = NewtonOptions {
                    tol: 1e-11,
                    max_iter: 12,
                    fd_step: 1e-7,
                    max_step: vec![0.2; z.len()],
                    one_sided: true,
                    backtrack: true,
                };
                let found = jacobians.solve(|y| solver.residual(y), z, &opts)?;
                if found.iter().all(|x| x.is_finite()) {
                    Ok(found)
                } else {
                    Err(SolverError::NewtonFailed {
                        residual: f64::NAN,
                        iterations: opts.max_iter,
                    })
                }
            }
        }
    }

    /// The stability of the root `z` ([`Linearization::verdict`]).
    pub fn verdict(&mut self, z: &[f64]) -> Verdict {
        match self {
            Balances::Two(solver) => Linearization::of_two_modes(solver, four(z)).verdict(),
            Balances::General(solver) => Linearization::at(solver, z).verdict(),
        }
    }

    /// The co-moving steady field of the droplet `z` (normalised coefficients, `[kx][ky]`, as
    /// the time steppers hold theirs): what a leap scales a run's field towards.
    pub fn root_field(&mut self, z: &[f64]) -> Vec<Complex64> {
        match self {
            Balances::Two(solver) => solver.field_and_forces(z[0], z[1], z[2], z[3]).0.to_vec(),
            Balances::General(solver) => {
                solver.forces(z[0], z[1], &Modes::of_state(z));
                solver.field_spectrum().to_vec()
            }
        }
    }
}

impl Balances {
    /// The balances of `params` on an `n x n` grid, with its shape modes `2..=params.modes`
    /// (the general ones with the friction law of `params`, which enters eigenvalues only;
    /// the modes within [`crate::contract::limits::check_modes`]).
    pub fn new(params: ModelParams, n: usize) -> Result<Self, SolverError> {
        let modes = params.modes;
        Ok(if modes == 2 {
            Balances::Two(TwoModeSolver::new(params, n)?)
        } else {
            crate::contract::limits::check_modes(&params, n, modes)?;
            Balances::General(SteadySolver::new(params, n)?)
        })
    }

    /// The model's parameters.
    pub fn params(&self) -> &ModelParams {
        match self {
            Balances::Two(solver) => solver.params(),
            Balances::General(solver) => solver.params(),
        }
    }

    /// Grid points per side.
    pub fn n(&self) -> usize {
        match self {
            Balances::Two(solver) => solver.grid().n,
            Balances::General(solver) => solver.n(),
        }
    }

    /// The model's shape modes `K` (its states have `2K` unknowns).
    pub fn modes(&self) -> usize {
        match self {
            Balances::Two(_) => 2,
            Balances::General(solver) => solver.params().modes,
        }
    }

    /// Moves the balances to `(eta_t, kappa2)`, the other parameters kept.
    pub fn set_control(&mut self, eta_t: f64, kappa2: f64) {
        match self {
            Balances::Two(solver) => solver.set_control(eta_t, kappa2),
            Balances::General(solver) => solver.set_control(eta_t, kappa2),
        }
    }

    /// Moves the balances to another value of one model parameter (refused, leaving them as
    /// they were, where the parameters would be invalid or unresolved).
    pub fn set_param(&mut self, param: ModelParam, x: f64) -> Result<(), SolverError> {
        match self {
            Balances::Two(solver) => solver.set_param(param, x),
            Balances::General(solver) => solver.set_param(param, x),
        }
    }

    /// The state `(vx, vy, a_2..a_K, b_2..b_K)` moving at `v` along `mirror` with the shape
    /// `a = a_2..a_K` in the line's own frame (mirror-symmetric about it): on the x axis
    /// `(v, 0, a, 0)`, on the diagonal that state turned by 45 degrees (mode `k` by `k` times
    /// 45; for `K = 2` exactly `(v, v, 0, a2 sqrt 2) / sqrt 2`).
    pub fn on_mirror(&self, mirror: MirrorLine, v: f64, a: &[f64]) -> Vec<f64> {
        match (self, mirror) {
            (Balances::Two(_), _) => mirror.two_mode_state(v, a[0]).to_vec(),
            (Balances::General(_), MirrorLine::X) => on_x_axis(v, a),
            (Balances::General(_), MirrorLine::Diagonal) => {
                turned(&on_x_axis(v, a), mirror.angle())
            }
        }
    }

    /// The shape amplitudes `a_2..a_K` in the frame of `mirror` of a state `z` lying along
    /// it (the inverse of [`Self::on_mirror`] for the shape): on the x axis `a_k`; on the
    /// diagonal the amplitudes of `z` turned back by 45 degrees (for `K = 2` exactly `b2`).
    pub fn shape_on(&self, mirror: MirrorLine, z: &[f64]) -> Vec<f64> {
        match (self, mirror) {
            (Balances::Two(_), MirrorLine::X) => vec![z[2]],
            (Balances::Two(_), MirrorLine::Diagonal) => vec![z[3]],
            (Balances::General(solver), _) => {
                turned(z, -mirror.angle())[2..=solver.params().modes].to_vec()
            }
        }
    }

    /// The balances of [`Self::on_mirror`]'s state in the line's own frame: along the motion,
    /// then the shape balances of `a_2..a_K` (`K` values; the others vanish by the mirror
    /// symmetry).
    pub fn residual_on(&mut self, mirror: MirrorLine, v: f64, a: &[f64]) -> Vec<f64> {
        match self {
            Balances::Two(solver) => solver.residual_on(mirror, v, a[0]).to_vec(),
            Balances::General(solver) => {
                solver.set_axis(mirror.angle());
                let y: Vec<f64> = std::iter::once(v).chain(a.iter().copied()).collect();
                solver.residual_x(&y)
            }
        }
    }

    /// Plain Newton on all the balances from `z` with the caller's options (no kept
    /// Jacobians: an independent check of a root, as the audit makes it).
    pub fn root_from(&mut self, z: &[f64], opts: &NewtonOptions) -> Result<Vec<f64>, SolverError> {
        match self {
            Balances::Two(solver) => Ok(solver.root_from(four(z), opts)?.to_vec()),
            Balances::General(solver) => {
                Ok(crate::numerics::newton::solve(|y| solver.residual(y), z, opts)?.x)
            }
        }
    }

    /// The force balance at `z`, in `z`'s layout: the velocity's, then each shape mode's
    /// (zero at a steady state; it turns with the state, mode `k` `k` times).
    pub fn residual(&mut self, z: &[f64]) -> Vec<f64> {
        match self {
            Balances::Two(solver) => {
                let p = *solver.params();
                let f = solver.forces(z[0], z[1], z[2], z[3]);
                dynamics::force_balance(&p, four(z), &f).to_vec()
            }
            Balances::General(solver) => solver.residual(z),
        }
    }
}

/// The steady field in the lab frame (for pictures and checks) of the droplet `z = (vx, vy, a_2..a_K, b_2..b_K)` centred at `(x, y)`, on
/// the solver's grid (row-major, `values[iy * n + ix]` at `((ix - n/2) dx, (iy - n/2) dx)`).
pub fn lab_field(solver: &mut SteadySolver, z: &[f64], x: f64, y: f64) -> crate::stepping::Field {
    solver.forces(z[0], z[1], &crate::model::modes::Modes::of_state(z));
    let n = solver.n();
    let len = solver.params().box_len;
    let mut spec = solver.field_spectrum().to_vec();
    solver.grid().shift_spectrum(&mut spec, x, y);
    let mut values = vec![0.0; n * n];
    crate::numerics::fft2::PrunedFft2::new(n).inverse(&mut spec, &mut values, 0, n - 1);
    crate::stepping::Field { n, len, values }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn with_two_modes_at_the_centre_it_is_the_two_mode_steady_field() {
        let p = ModelParams::at(0.085, 0.112);
        let mut modes = SteadySolver::new(p, 64).unwrap();
        let mut two = TwoModeSolver::new(p, 64).unwrap();
        let f = lab_field(&mut modes, &[0.3, 0.1, -0.2, 0.05], 0.0, 0.0);
        let g = two.field(0.3, 0.1, -0.2, 0.05);
        let peak = g.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let diff = f
            .values
            .iter()
            .zip(&g)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(peak > 0.01 && diff < 1e-12 * peak, "{diff} of {peak}");
    }

    #[test]
    fn moving_the_centre_by_whole_cells_moves_the_field() {
        // A shift by (3, -2) cells moves the field's samples with it, exactly but for the
        // Nyquist modes, which the spectral shift (like the derivatives) leaves out: a part in
        // 1e-4 of the peak at N = 64. A shift the wrong way would be off by a fifth of it.
        let p = ModelParams::at(0.085, 0.112);
        let mut s = SteadySolver::new(p, 64).unwrap();
        let z = [0.3, 0.0, -0.2, 0.04, 0.0, 0.01];
        let at0 = lab_field(&mut s, &z, 0.0, 0.0);
        let dx = p.box_len / 64.0;
        let moved = lab_field(&mut s, &z, 3.0 * dx, -2.0 * dx);
        let peak = at0.values.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for iy in 10..54 {
            for ix in 10..54 {
                let a = moved.values[iy * 64 + ix];
                let b = at0.values[(iy + 2) * 64 + ix - 3];
                assert!((a - b).abs() < 1e-4 * peak, "({ix}, {iy}): {a} vs {b}");
            }
        }
    }
}
