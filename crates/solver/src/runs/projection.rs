//! Projective steps along a run's slow phase (setting `projective_steps`; docs/numerics.md,
//! "Projective steps along slow phases"): once a run has taken [`INNER`] steps of one size in a row (in a slow
//! phase, the step cap), its fast parts (the field's modes, decaying at `1 + k^2 >= 1`, the
//! velocity's and the shape's relaxation) have decayed towards the slow manifold, and the last
//! step's change is the slow flow's. The run then moves on along that chord, field and
//! unknowns alike, by `M` steps' time at once (projective forward Euler): `y + M (y - y_prev)`.
//!
//! Error control: the linear extrapolation over `M` steps is off by about `M^2 / 2` times the
//! second difference of the unknowns over the last two steps, which the projection keeps
//! below the run's step tolerance, the bound every step meets ([`PROJECTION_TOL`] of it); and
//! in every unknown the chord's slope may change by at most a tenth over the projection
//! ([`SLOPE_CHANGE`]): an unknown still relaxing, or a mode that turns, holds it back, however
//! small its part.
//! Stability: a mode decaying at `mu` is multiplied per cycle by
//! `rho^(INNER - 1) (rho - M (1 - rho))`, `rho = exp(-mu h)`: with `INNER` = 8 and
//! `M <= `[`MAX_FACTOR`] = 20 its size stays below 0.70 for every mode the projection does not
//! follow (`mu (INNER + M) h > 2`), whatever `mu`.
//!
//! A projection never passes a time at which the run has something to do (a series row, a
//! Newton try, `t_max`): the caller's `limit`.
use crate::contract::settings::SolverSettings;
use crate::stepping::Scheme;
use rustfft::num_complex::Complex64;

/// Steps of one size in a row before a projection.
pub const INNER: usize = 8;
/// The largest projection, in steps.
pub const MAX_FACTOR: f64 = 20.0;
/// The smallest projection worth its restart of the predictor, in steps.
pub const MIN_FACTOR: f64 = 2.0;
/// How much the chord's slope may change over a projection, in every unknown (its relative
/// change per step, the second difference over the first, times `M`): an unknown still
/// relaxing at `mu`, or turning at `omega`, changes it by `mu h` or `omega h` a step, so it
/// holds the projection back to `SLOPE_CHANGE / (mu h)` steps, less than 2 for `mu > 0.2` at
/// the cap: the projection waits until every unknown is on the slow manifold, however small
/// its part (at `(0.0925, 0.10075)` from iv a droplet at rest drifts at `vy = 5e-5` while `vx`
/// relaxes through 1e-6: a projection through that relaxation changed where the Newton finish
/// ended the run, ID to MD).
pub const SLOPE_CHANGE: f64 = 0.1;
/// A change per step below which an unknown counts as still (round-off, or a mirror-symmetric
/// run's zero components).
pub const SLOPE_FLOOR: f64 = 1e-10;
/// The projection's error bound, as a share of the run's step tolerance: a projection is held
/// to the bound of every step.
pub const PROJECTION_TOL: f64 = 1.0;

/// The projective steps of one run.
pub(super) struct Projection {
    tol: f64,
    /// Accepted steps of the size `h` in a row since the last projection.
    count: usize,
    h: f64,
    /// The unknowns after the last three steps (oldest first).
    last: [Vec<f64>; 3],
    /// The state one step before the last: the field's spectrum, the unknowns, the centre.
    field: Vec<Complex64>,
    z: Vec<f64>,
    centre: (f64, f64),
}

impl Projection {
    /// For a run whose steps meet the tolerance `tol`.
    pub(super) fn new(tol: f64) -> Self {
        Self {
            tol: tol * PROJECTION_TOL,
            count: 0,
            h: 0.0,
            last: Default::default(),
            field: Vec::new(),
            z: Vec::new(),
            centre: (0.0, 0.0),
        }
    }

    /// The projective steps of a run of a model with shape modes `2..modes` and `settings`:
    /// with the setting on, where the run reads it (adaptive spectral steps, the centre free;
    /// [`SolverSettings::unread_reason`]).
    pub(super) fn for_run(settings: &SolverSettings, modes: usize) -> Option<Self> {
        (settings.projective_steps && settings.reads(modes, "projective_steps"))
            .then(|| Self::new(settings.tol))
    }

    /// Starts counting again (after a leap that was not a projection).
    pub(super) fn reset(&mut self) {
        self.count = 0;
    }

