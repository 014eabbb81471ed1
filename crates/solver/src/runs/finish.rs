//! Finishing a run by Newton instead of creeping to the paper's steady test (docs/model.md,
//! "Steady states as roots"; docs/numerics.md): the state a run converges to is a root of the co-moving force balance, which
//! [`crate::roots::balances::Balances`] computes directly, and its stability ([`crate::roots::verdict`])
//! says whether time stepping would stay there.
//!
//! When it is tried: once the run's change per steady window falls below
//! [`TRIGGER_FACTOR`] times the steady tolerance (the run is near a fixed point or creeping
//! along a slow mode), and whenever the paper's test fires; after a try that did not end the
//! run, not again for `max(10, t / 4)` time units (a saddle's neighbourhood, where runs slow
//! down too, is not retried every window). A run with more than two shape modes, whose own
//! trigger is ten times stricter, is tried early from the 2-mode runs' trigger on, and ends
//! there only where its orientation is not in doubt ([`crate::runs::early_try`]).
//!
//! When it ends the run: Newton on all four unknowns `(vx, vy, a2, b2)` from the current state
//! converges to a root `z*` whose eigenvalues all have negative real parts (the rotation mode
//! included: the run ends where the box would leave it), and the run is on its way there: its
//! speed and deformation differ from `z*`'s by at most 10 times what the linear decay at the
//! slowest decisive rate predicts from its present change (`(change / window) / |lambda|`),
//! and at most [`MAX_SETTLED`]; and its orientation is within [`crate::runs::orientation::ORIENTATION`] of `z*`'s, or
//! closer to it than at the previous try (it turns at the slow rotation rate). Orientations
//! are compared like with like: directions of motion when both move, long axes otherwise (a
//! run slowing down onto a resting ID moves along its short axis). The run then ends
//! `steady` at `z*` (`ended_by`: `newton`, or `test` if the paper's test fired first). A
//! state the paper's test would accept but whose root is unstable (a slowly growing mode,
//! e.g. the resting disk just past the onset of motion) does not end the run: it keeps
//! stepping.
//!
//! Neutral modes, deliberately: translation is absent (co-moving frame). Rotation: a moving
//! droplet in the square box turns, over thousands of time units, from the mirror line whose
//! state is unstable in its rotation mode to the other one (axis <-> diagonal), if it leans
//! away from the first at all. When the root near the run is unstable only in that mode, the
//! lean `phi` of the run from it decides ([`NewtonFinish::stable_root`]): a run that started
//! mirror-symmetric (`phi = 0`; leans below 1e-9 rad are its round-off) never turns and
//! ends at that root (any other run turns, however small its lean: numerics 7); otherwise it
//! turns to the first stable zero of the orientation's slow flow the way that flow points
//! ([`crate::runs::rotation_flow::flow_zero`], numerics 8), or, failing that, to the first
//! stable root on the side it leans to, looked for by Newton from the state turned by [`crate::runs::orientation::TURN_SEARCH`] degrees (a pitchfork pair a degree or
//! so off the line, else the root on the next mirror line), and the run ends there: speed and
//! deformation settle long before the orientation, and that root's `v` and `s` are what the
//! time stepper reaches after the turn; no run ends on a turned root it has turned away from
//! since the last try (numerics 11). Runs with more shape modes (no orientation flow) end
//! on such a turned root only while they leave the root they turn from (within
//! [`crate::runs::rotation_flow::LINEAR_LEAN`] of it) or turn towards the turned root
//! (numerics modes-7): on their grids the lattice holds roots between the mirror lines.
//!
//! Slow runs (setting `landing`, on by default): when Newton near the run does not end it,
//! the run's one-dimensional slow flow ([`crate::runs::landing`]) says which root it lands on;
//! [`NewtonFinish::landing_root`] confirms that root by Newton on all four equations and its
//! eigenvalues (a root unstable only in rotation: the run turns there, as above), and the run
//! ends there (`ended_by`: `landing`). The flow holds the run's lean fixed: a run whose lean
//! grows is not landed until it stops growing ([`LEAN_GROWTH`]). A run caught turning between
//! two mirror lines ends on the stable one of their roots when the other is unstable only in
//! its rotation mode ([`NewtonFinish::turn_root`]).
//!
//! Beside a saddle (setting `stop_beside_saddle`): when the root near the run has a growing
//! mode, the run's distance `d` to it (max over `vx, vy, a2, b2`) grows at most like
//! `d exp(lambda (t_max - t))`, `lambda` the largest real part of its eigenvalues (rotation
//! included; decaying parts of `d` only shrink, so this bounds the growing part from above).
//! If that bound stays below [`LEAVE`] the run would still be beside the saddle at `t_max`,
//! where the paper's rule gives up on it; and if every speed and deformation within the bound
//! of the saddle's has the class of the run's present state, it would end with that class.
//! It then stops now with status `saddle`, its own state (not the root's) and a diagnosis
//! that starts like a `t_max` run's there ([`crate::runs::finding::BESIDE_UNSTABLE`]).
//!
//! Leaving a saddle (setting `leap_departures`): when two tries find the run leaving the same
//! saddle along one growing mode, still in its linear stretch, the run leaps along the mode
//! ([`crate::runs::leap`]) instead of stepping through the exponential.
use crate::contract::ending::Ending;
use crate::contract::outcome::Unsettled;
use crate::contract::profile::{self, Part};
use crate::contract::settings::SolverSettings;
use crate::error::SolverError;
use crate::model::params::ModelParams;
use crate::model::state::max_distance;
use crate::roots::balances::Balances;
use crate::roots::kept_jacobians::KeptJacobians;
use crate::roots::verdict::Verdict;
use crate::runs::finding::{Diagnosis, Finding, MAX_SETTLED};
use crate::runs::leap::{leap, Leap, Sighting};
use crate::runs::orientation::{
    angle_to, class_of, invariant_distance, one_class_within, ORIENTATION,
};
use crate::runs::rotation_flow::LINEAR_LEAN;
use rustfft::num_complex::Complex64;

