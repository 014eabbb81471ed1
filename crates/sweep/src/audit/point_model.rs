//! What the audit asks of a point's states, at any number of shape modes through the solver's
//! one interface to the steady balances ([`Balances`]: the paper's 2-mode equations and
//! eigenvalues, or the general model's with shape modes `2..K`, a map with `params.modes: K`):
//! is the resting disk stable here, and which root does Newton reach from a run's final state,
//! with what class and stability.
use crate::error::SweepError;
use droplet_solver::model::params::ModelParams;
use droplet_solver::model::state::speed_and_deformation;
use droplet_solver::numerics::newton::NewtonOptions;
use droplet_solver::roots::balances::Balances;
use droplet_solver::roots::verdict::Verdict;

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

    fn of(v: &Verdict) -> Self {
        Self {
            unstable: v.unstable,
            max_re: v.max_re,
        }
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

/// The balances of a map's model at `params` (its shape modes and their friction law, which
/// moves the eigenvalues, among them) on an `n` grid.
pub fn for_map(params: ModelParams, n: usize) -> Result<Balances, SweepError> {
    Ok(Balances::new(params, n)?)
}

/// The resting disk's growth here (each shape mode decouples at the circle and has its own
/// onset, `kappa_k = k^2 kappa2 / 4`).
pub fn disk(balances: &mut Balances) -> Growth {
    let z = vec![0.0; 2 * balances.modes()];
    Growth::of(&balances.verdict(&z))
}

/// Newton on every steady equation from `state` (`(vx, vy, a2..aK, b2..bK)`), and the root's
/// class and growth (`None`: no convergence).
pub fn root_near(balances: &mut Balances, state: &[f64]) -> Option<Root> {
    // To 1e-11 in at most 30 iterations; the 2-mode shape steps limited, every K-mode one.
    let opts = match balances.modes() {
        2 => NewtonOptions {
            tol: 1e-11,
            max_iter: 30,
            fd_step: 1e-6,
            max_step: vec![f64::INFINITY, f64::INFINITY, 0.2, 0.2],
            one_sided: false,
            backtrack: false,
        },
        _ => NewtonOptions {
            tol: 1e-11,
            max_iter: 30,
            fd_step: 1e-7,
            max_step: vec![0.2; state.len()],
            one_sided: false,
            backtrack: false,
        },
    };
    let x = balances.root_from(state, &opts).ok()?;
    let (v, s) = speed_and_deformation(&x);
    Some(Root {
        v,
        s,
        growth: Growth::of(&balances.verdict(&x)),
    })
}