    /// After an accepted step of `h` of `scheme` to the unknowns `z`: projects the run on if
    /// it is due and the slow flow allows, by at most `limit` time units; the time projected.
    pub(super) fn after_step(
        &mut self,
        scheme: &mut dyn Scheme,
        h: f64,
        z: &[f64],
        limit: f64,
    ) -> Option<f64> {
        if (h - self.h).abs() > 1e-12 * h {
            self.count = 0;
            self.h = h;
        }
        self.count += 1;
        self.last.rotate_left(1);
        self.last[2].clear();
        self.last[2].extend_from_slice(z);
        if self.count == INNER - 1 {
            let spectrum = scheme.spectrum()?;
            self.field.clear();
            self.field.extend_from_slice(spectrum);
            self.z.clear();
            self.z.extend_from_slice(z);
            let st = scheme.state();
            self.centre = (st.x, st.y);
        }
        if self.count < INNER {
            return None;
        }
        self.count = 0;
        let [a, b, c] = &self.last;
        let mut m = MAX_FACTOR;
        for ((a, b), c) in a.iter().zip(b).zip(c) {
            let curvature = (c - 2.0 * b + a).abs();
            if curvature == 0.0 {
                continue;
            }
            // The error bound, and this unknown's slope changing by at most SLOPE_CHANGE
            // (an unknown that moves by less than SLOPE_FLOOR a step is held to that).
            let slope = (c - b).abs().max(SLOPE_FLOOR);
            m = m
                .min((2.0 * self.tol / curvature).sqrt())
                .min(SLOPE_CHANGE * slope / curvature);
        }
        let m = m.min(MAX_FACTOR).min(limit / h);
        if m.is_nan() || m < MIN_FACTOR {
            return None;
        }
        let st = scheme.state();
        let shift = [m * (st.x - self.centre.0), m * (st.y - self.centre.1)];
        scheme
            .leap(&self.z, &self.field, 1.0 + m, shift)
            .then_some(m * h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::state::DropletState;
    use crate::stepping::{Attempt, Field, Stepper};

    /// A linear system stepped exactly: `a2' = -eps a2` (slow), `vx' = -mu (vx - a2)` and the
    /// one-mode field `w' = -mu (w - a2)` (fast, slaved to `a2`), and `(vy, b2)` turning at
    /// `omega` while decaying at `damping`.
    struct Toy {
        eps: f64,
        mu: f64,
        omega: f64,
        damping: f64,
        st: DropletState,
        w: Vec<Complex64>,
    }

    impl Toy {
        fn new(eps: f64, mu: f64, omega: f64, damping: f64, start: [f64; 4]) -> Self {
            let [vx, vy, a2, b2] = start;
            Self {
                eps,
                mu,
                omega,
                damping,
                st: DropletState {
                    vx,
                    vy,
                    a2,
                    b2,
                    ..Default::default()
                },
                w: vec![Complex64::default()],
            }
        }

        /// `x' = -mu x + mu a2(t)` over `h` with `a2` decaying at `eps` from `a2`.
        fn slaved(&self, x: f64, a2: f64, h: f64) -> f64 {
            let (e_slow, e_fast) = ((-self.eps * h).exp(), (-self.mu * h).exp());
            x * e_fast + self.mu * a2 * (e_slow - e_fast) / (self.mu - self.eps)
        }
    }

    impl Stepper for Toy {
        fn attempt(&mut self, h: f64, _max_error: f64) -> Attempt {
            let a2 = self.st.a2;
            self.st.vx = self.slaved(self.st.vx, a2, h);
            self.w[0].re = self.slaved(self.w[0].re, a2, h);
            self.st.a2 = a2 * (-self.eps * h).exp();
            let (c, s) = ((self.omega * h).cos(), (self.omega * h).sin());
            let decay = (-self.damping * h).exp();
            let (vy, b2) = (self.st.vy, self.st.b2);
            self.st.vy = decay * (c * vy - s * b2);
            self.st.b2 = decay * (s * vy + c * b2);
            self.st.x += h * self.st.vx;
            Attempt {
                accepted: true,
                error: None,
            }
        }
    }

    impl Scheme for Toy {
        fn state(&self) -> DropletState {
            self.st
        }
        fn mass(&self) -> f64 {
            0.0
        }
        fn field(&mut self) -> Field {
            Field {
                n: 1,
                len: 1.0,
                values: vec![self.w[0].re],
            }
        }
        fn spectrum(&self) -> Option<&[Complex64]> {
            Some(&self.w)
        }
        fn leap(
            &mut self,
            root: &[f64],
            field: &[Complex64],
            factor: f64,
            shift: [f64; 2],
        ) -> bool {
            crate::stepping::scale_displacement(&mut self.w, field, factor);
            let st = &mut self.st;
            crate::stepping::scale_displacement(
                [&mut st.vx, &mut st.vy, &mut st.a2, &mut st.b2],
                root,
                factor,
            );
            st.x += shift[0];
            true
        }
    }

    /// Steps `toy` by `h` with projections to `t_end`: its time, and the time projected.
    fn run(toy: &mut Toy, h: f64, t_end: f64) -> (f64, f64, u64) {
        let mut p = Projection::new(1e-4);
        let (mut t, mut projected, mut steps) = (0.0, 0.0, 0);
        while t < t_end - 1e-9 {
            toy.attempt(h, f64::INFINITY);
            t += h;
            steps += 1;
            let z = toy.st.monitored();
            if let Some(d) = p.after_step(toy, h, &z, t_end - t) {
                t += d;
                projected += d;
            }
        }
        (t, projected, steps)
    }

    #[test]
    fn a_slow_decay_is_followed_by_projections_to_within_their_error_bounds() {
        // A slow phase like a map's runs' (a change of 0.2 over a few hundred time units).
        let (eps, mu, h, t_end) = (0.003, 1.0, 0.25, 400.0);
        let mut toy = Toy::new(eps, mu, 0.0, 0.0, [0.0, 0.0, 0.2, 0.0]);
        let (t, projected, steps) = run(&mut toy, h, t_end);
        assert!((t - t_end).abs() < 1e-9, "{t}");
        // Most of the time is projected: fewer than half the steps.
        assert!(
            projected > 0.5 * t_end && steps < 800,
            "{projected} {steps}"
        );
        // The exact solution at t_end.
        let a2 = 0.2 * (-eps * t_end).exp();
        let vx = mu / (mu - eps) * (a2 - (-mu * t_end).exp());
        // Each projection's error is bounded by the tolerance (1e-4), and the decay shrinks
        // earlier errors: the sum of the bounds is the global bound.
        let bound = 1e-4 * PROJECTION_TOL * (projected / (MAX_FACTOR * h));
        assert!((toy.st.a2 - a2).abs() < bound, "{} vs {a2}", toy.st.a2);
        // The errors share a sign (each projection continues the chord's slope, which lags
        // the decay), so what they add to is closer to the slow decay's rate: within 1.5 % of
        // `a2` after 1.2 decay times (0.7 % measured).
        assert!(
            (toy.st.a2 / a2 - 1.0).abs() < 0.015,
            "{} vs {a2}",
            toy.st.a2
        );
        assert!((toy.st.vx - vx).abs() < bound, "{} vs {vx}", toy.st.vx);
        // The fast field stays on its slow manifold.
        assert!((toy.w[0].re - vx).abs() < bound, "{} vs {vx}", toy.w[0].re);
    }

    #[test]
    fn no_projection_while_a_fast_part_is_excited_or_a_mode_turns() {
        // A fast part far from its slaved value: none before it has decayed.
        let mut toy = Toy::new(0.01, 0.2, 0.0, 0.0, [5.0, 0.0, 1.0, 0.0]);
        let mut p = Projection::new(1e-4);
        for step in 1..=80 {
            toy.attempt(0.25, f64::INFINITY);
            let z = toy.st.monitored();
            let moved = p.after_step(&mut toy, 0.25, &z, f64::INFINITY);
            assert!(moved.is_none() || step > 40, "step {step}");
        }
        // A weakly damped oscillation at omega = 0.3: never, however small.
        let mut toy = Toy::new(0.0, 1.0, 0.3, 1e-3, [0.0, 1e-6, 0.0, 0.0]);
        let (_, projected, _) = run(&mut toy, 0.25, 200.0);
        assert_eq!(projected, 0.0);
    }

    #[test]
    fn the_modes_a_projection_does_not_follow_shrink_whatever_their_rate() {
        // Per cycle of INNER steps and a projection of M steps, a mode decaying at mu is
        // multiplied by rho^(INNER - 1) (rho - M (1 - rho)), rho = exp(-mu h); the modes it
        // does not follow are those with mu (INNER + M) h > 2.
        let h = 0.25;
        let mut largest: f64 = 0.0;
        for m in [MIN_FACTOR, 4.0, 8.0, 12.0, MAX_FACTOR] {
            for i in 1..200_000 {
                let mu = i as f64 * 2e-4;
                if mu * (INNER as f64 + m) * h <= 2.0 {
                    continue;
                }
                let rho = (-mu * h).exp();
                let f = rho.powi(INNER as i32 - 1) * (rho - m * (1.0 - rho));
                largest = largest.max(f.abs());
            }
        }
        assert!(largest < 0.70, "{largest}");
    }

    #[test]
    fn a_projection_never_passes_the_limit_nor_starts_after_a_change_of_step() {
        let mut toy = Toy::new(0.001, 1.0, 0.0, 0.0, [0.0, 0.0, 1.0, 0.0]);
        let mut p = Projection::new(1e-4);
        let mut moved = Vec::new();
        for step in 0..200 {
            // Another step size every 20 steps until step 100.
            let h = if step < 100 && (step / 20) % 2 == 1 {
                0.2
            } else {
                0.25
            };
            toy.attempt(h, f64::INFINITY);
            let z = toy.st.monitored();
            if let Some(d) = p.after_step(&mut toy, h, &z, 1.5) {
                moved.push((step, d));
            }
        }
        assert!(!moved.is_empty());
        for (step, d) in moved {
            assert!(d <= 1.5 + 1e-12, "{d}");
            // Each size is kept 20 steps: the first projection of a size comes INNER steps in.
            assert!(step >= 100 || step % 20 >= INNER - 1, "{step}");
        }
    }
}
