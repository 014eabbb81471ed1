//! Time stepping: the integrators of the droplet model ([`Scheme`]; each owns its field and the
//! droplet state) and what they are built from.
//!
//! - `comoving_etd`: the default pseudo-spectral ETD2RK in the droplet's co-moving frame,
//!   fixed or adaptive steps, for every `K` and its fast path for `K = 2`; `etd` the
//!   exponential time-differencing coefficients; `step_control` the PI step-size controller.
//! - `paper_fd`: the paper's forward-Euler finite differences (the baseline), for every `K`
//!   and for `K = 2`. Every one is a [`Scheme`], so one driver runs them.
//!
//! May use: `numerics`, `model`. Used by: `contract` (the scheme setting), `runs`.
pub mod comoving_etd;
pub mod etd;
pub mod paper_fd;
pub mod step_control;

use crate::error::SolverError;
use crate::model::state::DropletState;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// Which integrator a run uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SchemeKind {
    /// Pseudo-spectral ETD2RK in the droplet's co-moving frame (default).
    Spectral,
    /// The paper's forward-Euler finite-difference scheme on the lab grid (baseline).
    PaperFd,
}

impl SchemeKind {
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::Spectral => "spectral",
            Self::PaperFd => "paper-fd",
        }
    }
}

impl fmt::Display for SchemeKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for SchemeKind {
    type Err = SolverError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "spectral" => Ok(Self::Spectral),
            "paper-fd" => Ok(Self::PaperFd),
            other => Err(SolverError::UnknownScheme(other.to_string())),
        }
    }
}

/// The concentration field on a lab-frame grid: `values[iy * n + ix]` at
/// `x = (ix - n/2) dx`, `y = (iy - n/2) dx`.
#[derive(Debug, Clone)]
pub struct Field {
    pub n: usize,
    pub len: f64,
    pub values: Vec<f64>,
}

/// What became of one step attempt.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attempt {
    /// The step was taken (else nothing changed).
    pub accepted: bool,
    /// Embedded local error estimate: max over the droplet's integrated scalars of
    /// `|corrector - predictor|` (`None` for schemes without one).
    pub error: Option<f64>,
}

/// What the clock of a run ([`crate::runs::clock`]) steps: a droplet and its field, of any
/// number of shape modes.
pub trait Stepper: Send {
    /// Attempts a step of `h`. It is taken unless the scheme's embedded error estimate
    /// exceeds `max_error`; a refused step leaves the scheme unchanged. Schemes without an
    /// estimate always take the step.
    fn attempt(&mut self, h: f64, max_error: f64) -> Attempt;
    /// Advances by `h` unconditionally.
    fn step(&mut self, h: f64) {
        self.attempt(h, f64::INFINITY);
    }
}

/// One integrator of the droplet with shape modes `2..K`: a [`Stepper`] with its state, field
/// and mass, the rate it measures (`K > 2`) and the leap along a linear mode (`K = 2`).
pub trait Scheme: Stepper {
    /// The droplet's centre, velocity and mode-2 amplitudes.
    fn state(&self) -> DropletState;
    /// Its unknowns `(vx, vy, a_2..a_K, b_2..b_K)`; with two modes `(vx, vy, a2, b2)`.
    fn unknowns(&self) -> Vec<f64> {
        self.state().monitored().to_vec()
    }
    /// The rates `dz/dt` of the unknowns `(vx, vy, a_2..a_K, b_2..b_K)` at the present state,
    /// for schemes that measure them: those of `K > 2` modes, whose runs are watched by them
    /// (2-mode runs by the change over the paper's window,
    /// [`crate::contract::stop_rule::SteadyTest`]).
    fn rates(&mut self) -> Option<Vec<f64>> {
        None
    }
    /// `Integral u dA`.
    fn mass(&self) -> f64;
    /// The concentration in the lab frame.
    fn field(&mut self) -> Field;
    /// The co-moving field's normalised spectrum (`[kx][ky]`, the layout of
    /// [`Scheme::leap`]'s `root_field`), for schemes that hold one.
    fn spectrum(&self) -> Option<&[rustfft::num_complex::Complex64]> {
        None
    }
    /// Moves the run along a linear mode of the fixed point `root = (vx, vy, a_2..a_K,
    /// b_2..b_K)` whose co-moving field is `root_field` (normalised coefficients, `[kx][ky]`,
    /// as [`crate::roots::balances::Balances::root_field`] gives them): the displacement of
    /// the field and of the unknowns from the fixed point is multiplied by `factor` and the
    /// centre moves by `shift` ([`crate::runs::leap`]). Schemes without a co-moving spectrum
    /// return false and change nothing.
    fn leap(
        &mut self,
        _root: &[f64],
        _root_field: &[rustfft::num_complex::Complex64],
        _factor: f64,
        _shift: [f64; 2],
    ) -> bool {
        false
    }
}

/// The leap's move ([`Scheme::leap`]) of values displaced from a fixed point's `root`: each
/// becomes `root + (value - root) factor` (the field's spectrum and the unknowns alike).
pub(crate) fn scale_displacement<'a, T>(
    values: impl IntoIterator<Item = &'a mut T>,
    root: &[T],
    factor: f64,
) where
    T: 'a
        + Copy
        + std::ops::Add<Output = T>
        + std::ops::Sub<Output = T>
        + std::ops::Mul<f64, Output = T>,
{
    for (x, r) in values.into_iter().zip(root) {
        *x = *r + (*x - *r) * factor;
    }
}

/// The inertia a scheme of the model with shape modes `2..K` needs: it integrates the
/// velocity (`m dv/dt = -eta_t v + F`), so `m > 0` (the modes and the droplet the grid
/// resolves are the caller's to check, `contract::limits::check_run`).
pub(crate) fn require_inertia(
    params: &crate::model::params::ModelParams,
) -> Result<(), SolverError> {
    crate::error::require(
        params.mass > 0.0,
        "mass",
        params.mass,
        "a finite number > 0 (the K-mode run integrates the velocity)",
    )
}
