//! The MD saddle-node curve (the fold that bounds the bistable bands) in a window of two model
//! parameters `(x, y)`, for the model with shape modes `2..K`: pseudo-arclength continuation
//! in `(v, a_2..a_K, qx, qy)` (the shape in the mirror line's frame, the parameters scaled to
//! the window) of the extended system `R(v, a; x, y) = 0, det dR/d(v, a) = 0`, started from a
//! fold located on a one-parameter MD branch followed in `x` at a fixed `y`. It ends where it
//! leaves the window or where `v -> 0` (the fold reaches the onset of motion: there the
//! pitchfork changes from sub- to supercritical).
use crate::continuation::arclength::{fold_point, start, ArclengthOptions, CurvePoint, Stepper};
use crate::continuation::branch::{follow, Branch, Line};
use crate::continuation::problem::{Family, Problem};
use crate::continuation::window::Axis;
use crate::error::SolverError;
use crate::model::mirror::MirrorLine;
use crate::model::params::ModelParams;
use crate::model::state::turned;
use crate::numerics::newton::fd_jacobian;
use crate::roots::balances::Balances;

/// The determinant of a square matrix: by its formula for `2 x 2`, else nalgebra's LU.
fn det(a: &[Vec<f64>]) -> f64 {
    match a.len() {
        2 => a[0][0] * a[1][1] - a[0][1] * a[1][0],
        k => nalgebra::DMatrix::from_fn(k, k, |i, j| a[i][j]).determinant(),
    }
}

/// The extended system of the MD fold: `y = (v, a_2..a_K, qx, qy)`.
struct FoldSystem {
    balances: Balances,
    mirror: MirrorLine,
    x: Axis,
    y: Axis,
    /// Scale of `det` (the Jacobian's size squared at the start).
    det_scale: f64,
}

impl FoldSystem {
    /// The state's unknowns `(v, a_2..a_K)`: `K` of them.
    fn unknowns(&self) -> usize {
        self.balances.modes()
    }

    fn control(&self, y: &[f64]) -> (f64, f64) {
        let k = self.unknowns();
        (self.x.value(y[k]), self.y.value(y[k + 1]))
    }

    /// Moves the balances to `y`'s parameters; false where they are invalid.
    fn place(&mut self, y: &[f64]) -> bool {
        let (a, b) = self.control(y);
        self.balances.set_param(self.x.param, a).is_ok()
            && self.balances.set_param(self.y.param, b).is_ok()
    }

    /// `dR/d(v, a)` at `y` (the balances placed there).
    fn jac(&mut self, y: &[f64]) -> Vec<Vec<f64>> {
        let (mirror, k) = (self.mirror, self.unknowns());
        let balances = &mut self.balances;
        fd_jacobian(
            &mut |x: &[f64]| balances.residual_on(mirror, x[0], &x[1..]),
            &y[..k],
            1e-6,
        )
    }

    fn residual(&mut self, y: &[f64]) -> Vec<f64> {
        let k = self.unknowns();
        if !self.place(y) {
            return vec![f64::NAN; k + 1];
        }
        let mut r = self.balances.residual_on(self.mirror, y[0], &y[1..k]);
        let j = self.jac(y);
        r.push(det(&j) / self.det_scale);
        r
    }
}

/// The MD branch on `mirror` along `x` at `y = at` (the other parameters `base`'s).
pub fn md_branch(
    base: &ModelParams,
    n: usize,
    mirror: MirrorLine,
    x: Axis,
    y: Axis,
    at: f64,
) -> Result<Branch, SolverError> {
    let line = Line {
        base: y.param.with(base, at),
        n,
        parameter: x.param,
        from: x.range.0,
        to: x.range.1,
        max_points: 400,
        opts: ArclengthOptions::default(),
    };
    follow(&line, Family::MdMinor, mirror)
}

/// An MD fold in a plane of two parameters.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Fold {
    /// The speed along the mirror line.
    pub v: f64,
    /// The shape `a_2..a_K` in the mirror line's frame.
    pub a: Vec<f64>,
    /// The two parameters there.
    pub x: f64,
    pub y: f64,
}

