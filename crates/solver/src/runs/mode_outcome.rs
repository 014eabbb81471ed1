//! A run of the paper's general model with shape modes `2..K` (setting `modes`, `K > 2`) to a
//! [`RunOutcome`], as the sweep runs it, with either scheme:
//!
//! - spectral (default): the ETD2RK stepper of [`crate::runs::mode_run`] on the run's clock
//!   ([`crate::runs::clock`]: adaptive steps under `tol` and `dt_max` as 2-mode runs take
//!   them, or fixed steps `dt` with `tol: 0`), ended by the Newton finish of every `K`
//!   ([`crate::runs::finish::NewtonFinish`], `steady: newton`): once the largest rate
//!   `|dz/dt|` falls below [`crate::runs::finish::TRIGGER_FACTOR`] steady tolerances, Newton
//!   on all `2K` force balances from the run's state; the run ends `steady` on a root whose
//!   `2K x 2K` eigenproblem decays (the near-neutral rotation mode included) when it is on
//!   its way there (speed and deformation, and orientation, as for 2-mode runs), or, if the
//!   root is unstable only in rotation and the run leans from its mirror line, on the first
//!   stable root the turn search finds on the side it leans to. A run given up (`t_max`, run
//!   on as 2-mode runs are) is diagnosed as 2-mode runs are. With `steady: test` the
//!   paper's test alone ends it (every rate below the steady tolerance): pure time stepping.
//! - `paper-fd`: the paper's forward-Euler finite differences ([`crate::stepping::mode_fd`])
//!   at fixed steps `dt` to `t_max`, ended by the test alone (`steady: test`; every rate
//!   below the steady tolerance), as the paper ended its runs; not diagnosed when it does not
//!   settle.
//!
//! The class is the paper's, from `v` and `s = |a2|` (mode 2 alone); the higher amplitudes
//! `a_3..a_K, b_3..b_K` are in [`RunOutcome::higher_modes`]. Not here (refused by
//! [`crate::contract::limits::check_run`], or off in the finish): the landing, the
//! orientation flow, the saddle stop and the leap, which solve the 2-mode balances, and
//! pinned runs. Time series: [`simulate_modes_recorded`].
use crate::contract::ending::{Ending, SteadyMethod};
use crate::contract::outcome::{RunOutcome, RunStatus, SeriesRow, Unsettled};
use crate::contract::profile::{self, Part};
use crate::contract::settings::SolverSettings;
use crate::error::SolverError;
use crate::model::classify::StateClass;
use crate::model::initial::InitialCondition;
use crate::model::params::ModelParams;
use crate::model::state::DropletState;
use crate::runs::clock::{Clock, Step};
use crate::runs::finish::{Decision, NewtonFinish};
use crate::runs::mode_run::ModeStepper;
use crate::stepping::{mode_fd::ModeFd, SchemeKind};
use std::time::Instant;

/// The state `(vx, vy, a_2..a_K, b_2..b_K)` of `ic`: its amplitudes of modes `3..K`
/// ([`InitialCondition::higher`]), 0 for modes it does not give.
pub fn initial_modes(ic: &InitialCondition, k_max: usize) -> Vec<f64> {
    let mode = |k: usize| ic.higher.get(k - 3).copied().unwrap_or([0.0; 2]);
    let mut z = vec![ic.vx, ic.vy, ic.a2];
    z.extend((3..=k_max).map(|k| mode(k)[0]));
    z.push(ic.b2);
    z.extend((3..=k_max).map(|k| mode(k)[1]));
    z
}

/// The `K`-mode state `z = (vx, vy, a_2..a_K, b_2..b_K)` at `(x, y)` as the 2-mode state and
/// the higher amplitudes `a_3..a_K, b_3..b_K`.
fn split(z: &[f64], x: f64, y: f64) -> (DropletState, Vec<f64>) {
    let k = z.len() / 2;
    let state = DropletState {
        x,
        y,
        vx: z[0],
        vy: z[1],
        a2: z[2],
        b2: z[k + 1],
    };
    (
        state,
        z[3..k + 1].iter().chain(&z[k + 2..]).copied().collect(),
    )
}

/// Where a run is: its state `(vx, vy, a_2..a_K, b_2..b_K)`, centre, time and steps taken.
struct Snapshot<'a> {
    z: &'a [f64],
    x: f64,
    y: f64,
    t: f64,
    steps: u64,
}

