//! Where resting states of the `K`-mode model ([`ModeSolver`]) lose stability, from the
//! `lambda = 0` Jacobian of the force balance: the disk's onset of motion and each mode's
//! onset of deformation, the drift threshold of any resting state, and the analytic
//! onset of mode `k` for a sharp disk on the unbounded plane (docs/model.md).
use crate::numerics::newton;
use crate::roots::mode_solver::ModeSolver;

/// Where the resting disk of the `K`-mode model loses stability (pitchforks: real eigenvalues
/// crossing 0 of the `lambda = 0` Jacobian).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ModeThresholds {
    /// Onset of motion at the solver's `kappa2`: in the box the drift couples to the odd
    /// modes' `a_k` (through the periodic images), so it can move with `K` and `kappa2`.
    pub eta_t: f64,
    /// For `k = 2..=K`: the `kappa2` below which the `a_k` deformation grows (the diagonal
    /// entry of the shape block: `kappa_k^c = dG_k^(a)/da_k`, `kappa2 = 4 kappa_k^c / k^2`;
    /// the box's weak coupling of `k` with `k +- 4` left out).
    pub kappa2: Vec<f64>,
    /// The same for the `b_k` deformation (`dG_k^(b)/db_k`). At the circle `a_k` and `b_k`
    /// are one mode turned by `pi / (2k)`; the square box tells them apart, by 4e-4 in
    /// `kappa2` for `k = 2` at N = 192 (the diagonal onset above the axis one).
    pub kappa2_b: Vec<f64>,
}

/// The `eta_t` at which the drift along x of a resting state has a zero eigenvalue, from the
/// `lambda = 0` Jacobian `c` of [`ModeSolver::residual_x`] taken there with `eta_t = 0`
/// (unknowns `(v, a_2..a_K)`): the drift couples only to the odd modes (the mirror `x -> -x`),
/// so the threshold is the Schur complement `c00 - c0^T C_oo^-1 c0` over them. (At rest
/// `c0` vanishes, no shape feeling a net force, and it is `c00`; the complement keeps it
/// right wherever it is used.)
pub fn drift_threshold(c: &[Vec<f64>]) -> f64 {
    let k_max = c.len();
    let odd: Vec<usize> = (3..=k_max).filter(|k| k % 2 == 1).map(|k| k - 1).collect();
    let mut eta = c[0][0];
    if !odd.is_empty() {
        let block: Vec<Vec<f64>> = odd
            .iter()
            .map(|&i| odd.iter().map(|&j| c[i][j]).collect())
            .collect();
        let col: Vec<f64> = odd.iter().map(|&i| c[i][0]).collect();
        if let Some(x) = newton::lu_solve(block, &col) {
            eta -= odd.iter().zip(&x).map(|(&j, xj)| c[0][j] * xj).sum::<f64>();
        }
    }
    eta
}

/// The analytic onset of the mode-`k` deformation of a resting disk of radius `r` with a sharp
/// interface on the unbounded plane: `kappa_k^c = r^2 [I_1(r) K_1(r) - I_k(r) K_k(r)]` (from
/// the steady field of a disk perturbed along mode `k`, docs/model.md); in `kappa2`,
/// `4 kappa_k^c / k^2`. For `k = 2` it is the reduced model's `g0~` (0.119605 at `r = 1`).
pub fn analytic_kappa_c(k: usize, r: f64) -> f64 {
    let (i1, k1) = crate::numerics::bessel::ik(1, r);
    let (ik, kk) = crate::numerics::bessel::ik(k as u32, r);
    r * r * (i1 * k1 - ik * kk)
}

