//! The run driver: integrate from an initial condition until the steady state, `t_max`, or
//! divergence (paper Sect. 3 stop rule, [`crate::contract::stop_rule`]), recording a time series when
//! asked.
use crate::contract::ending::{Ending, SteadyMethod};
use crate::contract::outcome::{RunOutcome, RunStatus, SeriesRow, Unsettled};
use crate::contract::settings::{ModelKind, SolverSettings};
use crate::contract::stop_rule::{diverged, SteadyTest};
use crate::error::SolverError;
use crate::model::classify::StateClass;
use crate::model::initial::InitialCondition;
use crate::model::params::ModelParams;
use crate::runs::finding::Diagnosis;
use crate::runs::finish::{Decision, NewtonFinish};
use crate::stepping::step_control::PiController;
use crate::stepping::{comoving_etd::ComovingEtd, paper_fd::PaperFd, Scheme, SchemeKind};
use std::time::Instant;

/// A run in progress: the scheme plus the stop rules.
pub struct Run {
    params: ModelParams,
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
        crate::contract::limits::check_run(params, settings)?;
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
            params: *params,
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
        // A run that has not ended on a stable state by t_max runs on (setting `run_on`).
        let give_up = cfg.give_up_at();
        let max_steps = (give_up / cfg.dt).round() as u64;
        let step_cap = crate::contract::limits::adaptive_step_cap(&cfg);
        // Times within `slack` of a target count as reaching it (round-off of sums of steps).
        let slack = 1e-9 * cfg.dt;
        let mut controller = PiController::new(cfg.dt_max);
        let mut h = cfg.dt;
        let mut series = Vec::new();
        let start = self.scheme.state();
        let mut steady_test = SteadyTest::new(&cfg, 0.0, start.monitored());
        let mut next_record = self.record_every;
        if next_record.is_some() {
            series.push(SeriesRow::at(0.0, &start));
        }
        let (mut t, mut steps, mut rejected) = (0.0, 0u64, 0u64);
        let mut max_step_error: Option<f64> = None;
        let mut status = RunStatus::TMax;
        let mut t_steady = None;
        // The Newton finish needs the linearisation, which needs inertia: an overdamped
        // droplet (m = 0) is finished by the paper's test.
        let mut finish = (cfg.steady == SteadyMethod::Newton && self.params.mass > 0.0)
            .then(|| NewtonFinish::new(&self.params, &cfg));
        let mut ended_by = None;
        let mut polished: Option<[f64; 4]> = None;
        let mut saddle_diagnosis = None;
        let mut t_leapt = 0.0;
        loop {
            if adaptive {
                if t >= give_up - slack {
                    break;
                }
                if steps >= step_cap {
                    status = RunStatus::StepLimit;
                    break;
                }
                let mut h_try = h.min(give_up - t);
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
            if diverged(st.monitored(), &[st.x, st.y]) {
                status = RunStatus::Diverged;
                break;
            }
            if let (Some(tr), Some(every)) = (next_record, self.record_every) {
                if t >= tr - slack {
                    series.push(SeriesRow::at(t, &st));
                    next_record = Some(tr + every);
                }
            }
            let Some(change) = steady_test.judge(t, st.monitored()) else {
                continue;
            };
            let fired = change < cfg.steady_tol;
            let decision = match finish.as_mut() {
                None if fired => Decision::End(Ending::Test, st.monitored()),
                None => Decision::Continue,
                Some(f) => f.consider(t, st.monitored(), change, fired),
            };
            match decision {
                Decision::Continue => {}
                Decision::End(ending, z) => {
                    status = RunStatus::Steady;
                    t_steady = Some(t);
                    ended_by = Some(ending);
                    if finish.is_some() {
                        polished = Some(z);
                    }
                    break;
                }
                Decision::Saddle(diagnosis) => {
                    status = RunStatus::Saddle;
                    saddle_diagnosis = Some(diagnosis);
                    break;
                }
                // Leaps only in adaptive runs (a fixed-step run's time is its step count).
                Decision::Leap(leap) if adaptive => {
                    let leapt = finish
                        .as_mut()
                        .and_then(|f| f.root_field(leap.root).ok())
                        .is_some_and(|field| {
                            let shift = leap.shift(st.vx, st.vy);
                            self.scheme.leap(leap.root, &field, leap.factor(), shift)
                        });
                    if leapt {
                        t += leap.duration;
                        t_leapt += leap.duration;
                        let st = self.scheme.state();
                        steady_test = SteadyTest::new(&cfg, t, st.monitored());
                        if let (Some(tr), Some(every)) = (next_record, self.record_every) {
                            // The series skips the leapt times.
                            series.push(SeriesRow::at(t, &st));
                            if tr <= t {
                                next_record = Some(tr + every * (((t - tr) / every).floor() + 1.0));
                            }
                        }
                    }
                }
                Decision::Leap(_) => {}
            }
        }
        let mut state = self.scheme.state();
        // The series ends with the time-stepped state; the outcome, with the root if the
        // Newton finish ended the run.
        if series.last().is_some_and(|r| r.t < t - slack) {
            series.push(SeriesRow::at(t, &state));
        }
        if let Some([vx, vy, a2, b2]) = polished {
            (state.vx, state.vy, state.a2, state.b2) = (vx, vy, a2, b2);
        }
        let found = match status {
            RunStatus::Steady => None,
            RunStatus::Diverged => Some(Diagnosis {
                text: "left the model (a non-finite value, or s >= 1)".into(),
                reason: Unsettled::Diverged,
                heading: None,
            }),
            RunStatus::Saddle => Some(Diagnosis {
                text: saddle_diagnosis.unwrap_or_default(),
                reason: Unsettled::BesideSaddle,
                heading: None,
            }),
            RunStatus::TMax | RunStatus::StepLimit => {
                Some(self.diagnose(finish.as_mut(), state.monitored()))
            }
        };
        let (v, s) = (state.speed(), state.deformation());
        let diagnosis = found
            .as_ref()
            .filter(|d| d.reason != Unsettled::Diverged)
            .map(|d| d.text.clone());
        RunOutcome {
            status,
            // Only a run that ended on a stable steady state has a class (numerics 4).
            class: (status == RunStatus::Steady).then(|| StateClass::of(v, s)),
            state,
            v,
            s,
            t_end: t,
            t_steady,
            steps,
            rejected,
            max_step_error,
            wall_s: started.elapsed().as_secs_f64(),
            ended_by,
            diagnosis,
            t_leapt,
            unsettled: found.as_ref().map(|d| d.reason),
            heading: found.and_then(|d| d.heading),
            series,
        }
    }

    /// Why a run did not finish: what a Newton try from its final state `z` finds (spectral runs only; one try, about 0.1 s at N = 192).
    fn diagnose(&self, finish: Option<&mut NewtonFinish>, z: [f64; 4]) -> Diagnosis {
        if self.settings.scheme != SchemeKind::Spectral || self.settings.pinned {
            return Diagnosis {
                text: "not diagnosed (the steady equations are the spectral scheme's)".into(),
                reason: Unsettled::NotDiagnosed,
                heading: None,
            };
        }
        let mut own;
        let f = match finish {
            Some(f) => f,
            None => {
                own = NewtonFinish::new(&self.params, &self.settings);
                &mut own
            }
        };
        f.diagnose(z)
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