impl ModeStepper {
    fn snapshot(&self) -> Snapshot<'_> {
        Snapshot {
            z: &self.z,
            x: self.x,
            y: self.y,
            t: self.t,
            steps: self.steps,
        }
    }
}

impl ModeFd {
    fn snapshot(&self) -> Snapshot<'_> {
        Snapshot {
            z: &self.z,
            x: self.x,
            y: self.y,
            t: self.t,
            steps: self.steps,
        }
    }
}

/// Why a run did not settle: the reason, the class of the stable state it heads to, and
/// the diagnosis in words.
type Found = (Option<Unsettled>, Option<StateClass>, Option<String>);

/// The time series of a `K`-mode run: `(t, x, y, vx, vy, a2, b2, v, s)` and the higher
/// amplitudes `a_3..a_K, b_3..b_K` every `every` time units (adaptive steps land on each
/// sample time; fixed steps record the first step at or past it), and the end.
struct ModeRecorder {
    every: f64,
    next: f64,
    rows: Vec<SeriesRow>,
    higher: Vec<Vec<f64>>,
}

impl ModeRecorder {
    fn sample(&mut self, at: &Snapshot, force: bool) {
        if !(force || at.t >= self.next - 1e-9 * self.every) {
            return;
        }
        if self.rows.last().is_some_and(|r| r.t == at.t) {
            return;
        }
        let (state, higher) = split(at.z, at.x, at.y);
        self.rows.push(SeriesRow::at(at.t, &state));
        self.higher.push(higher);
        while self.next <= at.t + 1e-9 * self.every {
            self.next += self.every;
        }
    }
}

/// Runs `params` from `ic` with `settings.modes` shape modes to its outcome.
pub fn simulate_modes(
    params: &ModelParams,
    ic: &InitialCondition,
    settings: &SolverSettings,
) -> Result<RunOutcome, SolverError> {
    simulate_modes_recorded(params, ic, settings, None)
}

/// [`simulate_modes`], recording the time series every `every` time units when given
/// ([`RunOutcome::series`], [`RunOutcome::higher_series`]).
pub fn simulate_modes_recorded(
    params: &ModelParams,
    ic: &InitialCondition,
    settings: &SolverSettings,
    every: Option<f64>,
) -> Result<RunOutcome, SolverError> {
    let started = Instant::now();
    profile::start();
    params.validate()?;
    settings.validate()?;
    crate::contract::limits::check_run(params, settings)?;
    ic.check_modes(settings.modes)?;
    let mut rec = every
        .filter(|e| *e > 0.0 && e.is_finite())
        .map(|every| ModeRecorder {
            every,
            next: 0.0,
            rows: Vec::new(),
            higher: Vec::new(),
        });
    let z0 = initial_modes(ic, settings.modes);
    let mut out = match settings.scheme {
        SchemeKind::Spectral => newton_finished(params, &z0, settings, &mut rec)?,
        SchemeKind::PaperFd => paper_fd(params, &z0, settings, &mut rec)?,
    };
    out.wall_s = started.elapsed().as_secs_f64();
    out.profile = profile::finish();
    if let Some(rec) = rec {
        (out.series, out.higher_series) = (rec.rows, rec.higher);
    }
    Ok(out)
}

/// True when a run at `z` with largest rate `rate` has left the model (a non-finite value,
/// or `s >= 1`).
fn left_model(z: &[f64], rate: f64) -> bool {
    let k = z.len() / 2;
    !rate.is_finite() || z.iter().any(|x| !x.is_finite()) || z[2].hypot(z[k + 1]) >= 1.0
}

