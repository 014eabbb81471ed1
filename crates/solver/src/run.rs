//! The run driver: integrate from an initial condition until the steady state, `t_max`, or
//! divergence (paper Sect. 3 stop rule), recording a time series when asked.
use crate::classify::StateClass;
use crate::error::{require, SolverError};
use crate::initial::InitialCondition;
use crate::params::ModelParams;
use crate::scheme::{ComovingEtd, PaperFd, Scheme, SchemeKind};
use crate::state::DropletState;
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
    /// Time step.
    pub dt: f64,
    /// Give up (status `t_max`) at this time.
    pub t_max: f64,
    /// Steady when the max change of `vx, vy, a2, b2` over one window is below this.
    pub steady_tol: f64,
    /// Window of the steady-state test, in time units (paper: 0.1).
    pub steady_window: f64,
    /// Hold the centre fixed (deformation-only runs).
    pub pinned: bool,
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            model: ModelKind::Pde,
            h0: crate::reduced::coefficients::H0_PAPER,
            scheme: SchemeKind::Spectral,
            n: 192,
            dt: 0.02,
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
            ..Self::default()
        }
    }

    /// The reduced ODE model: RK4 with dt = 0.05 (error far below the steady tolerance).
    pub fn ode() -> Self {
        Self {
            model: ModelKind::Ode,
            dt: 0.05,
            ..Self::default()
        }
    }

    pub fn validate(&self) -> Result<(), SolverError> {
        require(self.dt > 0.0, "dt", self.dt, "a finite number > 0")?;
        require(self.t_max > 0.0, "t_max", self.t_max, "a finite number > 0")?;
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
        Ok(())
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
}

impl RunStatus {
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::Steady => "steady",
            Self::TMax => "t_max",
            Self::Diverged => "diverged",
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
    pub steps: u64,
    pub wall_s: f64,
    /// Recorded time series (empty unless asked for).
    pub series: Vec<SeriesRow>,
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
        if settings.model != ModelKind::Pde {
            return Err(SolverError::InvalidParameter {
                name: "model",
                value: 1.0,
                allowed: "pde for a field run (ODE runs go through `simulate`)",
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
    pub fn execute(&mut self) -> RunOutcome {
        let started = Instant::now();
        let cfg = self.settings;
        let dt = cfg.dt;
        let steps_per_window = ((cfg.steady_window / dt).round() as u64).max(1);
        let record_steps = self.record_every.map(|i| ((i / dt).round() as u64).max(1));
        let max_steps = (cfg.t_max / dt).round() as u64;
        let mut series = Vec::new();
        let mut last = self.scheme.state();
        if record_steps.is_some() {
            series.push(SeriesRow::at(0.0, &last));
        }
        let mut steps = 0u64;
        let mut status = RunStatus::TMax;
        let mut t_steady = None;
        while steps < max_steps {
            self.scheme.step(dt);
            steps += 1;
            let st = self.scheme.state();
            let t = steps as f64 * dt;
            if !st.is_finite() || st.deformation() >= 1.0 {
                status = RunStatus::Diverged;
                break;
            }
            if let Some(every) = record_steps {
                if steps.is_multiple_of(every) {
                    series.push(SeriesRow::at(t, &st));
                }
            }
            if steps.is_multiple_of(steps_per_window) {
                let change = st
                    .monitored()
                    .iter()
                    .zip(last.monitored())
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max);
                last = st;
                if change < cfg.steady_tol {
                    status = RunStatus::Steady;
                    t_steady = Some(t);
                    break;
                }
            }
        }
        let state = self.scheme.state();
        let t_end = steps as f64 * dt;
        if record_steps.is_some_and(|e| !steps.is_multiple_of(e)) {
            series.push(SeriesRow::at(t_end, &state));
        }
        let (v, s) = (state.speed(), state.deformation());
        RunOutcome {
            status,
            class: (status != RunStatus::Diverged).then(|| StateClass::of(v, s)),
            state,
            v,
            s,
            t_end,
            t_steady,
            steps,
            wall_s: started.elapsed().as_secs_f64(),
            series,
        }
    }
}

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
