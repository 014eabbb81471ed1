//! The predictor's droplet and the field's gradient on it in the general step
//! ([`super::general`]), from the last two accepted states.
//!
//! ETD2RK needs the forces at the predictor `(a, z_a)`: `Theta` of the predictor's shape and
//! the gradient of the predictor's field `a` on it. Both are `O(h^2)` from the path's values
//! at `t + h`, and both enter the step only through the corrector's `h phi2 (N(a) - N(w))`, so
//! the predictor's own error may be `O(h^2)` too without changing the scheme's order: the
//! local error stays `O(h^3)`. So, when the last step is known,
//! - the predictor's droplet is the extrapolation `cur + alpha (cur - prev)` of the last two
//!   states' `Theta` and transform, `alpha` the projection of the predictor's shape change
//!   onto the last step's ([`History::shape`]; no sample, no transform);
//! - the field's gradient at the predictor is the extrapolation `cur + beta (cur - prev)` of
//!   the last two states' gradients along the time axis, `beta = h / h_last`
//!   ([`History::gradient_factor`]; no inverse transform).
//!
//! At a fixed point the last two states are the same and the predictor is the state itself,
//! so both extrapolations are exact: the scheme's fixed points stay the steady states. The
//! 2-mode fast path extrapolates its shape transforms by the same rule; its forces at the
//! predictor are Parseval sums over the predictor's own field, which cost no transform.
use crate::model::forces::quadrature::{ForceQuadrature, GradientRows, SampledShape};
use crate::model::grid::Grid;
use crate::model::modes::Modes;

/// The largest extrapolation factor (`alpha`, `beta`) taken; beyond it the predictor's
/// droplet is sampled and transformed, and its field's gradient transformed back.
const MAX_FACTOR: f64 = 2.0;

/// One accepted state: its sampled droplet, its shape amplitudes `(a_2..a_K, b_2..b_K)` and
/// its field's gradient on the droplet.
struct Snapshot {
    sampled: SampledShape,
    shape: Vec<f64>,
    grad: GradientRows,
}

/// The last two accepted states ([`Snapshot`]) and the step between them.
pub(super) struct History {
    cur: Snapshot,
    prev: Snapshot,
    /// How many of the two are known (0 after a start or a leap).
    known: usize,
    /// The step from `prev` to `cur`.
    h_last: f64,
}

impl History {
    /// Empty buffers for `grid`.
    pub fn new(grid: &Grid) -> Self {
        let snapshot = || Snapshot {
            sampled: SampledShape::new(grid),
            shape: Vec::new(),
            grad: GradientRows::new(grid),
        };
        Self {
            cur: snapshot(),
            prev: snapshot(),
            known: 0,
            h_last: 0.0,
        }
    }

    /// Forgets both states (the state changed otherwise than by a step).
    pub fn forget(&mut self) {
        self.known = 0;
    }

    /// Records the state the run has reached, `h` after the last one, whose droplet and
    /// gradient `quad` holds (they become `cur`, taken without copying; `cur` becomes `prev`).
    pub fn record(&mut self, quad: &mut ForceQuadrature, shape: &[f64], h: f64) {
        std::mem::swap(&mut self.prev, &mut self.cur);
        quad.exchange(&mut self.cur.sampled);
        quad.exchange_gradient(&mut self.cur.grad);
        self.cur.shape.clear();
        self.cur.shape.extend_from_slice(shape);
        self.known = (self.known + 1).min(2);
        self.h_last = h;
    }

    /// The present state's transform of `Theta` (the step's start).
    pub fn start_spectrum(&self) -> &[rustfft::num_complex::Complex64] {
        &self.cur.sampled.spec
    }

    /// The last two states' transforms of `Theta`, `(cur, prev)`.
    pub fn spectra(
        &self,
    ) -> (
        &[rustfft::num_complex::Complex64],
        &[rustfft::num_complex::Complex64],
    ) {
        (&self.cur.sampled.spec, &self.prev.sampled.spec)
    }

