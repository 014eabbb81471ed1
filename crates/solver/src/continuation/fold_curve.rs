//! The MD saddle-node curve (the fold that bounds the bistable bands) in a window of two model
//! parameters `(x, y)`: pseudo-arclength continuation in `(v, c, qx, qy)` (the parameters
//! scaled to the window) of the extended system `R(v, c; x, y) = 0, det dR/d(v, c) = 0`,
//! started from a fold located on a one-parameter MD branch followed in `x` at a fixed `y`. It
//! ends where it leaves the window or where `v -> 0` (the fold reaches the onset of motion:
//! there the pitchfork changes from sub- to supercritical).
use crate::continuation::arclength::{start, ArclengthOptions, Stepper};
use crate::continuation::branch::{follow, Branch, Line};
use crate::continuation::problem::Family;
use crate::continuation::window::PlaneAxis;
use crate::error::SolverError;
use crate::model::params::ModelParams;
use crate::numerics::newton::fd_jacobian;
use crate::roots::steady_solver::{MirrorAxis, TwoModeSolver};

/// The extended system of the MD fold: `y = (v, c, qx, qy)`.
struct FoldSystem {
    solver: TwoModeSolver,
    mirror: MirrorAxis,
    x: PlaneAxis,
    y: PlaneAxis,
    /// Scale of `det` (the Jacobian's size squared at the start).
    det_scale: f64,
}

impl FoldSystem {
    fn control(&self, y: &[f64]) -> (f64, f64) {
        (self.x.value(y[2]), self.y.value(y[3]))
    }

    /// Moves the solver to `y`'s parameters; false where they are invalid.
    fn place(&mut self, y: &[f64]) -> bool {
        let (a, b) = self.control(y);
        self.solver.set_param(self.x.param, a).is_ok()
            && self.solver.set_param(self.y.param, b).is_ok()
    }

    /// `dR/d(v, c)` at `y` (the solver placed there).
    fn jac(&mut self, y: &[f64]) -> Vec<Vec<f64>> {
        let mirror = self.mirror;
        let solver = &mut self.solver;
        fd_jacobian(
            &mut |x: &[f64]| solver.residual_on(mirror, x[0], x[1]).to_vec(),
            &y[..2],
            1e-6,
        )
    }

    fn residual(&mut self, y: &[f64]) -> Vec<f64> {
        if !self.place(y) {
            return vec![f64::NAN; 3];
        }
        let r = self.solver.residual_on(self.mirror, y[0], y[1]);
        let j = self.jac(y);
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        vec![r[0], r[1], det / self.det_scale]
    }
}

/// The MD branch on `mirror` along `x` at `y = at` (the other parameters `base`'s).
pub fn md_branch(
    base: &ModelParams,
    n: usize,
    mirror: MirrorAxis,
    x: PlaneAxis,
    y: PlaneAxis,
    at: f64,
) -> Result<Branch, SolverError> {
    let line = Line {
        base: y.param.with(base, at),
        n,
        parameter: x.param,
        from: x.range.0,
        to: x.range.1,
        modes: 2,
        eta_k_exponent: 0.0,
        max_points: 400,
        opts: ArclengthOptions::default(),
    };
    follow(&line, Family::MdMinor, mirror)
}

/// The first fold of `branch` (followed at `y = at`): `(v, shape amplitude, x, y)` there.
pub fn fold_of(branch: &Branch, mirror: MirrorAxis, at: f64) -> Option<(f64, f64, f64, f64)> {
    let e = branch.events.iter().find(|e| e.kind == "SN")?;
    let (v, c) = match mirror {
        MirrorAxis::X => (e.point.z[0], e.point.z[2]),
        MirrorAxis::Diagonal => (e.point.v, e.point.z[3]),
    };
    Some((v, c, e.point.at, at))
}

/// The MD fold on the first of the lines `y = starts[i]` (`x` across the window) that has
/// one: `(v, shape amplitude, x, y)` there.
fn first_fold(
    base: &ModelParams,
    n: usize,
    mirror: MirrorAxis,
    (x, y): (PlaneAxis, PlaneAxis),
    starts: &[f64],
) -> Option<(f64, f64, f64, f64)> {
    starts.iter().find_map(|&at| {
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
    mirror: MirrorAxis,
    (x, y): (PlaneAxis, PlaneAxis),
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

/// The MD saddle-node curve through the fold `(v, c, x, y)`, continued both ways.
pub fn fold_curve_from(
    base: &ModelParams,
    n: usize,
    mirror: MirrorAxis,
    (x, y): (PlaneAxis, PlaneAxis),
    (v, c, at_x, at_y): (f64, f64, f64, f64),
) -> Result<Vec<(f64, f64)>, SolverError> {
    let mut sys = FoldSystem {
        solver: TwoModeSolver::new(*base, n)?,
        mirror,
        x,
        y,
        det_scale: 1.0,
    };
    let y0 = vec![v, c, x.q(at_x), y.q(at_y)];
    if !sys.place(&y0) {
        return Ok(Vec::new());
    }
    let j = sys.jac(&y0);
    let size = j.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    sys.det_scale = size * size;
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
