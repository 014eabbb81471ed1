//! The model the audit checks a point's states with: the paper's 2-mode steady equations and
//! eigenvalues ([`SteadySolver`], [`Linearization`]), or those of the general model with
//! shape modes `2..K` ([`ModeSolver`], [`ModeLinearization`]; a map with `params.modes: K`).
//! Either way the audit asks the same two questions: is the resting disk stable here, and
//! which root does Newton reach from a run's final state, with what class and stability.
use crate::error::SweepError;
use droplet_solver::model::params::ModelParams;
use droplet_solver::numerics::newton::{self, NewtonOptions};
use droplet_solver::roots::linearisation::Linearization;
use droplet_solver::roots::mode_linearisation::ModeLinearization;
use droplet_solver::roots::mode_solver::ModeSolver;
use droplet_solver::roots::steady_solver::SteadySolver;
use droplet_solver::roots::verdict::assess;

/// The growing modes of a state, the near-neutral rotation mode aside.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Growth {
    pub unstable: usize,
    /// The largest real part among the eigenvalues counted.
    pub max_re: f64,
}

impl Growth {
    pub fn stable(&self) -> bool {
        self.unstable == 0
    }
}

impl std::fmt::Display for Growth {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} growing mode(s), largest {:+.3e}",
            self.unstable, self.max_re
        )
    }
}

/// A root Newton reached from a run's final state: its speed, its mode-2 deformation `s`
/// (the class's), and its growth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Root {
    pub v: f64,
    pub s: f64,
    pub growth: Growth,
}

/// The steady equations and eigenvalues of one model, moved from point to point.
pub trait PointModel: Send {
    fn params(&self) -> &ModelParams;
    fn n(&self) -> usize;
    fn set_control(&mut self, eta_t: f64, kappa2: f64);
    /// The resting disk's growth here.
    fn disk(&mut self) -> Growth;
    /// Newton on every steady equation from `state` (`(vx, vy, a2..aK, b2..bK)`), and the
    /// root's class and growth (`None`: no convergence).
    fn root_near(&mut self, state: &[f64]) -> Option<Root>;
}

/// The model of a map with `modes` shape modes (their friction law's exponent
/// `eta_k_exponent`, which moves the eigenvalues) at `params` on an `n` grid.
pub fn for_map(
    (modes, eta_k_exponent): (usize, f64),
    params: ModelParams,
    n: usize,
) -> Result<Box<dyn PointModel>, SweepError> {
    Ok(if modes == 2 {
        Box::new(TwoModes(SteadySolver::new(params, n)?))
    } else {
        let mut solver = ModeSolver::new(params, n)?;
        solver.set_eta_k_exponent(eta_k_exponent);
        Box::new(KModes { solver, modes })
    })
}

/// The paper's model (`a2, b2`).
struct TwoModes(SteadySolver);

impl PointModel for TwoModes {
    fn params(&self) -> &ModelParams {
        self.0.params()
    }

    fn n(&self) -> usize {
        self.0.grid().n
    }

    fn set_control(&mut self, eta_t: f64, kappa2: f64) {
        self.0.set_control(eta_t, kappa2);
    }

    fn disk(&mut self) -> Growth {
        let v = assess(&Linearization::at(&mut self.0, [0.0; 4]), &[0.0; 4]);
        Growth {
            unstable: v.unstable,
            max_re: v.max_re,
        }
    }

    fn root_near(&mut self, state: &[f64]) -> Option<Root> {
        let opts = NewtonOptions {
            tol: 1e-11,
            max_iter: 30,
            fd_step: 1e-6,
            max_step: vec![f64::INFINITY, f64::INFINITY, 0.2, 0.2],
        };
        let z = [state[0], state[1], state[2], state[3]];
        let root = self.0.root_from(z, &opts).ok()?;
        let v = assess(&Linearization::at(&mut self.0, root), &root);
        Some(Root {
            v: root[0].hypot(root[1]),
            s: root[2].hypot(root[3]),
            growth: Growth {
                unstable: v.unstable,
                max_re: v.max_re,
            },
        })
    }
}

/// The general model with shape modes `2..K`.
struct KModes {
    solver: ModeSolver,
    modes: usize,
}

impl KModes {
    fn growth(&mut self, z: &[f64]) -> Growth {
        let v = ModeLinearization::at(&mut self.solver, z).verdict();
        Growth {
            unstable: v.unstable,
            max_re: v.max_re,
        }
    }
}

impl PointModel for KModes {
    fn params(&self) -> &ModelParams {
        self.solver.params()
    }

    fn n(&self) -> usize {
        self.solver.n()
    }

    fn set_control(&mut self, eta_t: f64, kappa2: f64) {
        self.solver.set_control(eta_t, kappa2);
    }

    fn disk(&mut self) -> Growth {
        // Each mode k decouples at the circle and has its own onset (kappa_k = k^2 kappa2 / 4).
        self.growth(&vec![0.0; 2 * self.modes])
    }

    fn root_near(&mut self, state: &[f64]) -> Option<Root> {
        let opts = NewtonOptions {
            tol: 1e-11,
            max_iter: 30,
            fd_step: 1e-7,
            max_step: vec![0.2; state.len()],
        };
        let solver = &mut self.solver;
        let x = newton::solve(|y| solver.residual(y), state, &opts).ok()?.x;
        let k = state.len() / 2;
        Some(Root {
            v: x[0].hypot(x[1]),
            s: x[2].hypot(x[k + 1]),
            growth: self.growth(&x),
        })
    }
}
