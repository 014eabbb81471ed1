//! The stop rules of a run (paper Sect. 3), shared by the PDE run driver and the ODE model:
//! the steady-state test (max change of `vx, vy, a2, b2` below `steady_tol` per
//! `steady_window` time units) and divergence (a non-finite value, or `s >= 1`, outside the
//! small-deformation model of eq. 31; with more shape modes a run also diverges when its
//! boundary reaches the centre, [`crate::model::modes::Modes::reaches_centre`]).
use crate::contract::settings::SolverSettings;

/// True when a state `(vx, vy, a2, b2)` (and anything else in `extra`) has left the model.
pub fn diverged(monitored: [f64; 4], extra: &[f64]) -> bool {
    let [_, _, a2, b2] = monitored;
    monitored.iter().chain(extra).any(|x| !x.is_finite()) || a2.hypot(b2) >= 1.0
}

/// The steady-state test. It compares states at least one window apart and scales the change
/// to one window (`change * window / elapsed`), so it keeps the paper's meaning (change per
/// 0.1 time units) for steps longer than the window.
#[derive(Debug, Clone)]
pub struct SteadyTest {
    window: f64,
    tol: f64,
    /// Times within `slack` of a target count as reaching it (round-off of sums of steps).
    slack: f64,
    checkpoint: (f64, [f64; 4]),
}

impl SteadyTest {
    /// A test with the window and tolerance of `settings`, starting from `monitored` at `t`.
    pub fn new(settings: &SolverSettings, t: f64, monitored: [f64; 4]) -> Self {
        Self {
            window: settings.steady_window,
            tol: settings.steady_tol,
            slack: 1e-9 * settings.dt,
            checkpoint: (t, monitored),
        }
    }

    /// Feeds the state at `t`; true when the state is steady.
    pub fn is_steady(&mut self, t: f64, monitored: [f64; 4]) -> bool {
        self.judge(t, monitored)
            .is_some_and(|change| change < self.tol)
    }

    /// Feeds the state at `t`: once a window has passed since the last judgement, the change
    /// since then scaled to one window (steady when below the tolerance); else `None`.
    pub fn judge(&mut self, t: f64, monitored: [f64; 4]) -> Option<f64> {
        let elapsed = t - self.checkpoint.0;
        if elapsed < self.window - self.slack {
            return None;
        }
        let change = monitored
            .iter()
            .zip(self.checkpoint.1)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        self.checkpoint = (t, monitored);
        Some(change * (self.window / elapsed).min(1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steady_after_one_quiet_window_and_diverged_outside_the_model() {
        let s = SolverSettings::default();
        let mut test = SteadyTest::new(&s, 0.0, [1.0, 0.0, 0.1, 0.0]);
        // Too early: not judged.
        assert!(!test.is_steady(0.05, [1.0, 0.0, 0.1, 0.0]));
        // One window later with a change of 1e-5: not steady; then a quiet window: steady.
        assert!(!test.is_steady(0.1, [1.0 + 1e-5, 0.0, 0.1, 0.0]));
        assert!(test.is_steady(0.2, [1.0 + 1e-5 + 5e-7, 0.0, 0.1, 0.0]));
        // A long step: the change is scaled to one window (2e-6 over 1.0 -> 2e-7 per 0.1).
        let mut long = SteadyTest::new(&s, 0.0, [0.0; 4]);
        assert!(long.is_steady(1.0, [2e-6, 0.0, 0.0, 0.0]));
        assert!(diverged([f64::NAN, 0.0, 0.0, 0.0], &[]));
        assert!(diverged([0.0, 0.0, 0.8, 0.6], &[]));
        assert!(diverged([0.0; 4], &[f64::INFINITY]));
        assert!(!diverged([1.0, 0.0, 0.5, 0.5], &[3.0]));
    }
}
