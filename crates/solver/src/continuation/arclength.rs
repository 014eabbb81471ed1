//! Pseudo-arclength continuation of the solution curve of `F(y) = 0`, `F: R^(n+1) -> R^n`
//! (Keller's method): a step of length `ds` along the unit tangent `t` (the null vector of
//! `F'(y)`, oriented like the previous one) is corrected by Newton on the bordered system
//! `F(y) = 0`, `t . (y - y0) = ds`, so that the curve is followed through folds where the
//! parameter turns back. The step length adapts to the corrector's effort and to the turning
//! of the tangent. Unknowns are expected to be scaled to order one (the caller maps its
//! parameter onto `[0, 1]`).
use crate::numerics::newton::{fd_jacobian, lu_solve};

/// Step control and corrector settings.
#[derive(Debug, Clone, PartialEq)]
pub struct ArclengthOptions {
    /// First step length.
    pub ds: f64,
    pub ds_min: f64,
    pub ds_max: f64,
    /// The corrector has converged when `max |F| <= tol` and its last update was below
    /// `100 tol`.
    pub tol: f64,
    /// Corrector iterations before a step is refused (and retried at half the length).
    pub max_iter: usize,
    /// Step of the central differences of `F'`.
    pub fd_step: f64,
    /// Smallest cosine between consecutive tangents of an accepted step (larger turns are
    /// refused, so folds are resolved).
    pub min_cos: f64,
}

impl Default for ArclengthOptions {
    fn default() -> Self {
        Self {
            ds: 0.01,
            ds_min: 1e-7,
            ds_max: 0.03,
            tol: 1e-11,
            max_iter: 8,
            fd_step: 1e-6,
            min_cos: 0.995,
        }
    }
}

/// A point on the curve with its unit tangent.
#[derive(Debug, Clone, PartialEq)]
pub struct CurvePoint {
    pub y: Vec<f64>,
    pub tangent: Vec<f64>,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn max_norm(r: &[f64]) -> f64 {
    r.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// The unit null vector of the `n x (n+1)` Jacobian `jac`, oriented so that `t . prev > 0`:
/// the solution of `[jac; prev^T] t = [0; 1]`, normalised. `None` at a singular point
/// (a branch point, where the null space is two-dimensional).
pub fn tangent(jac: &[Vec<f64>], prev: &[f64]) -> Option<Vec<f64>> {
    let mut a: Vec<Vec<f64>> = jac.to_vec();
    a.push(prev.to_vec());
    let mut rhs = vec![0.0; prev.len()];
    rhs[prev.len() - 1] = 1.0;
    let t = lu_solve(a, &rhs)?;
    let norm = dot(&t, &t).sqrt();
    (norm > 0.0).then(|| t.iter().map(|v| v / norm).collect())
}

/// Newton on `F(y) = 0`, `dir . (y - anchor) = s`, from `guess`. Returns the point and the
/// iterations it took.
pub fn correct(
    f: &mut impl FnMut(&[f64]) -> Vec<f64>,
    guess: &[f64],
    anchor: &[f64],
    dir: &[f64],
    s: f64,
    opts: &ArclengthOptions,
) -> Option<(Vec<f64>, usize)> {
    let mut y = guess.to_vec();
    let mut last_update = f64::INFINITY;
    for it in 0..=opts.max_iter {
        let mut r = f(&y);
        let offset: Vec<f64> = y.iter().zip(anchor).map(|(a, b)| a - b).collect();
        r.push(dot(dir, &offset) - s);
        let norm = max_norm(&r);
        if !norm.is_finite() {
            return None;
        }
        if norm <= opts.tol && last_update <= 100.0 * opts.tol.max(1e-13) {
            return Some((y, it));
        }
        if it == opts.max_iter {
            return None;
        }
        let mut jac = fd_jacobian(f, &y, opts.fd_step);
        jac.push(dir.to_vec());
        let minus_r: Vec<f64> = r.iter().map(|v| -v).collect();
        let dy = lu_solve(jac, &minus_r)?;
        last_update = max_norm(&dy);
        for (yi, d) in y.iter_mut().zip(&dy) {
            *yi += d;
        }
    }
    None
}

/// The point at arclength `s` from `from` along its tangent (the predictor-corrector step
/// without step control), with its tangent. Used to locate events between two accepted
/// points.
pub fn point_at(
    f: &mut impl FnMut(&[f64]) -> Vec<f64>,
    from: &CurvePoint,
    s: f64,
    opts: &ArclengthOptions,
) -> Option<(CurvePoint, usize)> {
    let guess: Vec<f64> = from
        .y
        .iter()
        .zip(&from.tangent)
        .map(|(y, t)| y + s * t)
        .collect();
    let (y, iterations) = correct(f, &guess, &from.y, &from.tangent, s, opts)?;
    let jac = fd_jacobian(f, &y, opts.fd_step);
    // At a branch point the null space is two-dimensional: keep the incoming direction.
    let t = tangent(&jac, &from.tangent).unwrap_or_else(|| from.tangent.clone());
    Some((CurvePoint { y, tangent: t }, iterations))
}

/// The tangent at a point already on the curve, oriented along `prev`.
pub fn start(
    f: &mut impl FnMut(&[f64]) -> Vec<f64>,
    y: &[f64],
    prev: &[f64],
    opts: &ArclengthOptions,
) -> Option<CurvePoint> {
    let jac = fd_jacobian(f, y, opts.fd_step);
    Some(CurvePoint {
        y: y.to_vec(),
        tangent: tangent(&jac, prev)?,
    })
}

/// The last point of the curve between `from` (where `ok` holds) and the point `ds` further
/// (where it does not): bisection in arclength to `ds / 2^20`. Where a corrector fails the
/// point counts as not `ok`; `from` itself when none further is.
pub fn last_where(
    f: &mut impl FnMut(&[f64]) -> Vec<f64>,
    from: &CurvePoint,
    ds: f64,
    ok: &mut impl FnMut(&[f64]) -> bool,
    opts: &ArclengthOptions,
) -> CurvePoint {
    let (mut lo, mut hi) = (0.0, ds);
    let mut best = from.clone();
    for _ in 0..20 {
        let s = 0.5 * (lo + hi);
        match point_at(f, from, s, opts) {
            Some((p, _)) if ok(&p.y) => {
                lo = s;
                best = p;
            }
            _ => hi = s,
        }
    }
    best
}

/// Walks along the curve one accepted step at a time, adapting the step length.
pub struct Stepper {
    pub opts: ArclengthOptions,
    /// The step length the next attempt starts with.
    pub ds: f64,
}

/// An accepted step.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    pub point: CurvePoint,
    /// Its arclength from the previous point.
    pub ds: f64,
}

impl Stepper {
    pub fn new(opts: ArclengthOptions) -> Self {
        Self { ds: opts.ds, opts }
    }

