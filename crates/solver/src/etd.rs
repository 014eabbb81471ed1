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

    /// The coefficients when `e = e^{ch}` is already known (the field modes, where
    /// `e^{-h(1 + kx^2 + ky^2)}` is a product of per-axis factors): no exponential per mode.
    #[inline(always)]
    pub fn from_exp(e: f64, c: f64, h: f64) -> Self {
        let z = c * h;
        if z.abs() < 0.1 {
            Self::new(c, h)
        } else {
            let em1 = e - 1.0;
            Self {
                e,
                p1: em1 / c,
                p2: (em1 - z) / (c * z),
            }
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

/// Per-axis factors `e^{-h kx^2}`, `e^{-h ky^2}` of the field's exact propagator.
#[derive(Debug, Clone, Default)]
pub struct SeparableExp {
    pub h: f64,
    pub ex: Vec<f64>,
    pub ey: Vec<f64>,
}

impl SeparableExp {
    /// Recomputes the factors for step `h` (O(N), no-op when `h` is unchanged).
    pub fn update(&mut self, h: f64, kx: &[f64], ky: &[f64]) {
        if self.h == h && !self.ex.is_empty() {
            return;
        }
        self.h = h;
        self.ex = kx.iter().map(|k| (-h * k * k).exp()).collect();
        self.ey = ky.iter().map(|k| (-h * (1.0 + k * k)).exp()).collect();
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
        for &(c, h) in &[(-1.0, 0.02), (-50.0, 0.02), (-3000.0, 0.01), (-1.5, 1e-4)] {
            let a = EtdCoef::new(c, h);
            let b = EtdCoef::from_exp((c * h).exp(), c, h);
            for (x, y) in [(a.e, b.e), (a.p1, b.p1), (a.p2, b.p2)] {
                assert!(
                    (x - y).abs() <= 1e-13 * x.abs().max(1e-300),
                    "{c} {h}: {x} vs {y}"
                );
            }
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
