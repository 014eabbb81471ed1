//! The time of a run: its steps, fixed (`dt`) or adaptive under the PI controller, the stop
//! on time, on the step cap or on a step too small to meet the error estimate; and its time
//! series, one row every `every` time units (and the state after a leap).
use crate::contract::outcome::{RunStatus, SeriesRow};
use crate::contract::profile::{self, Part};
use crate::contract::settings::SolverSettings;
use crate::model::state::DropletState;
use crate::stepping::step_control::PiController;
use crate::stepping::Stepper;

/// The outcome of one pass of the time loop's stepping.
pub(super) enum Step {
    Taken,
    /// An adaptive step was refused; try again with the smaller step.
    Retry,
    Stop(RunStatus),
}

/// The time of a run and its steps: fixed (`dt`), or adaptive under the PI controller.
pub(super) struct Clock {
    pub(super) adaptive: bool,
    /// A run that has not ended on a stable state by t_max runs on (setting `run_on`).
    pub(super) give_up: f64,
    pub(super) max_steps: u64,
    pub(super) step_cap: u64,
    /// Times within `slack` of a target count as reaching it (round-off of sums of steps).
    pub(super) slack: f64,
    pub(super) controller: PiController,
    pub(super) h: f64,
    /// The last accepted step.
    pub(super) last_h: f64,
    pub(super) t: f64,
    /// The part of `t` moved on by projective steps ([`crate::runs::projection`]).
    pub(super) projected: f64,
    pub(super) steps: u64,
    pub(super) rejected: u64,
    pub(super) max_step_error: Option<f64>,
}

impl Clock {
    pub(super) fn new(cfg: &SolverSettings) -> Self {
        let give_up = cfg.give_up_at();
        Self {
            adaptive: cfg.adaptive(),
            give_up,
            max_steps: (give_up / cfg.dt).round() as u64,
            step_cap: crate::contract::limits::adaptive_step_cap(cfg),
            slack: 1e-9 * cfg.dt,
            controller: PiController::new(cfg.dt_max),
            h: cfg.dt,
            last_h: 0.0,
            t: 0.0,
            projected: 0.0,
            steps: 0,
            rejected: 0,
            max_step_error: None,
        }
    }

    /// One step of `scheme` (of any number of shape modes), landing on `next_record`
    /// (adaptive steps), or why the run stops.
    pub(super) fn step<S: Stepper + ?Sized>(
        &mut self,
        scheme: &mut S,
        cfg: &SolverSettings,
        next_record: Option<f64>,
    ) -> Step {
        let _timed = profile::enter(Part::Stepping);
        if !self.adaptive {
            if self.steps >= self.max_steps {
                return Step::Stop(RunStatus::TMax);
            }
            let a = scheme.attempt(cfg.dt, f64::INFINITY);
            self.steps += 1;
            self.t = self.steps as f64 * cfg.dt;
            self.last_h = cfg.dt;
            self.max_step_error = larger(self.max_step_error, a.error);
            return Step::Taken;
        }
        if self.t >= self.give_up - self.slack {
            return Step::Stop(RunStatus::TMax);
        }
        if self.steps >= self.step_cap {
            return Step::Stop(RunStatus::StepLimit);
        }
        let mut h_try = self.h.min(self.give_up - self.t);
        if let Some(tr) = next_record {
            h_try = h_try.min(tr - self.t);
        }
        let a = scheme.attempt(h_try, cfg.tol);
        let err = a.error.unwrap_or(0.0) / cfg.tol;
        if !a.accepted {
            self.rejected += 1;
            self.h = self.controller.reject(h_try, err);
            if self.h < MIN_STEP {
                return Step::Stop(RunStatus::Diverged);
            }
            return Step::Retry;
        }
        self.h = self.controller.accept(h_try, err);
        self.t += h_try;
        self.last_h = h_try;
        self.steps += 1;
        self.max_step_error = larger(self.max_step_error, a.error);
        Step::Taken
    }
}

/// The time series of a run, one row every `every` time units (if asked): the droplet's
/// `(t, x, y, vx, vy, a2, b2, v, s)` and, with more than two shape modes, its higher
/// amplitudes `a_3..a_K, b_3..b_K` ([`crate::contract::outcome::RunOutcome::higher_series`]).
pub(super) struct Recorder {
    pub(super) every: Option<f64>,
    /// The next recording time.
    pub(super) next: Option<f64>,
    pub(super) slack: f64,
    pub(super) rows: Vec<SeriesRow>,
    pub(super) higher: Vec<Vec<f64>>,
}

impl Recorder {
    pub(super) fn new(every: Option<f64>, start: (&DropletState, Vec<f64>), slack: f64) -> Self {
        let mut rec = Self {
            every,
            next: every,
            slack,
            rows: Vec::new(),
            higher: Vec::new(),
        };
        if every.is_some() {
            rec.push(0.0, start);
        }
        rec
    }

    fn push(&mut self, t: f64, (st, higher): (&DropletState, Vec<f64>)) {
        self.rows.push(SeriesRow::at(t, st));
        if !higher.is_empty() {
            self.higher.push(higher);
        }
    }

    /// Records the droplet (state and higher amplitudes, made only when recorded) if `t`
    /// reached the next recording time.
    pub(super) fn sample(&mut self, t: f64, at: impl FnOnce() -> (DropletState, Vec<f64>)) {
        if let (Some(tr), Some(every)) = (self.next, self.every) {
            if t >= tr - self.slack {
                let (st, higher) = at();
                self.push(t, (&st, higher));
                self.next = Some(tr + every);
            }
        }
    }

    /// After a leap to `t`: the state there, and the next recording time past it (the series
    /// skips the leapt times).
    pub(super) fn after_leap(&mut self, t: f64, st: &DropletState) {
        if let (Some(tr), Some(every)) = (self.next, self.every) {
            self.push(t, (st, Vec::new()));
            if tr <= t {
                self.next = Some(tr + every * (((t - tr) / every).floor() + 1.0));
            }
        }
    }

    /// The series and the higher amplitudes' series, ending with the final droplet at `t`.
    pub(super) fn finish(
        mut self,
        t: f64,
        end: (&DropletState, Vec<f64>),
    ) -> (Vec<SeriesRow>, Vec<Vec<f64>>) {
        if self.rows.last().is_some_and(|r| r.t < t - self.slack) {
            self.push(t, end);
        }
        (self.rows, self.higher)
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
