//! How a run ended and what it recorded: status, final state and class, step counts, the
//! optional time series.
use crate::contract::settings::SolverSettings;
use crate::model::classify::StateClass;
use crate::model::state::DropletState;
use serde::{Deserialize, Serialize};

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RunStatus {
    /// The paper's steady-state test was met.
    Steady,
    /// `t_max` was reached first.
    TMax,
    /// A value became non-finite, or the boundary reached the centre (outside the
    /// small-deformation model; `s >= 1` with two modes, [`crate::contract::stop_rule`]).
    Diverged,
    /// The adaptive controller took [`crate::contract::limits::adaptive_step_cap`] steps before `t_max`
    /// (steps far below `dt_max` throughout): ended instead of running for ever.
    StepLimit,
    /// Stopped beside an unstable steady state (a saddle) that its largest growth rate shows
    /// it cannot leave before `t_max` (setting `stop_beside_saddle`): the outcome a `t_max`
    /// run beside it would have, without the wait.
    Saddle,
}

impl RunStatus {
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::Steady => "steady",
            Self::TMax => "t_max",
            Self::Diverged => "diverged",
            Self::StepLimit => "step_limit",
            Self::Saddle => "saddle",
        }
    }

    /// The run stopped without finishing: `t_max`, `step_limit` or `saddle`.
    pub fn unfinished(&self) -> bool {
        matches!(self, Self::TMax | Self::StepLimit | Self::Saddle)
    }
}

/// Why a run did not end on a stable steady state (the `unsettled` column; `None` for a
/// steady run). Such a run has no class: where it stopped is its status, `t_end` and state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Unsettled {
    /// Beside an unstable steady state (a saddle) that it had not left.
    BesideSaddle,
    /// A stable steady state is near, and the run had not reached it.
    Converging,
    /// Speed and deformation are those of a stable steady state, only the direction of
    /// motion / long axis still turns (the box's slow rotation mode).
    Turning,
    /// Newton finds no steady state near the final state.
    NoRoot,
    /// Not diagnosed (the paper's scheme, pinned runs, the paper's steady test alone).
    NotDiagnosed,
    /// Left the model: a non-finite value, or a boundary that reaches the centre.
    Diverged,
}

impl Unsettled {
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::BesideSaddle => "beside_saddle",
            Self::Converging => "converging",
            Self::Turning => "turning",
            Self::NoRoot => "no_root",
            Self::NotDiagnosed => "not_diagnosed",
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
    pub(crate) fn at(t: f64, st: &DropletState) -> Self {
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
    /// Class of the stable steady state the run ended on: `Some` only for a `steady` run
    /// (numerics 4; before, `t_max` runs carried the class of where they stopped).
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
    /// What ended a steady run (`None` otherwise, and in records from before it existed).
    #[serde(default)]
    pub ended_by: Option<crate::contract::ending::Ending>,
    /// For a run that did not finish (`t_max`, `step_limit`, `saddle`): what the steady equations say
    /// near its final state (see [`crate::contract::ending::Finding::describe`]).
    #[serde(default)]
    pub diagnosis: Option<String>,
    /// Time leapt along departures from unstable steady states (setting `leap_departures`,
    /// [`crate::runs::leap`]): part of `t_end`, not stepped. 0 in records from before it.
    #[serde(default)]
    pub t_leapt: f64,
    /// Time moved on by projective steps along slow phases (setting `projective_steps`,
    /// [`crate::runs::projection`]): part of `t_end`, not stepped. 0 in records from before it.
    #[serde(default)]
    pub t_projected: f64,
    /// Why the run did not end on a stable steady state (`None` for a steady run).
    #[serde(default)]
    pub unsettled: Option<Unsettled>,
    /// For an unsettled run: the class of the stable steady state it was heading to, when
    /// Newton or the run's slow flow ([`crate::runs::landing`]) names one.
    #[serde(default)]
    pub heading: Option<StateClass>,
    /// A `K`-mode run's higher shape amplitudes at its end, `a_3..a_K` then `b_3..b_K`
    /// (the model parameter `modes`; empty for the paper's 2-mode runs).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub higher_modes: Vec<f64>,
    /// Recorded time series (empty unless asked for).
    pub series: Vec<SeriesRow>,
    /// A recorded `K`-mode run's higher amplitudes `a_3..a_K, b_3..b_K` at each row of
    /// `series` (empty for 2-mode runs and unrecorded ones).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub higher_series: Vec<Vec<f64>>,
    /// Where the run's time went ([`crate::contract::profile`]): measured, not part of its
    /// result, so never stored.
    #[serde(skip)]
    pub profile: crate::contract::profile::RunProfile,
}

/// A fixed-step run whose largest embedded error estimate per step exceeds this took steps
/// too large to trust (a 1 % change per step in `v`, `a2` or `b2` from the step alone).
pub const STEP_ERROR_LIMIT: f64 = 1e-2;

impl RunOutcome {
    /// The co-moving unknowns of the end state, `(vx, vy, a_2..a_K, b_2..b_K)` (for the
    /// paper's 2-mode runs `(vx, vy, a2, b2)`).
    pub fn unknowns(&self) -> Vec<f64> {
        let (a, b) = self.higher_modes.split_at(self.higher_modes.len() / 2);
        let st = &self.state;
        let mut z = vec![st.vx, st.vy, st.a2];
        z.extend(a);
        z.push(st.b2);
        z.extend(b);
        z
    }

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

    /// The run ended on a stable steady state (for `steady: newton` runs; with the paper's
    /// test alone, on a state the test accepted) and has a class.
    pub fn settled(&self) -> bool {
        self.status == RunStatus::Steady
    }
}