/// The spectral run on the clock (adaptive or fixed steps), ended by the Newton finish of
/// every `K` ([`NewtonFinish`]): tried once the largest rate `|dz/dt|` is below
/// [`crate::runs::finish::TRIGGER_FACTOR`] steady tolerances, it ends the run on a stable
/// root the run is on its way to, or on the stable root a leaning run turns to (the turn
/// search), and diagnoses a run given up.
fn newton_finished(
    params: &ModelParams,
    z0: &[f64],
    settings: &SolverSettings,
    rec: &mut Option<ModeRecorder>,
) -> Result<RunOutcome, SolverError> {
    let mut run = ModeStepper::new(params, settings.n, z0)?;
    run.set_eta_k_exponent(settings.eta_k_exponent);
    let mut clock = Clock::new(settings);
    let newton = settings.steady == SteadyMethod::Newton;
    let mut finish = newton.then(|| NewtonFinish::new(params, settings).starting_at(z0));
    let (mut ended_by, mut end_root) = (None, None);
    let status = loop {
        if let Some(rec) = rec.as_mut() {
            rec.sample(&run.snapshot(), false);
        }
        let rate = {
            let _timed = profile::enter(Part::Stepping);
            run.rate()
        };
        if left_model(&run.z, rate) {
            break RunStatus::Diverged;
        }
        // The change per unit time is the rate; the paper's test, every rate below the
        // steady tolerance (with `steady: test` it alone ends the run: pure time stepping).
        let fired = rate < settings.steady_tol && run.t > 0.0;
        let decision = match finish.as_mut() {
            Some(f) => f.consider(run.t, &run.z, rate, fired),
            None if fired => Decision::End(Ending::Test, run.z.clone()),
            None => Decision::Continue,
        };
        match decision {
            Decision::End(ending, z) => {
                (ended_by, end_root) = (Some(ending), Some(z));
                break RunStatus::Steady;
            }
            Decision::Saddle(_) | Decision::Leap(_) | Decision::Continue => {}
        }
        // Adaptive steps land on the recorder's times.
        match clock.step(&mut run, settings, rec.as_ref().map(|r| r.next)) {
            Step::Taken | Step::Retry => {}
            Step::Stop(why) => break why,
        }
    };
    if let Some(rec) = rec.as_mut() {
        rec.sample(&run.snapshot(), true);
    }
    let found = match status {
        RunStatus::Steady => (None, None, None),
        RunStatus::Diverged => (Some(Unsettled::Diverged), None, None),
        _ => {
            let _timed = profile::enter(Part::Diagnosis);
            let mut own = NewtonFinish::new(params, settings);
            let d = finish.as_mut().unwrap_or(&mut own).diagnose(&run.z);
            (Some(d.reason), d.heading, Some(d.text))
        }
    };
    let at = run.snapshot();
    let mut out = outcome(
        &Snapshot {
            z: end_root.as_deref().unwrap_or(at.z),
            ..at
        },
        status,
        ended_by,
        found,
    );
    (out.rejected, out.max_step_error) = (clock.rejected, clock.max_step_error);
    Ok(out)
}

/// The paper's scheme at fixed steps `dt` to `t_max`, ended by the test alone: steady when
/// every rate `|dz/dt|` is below `steady_tol` (as the spectral run's test). Its end is not
/// a root of the spectral steady solver (the discretisations differ by `O(dx^2)`), so it is
/// neither polished nor diagnosed, as a 2-mode run of the paper's scheme.
fn paper_fd(
    params: &ModelParams,
    z0: &[f64],
    settings: &SolverSettings,
    rec: &mut Option<ModeRecorder>,
) -> Result<RunOutcome, SolverError> {
    let mut run = ModeFd::new(params, settings.n, z0)?;
    run.set_eta_k_exponent(settings.eta_k_exponent);
    let mut status = RunStatus::TMax;
    loop {
        if let Some(rec) = rec.as_mut() {
            rec.sample(&run.snapshot(), false);
        }
        let rate = run.rate();
        if left_model(&run.z, rate) {
            status = RunStatus::Diverged;
            break;
        }
        if rate < settings.steady_tol && run.t > 0.0 {
            status = RunStatus::Steady;
            break;
        }
        if run.t >= settings.t_max - 1e-9 * settings.dt {
            break;
        }
        run.advance(settings.dt);
    }
    if let Some(rec) = rec.as_mut() {
        rec.sample(&run.snapshot(), true);
    }
    let found = match status {
        RunStatus::Steady => (None, None, None),
        RunStatus::Diverged => (Some(Unsettled::Diverged), None, None),
        _ => (Some(Unsettled::NotDiagnosed), None, None),
    };
    let ended_by = (status == RunStatus::Steady).then_some(Ending::Test);
    Ok(outcome(&run.snapshot(), status, ended_by, found))
}

