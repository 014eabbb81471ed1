//! The paper's general droplet shape with modes `k = 2..K` (eq. for `f(theta)` in Sect. 2):
//! `f(theta) = R [1 + sum_k (a_k cos k theta + b_k sin k theta)]`, its smoothed indicator
//! `Theta = (1 + tanh(-(r - f) / sigma)) / 2` (the same profile as eq. 31 for `K = 2`), and the
//! incompressible fields `w_k^(a)`, `w_k^(b)` (eqs. wka, wkb) that move the boundary along one
//! mode: `w_k^(a) = grad[(R^2 / k) (r / R)^k cos k theta] = R^(2-k) (Re z^(k-1), -Im z^(k-1))`,
//! `w_k^(b) = R^(2-k) (Im z^(k-1), Re z^(k-1))` with `z = x + i y`.
use crate::model::shape::{profile, ShapeParams, BAND_Q};

/// Shape amplitudes `a_k`, `b_k` for `k = 2..=K` (`a[k - 2]`, `b[k - 2]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Modes {
    pub a: Vec<f64>,
    pub b: Vec<f64>,
}

/// Most shape modes of the `K`-mode model.
pub const MAX_MODES: usize = 16;

/// Checks a number of shape modes `K` alone (modes `2..=K`): from 2 to [`MAX_MODES`] (what the
/// grid resolves: [`crate::contract::limits::check_modes`]).
pub fn check_count(k_max: usize) -> Result<(), crate::error::SolverError> {
    crate::error::require(
        (2..=MAX_MODES).contains(&k_max),
        "modes",
        k_max as f64,
        format!("an integer from 2 (the paper's a2, b2) to {MAX_MODES}"),
    )
}

/// The restoring coefficient of shape mode `k`, `kappa_k = (k^2 / 4) kappa2` (the paper's
/// `kappa_k = pi k^2 tau R`, scaled by mode 2's).
pub fn kappa_k(kappa2: f64, k: usize) -> f64 {
    (k * k) as f64 / 4.0 * kappa2
}

/// `(Re, Im)` of `(x + i y)^p`.
fn power(x: f64, y: f64, p: usize) -> (f64, f64) {
    let (mut re, mut im) = (1.0, 0.0);
    for _ in 0..p {
        (re, im) = (re * x - im * y, re * y + im * x);
    }
    (re, im)
}

impl Modes {
    /// The circle with modes up to `k_max` (at least 2).
    pub fn circle(k_max: usize) -> Self {
        let m = k_max.max(2) - 1;
        Self {
            a: vec![0.0; m],
            b: vec![0.0; m],
        }
    }

    /// The shape of a state `z = (vx, vy, a_2..a_K, b_2..b_K)`.
    pub fn of_state(z: &[f64]) -> Self {
        let m = (z.len() - 2) / 2;
        Self {
            a: z[2..2 + m].to_vec(),
            b: z[2 + m..2 + 2 * m].to_vec(),
        }
    }

    /// The largest mode `K`.
    pub fn k_max(&self) -> usize {
        self.a.len() + 1
    }

    /// `sum_k (|a_k| + |b_k|)`: the largest relative change of the radius.
    fn reach(&self) -> f64 {
        self.a.iter().chain(&self.b).map(|c| c.abs()).sum()
    }

    /// The total deformation `sqrt(sum_k a_k^2 + b_k^2)`.
    pub fn deformation(&self) -> f64 {
        self.a
            .iter()
            .chain(&self.b)
            .map(|c| c * c)
            .sum::<f64>()
            .sqrt()
    }

    /// `sum_k (a_k cos k theta + b_k sin k theta)` for `(cos theta, sin theta) = (c, s)`.
    fn relative(&self, c: f64, s: f64) -> f64 {
        let (mut ck, mut sk) = (c, s);
        let mut sum = 0.0;
        for (a, b) in self.a.iter().zip(&self.b) {
            (ck, sk) = (ck * c - sk * s, sk * c + ck * s);
            sum += a * ck + b * sk;
        }
        sum
    }

    /// The boundary radius `f(theta)` for `(cos theta, sin theta) = (c, s)`.
    pub fn boundary(&self, shape: &ShapeParams, c: f64, s: f64) -> f64 {
        shape.radius * (1.0 + self.relative(c, s))
    }

    /// Whether the boundary `f(theta)` reaches the centre at some angle: the shape has left the
    /// model, `r = f(theta)` bounding no droplet. With mode 2 alone the smallest radius is
    /// `R (1 - s)` and this is the 2-mode rule `s >= 1` ([`crate::contract::stop_rule`]); with
    /// more modes the smallest of `32 K` equally spaced angles is taken (between them `f` is
    /// off its sampled minimum by at most `(pi / 32 K)^2 / 2 sum_k k^2 |c_k|`, below 1 % of the
    /// deformation: a collapsing run passes the line within a step or two).
    pub fn reaches_centre(&self) -> bool {
        if self.a.len() <= 1 {
            return self
                .a
                .first()
                .zip(self.b.first())
                .is_some_and(|(a, b)| a.hypot(*b) >= 1.0);
        }
        let samples = 32 * self.k_max();
        let step = std::f64::consts::TAU / samples as f64;
        (0..samples).any(|i| {
            let (s, c) = (i as f64 * step).sin_cos();
            1.0 + self.relative(c, s) <= 0.0
        })
    }

    /// Radius outside of which `Theta = 0`.
    pub fn outer_radius(&self, shape: &ShapeParams) -> f64 {
        shape.radius * (1.0 + self.reach()) + BAND_Q * shape.sigma
    }

    /// Radius inside of which `Theta = 1` (0 when the band reaches the centre).
    pub fn inner_radius(&self, shape: &ShapeParams) -> f64 {
        (shape.radius * (1.0 - self.reach()) - BAND_Q * shape.sigma).max(0.0)
    }

