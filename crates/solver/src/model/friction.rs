//! The friction `eta_k` of shape mode `k` in the paper's general model (its eqs. for
//! `d a_k/dt`, `d b_k/dt`: `eta_k d a_k/dt = -dE/da_k`, "positive coefficients to determine
//! the time scale of ... deformation"). The paper gives no law for `k >= 3`, since it keeps
//! `k = 2`. Here `eta_k = eta2 (k / 2)^p` with the exponent `p` a setting (`eta_k_exponent`):
//!
//! - `p = 0` (default): every mode has the friction of mode 2, `eta_k = eta2`;
//! - `p = -1`: the friction of the mode's own flow, `eta_k proportional to Int |w_k|^2 dA` over
//!   the disk, `= pi R^4 / k` for `w_k = grad[(R^2 / k) (r / R)^k cos k theta]`, so
//!   `eta_k = (2 / k) eta2` (the viscous dissipation of a flow `w_k` inside the droplet);
//! - any other `p` in `[-4, 4]` as a sensitivity check.
//!
//! `eta_k` sets only how fast a mode relaxes: it enters no steady state and no `lambda = 0`
//! threshold (onsets, folds), only the time stepping and the eigenvalues (so a Hopf point or a
//! complex pair's rate).

/// Largest `|p|` accepted: `(K / 2)^4` spans four decades at `K = 16`.
pub const MAX_ETA_K_EXPONENT: f64 = 4.0;

/// Checks a friction law's exponent for a model with modes `2..=k_max`: within
/// [`MAX_ETA_K_EXPONENT`], and 0 unless `k_max > 2` (with mode 2 alone only `eta2` enters).
pub fn check_exponent(exponent: f64, k_max: usize) -> Result<(), crate::error::SolverError> {
    let most = MAX_ETA_K_EXPONENT;
    crate::error::require(
        exponent.abs() <= most && (k_max > 2 || exponent == 0.0),
        "eta_k_exponent",
        exponent,
        format!(
            "a number from -{most} to {most} (eta_k = eta2 (k/2)^p for the shape modes k >= 3), \
             with modes > 2 (with modes 2 only eta2 enters; here modes = {k_max})"
        ),
    )
}

/// `eta_k = eta2 (k / 2)^exponent` (exactly `eta2` for `k = 2`, or for exponent 0).
pub fn eta_k(eta2: f64, k: usize, exponent: f64) -> f64 {
    if exponent == 0.0 || k == 2 {
        eta2
    } else {
        eta2 * (k as f64 / 2.0).powf(exponent)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_law_is_eta2_for_mode_2_and_the_flows_dissipation_at_minus_one() {
        assert_eq!(eta_k(0.1, 2, -1.0), 0.1);
        assert_eq!(eta_k(0.1, 5, 0.0), 0.1);
        // Int |w_k|^2 dA over the unit disk, by quadrature, against pi / k: eta_k / eta_2.
        for k in 3..=6 {
            let m = 400;
            let mut sum = 0.0;
            for i in 0..m {
                for j in 0..m {
                    let (r, th) = (
                        (i as f64 + 0.5) / m as f64,
                        (j as f64 + 0.5) / m as f64 * std::f64::consts::TAU,
                    );
                    let (wa, _) = crate::model::modes::w_fields(k, 1.0, r * th.cos(), r * th.sin());
                    sum += (wa[0] * wa[0] + wa[1] * wa[1]) * r;
                }
            }
            let integral = sum / (m * m) as f64 * std::f64::consts::TAU;
            // pi R^4 / k with R = 1, over its value for k = 2.
            let ratio = integral / (std::f64::consts::PI / 2.0);
            assert!(
                (ratio - eta_k(1.0, k, -1.0)).abs() < 1e-4,
                "k = {k}: {ratio}"
            );
        }
    }
}
