//! Finishing a run by Newton instead of creeping to the paper's steady test (docs/model.md,
//! "Steady states as roots"; docs/numerics.md): the state a run converges to is a root of the co-moving force balance, which
//! [`SteadySolver`] computes directly, and its stability ([`crate::roots::verdict`])
//! says whether time stepping would stay there.
//!
//! When it is tried: once the run's change per steady window falls below
//! [`TRIGGER_FACTOR`] times the steady tolerance (the run is near a fixed point or creeping
//! along a slow mode), and whenever the paper's test fires; after a try that did not end the
//! run, not again for `max(10, t / 4)` time units (a saddle's neighbourhood, where runs slow
//! down too, is not retried every window).
//!
//! When it ends the run: Newton on all four unknowns `(vx, vy, a2, b2)` from the current state
//! converges to a root `z*` whose eigenvalues all have negative real parts (the rotation mode
//! included: the run ends where the box would leave it), and the run is on its way there: its
//! speed and deformation differ from `z*`'s by at most 10 times what the linear decay at the
//! slowest decisive rate predicts from its present change (`(change / window) / |lambda|`),
//! and at most [`MAX_SETTLED`]; and its orientation is within [`ORIENTATION`] of `z*`'s, or
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
//! lean `phi` of the run from it decides ([`NewtonFinish::stable_root`]): a
//! mirror-symmetric run (`phi = 0`; leans below 1e-9 rad are its round-off) never turns and
//! ends at that root; otherwise the first stable root on the side it leans to is looked for
//! by Newton from the state turned by [`TURN_SEARCH`] degrees (a pitchfork pair a degree or
//! so off the line, else the root on the next mirror line), and the run ends there: speed and
//! deformation settle long before the orientation, and that root's `v` and `s` are what the
//! time stepper reaches after the turn.
//!
//! Slow runs (setting `landing`, on by default): when Newton near the run does not end it,
//! the run's one-dimensional slow flow ([`crate::runs::landing`]) says which root it lands on;
//! [`NewtonFinish::landing_root`] confirms that root by Newton on all four equations and its
//! eigenvalues, and the run ends there (`ended_by`: `landing`). A run caught turning between
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
//! that starts like a `t_max` run's there ([`BESIDE_UNSTABLE`]).
//!
//! Leaving a saddle (setting `leap_departures`): when two tries find the run leaving the same
//! saddle along one growing mode, still in its linear stretch, the run leaps along the mode
//! ([`crate::runs::leap`]) instead of stepping through the exponential.
use crate::contract::ending::Ending;
use crate::contract::outcome::Unsettled;
use crate::contract::settings::SolverSettings;
use crate::error::SolverError;
use crate::model::classify::StateClass;
use crate::model::dynamics::force_balance;
use crate::model::params::ModelParams;
use crate::model::state::max_distance;
use crate::numerics::newton::{solve, NewtonOptions};
use crate::roots::linearisation::Linearization;
use crate::roots::steady_solver::SteadySolver;
use crate::roots::verdict::{assess, Verdict};
use crate::runs::landing::{landings, rotated};
use crate::runs::leap::{leap, Leap, Sighting};
use rustfft::num_complex::Complex64;

/// Newton is first tried when the change per window is below this many steady tolerances.
pub const TRIGGER_FACTOR: f64 = 100.0;

/// What a Newton try found: the root, its stability, and whether it is the turned root.
#[derive(Debug, Clone, PartialEq)]
pub struct Finding {
    /// The root, `(vx, vy, a2, b2)`.
    pub z: [f64; 4],
    pub verdict: Verdict,
    /// The root of the turned state (the run is to turn there), not the one near the run.
    pub turned: bool,
}

impl Finding {
    /// Largest real part of all eigenvalues, the rotation mode included.
    pub fn slowest(&self) -> f64 {
        self.verdict.eigenvalues.first().map_or(-1.0, |l| l[0])
    }

    /// Every eigenvalue decays (the rotation mode included).
    pub fn stable(&self) -> bool {
        self.slowest() < 0.0
    }

