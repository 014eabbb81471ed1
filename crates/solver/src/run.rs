//! The run driver: integrate from an initial condition until the steady state, `t_max`, or
//! divergence (paper Sect. 3 stop rule), recording a time series when asked.
use crate::classify::StateClass;
use crate::error::{require, SolverError};
use crate::initial::InitialCondition;
use crate::params::ModelParams;
use crate::scheme::{ComovingEtd, PaperFd, Scheme, SchemeKind};
use crate::state::DropletState;
use crate::step_control::PiController;
use serde::{Deserialize, Serialize};
use std::time::Instant;

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
    /// step, in the units of `vx, vy, a2, b2` ([`crate::step_control`]). `0` = fixed step `dt`
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
            h0: crate::reduced::coefficients::H0_PAPER,
            scheme: SchemeKind::Spectral,
            n: 192,
            dt: 0.02,
            tol: DEFAULT_TOL,
            dt_max: DEFAULT_DT_MAX,
            t_max: 2000.0,
            steady_tol: 1e-6,
            steady_window: 0.1,
            pinned: false,
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
            ..Self::default()
        }
    }

    /// The reduced ODE model: RK4 with dt = 0.05 (error far below the steady tolerance).
    pub fn ode() -> Self {
        Self {
            model: ModelKind::Ode,
            dt: 0.05,
            tol: 0.0,
            ..Self::default()
        }
    }

    /// Adaptive step control is on.
    pub fn adaptive(&self) -> bool {
        self.tol > 0.0
    }

    pub fn validate(&self) -> Result<(), SolverError> {
        require(self.dt > 0.0, "dt", self.dt, "a finite number > 0")?;
        require(self.t_max > 0.0, "t_max", self.t_max, "a finite number > 0")?;
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
        require(
            self.n >= 16 && self.n.is_multiple_of(2),
            "n",
            self.n as f64,
            "an even integer >= 16",
        )?;
        crate::limits::check_steps(self)
    }
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RunStatus {
    /// The paper's steady-state test was met.
    Steady,
    /// `t_max` was reached first.
    TMax,
    /// A value became non-finite, or `s >= 1` (outside the small-deformation model).
    Diverged,
    /// The adaptive controller took [`crate::limits::adaptive_step_cap`] steps before `t_max`
    /// (steps far below `dt_max` throughout): ended instead of running for ever.
    StepLimit,
}

impl RunStatus {
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::Steady => "steady",
            Self::TMax => "t_max",
            Self::Diverged => "diverged",
            Self::StepLimit => "step_limit",
        }
    }
}

/// One row of a time series.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SeriesRow {
    pub t: f64,
    pub x: f64,
    pub y: f64,
    pub vx: f64,
    pub vy: f64,
    pub a2: f64,
    pub b2: f64,
    pub v: f64,
    pub s: f64,
}

impl SeriesRow {
    fn at(t: f64, st: &DropletState) -> Self {
        Self {
            t,
            x: st.x,
            y: st.y,
            vx: st.vx,
            vy: st.vy,
            a2: st.a2,
            b2: st.b2,
            v: st.speed(),
            s: st.deformation(),
        }
    }
}

/// Result of one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunOutcome {
    pub status: RunStatus,
    /// Class of the final state (also for `t_max` runs; `None` when diverged).
    pub class: Option<StateClass>,
    pub state: DropletState,
    pub v: f64,
    pub s: f64,
    pub t_end: f64,
    /// Time at which the steady test was met.
    pub t_steady: Option<f64>,
    /// Accepted steps.
    pub steps: u64,
    /// Refused adaptive steps.
    #[serde(default)]
    pub rejected: u64,
    /// Largest embedded local error estimate of an accepted step (`None`: the scheme has none).
    /// For a fixed step, a value above [`STEP_ERROR_LIMIT`] says `dt` is too large.
    #[serde(default)]
    pub max_step_error: Option<f64>,
    pub wall_s: f64,
    /// Recorded time series (empty unless asked for).
    pub series: Vec<SeriesRow>,
}

/// A fixed-step run whose largest embedded error estimate per step exceeds this took steps
/// too large to trust (a 1 % change per step in `v`, `a2` or `b2` from the step alone).
pub const STEP_ERROR_LIMIT: f64 = 1e-2;

impl RunOutcome {
    /// Why `dt` looks too large for this fixed-step run, if it does (adaptive runs keep the
    /// estimate below their `tol`; schemes without an estimate are not judged).
    pub fn dt_warning(&self, settings: &SolverSettings) -> Option<String> {
        let e = self.max_step_error?;
        (!settings.adaptive() && (e.is_nan() || e > STEP_ERROR_LIMIT)).then(|| {
            format!(
                "dt = {} is too large: the embedded local error estimate reached {e:.2e} per step (limit {STEP_ERROR_LIMIT:e}){}; use a smaller --dt or adaptive stepping (--tol)",
                settings.dt,
                if self.status == RunStatus::Diverged {
                    ", so the divergence is likely numerical"
                } else {
                    ""
                }
            )
        })
    }
}

/// A run in progress: the scheme plus the stop rules.
pub struct Run {
    scheme: Box<dyn Scheme>,
    settings: SolverSettings,
    record_every: Option<f64>,
}