/// The first fold of the MD branch on `mirror` along `x` with `balances` (their parameters
/// those of the line `y = at`): from its state at `x`'s
/// start ([`Problem::root_at`]) towards `x`'s end by pseudo-arclength, located where the
/// tangent's parameter component changes sign ([`fold_point`]), before the branch leaves the
/// line or meets rest (`v` below 1e-3). No verdicts on the way: at `K > 2` a state's `2K x 2K`
/// eigenproblem costs more than its continuation step. `None` where the line's start has no
/// moving state or the branch no fold.
pub fn walk_to_fold(balances: Balances, mirror: MirrorLine, x: Axis, at: f64) -> Option<Fold> {
    let (from, to) = x.range;
    let mut prob = Problem::new(balances, Family::MdMinor, mirror, x.param, from, to);
    let y0 = prob.root_at(from)?;
    let opts = ArclengthOptions {
        ds_max: 0.02,
        ..ArclengthOptions::default()
    };
    let mut f = |y: &[f64]| prob.residual(y);
    let mut prev = vec![0.0; y0.len()];
    *prev.last_mut().expect("q") = 1.0;
    let mut p = start(&mut f, &y0, &prev, &opts)?;
    let q_of = |p: &CurvePoint| *p.tangent.last().expect("q");
    let mut stepper = Stepper::new(opts.clone());
    for _ in 0..2000 {
        let step = stepper.advance(&mut f, &p)?;
        let yv = &step.point.y;
        let q = *yv.last().expect("q");
        if !(0.0..=1.0).contains(&q) || yv[0] < 1e-3 {
            return None;
        }
        if q_of(&step.point) * q_of(&p) < 0.0 {
            let best = fold_point(&mut f, &p, &step, &opts).y;
            let k = best.len() - 1;
            return Some(Fold {
                v: best[0],
                a: best[1..k].to_vec(),
                x: x.value(best[k]),
                y: at,
            });
        }
        p = step.point;
    }
    None
}

/// The first fold of `branch` (followed at `y = at`).
pub fn fold_of(branch: &Branch, mirror: MirrorLine, at: f64) -> Option<Fold> {
    let e = branch.events.iter().find(|e| e.kind == "SN")?;
    let z = &e.point.z;
    let k = z.len() / 2;
    let (v, a) = match (mirror, k) {
        (MirrorLine::X, _) => (z[0], e.point.a_k().to_vec()),
        (MirrorLine::Diagonal, 2) => (e.point.v, vec![z[3]]),
        (MirrorLine::Diagonal, _) => {
            let back = turned(z, -mirror.angle());
            (back[0], back[2..k + 1].to_vec())
        }
    };
    Some(Fold {
        v,
        a,
        x: e.point.at,
        y: at,
    })
}

/// The MD fold on the first of the lines `y = starts[i]` (`x` across the window) that has
/// one: `(v, shape amplitude, x, y)` there.
fn first_fold(
    base: &ModelParams,
    n: usize,
    mirror: MirrorLine,
    (x, y): (Axis, Axis),
    starts: &[f64],
) -> Option<Fold> {
    starts.iter().find_map(|&at| {
        // K = 2: the branch's SN event (its verdicts cost little).
        if base.modes > 2 {
            let balances = Balances::new(y.param.with(base, at), n).ok()?;
            return walk_to_fold(balances, mirror, x, at);
        }
        let branch = md_branch(base, n, mirror, x, y, at).ok()?;
        fold_of(&branch, mirror, at)
    })
}

/// The MD saddle-node curve on `mirror` in the window `(x, y)`: located on the one-parameter
/// MD branch at the first `y` of `starts` that has a fold, then continued both ways; `(x, y)`
/// points in order along it.
pub fn md_fold_curve(
    base: &ModelParams,
    n: usize,
    mirror: MirrorLine,
    (x, y): (Axis, Axis),
    starts: &[f64],
) -> Result<Vec<(f64, f64)>, SolverError> {
    let Some(first) = first_fold(base, n, mirror, (x, y), starts) else {
        return Ok(Vec::new());
    };
    fold_curve_from(base, n, mirror, (x, y), first)
}

/// The corrector and step settings of a fold curve's continuation.
pub fn fold_options() -> ArclengthOptions {
    ArclengthOptions {
        // det dR/d(v, c) comes from central differences (relative noise ~1e-10), so the
        // corrector stops at 1e-9; the folds it finds agree with the one-parameter
        // location by tangent to 1e-15 (measured).
        tol: 1e-9,
        fd_step: 1e-5,
        ds: 0.01,
        ds_max: 0.04,
        max_iter: 10,
        ..ArclengthOptions::default()
    }
}