    /// Why a run stopped at `z` (the state Newton started from) is not settled on this root.
    pub fn reason(&self, z: &[f64; 4]) -> Unsettled {
        if self.verdict.unstable > 0 {
            Unsettled::BesideSaddle
        } else if self
            .verdict
            .rotation
            .is_some_and(|r| r >= self.verdict.max_re)
            && invariant_distance(z, &self.z) <= SETTLED_WITHIN
            && class_of(z) == class_of(&self.z)
        {
            Unsettled::Turning
        } else {
            Unsettled::Converging
        }
    }

    /// The class of the root, if it is stable (rotation mode aside): where a run near it
    /// is heading.
    pub fn heading(&self) -> Option<StateClass> {
        (self.verdict.unstable == 0).then(|| class_of(&self.z))
    }

    /// A sentence for the `diagnosis` column of a run stopped at `z` (the state Newton started
    /// from). Only the rotation mode slow and the run's speed and deformation within
    /// [`SETTLED_WITHIN`] of the root's, with its class: [`SETTLED`] (the run only turns).
    pub fn describe(&self, z: &[f64; 4]) -> String {
        let rot = self.verdict.rotation;
        if self.verdict.unstable > 0 {
            format!(
                "{BESIDE_UNSTABLE} ({} growing mode(s), largest {:+.2e})",
                self.verdict.unstable, self.verdict.max_re
            )
        } else if let Some(r) = rot.filter(|r| *r >= self.verdict.max_re) {
            let d = invariant_distance(z, &self.z);
            if d <= SETTLED_WITHIN && class_of(z) == class_of(&self.z) {
                format!(
                    "rotation mode {r:+.2e}: the direction of motion / long axis turns slowly (box effect); {SETTLED}"
                )
            } else {
                format!(
                    "rotation mode {r:+.2e} slowest, but v and s are {d:.1e} from the root's: still on the way"
                )
            }
        } else {
            format!(
                "slowest eigenvalue {:+.2e}: converging slowly",
                self.slowest()
            )
        }
    }
}

/// Largest difference in speed or deformation between a run and its root for the run to be
/// settled (with the root's class) when only the rotation mode is slow: [`MAX_SETTLED`], the
/// bound for a run approaching a root (a run turning between the box's mirror lines differs
/// from the root on one by the box's anisotropy, up to 2e-2 in `v` for the fastest MD).
/// Before numerics version 3 the run's distance was not checked, and a run still leaving
/// the resting disk towards an MD root far away was called settled.
pub const SETTLED_WITHIN: f64 = MAX_SETTLED;

/// The end of a diagnosis whose run has settled in speed and deformation (only its direction
/// still turns, at the box's slow rotation rate): its class is that of its final state.
pub const SETTLED: &str = "v and s are settled";

/// The start of a diagnosis whose run stopped beside an unstable steady state.
pub const BESIDE_UNSTABLE: &str = "near an unstable steady state";

/// Largest difference in speed or deformation between a run and the root it is taken to be
/// approaching.
pub const MAX_SETTLED: f64 = 0.05;

/// Largest angle between a run's orientation and a stable root's for the run to be taken to
/// be turning towards it.
/// Known limitation: a run within this angle whose lean is growing (just past the basin
/// boundary between two stable orientations, e.g. at (0.1, 0.1) from IC iv) is also taken,
/// and ends on the wrong mirror line: same class, `s` off by the box's anisotropy (docs/numerics.md,
/// "Finishing runs by Newton").
pub const ORIENTATION: f64 = std::f64::consts::PI / 16.0;

/// The turns (degrees) from a state on a mirror line that is unstable in its rotation mode
/// at which [`NewtonFinish::stable_root`] looks for the stable root the run turns to.
pub const TURN_SEARCH: [f64; 7] = [1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 45.0];

/// Largest distance from a saddle (max over `vx, vy, a2, b2`) that a run may reach by `t_max`
/// and still be taken to be beside it then (with `stop_beside_saddle`): the class threshold.
pub const LEAVE: f64 = crate::model::classify::CLASS_THRESHOLD;

/// Leans (radians) below this are round-off of a mirror-symmetric run and count as none.
pub const LEAN_FLOOR: f64 = 1e-9;

