//! Step-size control for the adaptive co-moving ETD2RK scheme: a PI controller
//! (Gustafsson 1991; Hairer & Wanner, Sect. IV.2) on the embedded error estimate.
//!
//! The estimate is ETD2RK's corrector minus its ETD1 predictor ([`crate::stepping::etd`]), the local
//! error of the first-order companion, so it scales as `h^2`. With `e_n = estimate / tol`
//! the next step is `h * safety * e_n^(-beta1/2) * e_(n-1)^(beta2/2)`, bounded to
//! `[min_factor, max_factor] * h` and to `h_max`; a step with `e_n > 1` is rejected and
//! retried with `h * max(min_factor, safety * e_n^(-1/2))`, and the step after a rejection
//! may not grow.

/// PI step-size controller (one per run).
#[derive(Debug, Clone)]
pub struct PiController {
    h_max: f64,
    /// Normalised error of the last accepted step.
    prev: f64,
    /// The last attempt was rejected.
    rejected: bool,
}

const SAFETY: f64 = 0.9;
const BETA1: f64 = 0.7;
const BETA2: f64 = 0.4;
const MIN_FACTOR: f64 = 0.2;
const MAX_FACTOR: f64 = 5.0;
/// Exponent denominator: the estimate is the local error of a first-order method, `O(h^2)`.
const ORDER: f64 = 2.0;
/// Floor on normalised errors so that a zero estimate (an exact fixed point) cannot divide by 0.
const ERR_FLOOR: f64 = 1e-10;

impl PiController {
    pub fn new(h_max: f64) -> Self {
        Self {
            h_max,
            prev: 1.0,
            rejected: false,
        }
    }

    /// Next step after accepting a step `h` with normalised error `err <= 1`.
    pub fn accept(&mut self, h: f64, err: f64) -> f64 {
        let err = err.max(ERR_FLOOR);
        let mut factor = SAFETY * err.powf(-BETA1 / ORDER) * self.prev.powf(BETA2 / ORDER);
        factor = factor.clamp(MIN_FACTOR, MAX_FACTOR);
        if self.rejected {
            factor = factor.min(1.0);
        }
        self.prev = err;
        self.rejected = false;
        (h * factor).min(self.h_max)
    }

    /// Step to retry with after rejecting `h` with normalised error `err > 1` (or non-finite).
    pub fn reject(&mut self, h: f64, err: f64) -> f64 {
        self.rejected = true;
        let factor = if err.is_finite() {
            (SAFETY * err.powf(-1.0 / ORDER)).max(MIN_FACTOR)
        } else {
            MIN_FACTOR
        };
        (h * factor).min(self.h_max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grows_on_small_errors_and_shrinks_on_rejection() {
        let mut c = PiController::new(1.0);
        let h = c.accept(0.01, 1e-4);
        assert!(h > 0.01 && h <= 0.05 + 1e-15, "{h}");
        let h2 = c.reject(h, 16.0);
        assert!((h2 - h * 0.9 / 4.0).abs() < 1e-15);
        // No growth right after a rejection, however small the error.
        assert!(c.accept(h2, 1e-6) <= h2);
        // Bounded by h_max; a zero estimate does not blow up.
        let mut c = PiController::new(0.5);
        assert_eq!(c.accept(0.4, 0.0), 0.5);
        assert_eq!(c.reject(0.4, f64::NAN), 0.4 * MIN_FACTOR);
    }

    #[test]
    fn settles_where_the_error_meets_the_tolerance() {
        // A model estimate err = (h / h_star)^2: the controller should settle below h_star,
        // with errors under 1 but not far under it (the safety factor keeps a margin).
        let h_star: f64 = 0.3;
        let mut c = PiController::new(10.0);
        let mut h: f64 = 1e-3;
        for _ in 0..200 {
            let err = (h / h_star).powi(2);
            h = if err <= 1.0 {
                c.accept(h, err)
            } else {
                c.reject(h, err)
            };
        }
        let err = (h / h_star).powi(2);
        assert!(err < 1.0 && err > 0.3, "h {h} err {err}");
    }
}