/// Follows the curve `f = 0` (unknowns `(v, shape.., qx, qy)`, the last two the window's
/// scaled parameters) both ways from `y0` (first towards decreasing `qy`), each way until it
/// leaves the window or `v` falls below 1e-3 (that point kept) or after 400 steps: the points
/// of each way, from `y0` on.
pub fn fold_walk(
    f: &mut impl FnMut(&[f64]) -> Vec<f64>,
    y0: &[f64],
    opts: &ArclengthOptions,
) -> Vec<Vec<Vec<f64>>> {
    let (qx, qy) = (y0.len() - 2, y0.len() - 1);
    let mut halves = Vec::new();
    for sign in [-1.0, 1.0] {
        let mut prev = vec![0.0; y0.len()];
        prev[qy] = sign;
        let Some(mut p) = start(f, y0, &prev, opts) else {
            continue;
        };
        let mut stepper = Stepper::new(opts.clone());
        let mut pts = vec![p.y.clone()];
        for _ in 0..400 {
            let Some(step) = stepper.advance(f, &p) else {
                break;
            };
            let y = &step.point.y;
            let inside = (0.0..=1.0).contains(&y[qx]) && (0.0..=1.0).contains(&y[qy]);
            if !inside || y[0] < 1e-3 {
                pts.push(step.point.y);
                break;
            }
            p = step.point;
            pts.push(p.y.clone());
        }
        halves.push(pts);
    }
    halves
}

/// The MD saddle-node curve through the fold `(v, a, x, y)`, continued both ways.
pub fn fold_curve_from(
    base: &ModelParams,
    n: usize,
    mirror: MirrorLine,
    (x, y): (Axis, Axis),
    fold: Fold,
) -> Result<Vec<(f64, f64)>, SolverError> {
    let mut sys = FoldSystem {
        balances: Balances::new(*base, n)?,
        mirror,
        x,
        y,
        det_scale: 1.0,
    };
    let y0: Vec<f64> = std::iter::once(fold.v)
        .chain(fold.a)
        .chain([x.q(fold.x), y.q(fold.y)])
        .collect();
    if !sys.place(&y0) {
        return Ok(Vec::new());
    }
    // det scales as the Jacobian's size to the power K.
    let j = sys.jac(&y0);
    let size = j.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    sys.det_scale = (0..j.len()).fold(1.0, |d, _| d * size);
    let opts = fold_options();
    let halves = fold_walk(&mut |y: &[f64]| sys.residual(y), &y0, &opts);
    let to_plane = |y: &Vec<f64>| sys.control(y);
    let mut out: Vec<(f64, f64)> = Vec::new();
    if let Some(back) = halves.first() {
        out.extend(back.iter().rev().map(to_plane));
    }
    if let Some(fwd) = halves.get(1) {
        out.extend(fwd.iter().skip(1).map(to_plane));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::param::ModelParam;

    /// The MD branch along eta_t at kappa2 = 0.13 from 0.077, by [`walk_to_fold`] and by the
    /// one continuation ([`follow`]) with modes `2..=k_max`.
    fn both(k_max: usize, n: usize) -> (Fold, Branch) {
        let base = ModelParams::at(0.077, 0.13).with_modes(k_max);
        let x = Axis::new(ModelParam::EtaT, (0.077, 0.1));
        let balances = Balances::new(base, n).unwrap();
        let fold = walk_to_fold(balances, MirrorLine::X, x, 0.13).expect("a fold");
        let branch = follow(
            &Line {
                base,
                n,
                parameter: ModelParam::EtaT,
                from: 0.077,
                to: 0.1,
                max_points: 400,
                opts: ArclengthOptions::default(),
            },
            Family::MdMinor,
            MirrorLine::X,
        )
        .unwrap();
        (fold, branch)
    }

    #[test]
    fn the_continuation_folds_where_the_fold_search_does_and_loses_stability_there() {
        // Two computations of one fold: the walk (its own arclength walk from the line's
        // start, the tangent's q component bracketed) and the continuation's SN event
        // (located on its own branch by the Illinois method), with modes 2..2 and 2..3 at
        // N = 96 (the 2-mode branch folds at 0.0792728 at N = 192, docs/continuation.md).
        for k_max in [2, 3] {
            let (fold, branch) = both(k_max, 96);
            // The walk returns the first fold from the line's start, where the continuation
            // starts too (its backward trace leaves the line at once).
            let sns: Vec<_> = branch.events.iter().filter(|e| e.kind == "SN").collect();
            let sn = &sns.first().expect("a fold").point;
            assert!((fold.x - sn.at).abs() < 1e-9, "{fold:?} vs {}", sn.at);
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
