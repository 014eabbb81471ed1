//! The events along a branch, located on it: a fold (SN), a change in the number of unstable
//! eigenvalues (P, or H for a complex pair), the end of the line, the meeting with another
//! family; each by bisection on the arclength between two consecutive states. Where the count
//! changes because the near-neutral rotation mode passes the largest rate the verdict sets
//! aside as rotation ([`ROTATION_MAX`]), no eigenvalue crosses zero: that switch is reported
//! as its own kind, R.
use crate::continuation::arclength::{point_at, CurvePoint};
use crate::continuation::branch::{q_of, BranchEvent, BranchPoint, Stop, Tracer, MAX_DEFORMATION};
use crate::continuation::problem::{Family, Problem};
use crate::roots::verdict::{Verdict, ROTATION_MAX};

/// Largest `|Re lambda|` of the crossing eigenvalue at a located P or H event: located to
/// `1e-12` in arclength it is below `1e-10` (every committed 2-mode event); beyond this the
/// count changed by another eigenvalue than the one located.
const CROSSING_TOLERANCE: f64 = 1e-6;

impl Tracer<'_> {
    /// The point between `a` (`g(a) = ga`) and `b`, `a`'s arclength `ds` further (`g = gb`,
    /// opposite sign), where `g` vanishes: the Illinois variant of regula falsi in arclength.
    /// Returns it with its precision in the varied parameter (the last bracket's width);
    /// when no point inside could be corrected, `b` itself with the whole step's width.
    pub(super) fn locate(
        &mut self,
        (a, b): (&CurvePoint, &CurvePoint),
        ds: f64,
        (ga, gb): (f64, f64),
        g: &mut dyn FnMut(&mut Problem, &CurvePoint) -> f64,
    ) -> (CurvePoint, f64) {
        let (mut lo, mut hi, mut glo, mut ghi) = (0.0, ds, ga, gb);
        let (mut q_lo, mut q_hi) = (q_of(a), q_of(b));
        let mut side = 0i32;
        let mut best: Option<CurvePoint> = None;
        let mut exact = false;
        for _ in 0..60 {
            let s = if (ghi - glo).abs() > 0.0 {
                (lo * ghi - hi * glo) / (ghi - glo)
            } else {
                0.5 * (lo + hi)
            };
            let s = if s > lo && s < hi { s } else { 0.5 * (lo + hi) };
            let prob = &mut *self.prob;
            let Some((p, _)) = point_at(&mut |y: &[f64]| prob.residual(y), a, s, &self.opts) else {
                break;
            };
            let gs = g(self.prob, &p);
            let qs = q_of(&p);
            best = Some(p);
            if gs == 0.0 {
                exact = true;
                break;
            }
            if gs.signum() == glo.signum() {
                (lo, glo, q_lo) = (s, gs, qs);
                if side == -1 {
                    ghi *= 0.5;
                }
                side = -1;
            } else {
                (hi, ghi, q_hi) = (s, gs, qs);
                if side == 1 {
                    glo *= 0.5;
                }
                side = 1;
            }
            if (hi - lo) < 1e-12 {
                break;
            }
        }
        let span = self.prob.span.abs();
        let rounding = span * f64::EPSILON * 4.0;
        match best {
            Some(p) if exact => (p, rounding),
            Some(p) => (p, ((q_hi - q_lo).abs() * span).max(rounding)),
            None => (b.clone(), ((q_of(b) - q_of(a)).abs() * span).max(rounding)),
        }
    }

    /// Where the trace ends by `stop` between `a` and `b` (the last step, of size `ds`): the
    /// end of the line located exactly, or the meeting with another family as a pitchfork
    /// event; returns why the branch ends.
    pub(super) fn finish_at(
        &mut self,
        stop: Stop,
        (a, b): (&CurvePoint, &CurvePoint),
        ds: f64,
        out: &mut Vec<BranchPoint>,
        events: &mut Vec<BranchEvent>,
    ) -> String {
        let family = self.prob.family;
        match stop {
            Stop::Range(bound) => {
                let (g0, g1) = (q_of(a) - bound, q_of(b) - bound);
                let mut g = |_: &mut Problem, p: &CurvePoint| q_of(p) - bound;
                let (p, _) = self.locate((a, b), ds, (g0, g1), &mut g);
                // Not when only the step beyond the end could be had.
                if (q_of(&p) - bound).abs() < 1e-9 {
                    let v = self.prob.verdict(&p.y);
                    out.push(self.point(&p.y, v));
                }
                "end of the line".to_string()
            }
            Stop::Meets => {
                let Some(y) = self.prob.meeting(&a.y) else {
                    return "meets another family (not located)".to_string();
                };
                let verdict = self.prob.verdict(&y);
                let pt = self.point(&y, verdict);
                let other = if family == Family::ID || pt.s < 1e-6 {
                    "IC"
                } else {
                    "ID"
                };
                events.push(BranchEvent {
                    kind: "P",
                    what: format!("meets {other}"),
                    point: pt.clone(),
                    eigenvalue: None,
                    precision: 0.0,
                });
                out.push(pt);
                format!("meets {other} (pitchfork)")
            }
            Stop::Deformation => format!("deformation reached {MAX_DEFORMATION}"),
        }
    }

    /// The bifurcation between two consecutive states `a` and `b` (verdicts `va`, `vb`, step
    /// `ds`), located on the branch: a fold (the tangent's parameter component changes sign)
    /// or a change in the number of unstable eigenvalues (P, or H for a complex pair).
    pub(super) fn event_between(
        &mut self,
        (a, va): (&CurvePoint, &Verdict),
        (b, vb): (&CurvePoint, &Verdict),
        ds: f64,
    ) -> Option<BranchEvent> {
        let tq = |p: &CurvePoint| *p.tangent.last().expect("q");
        if tq(a) != 0.0 && tq(b).signum() != tq(a).signum() {
            let mut g = |_: &mut Problem, p: &CurvePoint| tq(p);
            let (p, precision) = self.locate((a, b), ds, (tq(a), tq(b)), &mut g);
            let verdict = self.prob.verdict(&p.y);
            let pt = self.point(&p.y, verdict);
            Some(BranchEvent {
                kind: "SN",
                what: "fold".into(),
                point: pt,
                eigenvalue: None,
                precision,
            })
        } else if va.unstable != vb.unstable {
            let idx = va.unstable.min(vb.unstable);
            let re_at = |v: &Verdict| v.decisive().get(idx).map_or(-1.0, |l| l.re);
            let (g0, g1) = (re_at(va), re_at(vb));
            let mut g = |prob: &mut Problem, p: &CurvePoint| re_at(&prob.verdict(&p.y));
            let (p, precision) = self.locate((a, b), ds, (g0, g1), &mut g);
            let verdict = self.prob.verdict(&p.y);
            let lambda = verdict.decisive().get(idx).copied();
            let complex = lambda.is_some_and(|l| l.im.abs() > 1e-7);
            let crossed = lambda.is_some_and(|l| l.re.abs() < CROSSING_TOLERANCE);
            let (kind, what, eigenvalue, precision) =
                if !crossed && va.rotation.is_some() != vb.rotation.is_some() {
                    // The count changed because the rotation mode passed the largest rate the
                    // verdict sets aside as rotation: no eigenvalue crosses zero, the switch is
                    // located where it happens.
                    // Located to round-off, the point may lie just past the limit, where the
                    // verdict no longer sets the mode aside: its rate is then the real
                    // eigenvalue nearest the limit (not the rate at either end of the step).
                    let past = |l: f64| (l.abs() - ROTATION_MAX).abs();
                    let nearest = verdict
                        .eigenvalues
                        .iter()
                        .filter(|[_, im]| *im == 0.0)
                        .map(|[re, _]| *re)
                        .min_by(|a, b| past(*a).total_cmp(&past(*b)));
                    let rotation = verdict.rotation.or(nearest).or(va.rotation).or(vb.rotation);
                    (
                        "R",
                        format!(
                        "the rotation mode passes |lambda| = {ROTATION_MAX} (beyond it, it counts)"
                    ),
                        rotation.map(|r| [r, 0.0]),
                        precision,
                    )
                } else {
                    let (kind, what) = if complex {
                        ("H", "complex pair crosses 0 (Hopf)")
                    } else {
                        ("P", "real eigenvalue crosses 0")
                    };
                    // Not crossed: another eigenvalue than the one located changed the count (two
                    // crossing in one step, or a root the eigenvalue search missed on one side);
                    // the bracket located nothing, and the event is the whole step's.
                    let step = (q_of(b) - q_of(a)).abs() * self.prob.span.abs();
                    let precision = if crossed {
                        precision
                    } else {
                        step.max(precision)
                    };
                    (
                        kind,
                        what.to_string(),
                        lambda.map(|l| [l.re, l.im]),
                        precision,
                    )
                };
            let pt = self.point(&p.y, verdict);
            Some(BranchEvent {
                kind,
                what,
                point: pt,
                eigenvalue,
                precision,
            })
        } else {
            None
        }
    }
}
