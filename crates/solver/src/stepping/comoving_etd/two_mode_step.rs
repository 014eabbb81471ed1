//! One step of [`TwoModeEtd`] in its four parts: the predictor half (ETD1 scalars and the
//! first spectral pass, fused with the forces at the predictor), the scalar corrector, the
//! embedded error estimate (where a step may be refused before its second half), and the
//! field corrector (the second pass, fused with the forces at the new state).
use crate::model::dynamics;
use crate::model::forces::parseval::Forces;
use crate::model::state::DropletState;
use crate::stepping::comoving_etd::spectral_pass::{
    CorrectorPass, Modes, PredictorPass, PredictorShape,
};
use crate::stepping::comoving_etd::TwoModeEtd;
use crate::stepping::etd::EtdCoef;

impl TwoModeEtd {
    /// The first half of a step of size `h`: the ETD1 predictor of the scalars and the field
    /// predictor fused with the forces there (one spectral pass).
    pub(super) fn predict(&mut self, h: f64) -> Half {
        let f0 = self.ensure_current();
        let p = self.params;
        let st = self.state;
        let (rate_v, rate_s) = dynamics::linear_rates(&p, self.pinned);
        let vel = EtdCoef::new(rate_v, h);
        let shp = EtdCoef::new(rate_s, h);
        let pos = EtdCoef::new(0.0, h);
        self.exp.update(h, &self.grid.kx, &self.grid.ky);
        let n = self.grid.n;
        let norm = 1.0 / (n as f64 * n as f64);

        // Predictor (ETD1) for the scalars; then the predictor's shape spectra.
        let v0 = self.stage_velocity(&f0, (st.vx, st.vy));
        let r0 = self.scalar_rates(&f0);
        let predicted = [
            vel.predict(st.vx, r0[0]),
            vel.predict(st.vy, r0[1]),
            shp.predict(st.a2, r0[2]),
            shp.predict(st.b2, r0[3]),
        ];
        let alpha = self.predictor_shape(predicted[2], predicted[3]);

        // Field predictor fused with the forces at the predictor.
        let (base, back, alpha) = match alpha {
            Some(alpha) => (&self.cur, &self.prev, alpha),
            None => (&self.next, &self.next, 0.0),
        };
        let area = base.area + alpha * (base.area - back.area);
        let modes = Modes {
            grid: &self.grid,
            exp: &self.exp,
            inv_c: &self.inv_c,
            h,
        };
        let sums = PredictorPass {
            modes,
            velocity: v0,
            src0: norm / self.cur.area,
            w: &self.w_hat,
            cur_p: &self.cur.p,
            shape: PredictorShape {
                base_p: &base.p,
                base_y: &base.y,
                back_p: &back.p,
                back_y: &back.y,
                alpha,
            },
            n0: &mut self.n0,
            a_hat: &mut self.a_hat,
            pred_th: &mut self.pred_th,
        }
        .run();
        let forces = sums.finish(self.grid.dx * self.grid.dx, area);
        Half {
            h,
            vel,
            shp,
            pos,
            v0,
            r0,
            predicted,
            area,
            forces,
        }
    }

    /// The corrector of the scalars after `half`: the candidate new state and the velocity the
    /// field is advected with in the corrector.
    pub(super) fn correct_scalars(&self, half: &Half) -> (DropletState, (f64, f64)) {
        let st = self.state;
        let (vel, shp, pos, v0, r0) = (&half.vel, &half.shp, &half.pos, half.v0, half.r0);
        let [vxa, vya, a2a, b2a] = half.predicted;
        let (vax, vay) = self.stage_velocity(&half.forces, (vxa, vya));
        let ra = self.scalar_rates(&half.forces);
        let mut next = DropletState {
            x: pos.correct(pos.predict(st.x, v0.0), v0.0, vax),
            y: pos.correct(pos.predict(st.y, v0.1), v0.1, vay),
            vx: vel.correct(vxa, r0[0], ra[0]),
            vy: vel.correct(vya, r0[1], ra[1]),
            a2: shp.correct(a2a, r0[2], ra[2]),
            b2: shp.correct(b2a, r0[3], ra[3]),
        };
        let inertial = self.params.mass > 0.0 && !self.pinned;
        if !inertial {
            (next.vx, next.vy) = (st.vx, st.vy);
        }
        if self.pinned {
            (next.x, next.y) = (st.x, st.y);
        }
        (next, (vax, vay))
    }

    /// The embedded error estimate of the step to `next`: the corrector minus the ETD1
    /// predictor of the integrated scalars (the shape, and the velocity, or the position when
    /// overdamped).
    pub(super) fn step_error(&self, half: &Half, next: &DropletState) -> f64 {
        let st = self.state;
        let [vxa, vya, a2a, b2a] = half.predicted;
        if self.pinned {
            (next.a2 - a2a).abs().max((next.b2 - b2a).abs())
        } else if self.params.mass > 0.0 {
            [next.vx - vxa, next.vy - vya, next.a2 - a2a, next.b2 - b2a]
                .iter()
                .fold(0.0f64, |m, d| m.max(d.abs()))
        } else {
            let (xa, ya) = (
                half.pos.predict(st.x, half.v0.0),
                half.pos.predict(st.y, half.v0.1),
            );
            [next.x - xa, next.y - ya, next.a2 - a2a, next.b2 - b2a]
                .iter()
                .fold(0.0f64, |m, d| m.max(d.abs()))
        }
    }

    /// The second half of an accepted step: the new state's shape spectra and the field
    /// corrector fused with the forces there (one spectral pass); the run moves to `next`.
    pub(super) fn correct_field(&mut self, half: &Half, next: DropletState, velocity: (f64, f64)) {
        let n = self.grid.n;
        let norm = 1.0 / (n as f64 * n as f64);
        let sample_next = next.is_finite() && next.deformation() < 1.0;
        if sample_next {
            Self::shape_spectra(&mut self.shapes, next.a2, next.b2, &mut self.next);
        }
        let modes = Modes {
            grid: &self.grid,
            exp: &self.exp,
            inv_c: &self.inv_c,
            h: half.h,
        };
        let sums = CorrectorPass {
            modes,
            velocity,
            srca: norm / half.area,
            a_hat: &self.a_hat,
            pred_th: &self.pred_th,
            n0: &self.n0,
            next_p: &self.next.p,
            next_y: &self.next.y,
            w_new: &mut self.w_new,
        }
        .run();
        std::mem::swap(&mut self.w_hat, &mut self.w_new);
        self.state = next;
        if sample_next {
            std::mem::swap(&mut self.prev, &mut self.cur);
            std::mem::swap(&mut self.cur, &mut self.next);
            self.prev_valid = true;
            let f = sums.finish(self.grid.dx * self.grid.dx, self.cur.area);
            self.set_overdamped_velocity(&f);
            self.forces0 = Some(f);
        } else {
            self.forces0 = None;
        }
    }
}

/// The first half of a step: its coefficients, the velocity and scalar rates at its start,
/// the ETD1 predictor `(vx, vy, a2, b2)`, and the predictor's area and forces.
pub(super) struct Half {
    h: f64,
    vel: EtdCoef,
    shp: EtdCoef,
    pos: EtdCoef,
    v0: (f64, f64),
    r0: [f64; 4],
    predicted: [f64; 4],
    area: f64,
    forces: Forces,
}