/// Newton is first tried when the change per window is below this many steady tolerances.
pub const TRIGGER_FACTOR: f64 = 100.0;

/// Largest growth of a run's lean between two landing tries, relative to that of its speed
/// (or deformation at rest), `d ln(lean) <= LEAN_GROWTH |d ln(coordinate)|`, for the landing
/// to hold the lean fixed (a departure by a factor 1000 turns such a run by at most 40 %
/// of its lean, in the measured cases by far less).
pub const LEAN_GROWTH: f64 = 0.05;

/// Largest distance from a saddle (max over `vx, vy, a2, b2`) that a run may reach by `t_max`
/// and still be taken to be beside it then (with `stop_beside_saddle`): the class threshold.
pub const LEAVE: f64 = crate::model::classify::CLASS_THRESHOLD;

/// The decision after one judged window.
#[derive(Debug, Clone, PartialEq)]
pub enum Decision {
    Continue,
    /// End steady at this `(vx, vy, a_2..a_K, b_2..b_K)`.
    End(Ending, Vec<f64>),
    /// Stop beside a saddle the run cannot leave before `t_max`, with this diagnosis.
    Saddle(String),
    /// Leap along the growing mode of a saddle the run is leaving.
    Leap(Leap),
}

/// When a try at `t` that did not end the run may be made again: after `max(10, t / 4)` (a
/// saddle's neighbourhood, where runs slow down too, is not retried every window).
pub(super) fn retry_after(t: f64) -> f64 {
    t + (0.25 * t).max(10.0)
}

