//! Numerical settings of a run (which model and scheme, grid, steps, stop rules) and their
//! validation, shared by the PDE run driver, the ODE model and the sweep specs.
use crate::contract::ending::SteadyMethod;
use crate::error::{require, SolverError};
use crate::stepping::SchemeKind;
use serde::{Deserialize, Serialize};

pub const H0_PAPER: f64 = 0.1436;

/// Most steps one run may be planned to take (1e8: the paper's scheme at dt = 1e-4 reaches
/// t = 10 000; at N = 192 the spectral scheme needs about a day for that many).
pub const MAX_STEPS: f64 = 1e8;

/// Which equations a run integrates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum ModelKind {
    /// The PDE model of Sect. 3 (field + droplet).
    #[default]
    Pde,
    /// The reduced ODE model, eqs. (58)-(59) ([`crate::reduced::ode`]).
    Ode,
}

impl ModelKind {
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::Pde => "pde",
            Self::Ode => "ode",
        }
    }
}

/// Numerical settings of a run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSettings {
    /// PDE or reduced ODE.
    pub model: ModelKind,
    /// Cubic coefficient `h0` of the ODE model (unused by the PDE).
    pub h0: f64,
    pub scheme: SchemeKind,
    /// Grid points per side.
    pub n: usize,
    /// Time step: the fixed step, or the first step when `tol > 0`.
    pub dt: f64,
    /// Adaptive stepping (spectral scheme): the largest accepted embedded error estimate per
    /// step, in the units of `vx, vy, a2, b2` ([`crate::stepping::step_control`]). `0` = fixed step `dt`
    /// (also for records written before adaptive stepping existed).
    #[serde(default)]
    pub tol: f64,
    /// Largest step the adaptive controller may take.
    #[serde(default)]
    pub dt_max: f64,
    /// Give up (status `t_max`) at this time.
    pub t_max: f64,
    /// Steady when the max change of `vx, vy, a2, b2` over one window is below this.
    pub steady_tol: f64,
    /// Window of the steady-state test, in time units (paper: 0.1).
    pub steady_window: f64,
    /// Hold the centre fixed (deformation-only runs).
    pub pinned: bool,
    /// How a run decides it is steady: the paper's test, or the Newton finish
    /// ([`crate::runs::finish`]). Records written before it existed used the test; a run
    /// with the test has the run key it had before.
    #[serde(default, skip_serializing_if = "SteadyMethod::is_test")]
    pub steady: SteadyMethod,
    /// With the Newton finish: end a run beside an unstable steady state as soon as its
    /// largest growth rate shows it cannot leave before `t_max` (status `saddle`, see
    /// [`crate::runs::finish::LEAVE`]) instead of creeping there. Off in records written
    /// before it existed; a run without it has the run key it had before.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub stop_beside_saddle: bool,
    /// With the Newton finish: leap along the linear stretch of a departure from an unstable
    /// steady state instead of stepping through it ([`crate::runs::leap`]). Off in
    /// records written before it existed; a run without it has the run key it had before.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub leap_departures: bool,
    /// With the Newton finish: end a slow run on the stable root its one-dimensional
    /// quasi-steady flow lands on ([`crate::runs::landing`]), once that root is certain, instead of
    /// creeping there (`ended_by`: `steady_by_landing`). On by default (numerics 4); off
    /// reproduces plain time stepping.
    #[serde(default = "on")]
    pub landing: bool,
    /// With the Newton finish (2-mode runs): end a run that leans from a root stable in
    /// rotation on that root only if the orientation's slow flow turns it back there, and
    /// turn a run leaning from a root unstable in rotation to where that flow takes it
    /// ([`crate::runs::rotation_flow`]): the box's anisotropy can put roots of the flow
    /// between a mirror line and the run. On by default (numerics 8); off gives numerics 7's
    /// runs.
    #[serde(default = "on")]
    pub orientation_flow: bool,
    /// With the Newton finish: a run that has not ended on a stable state by `t_max` runs on,
    /// up to [`RUN_ON_FAR`] times `t_max` (adaptive steps, numerics 6; [`RUN_ON`] times with
    /// fixed steps), before it is given up as unsettled (its `t_end` says how long it ran).
    /// On by default (numerics 4); off gives up at `t_max`, as the paper.
    #[serde(default = "on")]
    pub run_on: bool,
    /// Adaptive spectral runs: move on along a slow phase by projective steps, the chord of
    /// the last step continued over up to 20 steps' time once 8 steps of one size in a row
    /// show the fast parts decayed, its error kept below `tol` and every unknown's slope
    /// changing by at most a tenth
    /// ([`crate::runs::projection`], numerics 12 and `modes-17`). On by default; off steps
    /// every step. Not written into a run's key when on (keys of runs that do not read it are
    /// those they had before it existed).
    #[serde(default = "on", skip_serializing_if = "is_on")]
    pub projective_steps: bool,
}