/// The direction of motion, or for a resting droplet the direction of its long axis.
fn orientation(z: &[f64; 4]) -> f64 {
    if z[0].hypot(z[1]) > 1e-9 {
        z[1].atan2(z[0])
    } else {
        0.5 * z[3].atan2(z[2])
    }
}

/// The angle from the root `root`'s orientation to the run `z`'s, compared like with like:
/// directions of motion when both move, else long axes (modulo pi; a run slowing down onto
/// a resting deformed root moves along its short axis, not its long one), and 0 for a
/// resting round root, which has no orientation. In (-pi/2, pi/2].
fn angle_to(z: &[f64; 4], root: &[f64; 4]) -> f64 {
    let moving = |z: &[f64; 4]| z[0].hypot(z[1]) > 1e-9;
    if moving(z) && moving(root) {
        return (z[1].atan2(z[0]) - root[1].atan2(root[0])).sin().asin();
    }
    if root[2].hypot(root[3]) <= 1e-9 {
        return 0.0;
    }
    let d = 0.5 * (z[3].atan2(z[2]) - root[3].atan2(root[2]));
    d - std::f64::consts::PI * (d / std::f64::consts::PI).round()
}

/// Speed `v` and deformation `s` of `(vx, vy, a2, b2)`.
fn speed_and_deformation(z: &[f64; 4]) -> (f64, f64) {
    (z[0].hypot(z[1]), z[2].hypot(z[3]))
}

/// The class of `(vx, vy, a2, b2)`.
fn class_of(z: &[f64; 4]) -> StateClass {
    let (v, s) = speed_and_deformation(z);
    StateClass::of(v, s)
}

/// Max of the differences in speed and in deformation (invariant under rotation).
fn invariant_distance(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    let ((va, sa), (vb, sb)) = (speed_and_deformation(a), speed_and_deformation(b));
    (va - vb).abs().max((sa - sb).abs())
}

/// Whether every state whose speed and deformation are within `reach` (max over the 4
/// components, so `sqrt(2) reach` in `v` and `s`) of the root `root`'s has the class of `z`.
/// Classes are quadrants of the `(v, s)` plane, so the corners of that box decide.
fn one_class_within(z: &[f64; 4], root: &[f64; 4], reach: f64) -> bool {
    let class = class_of(z);
    let (v, s) = speed_and_deformation(root);
    let r = std::f64::consts::SQRT_2 * reach;
    [(v - r).max(0.0), v + r].iter().all(|&v| {
        [(s - r).max(0.0), s + r]
            .iter()
            .all(|&s| StateClass::of(v, s) == class)
    })
}

/// What a run that did not finish was doing when it stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnosis {
    /// A sentence (the `diagnosis` column).
    pub text: String,
    pub reason: Unsettled,
    /// The class of the stable root it was heading to, if one is known.
    pub heading: Option<StateClass>,
}

/// The decision after one judged window.
#[derive(Debug, Clone, PartialEq)]
pub enum Decision {
    Continue,
    /// End steady at this `(vx, vy, a2, b2)`.
    End(Ending, [f64; 4]),
    /// Stop beside a saddle the run cannot leave before `t_max`, with this diagnosis.
    Saddle(String),
    /// Leap along the growing mode of a saddle the run is leaving.
    Leap(Leap),
}

/// The Newton finish of one run.
pub struct NewtonFinish {
    params: ModelParams,
    n: usize,
    t_max: f64,
    stop_beside_saddle: bool,
    leap_departures: bool,
    landing: bool,
    /// The last try that found the run beside a saddle (for `leap_departures`).
    sighting: Option<Sighting>,
    solver: Option<SteadySolver>,
    /// The root of the last try and the run's angle to it then.
    last_turn: Option<([f64; 4], f64)>,
    /// Roots already assessed and their verdicts (a run's later tries usually find the same
    /// root again; its eigenvalues are not recomputed).
    assessed: Vec<([f64; 4], Verdict)>,
    trigger: f64,
    window: f64,
    next_try: f64,
}