/// The Newton finish of one run.
pub struct NewtonFinish {
    pub(super) params: ModelParams,
    pub(super) n: usize,
    pub(super) t_max: f64,
    pub(super) stop_beside_saddle: bool,
    pub(super) leap_departures: bool,
    pub(super) landing: bool,
    /// The last try that found the run beside a saddle (for `leap_departures`).
    pub(super) sighting: Option<Sighting>,
    pub(super) solver: Option<Balances>,
    /// Whether the run started on a mirror line of the box (its own mirror image there), so
    /// that a lean below [`crate::runs::orientation::LEAN_FLOOR`] is none; else such a lean is round-off that grows.
    pub(super) mirror_symmetric: bool,
    /// The run's nearest mirror line, its lean from it and its coordinate (speed, or
    /// deformation at rest) at the last landing try.
    pub(super) last_lean: Option<((i64, bool), f64, f64)>,
    /// The root of the last try and the run's angle to it then.
    pub(super) last_turn: Option<(Vec<f64>, f64)>,
    /// The run's state at the last try (which way it turns since).
    pub(super) last_try: Option<Vec<f64>>,
    /// Roots already assessed and their verdicts (a run's later tries usually find the same
    /// root again; its eigenvalues are not recomputed).
    pub(super) assessed: Vec<(Vec<f64>, Verdict)>,
    /// Whether the orientation's slow flow decides where a leaning run ends (numerics 8 and
    /// 9; the setting `orientation_flow`).
    pub(super) orientation_flow: bool,
    /// What is known of the orientation's flow beside roots stable in rotation, per root and
    /// side (lean > 0) ([`crate::runs::rotation_flow::FlowScan`]).
    pub(super) flows: Vec<(Vec<f64>, bool, crate::runs::rotation_flow::FlowScan)>,
    /// Turns followed from roots unstable in rotation: the root, the lean the flow was
    /// followed from, the lean where it ended (its zero, or where the fast balances could not
    /// be solved), and the stable root found there, if any ([`NewtonFinish::flow_turn`]; a
    /// later try leaning in between ends the same way).
    pub(super) turns: Vec<(Vec<f64>, f64, f64, Option<Finding>)>,
    pub(super) trigger: f64,
    pub(super) window: f64,
    pub(super) next_try: f64,
    /// The early tries of a run with more than two shape modes ([`crate::runs::early_try`]).
    pub(super) early: crate::runs::early_tries::EarlyTries,
    /// The force balance's Jacobians at the roots found, for the chord method.
    pub(super) jacobians: KeptJacobians,
    /// What Newton found from a root turned by each angle of
    /// [`crate::runs::orientation::TURN_SEARCH`], per root and side (lean > 0): `None` for
    /// an angle not tried yet, `Some(None)` where Newton did not converge.
    #[allow(clippy::type_complexity)]
    pub(super) turn_searches: Vec<(Vec<f64>, bool, Vec<Option<Option<Finding>>>)>,
    /// The walks of the landing's tries along the families ([`crate::runs::landing::Walks`]).
    pub(super) walks: crate::runs::landing::Walks,
}

impl NewtonFinish {
    /// For a run of `settings` (its grid, steady tolerance and window, and `t_max`).
    ///
    /// Runs with shape modes `2..K`, `K > 2`, are finished by Newton on all `2K` balances,
    /// the turn search, the landing, the diagnosis, the saddle stop and the leap, as 2-mode
    /// runs are. The orientation's flow is off for them
    /// ([`crate::contract::honoured`] says so): on coarse grids
    /// the lattice gives the fast balances at a fixed orientation several solutions, and the
    /// flow followed from a root need not be the run's (modes 2..3, N = 96, (0.088, 0.1095)
    /// from IC i: the flow from the x-axis MD points back to it out to 10 degrees along a
    /// branch whose speed falls to 0.05, while the run, at 9.5 degrees and v = 0.16, turns on
    /// to 26.9). Their change is a rate, `|dz/dt|` (the steady window one time unit): the
    /// finish is tried only once every rate is below [`TRIGGER_FACTOR`] steady tolerances, ten
    /// times later than a 2-mode run's (results/k-mode-endings: with the 2-mode runs' trigger
    /// such runs end on roots that pure time stepping does not reach).
    pub fn new(params: &ModelParams, settings: &SolverSettings) -> Self {
        let two = params.modes == 2;
        let (n, steady_tol) = (settings.n, settings.steady_tol);
        Self {
            params: *params,
            n,
            t_max: settings.t_max,
            stop_beside_saddle: settings.stop_beside_saddle,
            leap_departures: settings.leap_departures,
            landing: settings.landing,
            sighting: None,
            last_turn: None,
            last_try: None,
            last_lean: None,
            mirror_symmetric: true,
            assessed: Vec::new(),
            orientation_flow: settings.orientation_flow && two,
            flows: Vec::new(),
            turns: Vec::new(),
            solver: None,
            trigger: TRIGGER_FACTOR * steady_tol,
            window: if two { settings.steady_window } else { 1.0 },
            next_try: 0.0,
            early: Default::default(),
            jacobians: KeptJacobians::default(),
            turn_searches: Vec::new(),
            walks: Default::default(),
        }
    }

