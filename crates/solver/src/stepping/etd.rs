//! Exponential time-differencing coefficients (Cox & Matthews 2002) for ETD2RK.
//!
//! For `y' = c y + N(y)` over a step `h`:
//! predictor `a = e^{ch} y_n + h phi1(ch) N(y_n)` (ETD1, first order),
//! corrector `y_{n+1} = a + h phi2(ch) (N(a) - N(y_n))` (second order).
//! The difference `y_{n+1} - a` is the embedded error estimate.

/// `phi1(z) = (e^z - 1) / z`, accurate for all real `z` (series near 0).
pub fn phi1(z: f64) -> f64 {
    if z.abs() < 1e-3 {
        1.0 + z / 2.0 + z * z / 6.0 + z * z * z / 24.0
    } else {
        z.exp_m1() / z
    }
}

/// `phi2(z) = (e^z - 1 - z) / z^2`, accurate for all real `z` (series near 0).
pub fn phi2(z: f64) -> f64 {
    if z.abs() < 0.1 {
        // Taylor series: sum z^k / (k + 2)!, 10 terms reach round-off for |z| < 0.1.
        let mut term = 0.5;
        let mut sum = 0.5;
        for k in 1..10 {
            term *= z / (k + 2) as f64;
            sum += term;
        }
        sum
    } else {
        (z.exp_m1() - z) / (z * z)
    }
}

/// The three coefficients of one mode with linear rate `c` for step `h`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EtdCoef {
    /// `e^{ch}`.
    pub e: f64,
    /// `h phi1(ch)`.
    pub p1: f64,
    /// `h phi2(ch)`.
    pub p2: f64,
}

impl EtdCoef {
    pub fn new(c: f64, h: f64) -> Self {
        let z = c * h;
        Self {
            e: z.exp(),
            p1: h * phi1(z),
            p2: h * phi2(z),
        }
    }

    /// Predictor `a = e y + p1 n0`.
    #[inline(always)]
    pub fn predict(&self, y: f64, n0: f64) -> f64 {
        self.e * y + self.p1 * n0
    }

    /// Corrector `a + p2 (na - n0)`.
    #[inline(always)]
    pub fn correct(&self, a: f64, n0: f64, na: f64) -> f64 {
        a + self.p2 * (na - n0)
    }
}

/// Per-axis factors of the field's exact propagator `e^{-h (1 + kx^2 + ky^2)}`, stored as
/// `expm1` values: `ax = e^{-h kx^2} - 1`, `ay = e^{-h (1 + ky^2)} - 1`. Then
/// `e - 1 = ax + ay + ax ay` without cancellation, `p1 = h phi1 = (e - 1) / c` and
/// `p2 = h phi2 = (p1 - h) / (c h)`: no exponential, division or branch per mode.
#[derive(Debug, Clone, Default)]
pub struct SeparableExp {
    pub h: f64,
    pub ax: Vec<f64>,
    pub ay: Vec<f64>,
}

impl SeparableExp {
    /// Recomputes the factors for step `h` (O(N), in place: adaptive steps change `h` every
    /// step; a no-op when `h` is unchanged).
    pub fn update(&mut self, h: f64, kx: &[f64], ky: &[f64]) {
        if self.h == h && self.ax.len() == kx.len() && self.ay.len() == ky.len() {
            return;
        }
        self.h = h;
        self.ax.resize(kx.len(), 0.0);
        self.ay.resize(ky.len(), 0.0);
        for (a, k) in self.ax.iter_mut().zip(kx) {
            *a = (-h * k * k).exp_m1();
        }
        for (a, k) in self.ay.iter_mut().zip(ky) {
            *a = (-h * (1.0 + k * k)).exp_m1();
        }
    }

    /// `(e, p1, p2)` of one mode from its axis factors and `1/c`.
    #[inline(always)]
    pub fn coef(ax: f64, ay: f64, inv_c: f64, h: f64, inv_h: f64) -> EtdCoef {
        let em1 = ax + ay + ax * ay;
        let p1 = em1 * inv_c;
        EtdCoef {
            e: 1.0 + em1,
            p1,
            p2: (p1 - h) * inv_c * inv_h,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phi_functions_are_continuous_across_branches() {
        for &z in &[-1e-3, 1e-3, -0.1, 0.1, -5.0, 3.0] {
            let e = 1e-9;
            assert!((phi1(z - e) - phi1(z + e)).abs() < 1e-8);
            assert!((phi2(z - e) - phi2(z + e)).abs() < 1e-8);
        }
        assert!((phi1(0.0) - 1.0).abs() < 1e-16);
        assert!((phi2(0.0) - 0.5).abs() < 1e-16);
        assert!((phi2(-2.0) - ((-2f64).exp() - 1.0 + 2.0) / 4.0).abs() < 1e-15);
    }

    #[test]
    fn separable_coefficients_match_direct_ones() {
        // (kx^2, ky^2, h): from the k = 0 mode (cancellation-prone) to stiff modes.
        let cases = [
            (0.0, 0.0, 0.02),
            (0.0, 0.0, 1e-4),
            (3.0, 46.0, 0.02),
            (2000.0, 1000.0, 0.01),
            (0.5, 0.0, 1e-4),
        ];
        for &(kx2, ky2, h) in &cases {
            let c = -(1.0f64 + kx2 + ky2);
            let a = EtdCoef::new(c, h);
            let ax = (-h * kx2).exp_m1();
            let ay = (-h * (1.0 + ky2)).exp_m1();
            let b = SeparableExp::coef(ax, ay, 1.0 / c, h, 1.0 / h);
            // e = 1 + (e - 1): absolute round-off (it multiplies w, so this is round-off in w).
            assert!((a.e - b.e).abs() <= 2e-16, "e {c} {h}");
            assert!(
                (a.p1 - b.p1).abs() <= 1e-14 * a.p1,
                "p1 {c} {h}: {} vs {}",
                a.p1,
                b.p1
            );
            // p2 = (p1 - h)/(c h) loses digits like 1/|z| at tiny |z| = |c h|.
            let z = (c * h).abs().min(1.0);
            assert!(
                (a.p2 - b.p2).abs() <= 1e-14 / z * a.p2,
                "p2 {c} {h}: {} vs {}",
                a.p2,
                b.p2
            );
        }
    }

    #[test]
    fn etd2rk_is_second_order_on_a_scalar_problem() {
        // y' = c y + y^2 / 2, against a fine run.
        let c = -2.0;
        let f = |y: f64| 0.5 * y * y;
        let run = |h: f64| {
            let k = EtdCoef::new(c, h);
            let mut y = 0.8;
            for _ in 0..(1.0 / h).round() as usize {
                let n0 = f(y);
                let a = k.predict(y, n0);
                y = k.correct(a, n0, f(a));
            }
            y
        };
        let reference = run(1e-5);
        let e1 = (run(0.02) - reference).abs();
        let e2 = (run(0.01) - reference).abs();
        let order = (e1 / e2).log2();
        assert!((order - 2.0).abs() < 0.15, "order {order}");
    }
}
