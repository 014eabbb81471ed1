//! Analytic phase boundaries of the reduced model (paper Appendix F, Fig. 3a):
//! `eta_t = f1` and `kappa2 = g0~` (IC stability), the ID stability line (eq. idmd)
//! `eta_t = f1 + f1~ sqrt((g0~ - kappa2) / h0)`, and the MD existence boundary
//! `H(s) = dH/ds = 0` (eq. Hs). Eliminating the bracket of `H` between the two equations
//! gives the MD boundary in closed parametric form in `s`:
//! `eta_t = f1 + (2 f3 h0 s^3 + f1~ g2~ s^2) / g2`,
//! `kappa2 = g0~ + (g2~ (eta_t - f1) + g2 f1~ - 3 f3 h0 s^2 - 2 f1~ g2~ s) / f3`.
use crate::reduced::coefficients::Coefficients;
use serde::Serialize;

/// One boundary curve in the `(eta_t, kappa2)` plane.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Boundary {
    pub name: &'static str,
    /// `(eta_t, kappa2)` points along the curve.
    pub points: Vec<(f64, f64)>,
}

/// The MD existence boundary at parameter `s`: `(eta_t, kappa2)`.
pub fn md_boundary_point(c: &Coefficients, s: f64) -> (f64, f64) {
    let eta = c.f1 + (2.0 * c.f3 * c.h0 * s.powi(3) + c.f1t * c.g2t * s * s) / c.g2;
    let kappa = c.g0t
        + (c.g2t * (eta - c.f1) + c.g2 * c.f1t
            - 3.0 * c.f3 * c.h0 * s * s
            - 2.0 * c.f1t * c.g2t * s)
            / c.f3;
    (eta, kappa)
}

/// `H(s)` of eq. (Hs) (minor-axis MD states are its roots `s > 0` with `v^2 > 0`).
pub fn h_of_s(c: &Coefficients, eta_t: f64, kappa2: f64, s: f64) -> f64 {
    c.f3 * c.h0 * s.powi(3)
        + c.f1t * c.g2t * s * s
        + (-c.f3 * (c.g0t - kappa2) - c.g2t * (eta_t - c.f1) - c.g2 * c.f1t) * s
        + c.g2 * (eta_t - c.f1)
}

/// The ID stability line (eq. idmd) at `kappa2 < g0~`.
pub fn id_stability_eta(c: &Coefficients, kappa2: f64) -> Option<f64> {
    (kappa2 < c.g0t).then(|| c.f1 + c.f1t * ((c.g0t - kappa2) / c.h0).sqrt())
}

/// All four boundaries, sampled over the window `eta`, `kappa` (each `(lo, hi)`).
pub fn boundaries(c: &Coefficients, eta: (f64, f64), kappa: (f64, f64)) -> Vec<Boundary> {
    let samples = 400;
    let lerp = |(lo, hi): (f64, f64), i: usize| lo + (hi - lo) * i as f64 / samples as f64;
    let ic_eta = Boundary {
        name: "eta_t = f1",
        points: vec![(c.f1, c.g0t.max(kappa.0)), (c.f1, kappa.1)],
    };
    let ic_kappa = Boundary {
        name: "kappa2 = g0~",
        points: vec![(c.f1.max(eta.0), c.g0t), (eta.1, c.g0t)],
    };
    let id_line = Boundary {
        name: "ID stability (eq. idmd)",
        points: (0..=samples)
            .map(|i| lerp((kappa.0, c.g0t), i))
            .filter_map(|k| id_stability_eta(c, k).map(|e| (e, k)))
            .collect(),
    };
    let md = Boundary {
        name: "MD existence H = H' = 0",
        points: (0..=samples)
            .map(|i| md_boundary_point(c, i as f64 / samples as f64))
            .take_while(|&(e, _)| e <= eta.1 + (eta.1 - eta.0))
            .collect(),
    };
    vec![ic_eta, ic_kappa, id_line, md]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn md_boundary_points_are_double_roots_of_h() {
        let c = Coefficients::paper();
        for &s in &[0.05, 0.1, 0.2, 0.3] {
            let (e, k) = md_boundary_point(&c, s);
            let d = 1e-6;
            let dh = (h_of_s(&c, e, k, s + d) - h_of_s(&c, e, k, s - d)) / (2.0 * d);
            assert!(h_of_s(&c, e, k, s).abs() < 1e-12, "H at s = {s}");
            assert!(dh.abs() < 1e-9, "H' at s = {s}: {dh}");
        }
        // It starts at (f1, g0~ + g2 f1~ / f3) ~ (0.0781, 0.156): the paper's kappa2 ~ 0.156 where
        // the drift pitchfork changes from super- to subcritical.
        let (e0, k0) = md_boundary_point(&c, 0.0);
        assert!((e0 - c.f1).abs() < 1e-15);
        assert!((k0 - 0.1555).abs() < 1e-3, "{k0}");
    }
}