impl Run {
    /// Sets up a run of `params` from `ic` (`u = 0`, `r_c = 0`).
    pub fn new(
        params: &ModelParams,
        ic: &InitialCondition,
        settings: &SolverSettings,
    ) -> Result<Self, SolverError> {
        params.validate()?;
        settings.validate()?;
        crate::limits::check_run(params, settings)?;
        if settings.model != ModelKind::Pde {
            return Err(SolverError::InvalidParameter {
                name: "model",
                value: 1.0,
                allowed: "pde for a field run (ODE runs go through `simulate`)".into(),
            });
        }
        let st = ic.state();
        let scheme: Box<dyn Scheme> = match settings.scheme {
            SchemeKind::Spectral => {
                Box::new(ComovingEtd::new(*params, settings.n, st, settings.pinned)?)
            }
            SchemeKind::PaperFd => {
                Box::new(PaperFd::new(*params, settings.n, st, settings.pinned)?)
            }
        };
        Ok(Self {
            scheme,
            settings: *settings,
            record_every: None,
        })
    }

    /// Records `(t, x, y, vx, vy, a2, b2, v, s)` every `interval` time units.
    pub fn record_every(mut self, interval: Option<f64>) -> Self {
        self.record_every = interval.filter(|i| *i > 0.0 && i.is_finite());
        self
    }

    /// The scheme (for the final field and mass).
    pub fn scheme_mut(&mut self) -> &mut dyn Scheme {
        self.scheme.as_mut()
    }

    /// Integrates until a stop rule fires.
    ///
    /// Fixed step: `dt` throughout. Adaptive (`tol > 0`): steps from the PI controller,
    /// clipped to land on `t_max` and on the recording times. The steady test compares
    /// states at least `steady_window` apart and scales the change to one window
    /// (`change * window / elapsed`), so it keeps the paper's meaning (change per 0.1) for
    /// steps longer than the window.
    pub fn execute(&mut self) -> RunOutcome {
        let started = Instant::now();
        let cfg = self.settings;
        let adaptive = cfg.adaptive();
        let max_steps = (cfg.t_max / cfg.dt).round() as u64;
        let step_cap = crate::limits::adaptive_step_cap(&cfg);
        // Times within `slack` of a target count as reaching it (round-off of sums of steps).
        let slack = 1e-9 * cfg.dt;
        let mut controller = PiController::new(cfg.dt_max);
        let mut h = cfg.dt;
        let mut series = Vec::new();
        let mut checkpoint = (0.0, self.scheme.state());
        let mut next_record = self.record_every;
        if next_record.is_some() {
            series.push(SeriesRow::at(0.0, &checkpoint.1));
        }
        let (mut t, mut steps, mut rejected) = (0.0, 0u64, 0u64);
        let mut max_step_error: Option<f64> = None;
        let mut status = RunStatus::TMax;
        let mut t_steady = None;
        loop {
            if adaptive {
                if t >= cfg.t_max - slack {
                    break;
                }
                if steps >= step_cap {
                    status = RunStatus::StepLimit;
                    break;
                }
                let mut h_try = h.min(cfg.t_max - t);
                if let Some(tr) = next_record {
                    h_try = h_try.min(tr - t);
                }
                let a = self.scheme.attempt(h_try, cfg.tol);
                let err = a.error.unwrap_or(0.0) / cfg.tol;
                if !a.accepted {
                    rejected += 1;
                    h = controller.reject(h_try, err);
                    if h < MIN_STEP {
                        status = RunStatus::Diverged;
                        break;
                    }
                    continue;
                }
                h = controller.accept(h_try, err);
                t += h_try;
                steps += 1;
                max_step_error = larger(max_step_error, a.error);
            } else {
                if steps >= max_steps {
                    break;
                }
                let a = self.scheme.attempt(cfg.dt, f64::INFINITY);
                steps += 1;
                t = steps as f64 * cfg.dt;
                max_step_error = larger(max_step_error, a.error);
            }
            let st = self.scheme.state();
            if !st.is_finite() || st.deformation() >= 1.0 {
                status = RunStatus::Diverged;
                break;
            }
            if let (Some(tr), Some(every)) = (next_record, self.record_every) {
                if t >= tr - slack {
                    series.push(SeriesRow::at(t, &st));
                    next_record = Some(tr + every);
                }
            }
            let elapsed = t - checkpoint.0;
            if elapsed >= cfg.steady_window - slack {
                let change = st
                    .monitored()
                    .iter()
                    .zip(checkpoint.1.monitored())
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max);
                checkpoint = (t, st);
                if change * (cfg.steady_window / elapsed).min(1.0) < cfg.steady_tol {
                    status = RunStatus::Steady;
                    t_steady = Some(t);
                    break;
                }
            }
        }
        let state = self.scheme.state();
        if series.last().is_some_and(|r| r.t < t - slack) {
            series.push(SeriesRow::at(t, &state));
        }
        let (v, s) = (state.speed(), state.deformation());
        RunOutcome {
            status,
            class: (status != RunStatus::Diverged).then(|| StateClass::of(v, s)),
            state,
            v,
            s,
            t_end: t,
            t_steady,
            steps,
            rejected,
            max_step_error,
            wall_s: started.elapsed().as_secs_f64(),
            series,
        }
    }
}

fn larger(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(x), Some(y)) => Some(x.max(y)),
        (x, None) => x,
        (None, y) => y,
    }
}

/// Smallest adaptive step before a run is declared diverged (the error estimate cannot be met).
const MIN_STEP: f64 = 1e-9;

/// Runs `params` from `ic` with `settings` to the end.
pub fn simulate(
    params: &ModelParams,
    ic: &InitialCondition,
    settings: &SolverSettings,
) -> Result<RunOutcome, SolverError> {
    match settings.model {
        ModelKind::Pde => Ok(Run::new(params, ic, settings)?.execute()),
        ModelKind::Ode => crate::reduced::ode::simulate(params, ic, settings),
    }
}