impl NewtonFinish {
    /// For a run of `settings` (its grid, steady tolerance and window, and `t_max`).
    pub fn new(params: &ModelParams, settings: &SolverSettings) -> Self {
        let (n, steady_tol, window) = (settings.n, settings.steady_tol, settings.steady_window);
        Self {
            params: *params,
            n,
            t_max: settings.t_max,
            stop_beside_saddle: settings.stop_beside_saddle,
            leap_departures: settings.leap_departures,
            landing: settings.landing,
            sighting: None,
            last_turn: None,
            assessed: Vec::new(),
            solver: None,
            trigger: TRIGGER_FACTOR * steady_tol,
            window,
            next_try: 0.0,
        }
    }

    /// Newton from `z` on all four unknowns, and the root's verdict.
    pub fn root_near(&mut self, z: [f64; 4]) -> Result<Finding, SolverError> {
        crate::error::require(
            self.params.mass > 0.0,
            "mass",
            self.params.mass,
            "> 0 for the linearisation (an overdamped droplet is finished by the paper's test)",
        )?;
        let p = self.params;
        self.steady_solver()?;
        // The field, not `self`: `self.assessed` is read below while the solver is in use.
        let solver = self.solver.as_mut().expect("made above");
        let opts = NewtonOptions {
            tol: 1e-12,
            // Converging solves from a run near its root take 3 to 8 iterations; a failing
            // one (a run mid-turn, see `aligned_root`) is not worth 30.
            max_iter: 12,
            fd_step: 1e-6,
            max_step: vec![f64::INFINITY, f64::INFINITY, 0.2, 0.2],
        };
        let sol = solve(
            |x| {
                let f = solver.forces(x[0], x[1], x[2], x[3]);
                force_balance(&p, [x[0], x[1], x[2], x[3]], &f).to_vec()
            },
            &z,
            &opts,
        )?;
        let root = [sol.x[0], sol.x[1], sol.x[2], sol.x[3]];
        // The same root as before (Newton's tolerance is 1e-12; 1e-9 is the same state).
        let known = self
            .assessed
            .iter()
            .find(|(z, _)| z.iter().zip(&root).all(|(a, b)| (a - b).abs() < 1e-9));
        let verdict = match known {
            Some((_, v)) => v.clone(),
            None => {
                let v = assess(&Linearization::at(solver, root), root);
                self.assessed.push((root, v.clone()));
                v
            }
        };
        Ok(Finding {
            z: root,
            verdict,
            turned: false,
        })
    }

    /// The root the run at `z` ends at, if Newton finds one, and whether it may
    /// end there: the root near `z`, if every eigenvalue decays. If that root is unstable only
    /// in its rotation mode (an orientation the box turns away from), the run turns away only
    /// if it leans at all (a lean `phi` grows like `phi exp(lambda_rot t)`, however long that
    /// takes: before numerics 4 a run that could not turn by 0.01 rad before `t_max` ended
    /// on the unstable line, `v` off by the box's anisotropy from where longer stepping
    /// lands); a mirror-symmetric run (`phi = 0`)
    /// ends at the root like the paper's test would. A run that can turn goes to the root of
    /// the state turned by 45 degrees (motion and long axis together, towards the side it
    /// leans to), where the box's other mirror line is, if that root is stable.
    pub fn stable_root(&mut self, z: [f64; 4]) -> Option<(Finding, bool)> {
        let near = match self.root_near(z) {
            Ok(near) => near,
            Err(_) => self.aligned_root(z)?,
        };
        if near.verdict.rotation.is_none() || near.stable() {
            let ok = near.stable();
            return Some((near, ok));
        }
        if near.verdict.unstable > 0 {
            return Some((near, false));
        }
        let lean = angle_to(&z, &near.z);
        // Below LEAN_FLOOR a lean is the round-off of a mirror-symmetric run: none.
        let lean = if lean.abs() < LEAN_FLOOR { 0.0 } else { lean };
        if lean == 0.0 {
            // A mirror-symmetric run stays on its line for ever.
            return Some((near, true));
        }
        let side = if lean >= 0.0 { 1.0 } else { -1.0 };
        // The run turns away from `near` towards the side it leans to, and ends on the first
        // stable root that way: where the unstable line's root lost its rotational stability
        // in a pitchfork, a pair of roots a few degrees to either side; else the root on the
        // box's next mirror line, 45 degrees away. Newton from the state turned by growing
        // angles finds the nearest first.
        let quarter = std::f64::consts::FRAC_PI_4;
        for degrees in TURN_SEARCH {
            let Ok(other) = self.root_near(rotated(&near.z, side * degrees.to_radians())) else {
                continue;
            };
            // A root the run turns to differs from `near` by the box's anisotropy only (its
            // class may differ where `s` is near the threshold: MD on one line, MC on the
            // other); one further away (a resting state, say) is not where a turn ends.
            let turn = side * angle_to(&other.z, &near.z);
            if other.stable()
                && invariant_distance(&other.z, &near.z) <= MAX_SETTLED
                && turn > 1e-6
                && turn <= quarter + 1e-6
            {
                return Some((
                    Finding {
                        turned: true,
                        ..other
                    },
                    true,
                ));
            }
        }
        Some((near, false))
    }

