//! The stop rules of a run (paper Sect. 3), shared by the PDE run driver and the ODE model:
//! the steady-state test (max change of `vx, vy, a2, b2` below `steady_tol` per
//! `steady_window` time units) and divergence (a non-finite value, or a boundary that reaches
//! the droplet's centre, outside the small-deformation model of eq. 31: `s >= 1` for two
//! modes).
use crate::contract::settings::SolverSettings;

/// True when a state `(vx, vy, a2, b2)` (and anything else in `extra`) has left the model.
pub fn diverged(monitored: [f64; 4], extra: &[f64]) -> bool {
    let [_, _, a2, b2] = monitored;
    monitored.iter().chain(extra).any(|x| !x.is_finite()) || a2.hypot(b2) >= 1.0
}

/// True when the shape `(a_2..a_K, b_2..b_K)` of a state has left the model: its boundary
/// `f(theta) = R (1 + sum_k a_k cos k theta + b_k sin k theta)` reaches the centre at some
/// angle, so `r = f(theta)` bounds no droplet. With mode 2 alone the smallest radius is
/// `R (1 - s)` and the rule is [`diverged`]'s `s >= 1`; with more modes the smallest of `32 K`
/// equally spaced angles is taken (between them `f` is off its sampled minimum by at most
/// `(pi / 32 K)^2 / 2 sum_k k^2 |c_k|`, below 1 % of the deformation: a collapsing run
/// passes the line within a step or two).
pub fn shape_collapsed(shape: &[f64]) -> bool {
    let m = shape.len() / 2;
    if m <= 1 {
        return shape
            .first()
            .zip(shape.get(1))
            .is_some_and(|(a, b)| a.hypot(*b) >= 1.0);
    }
    let (a, b) = shape.split_at(m);
    let samples = 32 * (m + 1);
    let step = std::f64::consts::TAU / samples as f64;
    (0..samples).any(|i| {
        let (s1, c1) = (i as f64 * step).sin_cos();
        let (mut ck, mut sk) = (c1, s1);
        let mut f = 1.0;
        for (ak, bk) in a.iter().zip(b) {
            (ck, sk) = (ck * c1 - sk * s1, sk * c1 + ck * s1);
            f += ak * ck + bk * sk;
        }
        f <= 0.0
    })
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

    #[test]
    fn a_shape_collapses_where_its_boundary_reaches_the_centre() {
        // Two modes: exactly s >= 1.
        assert!(!shape_collapsed(&[0.6, 0.79]));
        assert!(shape_collapsed(&[0.6, 0.8]));
        // Modes 2..4 on the x axis, (a2, a3, a4, b2, b3, b4): f(0) = 1 + a2 + a3 + a4.
        assert!(!shape_collapsed(&[-0.51, 0.0, 0.11, 0.0, 0.0, 0.0]));
        assert!(shape_collapsed(&[-0.6, 0.0, -0.45, 0.0, 0.0, 0.0]));
        // Every amplitude below 1 and s < 1: the rule agrees with a scan of 100 000 angles
        // (smallest radius -0.11, 0.087 and 0.31 R).
        for shape in [
            [0.4, -0.3, 0.35, 0.2, 0.1, -0.3],
            [-0.5, 0.45, 0.1, 0.0, 0.0, 0.2],
            [0.2, 0.2, 0.2, 0.2, 0.2, 0.2],
        ] {
            let fine = (0..100_000)
                .map(|i| {
                    let t = std::f64::consts::TAU * i as f64 / 1e5;
                    1.0 + (0..3)
                        .map(|j| {
                            let k = (j + 2) as f64;
                            shape[j] * (k * t).cos() + shape[j + 3] * (k * t).sin()
                        })
                        .sum::<f64>()
                })
                .fold(f64::INFINITY, f64::min);
            assert_eq!(shape_collapsed(&shape), fine <= 0.0, "{shape:?}: {fine}");
        }
    }
}
