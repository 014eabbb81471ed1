//! Points of a refined map certified without runs (`refine.certify_midpoints`, off by
//! default).
//!
//! Refinement adds the midpoints of a split cell's edges and its centre; many lie midway
//! between two coarser points of one state: an edge midpoint between the ends of its edge
//! (the edge of a cell whose other corners differ), a centre between two opposite corners of
//! its cell (one diagonal of a cell with three corners of one state), the pairs
//! [`crate::map::refine::midway`] lists, tried in turn ([`first_candidate`]). Such a point's
//! runs are not stepped when all of this holds for one pair:
//! - the two neighbours' runs all ended steady on one class `C` (IC, ID or MD), so both are
//!   single-state points of that class; with `certify_midpoints: true` every one of those
//!   runs was stepped, with `chained` a neighbour may have been certified itself (its runs'
//!   ends are then the roots its own certificate continued, and every chain of certificates
//!   starts at points whose runs were stepped, at the latest the corners of the level-0 cell
//!   around the point);
//! - at the point, the runs' Newton finish from the end of each neighbour's run from the same
//!   initial condition reaches, from both neighbours, one root (`v`, `s` within
//!   1e-6) of class `C` with no growing eigenvalue, the rotation mode included (a root
//!   unstable only in rotation is left by the run's own stepping, slowly, for another
//!   orientation the grid pins); for IC, the resting disk's own eigenvalues;
//! - no other class has a stable steady state there among those the audit and `droplet
//!   stability` know: the resting disk (its eigenvalues), ID and MD on both mirror axes
//!   ([`droplet_solver::roots::named_state::find`]).
//!
//! Each run of the point then ends, without a step, on the root continued from its
//! neighbours' ends (`ended_by: certified_midway`, `steps` 0, `t_end` 0, position 0, `wall_s`
//! the certificate's time shared by its runs). Anything else (a failed Newton, two roots, a
//! second stable class, a model whose balances cannot be linearised) leaves the point to its
//! runs. What is proven is the point's state set among the named states, not that every
//! initial condition reaches `C`: a state that is none of them (a periodic orbit, a root off
//! the mirror axes of another class) is not looked for, which is why the option is off by
//! default and a map says how many of its runs were certified (the summary, `ended_by`).
//! The end of a moving or deformed run is one stable root of its class, the neighbours'
//! orientation: where the grid pins the droplet at several orientations, the run's own
//! stepping may reach another (measured at N = 96 before roots unstable in rotation were
//! refused: 5 of 932 certified runs, up to 1.6e-2 in `v`; the class was the stepped runs' in
//! all 932; results/map-profile, "Points certified without runs"; at N = 192, with the
//! rotation rule, `droplet bench --map --certify` finds every certified run of the committed
//! 2-mode and 4-mode maps on its own run's root). The resting disk has no orientation: a
//! certified IC run's end is exact.
use crate::spec::lattice::Certify;
use crate::store::plan::Plan;
use crate::store::run_store::RunRecord;
use droplet_solver::contract::ending::Ending;
use droplet_solver::contract::outcome::{RunOutcome, RunStatus};
use droplet_solver::model::classify::StateClass;
use droplet_solver::model::mirror::MirrorLine;
use droplet_solver::model::params::ModelParams;
use droplet_solver::model::state::{speed_and_deformation, DropletState};
use droplet_solver::roots::balances::Balances;
use droplet_solver::roots::kept_jacobians::KeptJacobians;
use droplet_solver::roots::named_state::{find, StateKind};
use std::collections::HashMap;
use std::time::Instant;

/// Two roots closer than this in `v` and `s` are one.
pub const SAME_ROOT: f64 = 1e-6;

/// Why a point was left to its runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Refusal {
    /// Not a candidate: the neighbours' runs did not all end steady on one class IC, ID or MD
    /// (the usual case: the edge of a cell whose corners differ). Not counted as a refusal.
    NotCandidate,
    /// A neighbour's runs were certified themselves, not stepped (`certify_midpoints: true`;
    /// `chained` accepts them).
    NeighbourCertified,
    /// The model's steady balances cannot be set up or linearised at the point (no inertia).
    Balances,
    /// The resting disk is stable at a point of another class, or unstable at an IC one.
    Disk,
    /// ID or MD of another class is stable at the point.
    OtherState,
    /// Newton from a neighbour's end finds no stable root of the class.
    NoRoot,
    /// The root it finds is stable but for its rotation mode: the runs turn away from it.
    Turns,
    /// The two neighbours' ends continue to different roots.
    TwoRoots,
}

impl Refusal {
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::NotCandidate => "not_candidate",
            Self::NeighbourCertified => "neighbour_certified",
            Self::Balances => "balances",
            Self::Disk => "disk",
            Self::OtherState => "other_state",
            Self::NoRoot => "no_root",
            Self::Turns => "turns",
            Self::TwoRoots => "two_roots",
        }
    }
}

