//! The MD branch of the `K`-mode model ([`crate::roots::steady_solver`]) on the x axis (motion
//! along x, `b_k = 0`), followed in `eta_t` or `kappa2` by pseudo-arclength continuation of
//! `(v, a_2..a_K, q)`, and its fold (the saddle-node that bounds the bistable bands): where
//! the tangent's `q` component changes sign, located by bisection in arclength. The branch
//! along a whole line, with every state's stability and its events, is
//! [`crate::continuation::branch::follow`] (tested against this fold).
use crate::continuation::arclength::{
    point_at, start, ArclengthOptions, CurvePoint, Step, Stepper,
};
use crate::error::SolverError;
use crate::model::param::ModelParam;
use crate::model::params::ModelParams;
use crate::roots::named_state::md_state;
use crate::roots::steady_solver::{AxisState, SteadySolver};

/// A line in `eta_t` or `kappa2` for the `K`-mode MD branch.
#[derive(Debug, Clone)]
pub struct ModeLine {
    /// The parameters at the line's start (`parameter` = `from`).
    pub base: ModelParams,
    pub n: usize,
    /// Modes `2..=k_max`.
    pub k_max: usize,
    /// `EtaT` or `Kappa2`.
    pub parameter: ModelParam,
    pub from: f64,
    pub to: f64,
    /// The friction law of the modes `k >= 3` ([`crate::model::friction`]; 0: `eta_k =
    /// eta2`): it moves no state or fold, only the eigenvalues of the verdicts.
    pub eta_k_exponent: f64,
}

/// The fold of a `K`-mode MD branch.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ModeFold {
    /// The parameter's value there.
    pub at: f64,
    pub v: f64,
    /// `a_k` for `k = 2..=K`.
    pub a: Vec<f64>,
}

/// The fold between `p` and the accepted `step` after it along a curve `(.., q)` whose
/// tangent's `q` component changes sign there: that component's root in arclength, by
/// Illinois regula falsi ([`crate::numerics::bracket::illinois`]: it is linear in arclength
/// near a fold, so about 6 correctors reach `1e-13` where bisection takes 40). The step's
/// point if a corrector fails.
pub(crate) fn fold_point(
    f: &mut impl FnMut(&[f64]) -> Vec<f64>,
    p: &CurvePoint,
    step: &Step,
    opts: &ArclengthOptions,
) -> CurvePoint {
    let q_of = |p: &CurvePoint| *p.tangent.last().expect("q");
    let mut corrected: Vec<(f64, CurvePoint)> = Vec::new();
    let mut q_at = |s: f64| match point_at(f, p, s, opts) {
        Some((c, _)) => {
            let q = q_of(&c);
            corrected.push((s, c));
            q
        }
        None => f64::NAN,
    };
    let root = crate::numerics::bracket::illinois(
        &mut q_at,
        (0.0, q_of(p)),
        (step.ds, q_of(&step.point)),
        1e-13,
    );
    match root {
        Some(s) => corrected
            .into_iter()
            .min_by(|a, b| (a.0 - s).abs().total_cmp(&(b.0 - s).abs()))
            .filter(|(at, _)| *at == s)
            .map_or_else(
                || point_at(f, p, s, opts).map_or(step.point.clone(), |(c, _)| c),
                |(_, c)| c,
            ),
        None => step.point.clone(),
    }
}

/// Follows the MD branch from `line.from` towards `line.to` ([`md_state`] there) and returns
/// its first fold, if it has one before the line's end or the branch's meeting with the
/// resting state (`v -> 0`).
pub fn md_fold(line: &ModeLine) -> Result<Option<ModeFold>, SolverError> {
    let mut solver = SteadySolver::new(line.base, line.n)?;
    let st = md_state(&mut solver, line.k_max)?;
    md_fold_from(line, solver, &st)
}

