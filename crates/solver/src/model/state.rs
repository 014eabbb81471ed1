//! The droplet's mechanical state: centre `r_c`, velocity `v`, shape amplitudes `a2, b2`.
use serde::{Deserialize, Serialize};

/// The mode-2 amplitudes `(a2, b2)` of unknowns `z = (vx, vy, a_2..a_K, b_2..b_K)`.
pub fn mode_two(z: &[f64]) -> (f64, f64) {
    (z[2], z[z.len() / 2 + 1])
}

/// Speed `v = |(vx, vy)|` and deformation `s = |a2 + i b2|` (mode 2, the paper's) of unknowns
/// `z = (vx, vy, a_2..a_K, b_2..b_K)`: the `v` and `s` that every table and `--json` reports.
pub fn speed_and_deformation(z: &[f64]) -> (f64, f64) {
    let (a2, b2) = mode_two(z);
    (z[0].hypot(z[1]), a2.hypot(b2))
}

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

    /// The droplet of unknowns `z = (vx, vy, a_2..a_K, b_2..b_K)` centred at `(x, y)`, and its
    /// higher amplitudes `a_3..a_K, b_3..b_K` (none for `K = 2`).
    pub fn of_unknowns(z: &[f64], x: f64, y: f64) -> (Self, Vec<f64>) {
        let k = z.len() / 2;
        let state = Self {
            x,
            y,
            vx: z[0],
            vy: z[1],
            a2: z[2],
            b2: z[k + 1],
        };
        let higher = z[3..k + 1].iter().chain(&z[k + 2..]).copied().collect();
        (state, higher)
    }

    /// True when every component is finite.
    pub fn is_finite(&self) -> bool {
        [self.x, self.y, self.vx, self.vy, self.a2, self.b2]
            .iter()
            .all(|c| c.is_finite())
    }
}

/// The largest magnitude of `values`, NaN if any of them is NaN (`f64::max` passes over NaN,
/// and a run that left the model must not read as one at rest): a step's error estimate, a
/// run's largest rate.
pub fn largest_magnitude(values: impl IntoIterator<Item = f64>) -> f64 {
    values.into_iter().fold(0.0, |m: f64, x| {
        let a = x.abs();
        if m.is_nan() || a.is_nan() {
            f64::NAN
        } else {
            m.max(a)
        }
    })
}

/// The distance of two co-moving states `(vx, vy, a_2..a_K, b_2..b_K)` (for `K = 2` the
/// monitored `(vx, vy, a2, b2)`): the largest difference of a component (the paper's steady
/// test's norm).
pub fn max_distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The co-moving unknowns `(vx, vy, a_2..a_K, b_2..b_K)` of the droplet `z` turned by `phi`:
/// the velocity by `phi`, shape mode `k` by `k phi` (`r(theta) -> r(theta - phi)`). For
/// `K = 2`, `(vx, vy, a2, b2)`: the velocity once, the mode-2 shape twice.
pub fn turned(z: &[f64], phi: f64) -> Vec<f64> {
    let k_max = z.len() / 2;
    let (c, s) = (phi.cos(), phi.sin());
    let mut out = z.to_vec();
    out[0] = c * z[0] - s * z[1];
    out[1] = s * z[0] + c * z[1];
    for k in 2..=k_max {
        let (a, b) = (z[k], z[k_max - 1 + k]);
        let (ck, sk) = ((k as f64 * phi).cos(), (k as f64 * phi).sin());
        out[k] = ck * a - sk * b;
        out[k_max - 1 + k] = sk * a + ck * b;
    }
    out
}