    /// Whether the run has shape modes beyond the paper's two, and so no orientation flow.
    /// Three rules of the finish follow from it (the third:
    /// [`NewtonFinish::settled_beside`], numerics `modes-12`):
    /// - the landing may end a 2-mode run leaning from its mirror line by more than
    ///   [`crate::runs::rotation_flow::LINEAR_LEAN`] on the line's root when that root is
    ///   stable in rotation (with the flow's basin check, or without it as numerics 7 did),
    ///   not a run with more modes: on coarse grids the lattice holds them at roots a few
    ///   degrees off the line (modes 2..3, N = 96, (0.088, 0.1095) from iv: 5.9 degrees off
    ///   the diagonal, where the landing put it on the diagonal);
    /// - the turn search of a run with more modes takes a stable root found past the next
    ///   mirror line as its mirror image in that line (numerics modes-10: at
    ///   (0.076, 0.14175), modes 2..4, from ii the run turns from the x-axis MD to the stable
    ///   root 5 degrees short of the diagonal, and Newton from the turned states finds only
    ///   its image 5 degrees past it); 2-mode runs keep numerics 10's search: their
    ///   orientation flow finds such roots first.
    pub(super) fn beyond_two_modes(&self) -> bool {
        self.params.modes > 2
    }

    /// Whether two roots Newton found are the same state, so that what a run's tries learnt
    /// of a root is found again: equal in every unknown to 1e-9 with two shape modes (Newton's
    /// tolerance is 1e-12), to 1e-6 with more, whose roots Newton fixes along the slow
    /// rotation only to its residual over the rotation rate (the Fig. 1c MD, modes 2..4,
    /// found again from the run a window later: 4.5e-8 apart; the lattice's roots beside a
    /// mirror line differ by 1e-4 and more).
    pub(super) fn same_root(&self, a: &[f64], b: &[f64]) -> bool {
        let tol = if self.beyond_two_modes() { 1e-6 } else { 1e-9 };
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < tol)
    }

    /// For a run that starts at `(vx, vy, a2, b2)`: only a run that starts mirror-symmetric
    /// ([`crate::runs::orientation::mirror_symmetric`]; the paper's i' and ii') stays on an
    /// unstable line for ever (numerics 7). A finish made without its start (a diagnosis)
    /// takes a lean below [`crate::runs::orientation::LEAN_FLOOR`] to be none.
    pub fn starting_at(mut self, z0: &[f64]) -> Self {
        self.mirror_symmetric = crate::runs::orientation::mirror_symmetric(z0);
        self
    }

    /// Newton from `z` on all four unknowns, and the root's verdict.
    pub fn root_near(&mut self, z: &[f64]) -> Result<Finding, SolverError> {
        let root = self.newton_root(z)?;
        Ok(self.assess(root))
    }

    /// The root Newton finds from `z`, without its verdict ([`Self::root_near`]).
    pub(super) fn newton_root(&mut self, z: &[f64]) -> Result<Vec<f64>, SolverError> {
        crate::error::require(
            self.params.mass > 0.0,
            "mass",
            self.params.mass,
            "> 0 for the linearisation (an overdamped droplet is finished by the paper's test)",
        )?;
        self.balances()?;
        let balances = self.solver.as_mut().expect("made above");
        let _timed = profile::enter(Part::Newton);
        balances.root_near(z, &mut self.jacobians)
    }

    /// A root with its verdict: the one a run's earlier try found for it (its eigenvalues
    /// are not recomputed), else the eigenvalues'.
    pub(super) fn assess(&mut self, root: Vec<f64>) -> Finding {
        let known = self.assessed.iter().find(|(z, _)| self.same_root(z, &root));
        let verdict = match known {
            Some((_, v)) => v.clone(),
            None => {
                let _timed = profile::enter(Part::Eigen);
                let balances = self.solver.as_mut().expect("made by newton_root");
                let v = balances.verdict(&root);
                self.assessed.push((root.clone(), v.clone()));
                v
            }
        };
        Finding {
            z: root,
            verdict,
            turned_from: None,
        }
    }

    /// Why a run stopped at `z` did not finish: what Newton from `z` finds
    /// ([`Finding::describe`]), or from `z` turned onto the box's nearest mirror lines if
    /// Newton from `z` does not converge (a run caught mid-turn); and where it was heading:
    /// the stable root near it, or the one its slow flow lands on ([`crate::runs::landing`]).
    pub fn diagnose(&mut self, z: &[f64]) -> Diagnosis {
        let (text, reason, mut heading) = match self.root_near(z) {
            Ok(found) => (found.describe(z), found.reason(z), found.heading()),
            Err(SolverError::NewtonFailed { .. }) => match self.aligned_root(z) {
                Some(found) => (
                    format!(
                        "caught turning between the box's mirror lines; the steady state on one: {}",
                        found.describe(z)
                    ),
                    found.reason(z),
                    found.heading(),
                ),
                None => (
                    "no steady state near the final state (Newton did not converge)".into(),
                    Unsettled::NoRoot,
                    None,
                ),
            },
            Err(e) => (format!("not diagnosed: {e}"), Unsettled::NotDiagnosed, None),
        };
        if reason != Unsettled::Turning && reason != Unsettled::Converging {
            if let Some(landed) = self.landing_root(z, false, None) {
                heading = Some(class_of(&landed.z));
            }
        }
        Diagnosis {
            text,
            reason,
            heading,
        }
    }

    /// One judged window at time `t`: the state `z`, its change over the window (scaled to
    /// one window; `(all, across)`: all of it, and what is left across the rotation, see
    /// [`crate::runs::driver`]), and whether the paper's test fired. A run whose change
    /// across the rotation is below the trigger but not all of it is turning: it is tried,
    /// and ends only on a turned root (the turn search from a root unstable only in
    /// rotation) or by the landing; a root stable in rotation near it holds it only once it
    /// has stopped turning (without the orientation's flow nothing says whether the turn
    /// stops there: modes 2..3, N = 96, (0.088, 0.1095) from i passes the x-axis MD, stable
    /// in rotation, 9 degrees off it and turns on to 26.9).
    pub fn consider(
        &mut self,
        t: f64,
        z: &[f64],
        (all, change): (f64, f64),
        test_fired: bool,
    ) -> Decision {
        if t < self.next_try {
            return Decision::Continue;
        }
        if !(test_fired || change < self.trigger) {
            return self.try_early(t, z, (all, change));
        }
        let turning = !test_fired && all >= self.trigger;
        let before = self.last_try.replace(z.to_vec());
        let found = self.stable_root(z);
        let Some((f, may_end, basin_left)) = found else {
            // No root near (a run passing the ghost of a saddle-node, or caught mid-turn):
            // where its slow flow lands, else on by time stepping. The paper's test alone
            // never ends a run on a state that is not a stable root (numerics 4).
            if let Some(end) = self.land_now(z) {
                return end;
            }
            self.next_try = retry_after(t);
            return Decision::Continue;
        };
        // The run's speed and deformation relax at the decisive rates: their distance to the
        // root's, against what the linear decay at the slowest decisive rate predicts from
        // the run's present change. Its orientation relaxes at the rotation rate, slowly: it
        // need only be within ORIENTATION of the root's, or closer to it than at the last try
        // (turning towards it), or the root be the turned one. A run that is to turn has
        // settled when it has settled on the root it turns from (the two differ by the box's
        // anisotropy, 3 % in v for the fast MD with modes 2..4) or already on the turned one.
        let bound = self.settled_within(&f, change);
        let lean = angle_to(z, &f.z);
        let turn = lean.abs();
        let turning_to = self.last_turn.as_ref().is_some_and(|(root, before)| {
            root.iter().zip(&f.z).all(|(a, b)| (a - b).abs() < 1e-6) && turn < *before
        });
        self.last_turn = Some((f.z.clone(), turn));
        // A run with more shape modes turning back to a stable root may have settled beside
        // it instead (its speed and shape those of the root's family at its own orientation):
        // asked only of a run that may end there and is turning towards it, since the
        // question samples the orientation's flow.
        let settled = invariant_distance(z, &f.z) <= bound
            || f.turned_from
                .as_ref()
                .is_some_and(|near| invariant_distance(z, near) <= bound)
            || (may_end && !turning && turning_to && self.settled_beside(z, &f, lean, bound));
        // A turned root ends a run that leaves the root it turns from (within LINEAR_LEAN
        // of it, where that root's rotation eigenvalue decides), or one turning towards it;
        // 2-mode runs always (their orientation's flow found it). Runs with more shape
        // modes have no flow, and their grid's lattice holds roots between the box's mirror
        // lines: modes 2..3, N = 192, (0.085, 0.112) from iv, 17 degrees from the diagonal
        // MD (unstable in rotation) and turning towards it, to a root 2.25 degrees short of
        // it, had ended on the y-axis MD the turn search finds from the diagonal.
        //
        // And a turned root ends no run turning away from it (its angle to that root grown
        // since the last try by more than LINEAR_LEAN), whatever the flow on the root's family
        // says: a run still gaining speed turns as its transient turns it. 2 modes, N = 192,
        // (0.089, 0.1075) from i at t = 186: 16.3 degrees off the x axis, 12 % below its
        // speed and turning up at 0.017 degrees per time unit to the stable root at 18.0
        // degrees, it is next to a root of the lattice at 16.6 degrees unstable in rotation,
        // whose flow on the family leads down to 1.7 degrees; it had ended there.
        let turning_away = before
            .as_ref()
            .is_some_and(|b| turn > angle_to(b, &f.z).abs() + LINEAR_LEAN);
        let turned = !turning_away
            && f.turned_from
                .as_ref()
                .is_some_and(|from| self.lean_holds(angle_to(z, from), turning_to));
        let approaching = settled && (turned || turn <= ORIENTATION || turning_to);
        // The basin check of a root stable in rotation, left to here: only a run that would
        // end on it pays for the flow's samples (the same decisions, fewer samples).
        if may_end
            && (test_fired || approaching)
            && (!turning || f.turned())
            && (!basin_left || self.within_rotation_basin(&f, lean))
        {
            let ending = if test_fired {
                Ending::Test
            } else {
                Ending::Newton
            };
            return Decision::End(ending, f.z);
        }
        if let Some(end) = self.land_now(z) {
            return end;
        }
        if let Some(diagnosis) = self.cannot_leave(t, z, &f) {
            return Decision::Saddle(diagnosis);
        }
        if let Some(l) = self.departure(t, z, &f) {
            self.next_try = retry_after(t + l.duration);
            return Decision::Leap(l);
        }
        self.next_try = retry_after(t);
        Decision::Continue
    }

    /// With `leap_departures`, the leap of a run at `z` (time `t`) leaving the saddle `f`
    /// along one growing mode, if the previous try saw it on that mode too.
    fn departure(&mut self, t: f64, z: &[f64], f: &Finding) -> Option<Leap> {
        if !self.leap_departures || f.verdict.unstable == 0 || f.turned() {
            self.sighting = None;
            return None;
        }
        let now = Sighting {
            t,
            z: z.to_vec(),
            root: f.z.clone(),
        };
        let before = self.sighting.replace(now.clone())?;
        let l = leap(&before, &now, &f.verdict.eigenvalues, self.t_max)?;
        self.sighting = None;
        Some(l)
    }

    /// The run's steady balances, made at their first use.
    pub(super) fn balances(&mut self) -> Result<&mut Balances, SolverError> {
        if self.solver.is_none() {
            self.solver = Some(Balances::new(self.params, self.n)?);
        }
        Ok(self.solver.as_mut().expect("made above"))
    }

    /// The co-moving field of the steady state `root` (normalised coefficients, `[kx][ky]`):
    /// what a leap scales the run's field towards.
    pub fn root_field(&mut self, root: &[f64]) -> Result<Vec<Complex64>, SolverError> {
        Ok(self.balances()?.root_field(root))
    }

    /// With `stop_beside_saddle`, the diagnosis of a run at `z` (time `t`) beside the saddle
    /// `f` that it cannot leave before `t_max`: its distance grown at the largest rate stays
    /// below [`LEAVE`], and the class is the same everywhere within that distance.
    fn cannot_leave(&self, t: f64, z: &[f64], f: &Finding) -> Option<String> {
        if !self.stop_beside_saddle || f.verdict.unstable == 0 || f.turned() {
            return None;
        }
        let distance = max_distance(z, &f.z);
        let rate = f.slowest().max(f.verdict.max_re);
        let at_t_max = distance * (rate * (self.t_max - t).max(0.0)).min(700.0).exp();
        (at_t_max < LEAVE && one_class_within(z, &f.z, at_t_max)).then(|| {
            format!(
                "{}; stopped at t = {t:.1}, {distance:.1e} from it: at most {at_t_max:.1e} by t_max = {}",
                f.describe(z),
                self.t_max
            )
        })
    }

    /// How far from the root `f` a run whose change per window is `change` may be and be on
    /// its way there: what the linear decay at the slowest decisive rate still lets it move,
    /// `10 (change / window) / |lambda|`, at most [`MAX_SETTLED`].
    pub(super) fn settled_within(&self, f: &Finding, change: f64) -> f64 {
        let rate = f.verdict.max_re.abs().max(1e-12);
        (10.0 * (change / self.window) / rate).min(MAX_SETTLED) + 1e-9
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::classify::StateClass;
    use crate::model::state::turned;
    use crate::runs::finding::SETTLED;
    use crate::runs::orientation::{angle_to, one_class_within, orientation};

    #[test]
    fn orientations_compare_like_with_like() {
        let deg = |a: f64| a.to_degrees();
        // A run slowing down onto the diagonal ID moves along its short axis (+45 degrees)
        // while its long axis is within 1.5 degrees of the root's (-45 degrees).
        let run = [0.032, 0.0303, -0.0162, -0.3063];
        let id = [0.0, 0.0, 0.0, -0.3065];
        assert!(deg(angle_to(&run, &id)).abs() < 2.0);
        // Long axes are equal modulo 180 degrees: 89 and -89 degrees are 2 apart, and the
        // sign says which way round.
        let axis = |deg: f64| {
            let t = 2.0 * deg.to_radians();
            [0.0, 0.0, 0.3 * t.cos(), 0.3 * t.sin()]
        };
        assert!((deg(angle_to(&axis(89.0), &axis(-89.0))) + 2.0).abs() < 1e-9);
        assert!((deg(angle_to(&axis(-89.0), &axis(89.0))) - 2.0).abs() < 1e-9);
        // Two moving states: their directions of motion; a round resting root: no orientation.
        let md = [0.2, 0.0, 0.3, 0.0];
        assert!((deg(angle_to(&[0.0, 0.2, 0.3, 0.0], &md)) - 90.0).abs() < 1e-9);
        assert_eq!(angle_to(&run, &[0.0; 4]), 0.0);
    }

    #[test]
    fn a_saddle_stop_needs_one_class_within_the_reach() {
        // Beside the resting disk (v = s = 0): IC up to v, s < 0.01, i.e. reach < 0.01 / sqrt 2.
        let disk = [0.0; 4];
        let near = [1e-3, 0.0, 0.0, 0.0];
        assert!(one_class_within(&near, &disk, 0.005));
        assert!(!one_class_within(&near, &disk, 0.008));
        // A moving deformed saddle far from both thresholds keeps MD for any reach below them.
        let md = [0.1, 0.0, 0.2, 0.0];
        assert!(one_class_within(&[0.1, 1e-3, 0.2, 0.0], &md, 0.01));
        // A run already of another class than everything near the saddle: never.
        assert!(!one_class_within(&[0.02, 0.0, 0.0, 0.0], &disk, 1e-4));
    }

    #[test]
    fn the_root_near_a_moving_state_is_the_md_state_and_is_stable() {
        let p = ModelParams::at(0.085, 0.112);
        let settings = SolverSettings {
            n: 96,
            ..SolverSettings::default()
        };
        let mut f = NewtonFinish::new(&p, &settings);
        // Near MD, off the axis: Newton on all four unknowns finds the MD state (v and s as on
        // the axis, the box's weak anisotropy aside) and it is stable.
        let found = f.root_near(&[0.58, 0.05, -0.26, 0.02]).unwrap();
        let v = found.z[0].hypot(found.z[1]);
        assert!(v > 0.5 && v < 0.7, "{found:?}");
        // The resting disk is a root too, and unstable here (it deforms).
        let ic = f.root_near(&[1e-3, 0.0, 1e-3, 0.0]).unwrap();
        assert!(ic.z.iter().all(|x| x.abs() < 1e-10), "{ic:?}");
        assert!(!ic.stable() && ic.verdict.unstable > 0, "{ic:?}");
        let note = ic.describe(&[1e-3, 0.0, 1e-3, 0.0]);
        assert!(note.contains("unstable"), "{note}");
        // Only turning is settled only near the root, with its class: a run still leaving
        // the resting disk towards the MD root is on its way.
        let settled = found.describe(&[0.58, 0.05, -0.26, 0.02]);
        assert!(settled.ends_with(SETTLED), "{settled}");
        let run = [0.58, 0.05, -0.26, 0.02];
        assert_eq!(found.reason(&run), Unsettled::Turning);
        assert_eq!(found.heading(), Some(StateClass::MD));
        assert_eq!(ic.reason(&[1e-3, 0.0, 1e-3, 0.0]), Unsettled::BesideSaddle);
        assert_eq!(ic.heading(), None);
        let leaving = found.describe(&[0.17, 0.017, -0.0087, -0.0016]);
        assert!(!leaving.ends_with(SETTLED), "{leaving}");
        assert_eq!(
            found.reason(&[0.17, 0.017, -0.0087, -0.0016]),
            Unsettled::Converging
        );
    }

    #[test]
    fn a_run_caught_between_mirror_lines_finds_the_root_on_one() {
        let p = ModelParams::at(0.085, 0.112);
        let settings = SolverSettings {
            n: 96,
            ..SolverSettings::default()
        };
        let mut f = NewtonFinish::new(&p, &settings);
        let axis = f.root_near(&[0.58, 0.0, -0.26, 0.0]).unwrap();
        // Turned by 20 degrees, between the x axis and the diagonal.
        let found = f
            .aligned_root(&turned(&axis.z, 20f64.to_radians()))
            .unwrap();
        let phi = orientation(&found.z) / std::f64::consts::FRAC_PI_4;
        assert!((phi - phi.round()).abs() < 1e-6, "{found:?}");
        let speed = |z: &[f64]| z[0].hypot(z[1]);
        // The axis and diagonal states differ by the box's weak anisotropy only.
        assert!(
            (speed(&found.z) - speed(&axis.z)).abs() < 0.02,
            "{found:?} {axis:?}"
        );
        assert!(found.verdict.unstable == 0, "{found:?}");
    }
}