/// [`md_fold`] from the MD state `st` at the line's start, found by `solver` (its
/// parameters the line's `base`).
pub fn md_fold_from(
    line: &ModeLine,
    mut solver: SteadySolver,
    st: &AxisState,
) -> Result<Option<ModeFold>, SolverError> {
    let span = line.to - line.from;
    let base = line.base;
    let parameter = line.parameter;
    let mut f = |y: &[f64]| {
        let q = *y.last().expect("q");
        let p = parameter.with(&base, line.from + q * span);
        solver.set_control(p.eta_t, p.kappa2);
        solver.residual_x(&y[..y.len() - 1])
    };
    let y0: Vec<f64> = std::iter::once(st.v)
        .chain(st.a.iter().copied())
        .chain([0.0])
        .collect();
    let opts = ArclengthOptions {
        ds_max: 0.02,
        ..ArclengthOptions::default()
    };
    let mut prev = vec![0.0; y0.len()];
    *prev.last_mut().expect("q") = 1.0;
    let Some(mut p) = start(&mut f, &y0, &prev, &opts) else {
        return Ok(None);
    };
    let q_of = |p: &CurvePoint| *p.tangent.last().expect("q");
    let mut stepper = Stepper::new(opts.clone());
    for _ in 0..2000 {
        let Some(step) = stepper.advance(&mut f, &p) else {
            return Ok(None);
        };
        let y = &step.point.y;
        let q = *y.last().expect("q");
        if !(0.0..=1.0).contains(&q) || y[0] < 1e-3 {
            return Ok(None);
        }
        if q_of(&step.point) * q_of(&p) < 0.0 {
            let best = fold_point(&mut f, &p, &step, &opts);
            let y = &best.y;
            let k = y.len() - 1;
            return Ok(Some(ModeFold {
                at: line.from + y[k] * span,
                v: y[0],
                a: y[1..k].to_vec(),
            }));
        }
        p = step.point;
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::continuation::branch::{follow, Line};
    use crate::continuation::problem::Family;
    use crate::roots::steady_solver::MirrorAxis;

    /// The MD branch along eta_t at kappa2 = 0.13 from 0.077, by [`md_fold`] and by the one
    /// continuation ([`follow`]) with modes `2..=k_max`.
    fn both(k_max: usize, n: usize) -> (ModeFold, crate::continuation::branch::Branch) {
        let base = ModelParams::at(0.077, 0.13);
        let line = ModeLine {
            base,
            n,
            k_max,
            parameter: ModelParam::EtaT,
            from: 0.077,
            to: 0.1,
            eta_k_exponent: 0.0,
        };
        let fold = md_fold(&line).unwrap().expect("a fold");
        let branch = follow(
            &Line {
                base,
                n,
                parameter: ModelParam::EtaT,
                from: 0.077,
                to: 0.1,
                modes: k_max,
                eta_k_exponent: 0.0,
                max_points: 400,
                opts: ArclengthOptions::default(),
            },
            Family::MdMinor,
            MirrorAxis::X,
        )
        .unwrap();
        (fold, branch)
    }

    #[test]
    fn the_continuation_folds_where_the_fold_search_does_and_loses_stability_there() {
        // Two computations of one fold: the fold search here (its own arclength walk from the
        // line's start, the tangent's q component bracketed) and the continuation's SN event
        // (located on its own branch by the Illinois method), with modes 2..2 and 2..3 at
        // N = 96 (the 2-mode branch folds at 0.0792728 at N = 192, docs/continuation.md).
        for k_max in [2, 3] {
            let (fold, branch) = both(k_max, 96);
            // md_fold returns the first fold from the line's start, where the continuation
            // starts too (its backward trace leaves the line at once).
            let sns: Vec<_> = branch.events.iter().filter(|e| e.kind == "SN").collect();
            let sn = &sns.first().expect("a fold").point;
            assert!((fold.at - sn.at).abs() < 1e-9, "{fold:?} vs {}", sn.at);
            assert!((fold.v - sn.v).abs() < 1e-6, "{fold:?} vs {:?}", sn.z);
            for (a, b) in fold.a.iter().zip(sn.a_k()) {
                assert!((a - b).abs() < 1e-6, "{fold:?} vs {:?}", sn.z);
            }
            // Every fold is a change of stability and every change a fold (no other event on
            // this line): one real eigenvalue passes through zero at each, the rotation mode
            // aside.
            assert_eq!(sns.len(), branch.events.len(), "{:?}", branch.events);
            let stable: Vec<bool> = branch.points.iter().map(|p| p.verdict.stable()).collect();
            let changes = stable.windows(2).filter(|w| w[0] != w[1]).count();
            assert_eq!(changes, sns.len(), "K = {k_max}: {stable:?}");
            let near_zero = sn
                .verdict
                .eigenvalues
                .iter()
                .filter(|l| l[1].abs() < 1e-9 && Some(l[0]) != sn.verdict.rotation)
                .map(|l| l[0].abs())
                .fold(f64::INFINITY, f64::min);
            assert!(near_zero < 1e-4, "K = {k_max}: {:?}", sn.verdict);
        }
    }
}
