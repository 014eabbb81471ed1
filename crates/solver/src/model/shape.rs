//! The smoothed droplet indicator `Theta_sigma` (paper eq. 31).
//!
//! `Theta = (1 + tanh(-q)) / 2` with `q = (r - f(theta)) / sigma`,
//! `f(theta) = R (1 + a2 cos 2theta + b2 sin 2theta)`. Beyond `|q| = BAND_Q` the profile equals
//! 0 or 1 to within 1e-14, so `Theta` is only evaluated inside the annulus
//! `R (1 - s) - BAND_Q sigma <= r <= R (1 + s) + BAND_Q sigma` (the "window").

/// Half-width of the transition band in units of sigma: `1 - tanh(16) = 2.5e-14`.
pub const BAND_Q: f64 = 16.0;

/// Droplet radius and interface width, the only model parameters the shape needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeParams {
    pub radius: f64,
    pub sigma: f64,
}

impl ShapeParams {
    /// Radius outside of which `Theta = 0`.
    pub fn outer_radius(&self, a2: f64, b2: f64) -> f64 {
        self.radius * (1.0 + a2.hypot(b2)) + BAND_Q * self.sigma
    }

    /// Radius inside of which `Theta = 1` (0 when the band reaches the centre).
    pub fn inner_radius(&self, a2: f64, b2: f64) -> f64 {
        (self.radius * (1.0 - a2.hypot(b2)) - BAND_Q * self.sigma).max(0.0)
    }

    /// Boundary radius `f(theta)` for the direction `(cos theta, sin theta) = (cx, sy)`.
    pub fn boundary(&self, a2: f64, b2: f64, cx: f64, sy: f64) -> f64 {
        let c2 = cx * cx - sy * sy;
        let s2 = 2.0 * cx * sy;
        self.radius * (1.0 + a2 * c2 + b2 * s2)
    }

    /// `Theta` at offset `(x, y)` from the droplet centre.
    #[inline(always)]
    pub fn theta(&self, a2: f64, b2: f64, x: f64, y: f64) -> f64 {
        let r2 = x * x + y * y;
        if r2 == 0.0 {
            return if self.radius * (1.0 + a2) > 0.0 {
                1.0
            } else {
                0.0
            };
        }
        let inv_r2 = 1.0 / r2;
        let r = r2.sqrt();
        let f = self.radius * (1.0 + (a2 * (x * x - y * y) + b2 * 2.0 * x * y) * inv_r2);
        profile((r - f) / self.sigma)
    }
}

/// The interface profile `(1 - tanh q) / 2` of eq. 31, `q = (r - f) / sigma`: exactly 0 or 1
/// beyond `|q| = BAND_Q`.
#[inline(always)]
pub fn profile(q: f64) -> f64 {
    if q >= BAND_Q {
        0.0
    } else if q <= -BAND_Q {
        1.0
    } else {
        // (1 - tanh q) / 2 from one exponential, without cancellation for either sign.
        let e = (-2.0 * q.abs()).exp();
        if q >= 0.0 {
            e / (1.0 + e)
        } else {
            1.0 / (1.0 + e)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profile_limits_midpoint_and_tanh() {
        let s = ShapeParams {
            radius: 1.0,
            sigma: 0.03,
        };
        assert_eq!(s.theta(0.1, 0.02, 0.2, 0.1), 1.0);
        assert_eq!(s.theta(0.1, 0.02, 2.0, 0.1), 0.0);
        let (cx, sy) = (0.6f64, 0.8f64);
        let f = s.boundary(0.1, 0.02, cx, sy);
        assert!((s.theta(0.1, 0.02, f * cx, f * sy) - 0.5).abs() < 1e-12);
        for d in [-0.05, -0.01, 0.003, 0.04] {
            let r = f + d;
            let expect = 0.5 * (1.0 + (-d / 0.03f64).tanh());
            assert!((s.theta(0.1, 0.02, r * cx, r * sy) - expect).abs() < 1e-14);
        }
    }
}