    /// Puts the predictor's droplet, the shape `z_a[2..]`'s, in `quad`: `(alpha, area, lo,
    /// hi)`. When both states are known and the predictor's shape change projects onto the
    /// last step's by `|alpha| <= 2`, its `Theta` and transform are the extrapolation
    /// `cur + alpha (cur - prev)` (`alpha` returned; the transform is formed on the fly by the
    /// corrector's pass); else it is sampled and transformed (`alpha = None`).
    pub fn shape(
        &self,
        quad: &mut ForceQuadrature,
        z_a: &[f64],
    ) -> (Option<f64>, f64, usize, usize) {
        let shape = &z_a[2..];
        if self.known == 2 {
            let (c, q) = (&self.cur.shape, &self.prev.shape);
            let (mut dot, mut norm2) = (0.0, 0.0);
            for ((s, c), q) in shape.iter().zip(c).zip(q) {
                dot += (s - c) * (c - q);
                norm2 += (c - q) * (c - q);
            }
            let alpha = if norm2 > 0.0 { dot / norm2 } else { 0.0 };
            if alpha.abs() <= MAX_FACTOR {
                let (area, lo, hi) = quad.extrapolate(&self.cur.sampled, &self.prev.sampled, alpha);
                return (Some(alpha), area, lo, hi);
            }
        }
        let (area, lo, hi) = quad.theta_spectrum(&Modes::of_state(z_a));
        (None, area, lo, hi)
    }

    /// The factor `beta = h / h_last` of the predictor's gradient on the rows and columns
    /// `lo..=hi` of its droplet, when both states are known, their gradients hold those rows
    /// and `beta <= 2`; else `None` (the predictor's gradient is transformed back).
    pub fn gradient_factor(&self, h: f64, (lo, hi): (usize, usize)) -> Option<f64> {
        let holds = |g: &GradientRows| g.lo <= lo && hi <= g.hi;
        let beta = h / self.h_last;
        (self.known == 2 && holds(&self.cur.grad) && holds(&self.prev.grad) && beta <= MAX_FACTOR)
            .then_some(beta)
    }

    /// Puts the predictor's gradient `cur + beta (cur - prev)` on the rows and columns
    /// `lo..=hi` in `quad` ([`Self::gradient_factor`]).
    pub fn extrapolate_gradient(
        &self,
        quad: &mut ForceQuadrature,
        beta: f64,
        rows: (usize, usize),
    ) {
        quad.extrapolate_gradient(&self.cur.grad, &self.prev.grad, beta, rows);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::shape::ShapeParams;
    use rustfft::num_complex::Complex64;

    #[test]
    fn the_predictors_gradient_is_the_pointwise_extrapolation_when_the_last_step_allows() {
        let grid = Grid::new(32, 7.0).unwrap();
        let shape = ShapeParams {
            radius: 1.0,
            sigma: 0.1,
        };
        let mut quad = ForceQuadrature::new(grid.clone(), shape);
        let mut history = History::new(&grid);
        let droplet = Modes {
            a: vec![0.1, 0.02],
            b: vec![0.0, 0.01],
        };
        // Two states of one droplet with two fields, a step of 0.1 between them.
        let field = |c: f64| -> Vec<Complex64> {
            (0..grid.spectral_len())
                .map(|i| Complex64::new((i as f64 * c).sin(), (i as f64 * 0.3).cos()) * 1e-3)
                .collect()
        };
        let z = [0.3, 0.0, 0.1, 0.02, 0.0, 0.01];
        let mut record = |history: &mut History, c: f64, h: f64| {
            let (_, lo, hi) = quad.theta_spectrum(&droplet);
            quad.gradient(&field(c), lo, hi);
            history.record(&mut quad, &z[2..], h);
            (lo, hi)
        };
        let rows = record(&mut history, 0.5, 0.0);
        assert_eq!(history.gradient_factor(0.1, rows), None, "one state known");
        record(&mut history, 0.6, 0.1);
        assert_eq!(
            history.gradient_factor(0.25, rows),
            None,
            "beyond twice the last step"
        );
        assert_eq!(
            history.gradient_factor(0.1, (rows.0 - 1, rows.1)),
            None,
            "a wider window"
        );
        let beta = history.gradient_factor(0.15, rows).unwrap();
        assert!((beta - 1.5).abs() < 1e-15);
        history.extrapolate_gradient(&mut quad, beta, rows);
        let (ux, uy) = quad.gradient_rows();
        let (cur, prev) = (&history.cur.grad, &history.prev.grad);
        let n = grid.n;
        for iy in rows.0..=rows.1 {
            for ix in rows.0..=rows.1 {
                let i = iy * n + ix;
                assert_eq!(ux[i], cur.ux[i] + beta * (cur.ux[i] - prev.ux[i]));
                assert_eq!(uy[i], cur.uy[i] + beta * (cur.uy[i] - prev.uy[i]));
            }
        }
        assert!(cur.ux != prev.ux);
        history.forget();
        assert_eq!(history.gradient_factor(0.1, rows), None, "forgotten");
    }
}
