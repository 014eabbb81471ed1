//! The co-moving steady force balances of the model with shape modes `2..K`, one interface
//! over its two solvers: the 2-mode steady solver (the fast path: its chord method with kept
//! Jacobians, and the constrained solves of the landing) and the general one
//! ([`crate::roots::mode_solver::ModeSolver`]). States are `(vx, vy, a_2..a_K, b_2..b_K)`,
//! for `K = 2` `(vx, vy, a2, b2)`.
use crate::error::SolverError;
use crate::model::dynamics;
use crate::model::params::ModelParams;
use crate::model::state::four;
use crate::numerics::newton::NewtonOptions;
use crate::roots::linearisation::Linearization;
use crate::roots::mode_linearisation::ModeLinearization;
use crate::roots::mode_solver::ModeSolver;
use crate::roots::steady_solver::{KeptJacobians, SteadySolver};
use crate::roots::verdict::{assess, Verdict};

/// The steady force balances a finish solves: the 2-mode solver (with the chord method's
/// kept Jacobians, and the constrained solves of the landing and the orientation flow), or
/// the general one with shape modes `2..K`.
pub enum Balances {
    Two(SteadySolver),
    /// The general solver and the model's `K` (its states `(vx, vy, a_2..a_K, b_2..b_K)`).
    General {
        solver: ModeSolver,
        modes: usize,
    },
}

impl Balances {
    /// Newton on all the balances from `z`: `(vx, vy, a2, b2)`, or `(vx, vy, a_2..a_K,
    /// b_2..b_K)`.
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
                };
                Ok(solver.root_near(four(z), &opts, jacobians)?.to_vec())
            }
            Balances::General { solver, .. } => {
                // The settings K-mode runs have been finished with: to 1e-11, every
                // unknown's step limited.
                let opts = NewtonOptions {
                    tol: 1e-11,
                    max_iter: 12,
                    fd_step: 1e-7,
                    max_step: vec![0.2; z.len()],
                };
                let found = crate::numerics::newton::solve(|y| solver.residual(y), z, &opts)?;
                if found.x.iter().all(|x| x.is_finite()) {
                    Ok(found.x)
                } else {
                    Err(SolverError::NewtonFailed {
                        residual: f64::NAN,
                        iterations: opts.max_iter,
                    })
                }
            }
        }
    }

    /// The stability of the root `z` ([`crate::roots::verdict::assess`]).
    pub fn verdict(&mut self, z: &[f64]) -> Verdict {
        match self {
            Balances::Two(solver) => assess(&Linearization::at(solver, four(z)), z),
            Balances::General { solver, .. } => ModeLinearization::at(solver, z).verdict(),
        }
    }
}

impl Balances {
    /// The balances of `params` on an `n x n` grid with shape modes `2..=modes` (the general
    /// ones with the friction law's exponent `eta_k_exponent`, which enters eigenvalues only;
    /// `modes` within [`crate::contract::limits::check_modes`]).
    pub fn new(
        params: ModelParams,
        n: usize,
        modes: usize,
        eta_k_exponent: f64,
    ) -> Result<Self, SolverError> {
        Ok(if modes == 2 {
            Balances::Two(SteadySolver::new(params, n)?)
        } else {
            crate::contract::limits::check_modes(&params, n, modes)?;
            let mut solver = ModeSolver::new(params, n)?;
            solver.set_eta_k_exponent(eta_k_exponent);
            Balances::General { solver, modes }
        })
    }

    /// The model's parameters.
    pub fn params(&self) -> &ModelParams {
        match self {
            Balances::Two(solver) => solver.params(),
            Balances::General { solver, .. } => solver.params(),
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
            Balances::General { solver, .. } => solver.residual(z),
        }
    }
}
