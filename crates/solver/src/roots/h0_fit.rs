//! The Appendix E fit of `h0`: steady deformation `s` of a droplet held in place (no
//! translation) over a range of `kappa2`, and the least-squares fit `kappa2 = p0 - p2 s^2` over
//! `0.001 < s < 0.3`; `p2` is the reduced model's `h0`.
//!
//! The steady states come from the exact steady evaluator ([`crate::roots::steady_solver::TwoModeSolver`]
//! with `v = 0`, a one-dimensional Newton solve in `a2`), continued from one `kappa2` to the
//! next: the same fixed points that deformation-only time integration converges to, without
//! its slow relaxation near the threshold.
use crate::error::SolverError;
use crate::model::params::ModelParams;
use crate::roots::steady_solver::TwoModeSolver;
use serde::Serialize;

/// Result of the fit.
#[derive(Debug, Clone, Serialize)]
pub struct H0Fit {
    pub p0: f64,
    pub p2: f64,
    /// `(kappa2, s)` of every solved point.
    pub points: Vec<(f64, f64)>,
    /// Points inside the fit window `0.001 < s < 0.3`.
    pub used: usize,
    pub n: usize,
}

/// Solves the deformation-only steady states at `kappa2s` (any order) and fits.
pub fn fit_h0(base: &ModelParams, n: usize, kappa2s: &[f64]) -> Result<H0Fit, SolverError> {
    let mut ks = kappa2s.to_vec();
    ks.sort_by(f64::total_cmp);
    let mut points = Vec::with_capacity(ks.len());
    // Start from the reduced model's estimate at the smallest kappa2, then continue.
    let mut guess = ((0.1196 - ks[0]).max(1e-4) / 0.1436).sqrt();
    for &k in &ks {
        let p = ModelParams { kappa2: k, ..*base };
        let mut solver = TwoModeSolver::new(p, n)?;
        let s = match solver.newton(0.0, guess.max(0.02), 1e-13) {
            Ok(st) => st.a2.abs(),
            Err(_) => 0.0,
        };
        if s > 1e-3 {
            guess = s;
        }
        points.push((k, s));
    }
    let used: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|&(_, s)| s > 1e-3 && s < 0.3)
        .collect();
    let (p0, p2) = least_squares(&used);
    Ok(H0Fit {
        p0,
        p2,
        used: used.len(),
        points,
        n,
    })
}

/// Least squares `kappa2 = p0 - p2 s^2`: a straight line in `x = s^2`.
fn least_squares(pts: &[(f64, f64)]) -> (f64, f64) {
    let m = pts.len() as f64;
    let (sx, sy) = pts
        .iter()
        .fold((0.0, 0.0), |(a, b), &(k, s)| (a + s * s, b + k));
    let (mx, my) = (sx / m, sy / m);
    let (mut sxx, mut sxy) = (0.0, 0.0);
    for &(k, s) in pts {
        let x = s * s - mx;
        sxx += x * x;
        sxy += x * (k - my);
    }
    let slope = sxy / sxx;
    (my - slope * mx, -slope)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn least_squares_recovers_a_line() {
        let pts: Vec<(f64, f64)> = [0.05, 0.1, 0.2, 0.25]
            .iter()
            .map(|&s| (0.12 - 0.15 * s * s, s))
            .collect();
        let (p0, p2) = least_squares(&pts);
        assert!((p0 - 0.12).abs() < 1e-14 && (p2 - 0.15).abs() < 1e-13);
    }
}