/// One neighbour run's end as the certificate reads it.
#[derive(Debug, Clone)]
pub struct End {
    /// Its class if it ended steady.
    pub class: Option<StateClass>,
    /// It was certified itself, not stepped.
    pub certified: bool,
    /// Its end `(vx, vy, a_2..a_K, b_2..b_K)`.
    pub z: Vec<f64>,
}

impl End {
    fn of(o: &RunOutcome) -> Self {
        Self {
            class: o.class.filter(|_| o.status == RunStatus::Steady),
            certified: o.ended_by == Some(Ending::Certified),
            z: o.unknowns(),
        }
    }
}

/// The certificate at a point of the model `params` on an `n` grid from the ends of its two
/// neighbours' runs (`a`, `b`: one per initial condition, in the same order) under `mode`:
/// the class and each run's end, or why it does not hold (see the module).
pub fn certify_ends(
    params: ModelParams,
    n: usize,
    a: &[End],
    b: &[End],
    mode: Certify,
) -> Result<(StateClass, Vec<Vec<f64>>), Refusal> {
    let class = single_class(a.iter().chain(b)).ok_or(Refusal::NotCandidate)?;
    if mode != Certify::Chained && a.iter().chain(b).any(|e| e.certified) {
        return Err(Refusal::NeighbourCertified);
    }
    // The named states' eigenvalues need inertia (`find` refuses `m = 0`, which would
    // otherwise read as "no other state").
    if params.mass <= 0.0 {
        return Err(Refusal::Balances);
    }
    let mut balances = Balances::new(params, n).map_err(|_| Refusal::Balances)?;
    let disk_stable = balances.verdict(&vec![0.0; 2 * balances.modes()]).unstable == 0;
    if disk_stable != (class == StateClass::IC) {
        return Err(Refusal::Disk);
    }
    if !others_unstable(&mut balances, class) {
        return Err(Refusal::OtherState);
    }
    let mut jacobians = KeptJacobians::default();
    let mut ends = Vec::with_capacity(a.len());
    for (ea, eb) in a.iter().zip(b) {
        let end = if class == StateClass::IC {
            vec![0.0; 2 * balances.modes()]
        } else {
            let mut root = |e: &End| stable_root(&mut balances, &mut jacobians, &e.z, class);
            let (za, zb) = (root(ea)?, root(eb)?);
            let (va, sa) = speed_and_deformation(&za);
            let (vb, sb) = speed_and_deformation(&zb);
            if (va - vb).abs() > SAME_ROOT || (sa - sb).abs() > SAME_ROOT {
                return Err(Refusal::TwoRoots);
            }
            za
        };
        ends.push(end);
    }
    Ok((class, ends))
}

/// The first of `pairs` whose two points are a candidate ([`Refusal::NotCandidate`] if none
/// is): `certify` of each pair in turn, until one certifies or refuses.
pub fn first_candidate<P: Copy, T>(
    pairs: &[P],
    mut certify: impl FnMut(P) -> Result<T, Refusal>,
) -> Result<T, Refusal> {
    for &pair in pairs {
        match certify(pair) {
            Err(Refusal::NotCandidate) => continue,
            decided => return decided,
        }
    }
    Err(Refusal::NotCandidate)
}

/// The records of the runs of plan point `p`, certified without runs from the stored runs of
/// the points `pair` it lies midway between, or why the certificate does not hold (see the
/// module).
pub fn certify(
    plan: &Plan,
    p: usize,
    pair: [usize; 2],
    records: &HashMap<String, RunRecord>,
    mode: Certify,
) -> Result<Vec<RunRecord>, Refusal> {
    let started = Instant::now();
    let per_point = plan.ic_names.len().max(1);
    let ends_of = |q: usize| -> Result<Vec<End>, Refusal> {
        (0..per_point)
            .map(|i| {
                let r = records.get(&plan.task(q * per_point + i).key);
                r.map(|r| End::of(&r.outcome))
            })
            .collect::<Option<_>>()
            .ok_or(Refusal::NotCandidate)
    };
    let (a, b) = (ends_of(pair[0])?, ends_of(pair[1])?);
    let task0 = plan.task(p * per_point);
    let (class, ends) = certify_ends(task0.params, task0.settings.n, &a, &b, mode)?;
    let wall_s = started.elapsed().as_secs_f64() / per_point as f64;
    Ok(ends
        .into_iter()
        .enumerate()
        .map(|(i, z)| {
            let task = plan.task(p * per_point + i);
            RunRecord {
                key: task.key.clone(),
                params: task.params,
                ic: task.ic.clone(),
                settings: task.settings,
                solver_version: droplet_solver::solver_version(
                    task.settings.model,
                    task.params.modes,
                )
                .to_string(),
                outcome: outcome(&z, class, wall_s),
            }
        })
        .collect())
}

/// The one class every end is steady on, if it is IC, ID or MD.
fn single_class<'a>(ends: impl Iterator<Item = &'a End>) -> Option<StateClass> {
    let mut class = None;
    for e in ends {
        let c = e.class?;
        if *class.get_or_insert(c) != c {
            return None;
        }
    }
    class.filter(|c| matches!(c, StateClass::IC | StateClass::ID | StateClass::MD))
}