/// The co-moving unknowns of the droplet `z` reflected in the line through its centre at the
/// angle `alpha` (`r(theta) -> r(2 alpha - theta)`): the velocity `v -> e^(2 i alpha) conj(v)`,
/// shape mode `k`, `a_k + i b_k -> e^(2 k i alpha) conj(a_k + i b_k)`. In one of the box's
/// mirror lines (`alpha` a multiple of 45 degrees) a root's image is a root, as stable.
pub fn reflected(z: &[f64], alpha: f64) -> Vec<f64> {
    let k_max = z.len() / 2;
    let mirror = |x: f64, y: f64, angle: f64| {
        let (c, s) = (angle.cos(), angle.sin());
        (c * x + s * y, s * x - c * y)
    };
    let mut out = z.to_vec();
    (out[0], out[1]) = mirror(z[0], z[1], 2.0 * alpha);
    for k in 2..=k_max {
        (out[k], out[k_max - 1 + k]) = mirror(z[k], z[k_max - 1 + k], 2.0 * k as f64 * alpha);
    }
    out
}

/// The 2-mode unknowns `(vx, vy, a2, b2)` of a state of `K = 2`.
pub fn four(z: &[f64]) -> [f64; 4] {
    z.try_into().expect("a state of the 2-mode model")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_largest_magnitude_is_nan_wherever_a_nan_stands() {
        assert_eq!(largest_magnitude([0.5, -2.0, 1.0]), 2.0);
        assert_eq!(largest_magnitude(std::iter::empty()), 0.0);
        for at in 0..3 {
            let mut v = [1e-3, -4.0, 2.0];
            v[at] = f64::NAN;
            assert!(largest_magnitude(v).is_nan(), "NaN at {at}");
        }
    }

    #[test]
    fn reflecting_twice_in_a_line_is_the_identity_and_in_two_lines_a_turn() {
        let z = [0.3, 0.1, -0.07, 0.01, 2e-3, 0.02, -1e-3, 5e-4];
        let quarter = std::f64::consts::FRAC_PI_4;
        let back = reflected(&reflected(&z, quarter), quarter);
        assert!(z.iter().zip(&back).all(|(a, b)| (a - b).abs() < 1e-15));
        // Reflections in lines alpha and beta compose to the turn by 2 (beta - alpha).
        let both = reflected(&reflected(&z, 0.0), quarter);
        let turn = turned(&z, 2.0 * quarter);
        assert!(both.iter().zip(&turn).all(|(a, b)| (a - b).abs() < 1e-15));
        // In the x axis: vy, b_k change sign.
        let x = reflected(&z, 0.0);
        assert_eq!(x, vec![0.3, -0.1, -0.07, 0.01, 2e-3, -0.02, 1e-3, -5e-4]);
    }

    #[test]
    fn turning_a_state_turns_its_motion_once_and_shape_mode_k_k_times() {
        let z = vec![0.5, 0.1, -0.2, 0.03, 0.01, 0.05, -0.02, 0.004];
        // Two turns add; a full turn is the identity.
        let twice = turned(&turned(&z, 0.3), 0.4);
        let once = turned(&z, 0.7);
        assert!(twice.iter().zip(&once).all(|(a, b)| (a - b).abs() < 1e-15));
        let full = turned(&z, 2.0 * std::f64::consts::PI);
        assert!(full.iter().zip(&z).all(|(a, b)| (a - b).abs() < 1e-15));
        // K = 2, 90 degrees: the velocity turns a quarter, the mode-2 shape changes sign.
        let r = turned(&[0.5, 0.1, -0.2, 0.05], std::f64::consts::FRAC_PI_2);
        let expect = [-0.1, 0.5, 0.2, -0.05];
        assert!(
            r.iter().zip(&expect).all(|(a, b)| (a - b).abs() < 1e-15),
            "{r:?}"
        );
        // An x-axis state of K = 4 turned by 45 degrees lies on the diagonal mirror: a2 = 0,
        // b3 = -a3, b4 = 0.
        let d = turned(
            &[0.4, 0.0, -0.25, 0.04, 0.01, 0.0, 0.0, 0.0],
            std::f64::consts::FRAC_PI_4,
        );
        assert!((d[0] - d[1]).abs() < 1e-15 && d[2].abs() < 1e-15);
        assert!((d[3] + d[6]).abs() < 1e-15 && d[7].abs() < 1e-15, "{d:?}");
    }
}