/// How far past `t_max` a run not yet on a stable state runs on with its own steps (setting
/// `run_on`).
pub const RUN_ON: f64 = 4.0;

/// How far past `t_max` an adaptive run not yet on a stable state runs on (setting `run_on`,
/// numerics 6), with its own steps. The runs that need it are turning or leaving a saddle at
/// rates of 1e-4 or less; in the Fig. 2a map the last one ends at t = 100 814
/// (docs/classification.md, "Running on"). Fixed-step runs stop at [`RUN_ON`] `t_max`.
pub const RUN_ON_FAR: f64 = 64.0;

fn on() -> bool {
    true
}

fn is_on(flag: &bool) -> bool {
    *flag
}

/// Default adaptive tolerance, chosen with `droplet bench` (results/bench): at N = 192 the
/// steady errors equal the fixed-step ones (the fixed point is exact) at 11-15x fewer wall
/// seconds than dt = 0.02; the time series' error (t <= 20) is 3.6e-3 against 1.8e-3 at
/// dt = 0.02 (use 1e-5 for 1.0e-3).
pub const DEFAULT_TOL: f64 = 1e-4;
/// Default step cap: larger steps relax slow modes at the wrong rate (dt_max = 1 left an ID
/// droplet drifting at v = 1e-3 when the steady test fired; see results/bench).
pub const DEFAULT_DT_MAX: f64 = 0.25;

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            model: ModelKind::Pde,
            h0: H0_PAPER,
            scheme: SchemeKind::Spectral,
            n: 192,
            dt: 0.02,
            tol: DEFAULT_TOL,
            dt_max: DEFAULT_DT_MAX,
            t_max: 2000.0,
            steady_tol: 1e-6,
            steady_window: 0.1,
            pinned: false,
            steady: SteadyMethod::default_for_runs(),
            stop_beside_saddle: false,
            leap_departures: false,
            landing: true,
            orientation_flow: true,
            run_on: true,
            projective_steps: true,
        }
    }
}

impl SolverSettings {
    /// The paper's own discretisation: dx = 0.025 on L = 7 (N = 280), dt = 1e-4.
    pub fn paper_fd() -> Self {
        Self {
            scheme: SchemeKind::PaperFd,
            n: 280,
            dt: 1e-4,
            tol: 0.0,
            steady: SteadyMethod::Test,
            ..Self::default()
        }
    }

    /// The reduced ODE model: RK4 with dt = 0.05 (error far below the steady tolerance).
    pub fn ode() -> Self {
        Self {
            model: ModelKind::Ode,
            dt: 0.05,
            tol: 0.0,
            steady: SteadyMethod::Test,
            ..Self::default()
        }
    }

    /// The time at which a run not yet steady is given up: `t_max`; with `run_on` and the
    /// Newton finish, [`RUN_ON_FAR`] times it (adaptive steps) or [`RUN_ON`] times it (fixed
    /// steps), for every number of shape modes.
    pub fn give_up_at(&self) -> f64 {
        let runs_on = self.run_on && self.steady == SteadyMethod::Newton;
        match (runs_on, self.adaptive()) {
            (true, true) => RUN_ON_FAR * self.t_max,
            (true, false) => RUN_ON * self.t_max,
            (false, _) => self.t_max,
        }
    }