    /// Why a run stopped at `z` did not finish: what Newton from `z` finds
    /// ([`Finding::describe`]), or from `z` turned onto the box's nearest mirror lines if
    /// Newton from `z` does not converge (a run caught mid-turn); and where it was heading:
    /// the stable root near it, or the one its slow flow lands on ([`crate::runs::landing`]).
    pub fn diagnose(&mut self, z: [f64; 4]) -> Diagnosis {
        let (text, reason, mut heading) = match self.root_near(z) {
            Ok(found) => (found.describe(&z), found.reason(&z), found.heading()),
            Err(SolverError::NewtonFailed { .. }) => match self.aligned_root(z) {
                Some(found) => (
                    format!(
                        "caught turning between the box's mirror lines; the steady state on one: {}",
                        found.describe(&z)
                    ),
                    found.reason(&z),
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
            if let Some(landed) = self.landing_root(z) {
                heading = Some(class_of(&landed.z));
            }
        }
        Diagnosis {
            text,
            reason,
            heading,
        }
    }

    /// The stable root the run at `z` lands on along its slow flow
    /// ([`crate::runs::landing`]), confirmed by Newton on all four equations and by its
    /// eigenvalues: the flow's root itself (speed and deformation equal to 1e-6; a flow's root
    /// on another mirror line than the run's, when the run was caught between them, to
    /// [`MAX_SETTLED`]). A flow's root unstable in its rotation mode is not landed on.
    /// Failing that, a run caught turning between two mirror lines ends where it turns to
    /// ([`Self::turn_root`]).
    pub fn landing_root(&mut self, z: [f64; 4]) -> Option<Finding> {
        for landing in landings(self.steady_solver().ok()?, z) {
            let Some((found, may_end)) = self.stable_root(landing.z) else {
                continue;
            };
            if found.turned {
                // The flow's root is unstable in its rotation mode: where the run ends depends
                // on how it turns while it speeds up or slows down (two stable orientations
                // can compete), which the one-dimensional flow does not follow. Time stepping
                // goes on; the Newton finish takes the run once it is near its root.
                continue;
            }
            let distance = invariant_distance(&found.z, &landing.z);
            // The flow's own root, or one the run turns to from it.
            let own = angle_to(&found.z, &landing.z).abs() <= ORIENTATION;
            let same = class_of(&found.z) == class_of(&landing.z)
                && distance <= if own { 1e-6 } else { MAX_SETTLED };
            if may_end && same {
                return Some(found);
            }
        }
        self.turn_root(z)
    }

    /// The root a run turning between the box's two mirror lines next to it ends on. The
    /// run's orientation is the slow coordinate (the near-neutral rotation mode); the
    /// roots on the two lines are the zeros of its flow next to it (by the box's symmetry).
    /// If one is stable and the other unstable in its rotation mode only, the run turns
    /// away from the second towards the first and ends there, provided that both roots have
    /// the run's class and the run's speed and deformation lie between theirs (within
    /// [`crate::runs::landing::FAMILY_TOL`]): it is on the circle of states joining them. Both
    /// stable (two orientations, each with its basin) or both unstable: no decision.
    pub fn turn_root(&mut self, z: [f64; 4]) -> Option<Finding> {
        let quarter = std::f64::consts::FRAC_PI_4;
        let phi = orientation(&z);
        let nearest = (phi / quarter).round() * quarter;
        let other = nearest + if phi >= nearest { quarter } else { -quarter };
        let class = class_of(&z);
        let mut roots = Vec::with_capacity(2);
        for target in [nearest, other] {
            let found = self.root_near(rotated(&z, target - phi)).ok()?;
            let on_line = (orientation(&found.z) - target).sin().abs() < 1e-6;
            if !on_line || class_of(&found.z) != class || found.verdict.unstable > 0 {
                return None;
            }
            roots.push(found);
        }
        let (b, a) = (roots.pop()?, roots.pop()?);
        let (run, ra, rb) = (
            speed_and_deformation(&z),
            speed_and_deformation(&a.z),
            speed_and_deformation(&b.z),
        );
        let tol = crate::runs::landing::FAMILY_TOL;
        let between = |x: f64, p: f64, q: f64| x >= p.min(q) - tol && x <= p.max(q) + tol;
        if !(between(run.0, ra.0, rb.0) && between(run.1, ra.1, rb.1)) {
            return None;
        }
        match (a.stable(), b.stable()) {
            (true, false) => Some(a),
            (false, true) => Some(b),
            _ => None,
        }
    }

    /// The root of a run caught mid-turn, between the box's mirror lines, where Newton from
    /// the run's own state need not converge: Newton from the state turned onto the nearest
    /// mirror line (motion or long axis at a multiple of 45 degrees), then onto the next one
    /// on the other side; the first stable root, else the first root found.
    pub fn aligned_root(&mut self, z: [f64; 4]) -> Option<Finding> {
        let quarter = std::f64::consts::FRAC_PI_4;
        let phi = orientation(&z);
        let nearest = (phi / quarter).round() * quarter;
        let other = nearest + if phi >= nearest { quarter } else { -quarter };
        let mut first = None;
        for target in [nearest, other] {
            let Ok(found) = self.root_near(rotated(&z, target - phi)) else {
                continue;
            };
            if found.stable() {
                return Some(found);
            }
            first.get_or_insert(found);
        }
        first
    }

    /// One judged window at time `t`: the state `z`, its change over the window (scaled to
    /// one window), and whether the paper's test fired.
    pub fn consider(&mut self, t: f64, z: [f64; 4], change: f64, test_fired: bool) -> Decision {
        if t < self.next_try || !(test_fired || change < self.trigger) {
            return Decision::Continue;
        }
        let found = self.stable_root(z);
        let Some((f, may_end)) = found else {
            // No root near (a run passing the ghost of a saddle-node, or caught mid-turn):
            // where its slow flow lands, else on by time stepping. The paper's test alone
            // never ends a run on a state that is not a stable root (numerics 4).
            if let Some(end) = self.land_now(z) {
                return end;
            }
            self.back_off(t);
            return Decision::Continue;
        };
        // The run's speed and deformation relax at the decisive rates: their distance to the
        // root's, against what the linear decay at the slowest decisive rate predicts from
        // the run's present change. Its orientation relaxes at the rotation rate, slowly: it
        // need only be within ORIENTATION of the root's, or closer to it than at the last try
        // (turning towards it), or the root be the turned one.
        let rate = f.verdict.max_re.abs().max(1e-12);
        let settled = invariant_distance(&z, &f.z)
            <= (10.0 * (change / self.window) / rate).min(MAX_SETTLED) + 1e-9;
        let turn = angle_to(&z, &f.z).abs();
        let turning_to = self.last_turn.is_some_and(|(root, before)| {
            root.iter().zip(&f.z).all(|(a, b)| (a - b).abs() < 1e-6) && turn < before
        });
        self.last_turn = Some((f.z, turn));
        let approaching = settled && (f.turned || turn <= ORIENTATION || turning_to);
        if may_end && (test_fired || approaching) {
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
        if let Some(diagnosis) = self.cannot_leave(t, &z, &f) {
            return Decision::Saddle(diagnosis);
        }
        if let Some(l) = self.departure(t, z, &f) {
            self.back_off(t + l.duration);
            return Decision::Leap(l);
        }
        self.back_off(t);
        Decision::Continue
    }

    /// With `landing`, the end of the run at `z` on the stable root its slow flow
    /// lands on ([`Self::landing_root`]).
    fn land_now(&mut self, z: [f64; 4]) -> Option<Decision> {
        if !self.landing {
            return None;
        }
        let found = self.landing_root(z)?;
        Some(Decision::End(Ending::Landing, found.z))
    }

    /// With `leap_departures`, the leap of a run at `z` (time `t`) leaving the saddle `f`
    /// along one growing mode, if the previous try saw it on that mode too.
    fn departure(&mut self, t: f64, z: [f64; 4], f: &Finding) -> Option<Leap> {
        if !self.leap_departures || f.verdict.unstable == 0 || f.turned {
            self.sighting = None;
            return None;
        }
        let now = Sighting { t, z, root: f.z };
        let before = self.sighting.replace(now)?;
        let l = leap(&before, &now, &f.verdict.eigenvalues, self.t_max)?;
        self.sighting = None;
        Some(l)
    }

    /// The run's steady solver, made at its first use.
    fn steady_solver(&mut self) -> Result<&mut SteadySolver, SolverError> {
        if self.solver.is_none() {
            self.solver = Some(SteadySolver::new(self.params, self.n)?);
        }
        Ok(self.solver.as_mut().expect("made above"))
    }

    /// The co-moving field of the steady state `root` (normalised coefficients, `[kx][ky]`):
    /// what a leap scales the run's field towards.
    pub fn root_field(&mut self, root: [f64; 4]) -> Result<Vec<Complex64>, SolverError> {
        Ok(self
            .steady_solver()?
            .field_and_forces(root[0], root[1], root[2], root[3])
            .0
            .to_vec())
    }

    /// With `stop_beside_saddle`, the diagnosis of a run at `z` (time `t`) beside the saddle
    /// `f` that it cannot leave before `t_max`: its distance grown at the largest rate stays
    /// below [`LEAVE`], and the class is the same everywhere within that distance.
    fn cannot_leave(&self, t: f64, z: &[f64; 4], f: &Finding) -> Option<String> {
        if !self.stop_beside_saddle || f.verdict.unstable == 0 || f.turned {
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

    fn back_off(&mut self, t: f64) {
        self.next_try = t + (0.25 * t).max(10.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let found = f.root_near([0.58, 0.05, -0.26, 0.02]).unwrap();
        let v = found.z[0].hypot(found.z[1]);
        assert!(v > 0.5 && v < 0.7, "{found:?}");
        // The resting disk is a root too, and unstable here (it deforms).
        let ic = f.root_near([1e-3, 0.0, 1e-3, 0.0]).unwrap();
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
    fn turning_a_state_turns_its_motion_once_and_its_shape_twice() {
        let z = [0.5, 0.1, -0.2, 0.05];
        let q = rotated(&rotated(&z, 0.3), 0.4);
        let direct = rotated(&z, 0.7);
        assert!(q.iter().zip(&direct).all(|(a, b)| (a - b).abs() < 1e-15));
        // 90 degrees: the velocity turns a quarter, the mode-2 shape changes sign.
        let r = rotated(&z, std::f64::consts::FRAC_PI_2);
        let expect = [-0.1, 0.5, 0.2, -0.05];
        assert!(
            r.iter().zip(&expect).all(|(a, b)| (a - b).abs() < 1e-15),
            "{r:?}"
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
        let axis = f.root_near([0.58, 0.0, -0.26, 0.0]).unwrap();
        // Turned by 20 degrees, between the x axis and the diagonal.
        let found = f
            .aligned_root(rotated(&axis.z, 20f64.to_radians()))
            .unwrap();
        let phi = orientation(&found.z) / std::f64::consts::FRAC_PI_4;
        assert!((phi - phi.round()).abs() < 1e-6, "{found:?}");
        let speed = |z: &[f64; 4]| z[0].hypot(z[1]);
        // The axis and diagonal states differ by the box's weak anisotropy only.
        assert!(
            (speed(&found.z) - speed(&axis.z)).abs() < 0.02,
            "{found:?} {axis:?}"
        );
        assert!(found.verdict.unstable == 0, "{found:?}");
    }
}
