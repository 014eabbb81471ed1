//! One branch of steady states followed along a parameter line with its stability, and its
//! bifurcation points (the PDE's Fig. 3b): a root of the family is found somewhere on the line
//! ([`Problem::root_at`]) and followed both ways by pseudo-arclength continuation
//! ([`crate::continuation::arclength`]) until the line's ends, the branch's end on another
//! family (`v -> 0`: it meets IC or ID), a deformation beyond the 2-mode model, or a loss of
//! convergence, each reported.
//!
//! Events between two accepted points, each located on the branch by the Illinois method in
//! arclength (to `1e-12` in arclength, far below `1e-7` in the parameter):
//! - `SN`: the parameter component of the tangent changes sign (a fold);
//! - `P`: a real eigenvalue crosses zero (the rotation mode excluded), or the branch ends on
//!   IC / ID (`v = 0`, or `c = 0` for ID);
//! - `H`: a complex pair crosses zero (an oscillating state would bifurcate: new physics).
use crate::continuation::arclength::{start, ArclengthOptions, CurvePoint, Stepper};
use crate::continuation::problem::{Family, Problem};
use crate::error::SolverError;
use crate::model::classify::StateClass;
use crate::model::mirror::MirrorLine;
use crate::model::param::ModelParam;
use crate::model::params::ModelParams;
use crate::model::state::speed_and_deformation;
use crate::roots::balances::Balances;
use crate::roots::verdict::Verdict;
use serde::Serialize;

/// A line of parameter values and how to follow a branch along it.
#[derive(Debug, Clone)]
pub struct Line {
    /// Parameters (the varied one is overwritten), the model's shape modes `2..=base.modes`
    /// and the friction law of the modes `k >= 3` (eigenvalues only,
    /// [`crate::model::friction`]) among them.
    pub base: ModelParams,
    pub n: usize,
    /// The varied parameter (any model parameter: `eta2` and `mass` move the eigenvalues
    /// only, so their branches are level in the state).
    pub parameter: ModelParam,
    pub from: f64,
    pub to: f64,
    /// Most points per direction.
    pub max_points: usize,
    pub opts: ArclengthOptions,
}

/// One state of a branch.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BranchPoint {
    /// The varied parameter's value.
    pub at: f64,
    pub eta_t: f64,
    pub kappa2: f64,
    /// `(vx, vy, a_2..a_K, b_2..b_K)`; `(vx, vy, a2, b2)` for `K = 2`.
    pub z: Vec<f64>,
    pub v: f64,
    /// The mode-2 deformation `sqrt(a2^2 + b2^2)` (the paper's `s`).
    pub s: f64,
    /// The paper's class of the state (thresholds 0.01).
    pub class: StateClass,
    pub verdict: Verdict,
}

impl BranchPoint {
    /// The shape amplitudes `a_2..a_K` of the state.
    pub fn a_k(&self) -> &[f64] {
        let k_max = self.z.len() / 2;
        &self.z[2..k_max + 1]
    }

    /// The shape amplitudes `b_2..b_K` of the state.
    pub fn b_k(&self) -> &[f64] {
        let k_max = self.z.len() / 2;
        &self.z[k_max + 1..]
    }
}

/// A bifurcation point on a branch.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BranchEvent {
    /// `P`, `SN` or `H`; `R` where the count of growing modes changes because the rotation
    /// mode passes the rate the verdict sets aside ([`crate::roots::verdict::ROTATION_MAX`]).
    pub kind: &'static str,
    /// What happens there, e.g. "fold", "real eigenvalue crosses 0", "meets IC".
    pub what: String,
    pub point: BranchPoint,
    /// The crossing eigenvalue at the event (`[re, im]`; `im` is the frequency at a Hopf
    /// point), for `P` / `H` by eigenvalue.
    pub eigenvalue: Option<[f64; 2]>,
    /// How far the event may lie from `point` in the varied parameter: the width of the last
    /// bracket of the location (at least the parameter's rounding on the line), or the whole
    /// step when the location failed. `0` for a meeting solved as a root. Events are
    /// trusted at [`EVENT_PRECISION`] or better.
    pub precision: f64,
}

/// The precision in the varied parameter that events are located to on a line within
/// [`PARAMETER_LIMIT`]; an event located worse than this is reported as such.
pub const EVENT_PRECISION: f64 = 1e-7;

/// Largest `eta_t` or `kappa2` a continuation line or a boundary window may reach. Far beyond
/// the paper's window (0.07-0.10 and 0.10-0.17), and small enough that the location of an
/// event (to 1e-12 in arclength on a line scaled to `[0, 1]`) stays below 1e-10 in the
/// parameter: on a line from 0.07 to 1e10 the onset of motion would be off by 2e-3.
pub const PARAMETER_LIMIT: f64 = 10.0;

/// A followed branch.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Branch {
    pub family: Family,
    pub mirror: MirrorLine,
    /// In order along the branch.
    pub points: Vec<BranchPoint>,
    pub events: Vec<BranchEvent>,
    /// How the branch ends, at its first and at its last point.
    pub ends: [String; 2],
}

/// The scaled parameter `q` of a point (the last unknown; 0 and 1 at the line's ends).
pub(super) fn q_of(p: &CurvePoint) -> f64 {
    *p.y.last().expect("q")
}

