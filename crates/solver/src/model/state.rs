//! The droplet's mechanical state: centre `r_c`, velocity `v`, shape amplitudes `a2, b2`.
use serde::{Deserialize, Serialize};

/// Centre, velocity and mode-2 amplitudes of the droplet.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct DropletState {
    pub x: f64,
    pub y: f64,
    pub vx: f64,
    pub vy: f64,
    pub a2: f64,
    pub b2: f64,
}

impl DropletState {
    /// Speed `v = |dr_c/dt|`.
    pub fn speed(&self) -> f64 {
        self.vx.hypot(self.vy)
    }

    /// Deformation magnitude `s = sqrt(a2^2 + b2^2)`.
    pub fn deformation(&self) -> f64 {
        self.a2.hypot(self.b2)
    }

    /// The four quantities of the paper's steady-state test.
    pub fn monitored(&self) -> [f64; 4] {
        [self.vx, self.vy, self.a2, self.b2]
    }

    /// True when every component is finite.
    pub fn is_finite(&self) -> bool {
        [self.x, self.y, self.vx, self.vy, self.a2, self.b2]
            .iter()
            .all(|c| c.is_finite())
    }
}

/// The distance of two monitored states `(vx, vy, a2, b2)`: the largest difference of a
/// component (the paper's steady test's norm).
pub fn max_distance(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}
