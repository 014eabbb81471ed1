//! The run driver, one for every number of shape modes: integrate from an initial condition
//! until the steady state, `t_max`, or divergence (paper Sect. 3 stop rule,
//! [`crate::contract::stop_rule`]), recording a time series when asked.
//!
//! The scheme is chosen once per run ([`Run::new`]): for two shape modes the 2-mode fast paths
//! (the co-moving ETD2RK with the droplet's point symmetry, or the paper's scheme), for
//! modes `2..K` the general ones ([`crate::stepping::comoving_etd::ComovingEtd`],
//! [`crate::stepping::paper_fd::PaperFd`]). What a run watches for its end is chosen with it:
//! a 2-mode run the change of `(vx, vy, a2, b2)` over the paper's window of 0.1, a `K`-mode
//! run the largest rate `|dz/dt|` its scheme measures (the Newton finish is tried once that is
//! below [`crate::runs::finish::TRIGGER_FACTOR`] steady tolerances; the paper's test fires
//! below one). The landing, the saddle stop and the leap act at every `K`; the orientation
//! flow is off for `K > 2` ([`crate::contract::honoured`] and the finish).
use crate::contract::ending::{Ending, SteadyMethod};
use crate::contract::outcome::{RunOutcome, RunStatus, Unsettled};
use crate::contract::profile::{self, Part};
use crate::contract::settings::{ModelKind, SolverSettings};
use crate::contract::stop_rule::{diverged, SteadyTest};
use crate::error::SolverError;
use crate::model::classify::StateClass;
use crate::model::initial::InitialCondition;
use crate::model::modes::Modes;
use crate::model::params::ModelParams;
use crate::model::state::{four, largest_magnitude, DropletState};
use crate::roots::verdict::{rotation_generator, ROTATION_MIN_NORM};
use crate::runs::clock::{Clock, Recorder, Step};
use crate::runs::finding::Diagnosis;
use crate::runs::finish::{Decision, NewtonFinish};
use crate::runs::leap::Leap;
use crate::runs::projection::Projection;
use crate::stepping::comoving_etd::ComovingEtd;
use crate::stepping::paper_fd::PaperFd;
use crate::stepping::{comoving_etd::TwoModeEtd, paper_fd::TwoModeFd, Scheme, SchemeKind};
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
        ic.check_modes(params.modes)?;
        let (st, n) = (ic.state(), settings.n);
        let scheme: Box<dyn Scheme> = match (settings.scheme, params.modes) {
            (SchemeKind::Spectral, 2) => {
                Box::new(TwoModeEtd::new(*params, n, st, settings.pinned)?)
            }
            (SchemeKind::PaperFd, 2) => Box::new(TwoModeFd::new(*params, n, st, settings.pinned)?),
            (SchemeKind::Spectral, k) => Box::new(ComovingEtd::new(params, n, &ic.unknowns(k))?),
            (SchemeKind::PaperFd, k) => Box::new(PaperFd::new(params, n, &ic.unknowns(k))?),
        };
        Ok(Self {
            params: *params,
            scheme,
            settings: *settings,
            record_every: None,
        })
    }

    /// Records `(t, x, y, vx, vy, a2, b2, v, s)` (and `a_3..a_K, b_3..b_K`) every `interval`
    /// time units.
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
        profile::start();
        let cfg = self.settings;
        let mut clock = Clock::new(&cfg);
        let start = self.scheme.unknowns();
        let at = self.scheme.state();
        let higher = DropletState::of_unknowns(&start, at.x, at.y).1;
        let mut rec = Recorder::new(self.record_every, (&at, higher), clock.slack);
        let mut watch = Watch::new(&cfg, &start);
        // The Newton finish needs the linearisation, which needs inertia: an overdamped
        // droplet (m = 0) is finished by the paper's test.
        let mut finish = (cfg.steady == SteadyMethod::Newton && self.params.mass > 0.0)
            .then(|| NewtonFinish::new(&self.params, &cfg).starting_at(&start));
        let mut end = End::default();
        let mut projection = Projection::for_run(&cfg, self.params.modes);
        loop {
            match clock.step(self.scheme.as_mut(), &cfg, rec.next) {
                Step::Taken => {}
                Step::Retry => continue,
                Step::Stop(status) => {
                    end.status = status;
                    break;
                }
            }
            let z = self.project(projection.as_mut(), &mut clock, rec.next, finish.as_ref());
            let st = self.scheme.state();
            if diverged(st.monitored(), &[st.x, st.y])
                || !z.iter().all(|x| x.is_finite())
                // With mode 2 alone that is `diverged`'s `s >= 1`.
                || (z.len() > 6 && Modes::of_state(&z).reaches_centre())
            {
                end.status = RunStatus::Diverged;
                break;
            }
            rec.sample(clock.t, || DropletState::of_unknowns(&z, st.x, st.y));
            let Some(change) = watch.judge(clock.t, &z, self.scheme.as_mut()) else {
                continue;
            };
            if !change.test.is_finite() {
                end.status = RunStatus::Diverged;
                break;
            }
            let fired = change.test < cfg.steady_tol;
            let decision = match finish.as_mut() {
                None if fired => Decision::End(Ending::Test, z),
                None => Decision::Continue,
                Some(f) => f.consider(clock.t, &z, (change.test, change.finish), fired),
            };
            match decision {
                Decision::Continue => {}
                Decision::End(ending, z) => {
                    end.status = RunStatus::Steady;
                    end.t_steady = Some(clock.t);
                    end.ended_by = Some(ending);
                    end.polished = finish.is_some().then_some(z);
                    break;
                }
                Decision::Saddle(diagnosis) => {
                    end.status = RunStatus::Saddle;
                    end.saddle_diagnosis = Some(diagnosis);
                    break;
                }
                // Leaps only in adaptive runs (a fixed-step run's time is its step count).
                Decision::Leap(leap) if cfg.adaptive() => {
                    if self.leap(&leap, finish.as_mut(), &st, projection.as_mut()) {
                        clock.t += leap.duration;
                        end.t_leapt += leap.duration;
                        let st = self.scheme.state();
                        watch = Watch::new_at(&cfg, clock.t, &self.scheme.unknowns());
                        rec.after_leap(clock.t, &st);
                    }
                }
                Decision::Leap(_) => {}
            }
        }
        self.outcome(clock, rec, end, finish, started)
    }

    /// A projective step after the step just taken ([`Projection::after_step`]), up to the
    /// run's next recording time, Newton try or end, whichever comes first; the unknowns
    /// after it.
    fn project(
        &mut self,
        p: Option<&mut Projection>,
        clock: &mut Clock,
        next_record: Option<f64>,
        finish: Option<&NewtonFinish>,
    ) -> Vec<f64> {
        let z = self.scheme.unknowns();
        let Some(p) = p else { return z };
        let mut limit = clock.give_up - clock.t;
        if let Some(next) = next_record {
            limit = limit.min(next - clock.t);
        }
        if let Some(f) = finish.filter(|f| f.next_try > clock.t) {
            limit = limit.min(f.next_try - clock.t);
        }
        match p.after_step(self.scheme.as_mut(), clock.last_h, &z, limit) {
            Some(d) => {
                clock.t += d;
                clock.projected += d;
                self.scheme.unknowns()
            }
            None => z,
        }
    }

    /// Moves the run at `st` along the leap (its field and unknowns towards the saddle's, its
    /// centre by the leap's shift); whether it did (the saddle's field known, the scheme able).
    /// The projective steps, if any, start counting again after it.
    fn leap(
        &mut self,
        leap: &Leap,
        finish: Option<&mut NewtonFinish>,
        st: &DropletState,
        projection: Option<&mut Projection>,
    ) -> bool {
        let _timed = profile::enter(Part::Leap);
        let leapt = finish
            .and_then(|f| f.root_field(&leap.root).ok())
            .is_some_and(|field| {
                let shift = leap.shift(st.vx, st.vy);
                self.scheme.leap(&leap.root, &field, leap.factor(), shift)
            });
        if let (true, Some(p)) = (leapt, projection) {
            p.reset();
        }
        leapt
    }

    /// The outcome of a run that stopped: the final state (the root, if the Newton finish
    /// ended it), its class if it ended steady, else why it did not settle.
    fn outcome(
        &self,
        clock: Clock,
        rec: Recorder,
        end: End,
        mut finish: Option<NewtonFinish>,
        started: Instant,
    ) -> RunOutcome {
        // The series ends with the time-stepped state; the outcome, with the root if the
        // Newton finish ended the run.
        let stepped = self.scheme.unknowns();
        let at = self.scheme.state();
        let (series, higher_series) = rec.finish(
            clock.t,
            (&at, DropletState::of_unknowns(&stepped, at.x, at.y).1),
        );
        let z = end.polished.unwrap_or(stepped);
        let (state, higher_modes) = DropletState::of_unknowns(&z, at.x, at.y);
        let status = end.status;
        let found = match status {
            RunStatus::Steady => None,
            RunStatus::Diverged => Some(Diagnosis {
                text: "left the model (a non-finite value, or a boundary f(theta) that reaches the centre: s >= 1 with two modes)".into(),
                reason: Unsettled::Diverged,
                heading: None,
            }),
            RunStatus::Saddle => Some(Diagnosis {
                text: end.saddle_diagnosis.unwrap_or_default(),
                reason: Unsettled::BesideSaddle,
                heading: None,
            }),
            RunStatus::TMax | RunStatus::StepLimit => Some(self.diagnose(finish.as_mut(), &z)),
        };
        let (v, s) = (state.speed(), state.deformation());
        let diagnosis = found
            .as_ref()
            .filter(|d| d.reason != Unsettled::Diverged)
            .map(|d| d.text.clone());
        RunOutcome {
            status,
            // Only a run that ended on a stable steady state has a class.
            class: (status == RunStatus::Steady).then(|| StateClass::of(v, s)),
            state,
            v,
            s,
            t_end: clock.t,
            t_steady: end.t_steady,
            steps: clock.steps,
            rejected: clock.rejected,
            max_step_error: clock.max_step_error,
            wall_s: started.elapsed().as_secs_f64(),
            ended_by: end.ended_by,
            diagnosis,
            t_leapt: end.t_leapt,
            t_projected: clock.projected,
            unsettled: found.as_ref().map(|d| d.reason),
            heading: found.and_then(|d| d.heading),
            higher_modes,
            series,
            higher_series,
            profile: profile::finish(),
        }
    }

    /// Why a run did not finish: what a Newton try from its final state `z` finds (spectral
    /// runs only; one try, about 0.1 s at N = 192 with two modes).
    fn diagnose(&self, finish: Option<&mut NewtonFinish>, z: &[f64]) -> Diagnosis {
        let _timed = profile::enter(Part::Diagnosis);
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

/// What a run watches for its end (see the module).
enum Watch {
    /// The change of `(vx, vy, a2, b2)` over the paper's window (2-mode runs).
    Window(SteadyTest),
    /// The rates `dz/dt` the scheme measures (`K > 2`).
    Rate,
}

/// A run's change as its watch measures it.
struct Change {
    /// What the paper's test compares with the steady tolerance: the change over the window,
    /// or the largest rate `|dz/dt|`.
    test: f64,
    /// What the Newton finish is tried and judged by: the same, but for a `K`-mode run the
    /// largest rate left when the part along the rotation generator is taken out (a run
    /// whose speed and shape have settled and that only turns, at the box's slow rotation
    /// rate, is tried as a 2-mode run is; its rate across the turn, `v dphi/dt`, stays above
    /// the trigger for the thousands of time units the turn takes).
    finish: f64,
}

impl Watch {
    /// The watch of a run from the state `z` at `t` (its shape modes those of `z`).
    fn new_at(cfg: &SolverSettings, t: f64, z: &[f64]) -> Self {
        if z.len() == 4 {
            Watch::Window(SteadyTest::new(cfg, t, four(z)))
        } else {
            Watch::Rate
        }
    }

    fn new(cfg: &SolverSettings, z: &[f64]) -> Self {
        Self::new_at(cfg, 0.0, z)
    }

    /// The run's change now (`None` while the window has not passed), scaled to the steady
    /// tolerance's meaning: per window of 0.1, or per unit time (a rate).
    fn judge(&mut self, t: f64, z: &[f64], scheme: &mut dyn Scheme) -> Option<Change> {
        match self {
            Watch::Window(test) => test
                .judge(t, four(z))
                .map(|c| Change { test: c, finish: c }),
            Watch::Rate => {
                let _timed = profile::enter(Part::Stepping);
                // NaN (the run left the model) if the scheme measured none.
                let Some(rates) = scheme.rates() else {
                    return Some(Change {
                        test: f64::NAN,
                        finish: f64::NAN,
                    });
                };
                // NaN (a rate of a run that left the model) is kept.
                let largest = |r: &[f64]| largest_magnitude(r.iter().copied());
                let g = rotation_generator(z);
                let gg: f64 = g.iter().map(|x| x * x).sum();
                let across = if gg.sqrt() > ROTATION_MIN_NORM {
                    let along = rates.iter().zip(&g).map(|(r, g)| r * g).sum::<f64>() / gg;
                    let rest: Vec<f64> = rates.iter().zip(&g).map(|(r, g)| r - along * g).collect();
                    largest(&rest)
                } else {
                    largest(&rates)
                };
                Some(Change {
                    test: largest(&rates),
                    finish: across,
                })
            }
        }
    }
}

/// How a run's time loop ended.
struct End {
    status: RunStatus,
    t_steady: Option<f64>,
    ended_by: Option<Ending>,
    /// The root the Newton finish ended the run at.
    polished: Option<Vec<f64>>,
    saddle_diagnosis: Option<String>,
    t_leapt: f64,
}

impl Default for End {
    fn default() -> Self {
        Self {
            status: RunStatus::TMax,
            t_steady: None,
            ended_by: None,
            polished: None,
            saddle_diagnosis: None,
            t_leapt: 0.0,
        }
    }
}

/// Runs `params` from `ic` with `settings` to the end.
pub fn simulate(
    params: &ModelParams,
    ic: &InitialCondition,
    settings: &SolverSettings,
) -> Result<RunOutcome, SolverError> {
    ic.check_modes(params.modes)?;
    match settings.model {
        ModelKind::Pde => Ok(Run::new(params, ic, settings)?.execute()),
        ModelKind::Ode => crate::reduced::ode::simulate(params, ic, settings),
    }
}
