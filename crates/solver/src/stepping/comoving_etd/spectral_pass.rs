//! The two fused passes over the spectrum of one ETD2RK step of [`super::TwoModeEtd`]: each
//! advances the field by one stage and, in the same sweep, accumulates the Parseval sums of
//! the forces at that stage's shape ([`crate::model::forces`]). No exponential or division per mode:
//! the propagator comes from [`SeparableExp`].
//!
//! The predictor's shape is either its own transform or the linear extrapolation
//! `S_a = S_n + alpha (S_n - S_{n-1})` of the transforms at the last two accepted states
//! ([`PredictorShape`]), formed on the fly so that it costs no transform and no extra pass.
use crate::model::forces::parseval::{ColumnSums, ForceSums};
use crate::model::grid::Grid;
use crate::stepping::etd::SeparableExp;
use rustfft::num_complex::Complex64;

/// The fixed inputs of a pass: wavenumbers, the propagator's factors and `1 / c` per mode.
pub struct Modes<'a> {
    pub grid: &'a Grid,
    pub exp: &'a SeparableExp,
    pub inv_c: &'a [f64],
    pub h: f64,
}

/// The predictor's packed shape transforms `p`, `y`, as `base + alpha (base - back)`.
/// With `alpha = 0` (and `back = base`) they are `base` itself.
pub struct PredictorShape<'a> {
    pub base_p: &'a [Complex64],
    pub base_y: &'a [Complex64],
    pub back_p: &'a [Complex64],
    pub back_y: &'a [Complex64],
    pub alpha: f64,
}

/// Predictor stage: from the field `w` and the current shape `cur_p` (source `Re p * src0`),
/// writes the explicit part `n0`, the ETD1 field `a_hat` and the predictor's `Theta_hat`
/// (`pred_th`, real), and returns the force sums of `a_hat` against the predictor's shape.
pub struct PredictorPass<'a> {
    pub modes: Modes<'a>,
    pub velocity: (f64, f64),
    pub src0: f64,
    pub w: &'a [Complex64],
    pub cur_p: &'a [Complex64],
    pub shape: PredictorShape<'a>,
    pub n0: &'a mut [Complex64],
    pub a_hat: &'a mut [Complex64],
    pub pred_th: &'a mut [f64],
}

/// Corrector stage: from `a_hat`, the predictor's `Theta_hat` (source `pred_th * srca`) and
/// `n0`, writes the new field `w_new` and returns its force sums against the new shape.
pub struct CorrectorPass<'a> {
    pub modes: Modes<'a>,
    pub velocity: (f64, f64),
    pub srca: f64,
    pub a_hat: &'a [Complex64],
    pub pred_th: &'a [f64],
    pub n0: &'a [Complex64],
    pub next_p: &'a [Complex64],
    pub next_y: &'a [Complex64],
    pub w_new: &'a mut [Complex64],
}

impl PredictorPass<'_> {
    /// Runs the pass.
    pub fn run(self) -> ForceSums {
        let Modes {
            grid,
            exp,
            inv_c,
            h,
        } = self.modes;
        let n = grid.n;
        let inv_h = 1.0 / h;
        let (vx, vy) = self.velocity;
        let s = &self.shape;
        let alpha = s.alpha;
        let mut sums = ForceSums::default();
        for jx in 0..=n / 2 {
            let (kx, ax) = (grid.kx_d[jx], exp.ax[jx]);
            let row = jx * n..(jx + 1) * n;
            let mut col = ColumnSums::default();
            let modes = grid.ky_d.iter().zip(&exp.ay).zip(&inv_c[row.clone()]);
            let fields = self.w[row.clone()].iter().zip(&self.cur_p[row.clone()]);
            let outs = self.n0[row.clone()]
                .iter_mut()
                .zip(&mut self.a_hat[row.clone()])
                .zip(&mut self.pred_th[row.clone()]);
            let base = s.base_p[row.clone()].iter().zip(&s.base_y[row.clone()]);
            let back = s.back_p[row.clone()].iter().zip(&s.back_y[row]);
            for ((((ky, ay), ic), (w, th)), (((n0, ah), pt), ((bp, by), (qp, qy)))) in
                modes.zip(fields).zip(outs.zip(base.zip(back)))
            {
                let cf = SeparableExp::coef(ax, *ay, *ic, h, inv_h);
                let kv = kx * vx + ky * vy;
                // Advection i k.v w plus the source Theta_hat / A (= Re p, see forces.rs).
                let nw = Complex64::new(-kv * w.im + th.re * self.src0, kv * w.re);
                *n0 = nw;
                let a = *w * cf.e + nw * cf.p1;
                *ah = a;
                let pp = *bp + (*bp - *qp) * alpha;
                let py = *by + (*by - *qy) * alpha;
                *pt = pp.re;
                col.add(*ky, a, pp, py);
            }
            sums.column(grid.column_weight(jx), kx, &col);
        }
        sums
    }
}

impl CorrectorPass<'_> {
    /// Runs the pass.
    pub fn run(self) -> ForceSums {
        let Modes {
            grid,
            exp,
            inv_c,
            h,
        } = self.modes;
        let n = grid.n;
        let inv_h = 1.0 / h;
        let (vx, vy) = self.velocity;
        let mut sums = ForceSums::default();
        for jx in 0..=n / 2 {
            let (kx, ax) = (grid.kx_d[jx], exp.ax[jx]);
            let row = jx * n..(jx + 1) * n;
            let mut col = ColumnSums::default();
            let modes = grid.ky_d.iter().zip(&exp.ay).zip(&inv_c[row.clone()]);
            let fields = self.a_hat[row.clone()]
                .iter()
                .zip(&self.pred_th[row.clone()])
                .zip(&self.n0[row.clone()]);
            let shape = self.next_p[row.clone()]
                .iter()
                .zip(&self.next_y[row.clone()]);
            for ((((ky, ay), ic), ((a, th), n0)), ((np, ny), wn)) in
                modes.zip(fields).zip(shape.zip(&mut self.w_new[row]))
            {
                let cf = SeparableExp::coef(ax, *ay, *ic, h, inv_h);
                let kv = kx * vx + ky * vy;
                let na = Complex64::new(-kv * a.im + th * self.srca, kv * a.re);
                let w = *a + (na - *n0) * cf.p2;
                *wn = w;
                col.add(*ky, w, *np, *ny);
            }
            sums.column(grid.column_weight(jx), kx, &col);
        }
        sums
    }
}
