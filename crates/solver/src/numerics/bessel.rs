//! Modified Bessel functions `I_n`, `K_n` (puruspe's `Inu_Knu`, accurate to ~1e-15), with the
//! argument checked: they are used for the Appendix D solution and the reduced-model
//! coefficients (eqs. F1 - tildeG2a), always at `x > 0`.

/// `(I_n(x), K_n(x))` for `x >= 0` (`K_n(0) = inf`); NaN for `x < 0` or non-finite `x`
/// (puruspe panics there).
pub fn ik(n: u32, x: f64) -> (f64, f64) {
    if x == 0.0 {
        return (if n == 0 { 1.0 } else { 0.0 }, f64::INFINITY);
    }
    if !(x > 0.0 && x.is_finite()) {
        return (f64::NAN, f64::NAN);
    }
    puruspe::Inu_Knu(n as f64, x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_values_and_wronskian() {
        // I0(1) = 1.2660658777520082, K0(1) = 0.42102443824070834 (Abramowitz & Stegun).
        let (i0, k0) = ik(0, 1.0);
        assert!((i0 - 1.266_065_877_752_008_2).abs() < 1e-14);
        assert!((k0 - 0.421_024_438_240_708_34).abs() < 1e-14);
        // Wronskian I_n K_{n+1} + I_{n+1} K_n = 1/x.
        for &x in &[0.3, 1.0, 2.5, 7.0] {
            for n in 0..4 {
                let (a, b) = ik(n, x);
                let (c, d) = ik(n + 1, x);
                assert!((a * d + c * b - 1.0 / x).abs() < 1e-13 / x);
            }
        }
        assert_eq!(ik(0, 0.0).0, 1.0);
        assert!(ik(1, -1.0).0.is_nan());
    }
}