    /// Adaptive step control is on.
    pub fn adaptive(&self) -> bool {
        self.tol > 0.0
    }

    /// Step counts: `t_max / dt` (fixed steps) or `t_max / dt_max` (the fewest adaptive
    /// steps) at most [`MAX_STEPS`] (also for the ODE model).
    pub fn check_steps(&self) -> Result<(), SolverError> {
        let fixed_steps = self.give_up_at() / self.dt;
        require(
            self.adaptive() || fixed_steps <= MAX_STEPS,
            "dt",
            self.dt,
            format!(
                "a step giving at most {MAX_STEPS:e} steps to t = {} (t_max, run on to {RUN_ON} t_max unless run_on is off; this one gives {fixed_steps:.3e}); raise dt or lower t_max",
                self.give_up_at()
            ),
        )?;
        let fewest = self.give_up_at() / self.dt_max;
        require(
            !self.adaptive() || fewest <= MAX_STEPS,
            "dt_max",
            self.dt_max,
            format!(
                "a largest step giving at most {MAX_STEPS:e} steps to t = {} (t_max, run on to {RUN_ON_FAR} t_max unless run_on is off; this one needs at least {fewest:.3e}); raise dt_max or lower t_max",
                self.give_up_at()
            ),
        )
    }

    pub fn validate(&self) -> Result<(), SolverError> {
        require(self.dt > 0.0, "dt", self.dt, "a finite number > 0")?;
        require(
            self.t_max >= self.dt,
            "t_max",
            self.t_max,
            format!("a finite number >= dt = {}", self.dt),
        )?;
        require(
            self.tol >= 0.0,
            "tol",
            self.tol,
            "a finite number >= 0 (0 = fixed step)",
        )?;
        require(
            self.dt_max >= self.dt || !self.adaptive(),
            "dt_max",
            self.dt_max,
            "a finite number >= dt (the first adaptive step)",
        )?;
        if self.adaptive() && (self.model != ModelKind::Pde || self.scheme != SchemeKind::Spectral)
        {
            return Err(SolverError::InvalidParameter {
                name: "tol",
                value: self.tol,
                allowed: "0 (fixed step): adaptive stepping needs the spectral PDE scheme".into(),
            });
        }
        require(
            self.steady_tol > 0.0,
            "steady_tol",
            self.steady_tol,
            "a finite number > 0",
        )?;
        require(
            self.steady_window >= self.dt,
            "steady_window",
            self.steady_window,
            "a finite number >= dt",
        )?;
        crate::model::grid::check_n(self.n)?;
        require(self.h0 > 0.0, "h0", self.h0, "a finite number > 0")?;
        if self.steady == SteadyMethod::Newton
            && (self.model != ModelKind::Pde || self.scheme != SchemeKind::Spectral || self.pinned)
        {
            return Err(SolverError::InvalidChoice {
                name: "steady",
                value: "newton".into(),
                allowed:
                    "test: the Newton finish needs the spectral PDE scheme with a free droplet"
                        .into(),
            });
        }
        if self.stop_beside_saddle && self.steady != SteadyMethod::Newton {
            return Err(SolverError::InvalidChoice {
                name: "stop_beside_saddle",
                value: "true".into(),
                allowed:
                    "only with steady = newton (the stop uses the Newton finish's growth rates)"
                        .into(),
            });
        }
        if self.leap_departures && (self.steady != SteadyMethod::Newton || !self.adaptive()) {
            return Err(SolverError::InvalidChoice {
                name: "leap_departures",
                value: "true".into(),
                allowed: "only with steady = newton and adaptive steps (tol > 0): the leap uses the Newton finish's roots and growth rates"
                    .into(),
            });
        }
        self.check_steps()
    }
}