/// The runs' Newton finish from `z` ([`Balances::root_near`], with the Jacobians kept at the
/// point), if it reaches a state of `class` stable in every mode, rotation included.
fn stable_root(
    balances: &mut Balances,
    jacobians: &mut KeptJacobians,
    z: &[f64],
    class: StateClass,
) -> Result<Vec<f64>, Refusal> {
    let x = balances
        .root_near(z, jacobians)
        .map_err(|_| Refusal::NoRoot)?;
    let (v, s) = speed_and_deformation(&x);
    let verdict = balances.verdict(&x);
    if StateClass::of(v, s) != class || !verdict.stable() {
        return Err(Refusal::NoRoot);
    }
    if !verdict.decays() {
        return Err(Refusal::Turns);
    }
    Ok(x)
}

/// Whether ID and MD, on both mirror axes, are absent or unstable here unless they are
/// `class` (a named state found of another class than asked counts by its own class).
fn others_unstable(balances: &mut Balances, class: StateClass) -> bool {
    for kind in [StateKind::ID, StateKind::MD] {
        for axis in [MirrorLine::X, MirrorLine::Diagonal] {
            let Ok(state) = find(balances, kind, axis, None) else {
                continue;
            };
            let (v, s) = speed_and_deformation(&state.z);
            if state.verdict.unstable == 0 && StateClass::of(v, s) != class {
                return false;
            }
        }
    }
    true
}

/// The outcome of a certified run ending on `z`.
fn outcome(z: &[f64], class: StateClass, wall_s: f64) -> RunOutcome {
    let (v, s) = speed_and_deformation(z);
    let (state, higher_modes) = DropletState::of_unknowns(z, 0.0, 0.0);
    RunOutcome {
        status: RunStatus::Steady,
        class: Some(class),
        state,
        v,
        s,
        t_end: 0.0,
        t_steady: None,
        steps: 0,
        rejected: 0,
        max_step_error: None,
        wall_s,
        ended_by: Some(Ending::Certified),
        diagnosis: None,
        t_leapt: 0.0,
        t_projected: 0.0,
        unsettled: None,
        heading: None,
        higher_modes,
        series: Vec::new(),
        higher_series: Vec::new(),
        profile: Default::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn end(class: Option<StateClass>, certified: bool) -> End {
        End {
            class,
            certified,
            z: vec![0.0; 4],
        }
    }

    #[test]
    fn only_neighbours_of_one_single_state_are_candidates_and_certified_ones_only_chained() {
        let p = ModelParams::default();
        let ic = |c| vec![end(Some(StateClass::IC), c); 4];
        // Two classes, an unsettled run, or a class the certificate does not know: not a
        // candidate; a certified neighbour: refused before anything is solved.
        let mut mixed = ic(false);
        mixed[2] = end(Some(StateClass::MD), false);
        let mut unsettled = ic(false);
        unsettled[0] = end(None, false);
        let mc = vec![end(Some(StateClass::MC), false); 4];
        for b in [mixed, unsettled] {
            assert_eq!(
                certify_ends(p, 64, &ic(false), &b, Certify::Stepped),
                Err(Refusal::NotCandidate)
            );
        }
        assert_eq!(
            certify_ends(p, 64, &mc, &mc, Certify::Chained),
            Err(Refusal::NotCandidate)
        );
        assert_eq!(
            certify_ends(p, 64, &ic(false), &ic(true), Certify::Stepped),
            Err(Refusal::NeighbourCertified)
        );
        // Chained, a certified neighbour is read as a stepped one.
        assert_ne!(
            certify_ends(p, 64, &ic(false), &ic(true), Certify::Chained),
            Err(Refusal::NeighbourCertified)
        );
    }

    #[test]
    fn a_root_unstable_only_in_rotation_is_not_certified() {
        // MD on the x axis at N = 96: at kappa2 = 0.105 stable in rotation too (-4.1e-3), at
        // 0.11 stable but for its rotation mode (+4.5e-2, inside the verdict's rotation
        // band): runs leave it, turning slowly.
        let at = |kappa2| {
            let p = ModelParams {
                kappa2,
                ..ModelParams::default()
            };
            let mut balances = Balances::new(p, 96).unwrap();
            let md = find(&mut balances, StateKind::MD, MirrorLine::X, None).unwrap();
            let rotation = md.verdict.rotation.unwrap();
            let ends = vec![
                End {
                    class: Some(StateClass::MD),
                    certified: false,
                    z: md.z.clone(),
                };
                4
            ];
            (
                certify_ends(p, 96, &ends, &ends, Certify::Stepped),
                md.z,
                rotation,
            )
        };
        let (held, z, rotation) = at(0.105);
        assert!(rotation < 0.0, "{rotation}");
        let (class, ends) = held.unwrap();
        assert_eq!(class, StateClass::MD);
        for end in ends {
            let gap = end
                .iter()
                .zip(&z)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(gap < 1e-9, "{gap}");
        }
        let (turns, _, rotation) = at(0.11);
        assert!(rotation > 0.0, "{rotation}");
        assert_eq!(turns.unwrap_err(), Refusal::Turns);
    }
}