/// The outcome of a run that stopped at `at` with `status` (`at` is the root if it ended
/// steady by the Newton finish), with what was found of it if it did not settle. Its wall
/// time is the caller's to set.
fn outcome(at: &Snapshot, status: RunStatus, ended_by: Option<Ending>, found: Found) -> RunOutcome {
    let (unsettled, heading, diagnosis) = found;
    let (state, higher_modes) = split(at.z, at.x, at.y);
    let (v, s) = (state.speed(), state.deformation());
    let steady = status == RunStatus::Steady;
    RunOutcome {
        status,
        class: steady.then(|| StateClass::of(v, s)),
        state,
        v,
        s,
        t_end: at.t,
        t_steady: steady.then_some(at.t),
        steps: at.steps,
        rejected: 0,
        max_step_error: None,
        wall_s: 0.0,
        ended_by,
        diagnosis,
        t_leapt: 0.0,
        unsettled,
        heading,
        higher_modes,
        series: Vec::new(),
        higher_series: Vec::new(),
        profile: Default::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_three_mode_run_ends_steady_on_the_three_mode_md_state() {
        // Fig. 1c with modes 2..3 at N = 96 from IC i: the Newton finish ends the run on the
        // MD state of the steady solver, a3 included, long before the rates fall to the test.
        let p = ModelParams::at(0.085, 0.112);
        let settings = SolverSettings {
            n: 96,
            dt: 0.05,
            modes: 3,
            ..SolverSettings::default()
        };
        let ic = InitialCondition::parse("i").unwrap();
        let out = simulate_modes(&p, &ic, &settings).unwrap();
        assert_eq!(out.status, RunStatus::Steady, "{out:?}");
        assert_eq!(out.class, Some(StateClass::MD), "{out:?}");
        assert_eq!(out.ended_by, Some(Ending::Newton), "{out:?}");
        let mut solver = crate::roots::mode_solver::ModeSolver::new(p, 96).unwrap();
        let md = crate::roots::named_state::md_state(&mut solver, 3).unwrap();
        assert!((out.v - md.v).abs() < 1e-8, "{out:?} {md:?}");
        let a3 = out.higher_modes[0].hypot(out.higher_modes[1]);
        assert!((a3 - md.a[1].abs()).abs() < 1e-8, "{out:?} {md:?}");
        assert_eq!(out.higher_modes.len(), 2);
        // With the friction law eta_k = (2/k) eta2 (mode 3 relaxes 1.5 times faster), the run
        // takes another path to the same state: eta_k enters no steady state.
        let faster = simulate_modes(
            &p,
            &ic,
            &SolverSettings {
                eta_k_exponent: -1.0,
                ..settings
            },
        )
        .unwrap();
        assert_eq!(faster.status, RunStatus::Steady, "{faster:?}");
        assert!((faster.v - md.v).abs() < 1e-8, "{faster:?} {md:?}");
        let a3 = faster.higher_modes[0].hypot(faster.higher_modes[1]);
        assert!((a3 - md.a[1].abs()).abs() < 1e-8, "{faster:?} {md:?}");
        assert_ne!(faster.steps, out.steps);
    }

    #[test]
    fn the_friction_law_sets_how_fast_a_mode_relaxes() {
        // A mode-3 dent on the resting disk at (0.1, 0.16), where the disk is stable, with
        // both schemes: after 0.5 time units it has relaxed further with eta_3 = (2/3) eta2
        // (exponent -1) than with eta_3 = eta2, and less with eta_3 = (3/2) eta2 (exponent 1);
        // its mean rate goes about as 1 / eta_3 (ratio 1.5; measured 1.583 with the spectral
        // scheme, 1.585 with the paper's: the field building up from 0 moves it a little).
        let p = ModelParams::at(0.1, 0.16);
        let ic = InitialCondition::parse("custom:0,0,0,0,0.05,0").unwrap();
        for scheme in [SchemeKind::Spectral, SchemeKind::PaperFd] {
            let a3 = |exponent: f64| {
                let settings = SolverSettings {
                    n: 64,
                    dt: 2e-3,
                    tol: 0.0,
                    t_max: 0.5,
                    run_on: false,
                    modes: 3,
                    eta_k_exponent: exponent,
                    scheme,
                    steady: match scheme {
                        SchemeKind::Spectral => crate::contract::ending::SteadyMethod::Newton,
                        SchemeKind::PaperFd => crate::contract::ending::SteadyMethod::Test,
                    },
                    ..SolverSettings::default()
                };
                simulate_modes(&p, &ic, &settings).unwrap().higher_modes[0]
            };
            let (slow, base, fast) = (a3(1.0), a3(0.0), a3(-1.0));
            assert!(
                0.0 < fast && fast < base && base < slow && slow < 0.05,
                "{scheme}"
            );
            let rate = |a: f64| -(a / 0.05).ln();
            let ratio = rate(fast) / rate(base);
            assert!(ratio > 1.3 && ratio < 1.8, "{scheme}: {ratio}");
        }
    }
}