impl ModeSolver {
    /// The `lambda = 0` Jacobian of [`Self::residual_x`] at the resting disk with `eta_t` set
    /// to 0 (the field's feedback on the speed, the stiffness on the shape), unknowns
    /// `(v, a_2..a_K)`.
    pub fn disk_jacobian(&mut self, k_max: usize) -> Vec<Vec<f64>> {
        let (eta_t, kappa2) = (self.params().eta_t, self.params().kappa2);
        self.set_control(0.0, kappa2);
        let j = newton::fd_jacobian(&mut |y: &[f64]| self.residual_x(y), &vec![0.0; k_max], 1e-5);
        self.set_control(eta_t, kappa2);
        j
    }

    /// The `b_k` diagonal entries `dG_k^(b)/db_k - kappa_k` (`k = 2..=k_max`) of the `lambda =
    /// 0` Jacobian of [`Self::residual`] at the resting disk, by central differences in each
    /// `b_k` alone.
    fn disk_b_entries(&mut self, k_max: usize) -> Vec<f64> {
        let h = 1e-5;
        (2..=k_max)
            .map(|k| {
                let i = k_max + k - 1;
                let mut z = vec![0.0; 2 * k_max];
                z[i] = h;
                let plus = self.residual(&z)[i];
                z[i] = -h;
                let minus = self.residual(&z)[i];
                (plus - minus) / (2.0 * h)
            })
            .collect()
    }

    /// The resting disk's thresholds with modes up to `k_max` (see [`ModeThresholds`]).
    pub fn disk_thresholds(&mut self, k_max: usize) -> ModeThresholds {
        let c = self.disk_jacobian(k_max);
        let b = self.disk_b_entries(k_max);
        let kappa2 = self.params().kappa2;
        let onset = |k: usize, entry: f64| 4.0 / (k * k) as f64 * entry + kappa2;
        ModeThresholds {
            eta_t: drift_threshold(&c),
            kappa2: (2..=k_max).map(|k| onset(k, c[k - 1][k - 1])).collect(),
            kappa2_b: (2..=k_max).zip(b).map(|(k, e)| onset(k, e)).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::ModelParams;

    #[test]
    fn the_disks_mode_thresholds_are_the_analytic_ones_up_to_the_box() {
        let p = ModelParams::at(0.085, 0.13);
        let mut s = ModeSolver::new(p, 192).unwrap();
        let th = s.disk_thresholds(6);
        let two = crate::roots::named_state::ic_thresholds(&p, 192).unwrap();
        // K = 2: the 2-mode model's thresholds (its a2 onset; the drift alone).
        assert!(
            (th.kappa2[0] - two.kappa2_a2).abs() < 1e-7,
            "{th:?} {two:?}"
        );
        // And its diagonal (b2) onset, which the box puts above the axis one.
        assert!(
            (th.kappa2_b[0] - two.kappa2_b2).abs() < 1e-7 && two.kappa2_b2 > two.kappa2_a2 + 1e-4,
            "{th:?} {two:?}"
        );
        assert!((s.disk_thresholds(2).eta_t - two.eta_t).abs() < 1e-7);
        // Each mode's onset is the sharp-interface, unbounded-plane value to within the box's
        // and the smoothing's 1.1 % (1.0 % for k = 2), closer as k grows (the field of a
        // higher mode decays faster, so the images matter less).
        let mut last = f64::INFINITY;
        for k in 2..=6 {
            let exact = 4.0 * analytic_kappa_c(k, 1.0) / (k * k) as f64;
            let rel = (th.kappa2[k - 2] - exact).abs() / exact;
            assert!(
                rel < 0.011 && rel < last + 1e-4,
                "k = {k}: {} vs {exact}",
                th.kappa2[k - 2]
            );
            last = rel;
        }
        assert!((4.0 * analytic_kappa_c(2, 1.0) / 4.0 - 0.119605).abs() < 1e-6);
        // The drift couples to a3 through the box only: the onset of motion moves by < 1e-6.
        assert!(
            (th.eta_t - two.eta_t).abs() < 1e-6,
            "{} vs {}",
            th.eta_t,
            two.eta_t
        );
    }
}