/// Where a branch stops although the step still converged.
pub(super) enum Stop {
    /// Left the line at `q = 0` or `1`.
    Range(f64),
    /// `v` (or `c` for ID) reached zero: the branch meets IC or ID.
    Meets,
    /// Deformation at or beyond this (outside the 2-mode model).
    Deformation,
}

/// Largest deformation followed.
pub const MAX_DEFORMATION: f64 = 0.9;

pub(super) struct Tracer<'a> {
    pub(super) prob: &'a mut Problem,
    pub(super) opts: ArclengthOptions,
}

impl Tracer<'_> {
    pub(super) fn point(&mut self, y: &[f64], verdict: Verdict) -> BranchPoint {
        let p = self.prob.params_at(*y.last().expect("q"));
        let z = self.prob.state(y);
        let (v, s) = speed_and_deformation(&z);
        BranchPoint {
            at: self.prob.parameter.get(&p),
            eta_t: p.eta_t,
            kappa2: p.kappa2,
            z,
            v,
            s,
            class: StateClass::of(v, s),
            verdict,
        }
    }

    /// Follows the branch from `first` (tangent oriented) until it stops.
    fn trace(
        &mut self,
        first: CurvePoint,
        max_points: usize,
    ) -> (Vec<BranchPoint>, Vec<BranchEvent>, String) {
        let family = self.prob.family;
        let mut stepper = Stepper::new(self.opts.clone());
        let first_verdict = self.prob.verdict(&first.y);
        let mut out = vec![self.point(&first.y, first_verdict.clone())];
        let mut events = Vec::new();
        let (mut a, mut va) = (first, first_verdict);
        let along = |p: &CurvePoint| -> f64 {
            match family {
                Family::IC => 1.0,
                Family::ID => p.y[0],
                Family::MdMinor | Family::MdMajor => p.y[0],
            }
        };
        let end = loop {
            if out.len() >= max_points {
                break format!("stopped after {max_points} points (--max-points)");
            }
            let prob = &mut *self.prob;
            let Some(step) = stepper.advance(&mut |y: &[f64]| prob.residual(y), &a) else {
                let at = self.prob.value(q_of(&a));
                break format!(
                    "no convergence beyond {} = {at:.7} (step below {:e})",
                    self.prob.parameter, self.opts.ds_min
                );
            };
            let b = step.point;
            let (_, cb) = self.prob.speed_and_shape(&b.y);
            let stop = if !(0.0..=1.0).contains(&q_of(&b)) {
                Some(Stop::Range(if q_of(&b) < 0.0 { 0.0 } else { 1.0 }))
            } else if family != Family::IC && along(&b).signum() != along(&a).signum() {
                Some(Stop::Meets)
            } else if cb.abs() >= MAX_DEFORMATION {
                Some(Stop::Deformation)
            } else {
                None
            };
            if let Some(stop) = stop {
                break self.finish_at(stop, (&a, &b), step.ds, &mut out, &mut events);
            }
            let vb = self.prob.verdict(&b.y);
            events.extend(self.event_between((&a, &va), (&b, &vb), step.ds));
            out.push(self.point(&b.y, vb.clone()));
            a = b;
            va = vb;
        };
        (out, events, end)
    }
}

/// Follows `family` on `mirror` along `line`. Errors: bad parameters, or no state of the
/// family found anywhere on the line.
pub fn follow(line: &Line, family: Family, mirror: MirrorLine) -> Result<Branch, SolverError> {
    let balances = Balances::new(line.base, line.n)?;
    let mut prob = Problem::new(balances, family, mirror, line.parameter, line.from, line.to);
    // Where to look for a first state: the ends, then ever finer points in between.
    let qs = [0.0, 1.0, 0.5, 0.25, 0.75, 0.125, 0.375, 0.625, 0.875];
    let y0 = qs
        .iter()
        .find_map(|&q| prob.root_at(prob.value(q)))
        .ok_or(SolverError::NoBranch {
            family: family.as_str(),
        })?;
    let k = y0.len();
    let mut e_q = vec![0.0; k];
    let opts = line.opts.clone();
    let mut traces = Vec::new();
    for sign in [-1.0, 1.0] {
        e_q[k - 1] = sign;
        let first = {
            let prob = &mut prob;
            start(&mut |y: &[f64]| prob.residual(y), &y0, &e_q, &opts)
        };
        let Some(first) = first else {
            traces.push((
                Vec::new(),
                Vec::new(),
                "singular at the first state".to_string(),
            ));
            continue;
        };
        let mut tracer = Tracer {
            prob: &mut prob,
            opts: opts.clone(),
        };
        traces.push(tracer.trace(first, line.max_points));
    }
    let (back, fwd) = (traces.remove(0), traces.remove(0));
    let mut points: Vec<BranchPoint> = back.0.into_iter().rev().collect();
    // The first state is in both traces.
    points.extend(fwd.0.into_iter().skip(usize::from(!points.is_empty())));
    let mut events = back.1;
    events.reverse();
    events.extend(fwd.1);
    Ok(Branch {
        family,
        mirror,
        points,
        events,
        ends: [back.2, fwd.2],
    })
}