    /// `Theta` at the radius `r` and the harmonics `(cos k theta, sin k theta)`, `k = 2..`,
    /// interleaved (at least this shape's modes; [`super::forces::polar`] tabulates them):
    /// [`Self::theta`] with its square root and recurrence taken beforehand, the same value.
    #[inline(always)]
    pub fn theta_on(&self, shape: &ShapeParams, r: f64, harmonics: &[f64]) -> f64 {
        if r == 0.0 {
            return 1.0;
        }
        let mut sum = 0.0;
        for ((a, b), h) in self.a.iter().zip(&self.b).zip(harmonics.chunks_exact(2)) {
            sum += a * h[0] + b * h[1];
        }
        profile((r - shape.radius * (1.0 + sum)) / shape.sigma)
    }

    /// `Theta` at offset `(x, y)` from the droplet centre.
    pub fn theta(&self, shape: &ShapeParams, x: f64, y: f64) -> f64 {
        // The square root of the squared radius, as the 2-mode shape takes it.
        let r = (x * x + y * y).sqrt();
        if r == 0.0 {
            return 1.0;
        }
        profile((r - self.boundary(shape, x / r, y / r)) / shape.sigma)
    }
}

/// `w_k^(a)` and `w_k^(b)` at `(x, y)` (relative to the centre) for a droplet of radius `r0`.
pub fn w_fields(k: usize, r0: f64, x: f64, y: f64) -> ([f64; 2], [f64; 2]) {
    let (re, im) = power(x, y, k - 1);
    let scale = r0.powi(2 - k as i32);
    ([scale * re, -scale * im], [scale * im, scale * re])
}

#[cfg(test)]
mod tests {
    use super::*;

    const SHAPE: ShapeParams = ShapeParams {
        radius: 1.0,
        sigma: 0.03,
    };

    #[test]
    fn a_shape_reaches_its_centre_where_its_boundary_does() {
        // (a_2..a_K, b_2..b_K) as a state holds them.
        let m = |shape: &[f64]| Modes::of_state(&[[0.0, 0.0].as_slice(), shape].concat());
        // Two modes: exactly s >= 1.
        assert!(!m(&[0.6, 0.79]).reaches_centre());
        assert!(m(&[0.6, 0.8]).reaches_centre());
        // Modes 2..4 on the x axis, (a2, a3, a4, b2, b3, b4): f(0) = 1 + a2 + a3 + a4.
        assert!(!m(&[-0.51, 0.0, 0.11, 0.0, 0.0, 0.0]).reaches_centre());
        assert!(m(&[-0.6, 0.0, -0.45, 0.0, 0.0, 0.0]).reaches_centre());
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
            assert_eq!(m(&shape).reaches_centre(), fine <= 0.0, "{shape:?}: {fine}");
        }
    }

    #[test]
    fn two_modes_are_the_paper_plane_shape() {
        let m = Modes {
            a: vec![0.12],
            b: vec![-0.05],
        };
        for (x, y) in [(0.3, 0.9), (-1.05, 0.2), (0.7, -0.74), (0.0, 1.1)] {
            let t = m.theta(&SHAPE, x, y);
            let t2 = SHAPE.theta(0.12, -0.05, x, y);
            assert!((t - t2).abs() < 1e-14, "{t} vs {t2} at ({x}, {y})");
        }
    }

    #[test]
    fn w_fields_are_divergence_free_and_move_the_boundary_along_their_mode() {
        let h = 1e-5;
        for k in 2..=6 {
            for (x, y) in [(0.3, 0.9), (-1.05, 0.2), (0.7, -0.74)] {
                for pick in [0, 1] {
                    let w = |x: f64, y: f64| {
                        let (a, b) = w_fields(k, 1.3, x, y);
                        [a, b][pick]
                    };
                    let div = (w(x + h, y)[0] - w(x - h, y)[0] + w(x, y + h)[1] - w(x, y - h)[1])
                        / (2.0 * h);
                    assert!(div.abs() < 1e-8, "k = {k}: div {div}");
                }
            }
            // On the circle r = R, w . e_r = R cos k theta (a) and R sin k theta (b):
            // the boundary's radial displacement of a unit a_k (b_k).
            let r0 = 1.3;
            for th in [0.1f64, 1.0, 2.5, 4.0] {
                let (c, s) = (th.cos(), th.sin());
                let (wa, wb) = w_fields(k, r0, r0 * c, r0 * s);
                let kf = k as f64;
                assert!((wa[0] * c + wa[1] * s - r0 * (kf * th).cos()).abs() < 1e-12);
                assert!((wb[0] * c + wb[1] * s - r0 * (kf * th).sin()).abs() < 1e-12);
            }
        }
        // k = 2 is the paper's w_2 (eq. 39): (x, -y) and (y, x).
        let (a, b) = w_fields(2, 1.0, 0.4, -0.7);
        assert_eq!((a, b), ([0.4, 0.7], [-0.7, 0.4]));
    }

    #[test]
    fn rotating_by_pi_over_k_flips_a_k() {
        // f(theta - pi / k) with a_k is f(theta) with -a_k.
        let k = 3;
        let mut m = Modes::circle(4);
        m.a[k - 2] = 0.1;
        let mut flipped = m.clone();
        flipped.a[k - 2] = -0.1;
        let rot = std::f64::consts::PI / k as f64;
        for th in [0.2f64, 1.3, 3.0, 5.5] {
            let f = m.boundary(&SHAPE, (th - rot).cos(), (th - rot).sin());
            let g = flipped.boundary(&SHAPE, th.cos(), th.sin());
            assert!((f - g).abs() < 1e-14, "{f} vs {g}");
        }
    }
}
