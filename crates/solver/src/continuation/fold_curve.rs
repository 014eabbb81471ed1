//! The MD saddle-node curve (the fold that bounds the bistable bands) in a window of two model
//! parameters `(x, y)`, for the model with shape modes `2..K`: pseudo-arclength continuation
//! in `(v, a_2..a_K, qx, qy)` (the shape in the mirror line's frame, the parameters scaled to
//! the window) of the extended system `R(v, a; x, y) = 0, det dR/d(v, a) = 0`, started from a
//! fold located on a one-parameter MD branch followed in `x` at a fixed `y`. It ends where it
//! leaves the window or where `v -> 0` (the fold reaches the onset of motion: there the
//! pitchfork changes from sub- to supercritical).
use crate::continuation::arclength::{start, ArclengthOptions, Stepper};
use crate::continuation::branch::{follow, Branch, Line};
use crate::continuation::problem::Family;
use crate::continuation::window::PlaneAxis;
use crate::error::SolverError;
use crate::model::params::ModelParams;
use crate::model::state::turned;
use crate::numerics::newton::fd_jacobian;
use crate::roots::balances::Balances;
use crate::roots::steady_solver::MirrorAxis;

/// The model of a fold curve: its grid and its shape modes `2..=modes` (the friction law
/// moves no fold).
#[derive(Debug, Clone, Copy)]
pub struct FoldModel {
    pub n: usize,
    pub modes: usize,
}

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
    mirror: MirrorAxis,
    x: PlaneAxis,
    y: PlaneAxis,
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
    model: FoldModel,
    mirror: MirrorAxis,
    x: PlaneAxis,
    y: PlaneAxis,
    at: f64,
) -> Result<Branch, SolverError> {
    let line = Line {
        base: y.param.with(base, at),
        n: model.n,
        parameter: x.param,
        from: x.range.0,
        to: x.range.1,
        modes: model.modes,
        eta_k_exponent: 0.0,
        max_points: 400,
        opts: ArclengthOptions::default(),
    };
    follow(&line, Family::MdMinor, mirror)
}

/// A fold: the speed along the mirror line, the shape `a_2..a_K` in its frame, and the two
/// parameters there.
pub type Fold = (f64, Vec<f64>, f64, f64);

/// The first fold of `branch` (followed at `y = at`).
pub fn fold_of(branch: &Branch, mirror: MirrorAxis, at: f64) -> Option<Fold> {
    let e = branch.events.iter().find(|e| e.kind == "SN")?;
    let z = &e.point.z;
    let k = z.len() / 2;
    let (v, a) = match (mirror, k) {
        (MirrorAxis::X, _) => (z[0], e.point.a_k().to_vec()),
        (MirrorAxis::Diagonal, 2) => (e.point.v, vec![z[3]]),
        (MirrorAxis::Diagonal, _) => {
            let back = turned(z, -std::f64::consts::FRAC_PI_4);
            (back[0], back[2..k + 1].to_vec())
        }
    };
    Some((v, a, e.point.at, at))
}

/// The MD fold on the first of the lines `y = starts[i]` (`x` across the window) that has
/// one: `(v, shape amplitude, x, y)` there.
fn first_fold(
    base: &ModelParams,
    model: FoldModel,
    mirror: MirrorAxis,
    (x, y): (PlaneAxis, PlaneAxis),
    starts: &[f64],
) -> Option<Fold> {
    starts.iter().find_map(|&at| {
        let branch = md_branch(base, model, mirror, x, y, at).ok()?;
        fold_of(&branch, mirror, at)
    })
}

/// The MD saddle-node curve on `mirror` in the window `(x, y)`: located on the one-parameter
/// MD branch at the first `y` of `starts` that has a fold, then continued both ways; `(x, y)`
/// points in order along it.
pub fn md_fold_curve(
    base: &ModelParams,
    model: FoldModel,
    mirror: MirrorAxis,
    (x, y): (PlaneAxis, PlaneAxis),
    starts: &[f64],
) -> Result<Vec<(f64, f64)>, SolverError> {
    let Some(first) = first_fold(base, model, mirror, (x, y), starts) else {
        return Ok(Vec::new());
    };
    fold_curve_from(base, model, mirror, (x, y), first)
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
    model: FoldModel,
    mirror: MirrorAxis,
    (x, y): (PlaneAxis, PlaneAxis),
    (v, a, at_x, at_y): Fold,
) -> Result<Vec<(f64, f64)>, SolverError> {
    let mut sys = FoldSystem {
        balances: Balances::new(*base, model.n, model.modes, 0.0)?,
        mirror,
        x,
        y,
        det_scale: 1.0,
    };
    let y0: Vec<f64> = std::iter::once(v)
        .chain(a)
        .chain([x.q(at_x), y.q(at_y)])
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