    /// The next point after `from`, or `None` when no step down to `ds_min` converges.
    pub fn advance(
        &mut self,
        f: &mut impl FnMut(&[f64]) -> Vec<f64>,
        from: &CurvePoint,
    ) -> Option<Step> {
        loop {
            let ds = self.ds;
            match point_at(f, from, ds, &self.opts) {
                Some((point, iterations))
                    if dot(&point.tangent, &from.tangent) >= self.opts.min_cos =>
                {
                    // Easy steps lengthen the next one, hard ones shorten it.
                    let factor = match iterations {
                        0..=2 => 1.5,
                        3 => 1.0,
                        _ => 0.7,
                    };
                    self.ds = (ds * factor).clamp(self.opts.ds_min, self.opts.ds_max);
                    return Some(Step { point, ds });
                }
                _ => {
                    if ds <= self.opts.ds_min {
                        return None;
                    }
                    self.ds = (ds * 0.5).max(self.opts.ds_min);
                }
            }
        }
    }
}

/// The fold between `p` and the accepted `step` after it along a curve `(.., q)` whose
/// tangent's `q` component changes sign there: that component's root in arclength, by
/// Illinois regula falsi ([`crate::numerics::bracket::illinois`]: it is linear in arclength
/// near a fold, so about 6 correctors reach `1e-13` where bisection takes 40). The step's
/// point if a corrector fails.
pub fn fold_point(
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit circle `x^2 + y^2 = 1` has folds in `y` (the "parameter") at `y = +-1`: the
    /// stepper goes around it, and every point is on it.
    #[test]
    fn follows_a_circle_through_its_folds() {
        let mut f = |y: &[f64]| vec![y[0] * y[0] + y[1] * y[1] - 1.0];
        let opts = ArclengthOptions {
            ds_max: 0.1,
            ..ArclengthOptions::default()
        };
        let mut p = start(&mut f, &[1.0, 0.0], &[0.0, 1.0], &opts).unwrap();
        let mut stepper = Stepper::new(opts);
        let mut length = 0.0;
        let mut folds = 0;
        while length < 2.0 * std::f64::consts::PI {
            let step = stepper.advance(&mut f, &p).unwrap();
            assert!((step.point.y[0].hypot(step.point.y[1]) - 1.0).abs() < 1e-11);
            if step.point.tangent[1].signum() != p.tangent[1].signum() {
                folds += 1;
            }
            length += step.ds;
            p = step.point;
        }
        // Around once: two folds, back near the start (the chord is shorter than the arc).
        assert_eq!(folds, 2);
        assert!((p.y[0] - 1.0).hypot(p.y[1]) < 0.2, "{p:?}");
    }
}
