//! Where resting states lose stability, from the `lambda = 0` Jacobian of the force balance:
//! the resting disk's onset of motion and each shape mode's onset of deformation (one
//! [`IcThresholds`] for every `K`), the drift threshold of any resting state, the onset of
//! motion of an ID state, and the analytic onset of mode `k` for a sharp disk on the unbounded
//! plane (docs/model.md).
//!
//! With two shape modes the disk's linearisation decouples (drift `(vx, vy)`, shape `a2`,
//! shape `b2`) and each threshold is read off the 4 x 4 `lambda = 0` Jacobian of the 2-mode
//! solver (the fast path); with modes `2..K` off the general solver's, by differences, where the
//! drift couples to the odd modes through the box (a Schur complement over them).
use crate::error::SolverError;
use crate::model::mirror::MirrorLine;
use crate::model::params::ModelParams;
use crate::numerics::newton;
use crate::roots::linearisation::Linearization;
use crate::roots::steady_solver::SteadySolver;
use crate::roots::steady_solver::TwoModeSolver;
use serde::Serialize;

/// Where the resting disk loses stability, at the grid and box of its parameters (its
/// `eta_t` and `kappa2` do not matter: at the disk neither block of the linearisation depends
/// on the other parameter). Real crossings: pitchforks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct IcThresholds {
    /// Onset of motion: the disk is unstable to drift for `eta_t` below this. In the box the
    /// drift couples to the odd modes' `a_k` (through the periodic images), so with `K > 2`
    /// it can move with `K` and `kappa2` (by < 1e-6 at N = 192).
    pub eta_t: f64,
    /// Onset of an `a2` deformation (long axis on the x axis): unstable for `kappa2` below
    /// this (`kappa2_a[0]`).
    pub kappa2_a2: f64,
    /// Onset of a `b2` deformation (long axis on the box diagonal; `kappa2_b[0]`). At the
    /// circle `a_k` and `b_k` are one mode turned by `pi / (2k)`; the square box tells them
    /// apart, by 4e-4 in `kappa2` for `k = 2` at N = 192 (the diagonal onset above the axis one).
    pub kappa2_b2: f64,
    /// For `k = 2..=K`: the `kappa2` below which the `a_k` deformation grows (the diagonal
    /// entry of the shape block: `kappa_k^c = dG_k^(a)/da_k`, `kappa2 = 4 kappa_k^c / k^2`;
    /// the box's weak coupling of `k` with `k +- 4` left out).
    pub kappa2_a: Vec<f64>,
    /// The same for the `b_k` deformation (`dG_k^(b)/db_k`).
    pub kappa2_b: Vec<f64>,
}

/// The resting disk's thresholds with shape modes `2..=modes` (see [`IcThresholds`]): for
/// `modes = 2` from the 2-mode solver's Jacobian, else [`disk_thresholds`].
pub fn ic_thresholds(
    params: &ModelParams,
    n: usize,
    modes: usize,
) -> Result<IcThresholds, SolverError> {
    if modes > 2 {
        return Ok(disk_thresholds(&mut SteadySolver::new(*params, n)?, modes));
    }
    Ok(two_mode_thresholds(&mut TwoModeSolver::new(*params, n)?))
}

/// The resting disk's thresholds with two shape modes, read off the 2-mode solver's 4 x 4
/// `lambda = 0` Jacobian (the fast path of [`ic_thresholds`]).
pub fn two_mode_thresholds(solver: &mut TwoModeSolver) -> IcThresholds {
    let params = *solver.params();
    let j0 = Linearization::of_two_modes(solver, [0.0; 4]).jacobian0();
    let (a2, b2) = (j0[2][2] + params.kappa2, j0[3][3] + params.kappa2);
    IcThresholds {
        eta_t: j0[0][0] + params.eta_t,
        kappa2_a2: a2,
        kappa2_b2: b2,
        kappa2_a: vec![a2],
        kappa2_b: vec![b2],
    }
}

/// The resting disk's thresholds with shape modes `2..=k_max` from the general solver, at any
/// `K` (the truncation study compares every `K` with this one computation).
pub fn disk_thresholds(solver: &mut SteadySolver, k_max: usize) -> IcThresholds {
    let c = disk_jacobian(solver, k_max);
    let b = disk_b_entries(solver, k_max);
    let kappa2 = solver.params().kappa2;
    let onset = |k: usize, entry: f64| 4.0 / (k * k) as f64 * entry + kappa2;
    let kappa2_a: Vec<f64> = (2..=k_max).map(|k| onset(k, c[k - 1][k - 1])).collect();
    let kappa2_b: Vec<f64> = (2..=k_max).zip(b).map(|(k, e)| onset(k, e)).collect();
    IcThresholds {
        eta_t: drift_threshold(&c),
        kappa2_a2: kappa2_a[0],
        kappa2_b2: kappa2_b[0],
        kappa2_a,
        kappa2_b,
    }
}

/// The `lambda = 0` Jacobian of [`SteadySolver::residual_x`] at the resting disk with `eta_t`
/// set to 0 (the field's feedback on the speed, the stiffness on the shape), unknowns
/// `(v, a_2..a_K)`.
pub fn disk_jacobian(solver: &mut SteadySolver, k_max: usize) -> Vec<Vec<f64>> {
    let (eta_t, kappa2) = (solver.params().eta_t, solver.params().kappa2);
    solver.set_control(0.0, kappa2);
    let j = newton::fd_jacobian(
        &mut |y: &[f64]| solver.residual_x(y),
        &vec![0.0; k_max],
        1e-5,
    );
    solver.set_control(eta_t, kappa2);
    j
}

/// The `b_k` diagonal entries `dG_k^(b)/db_k - kappa_k` (`k = 2..=k_max`) of the `lambda = 0`
/// Jacobian of [`SteadySolver::residual`] at the resting disk, by central differences in each
/// `b_k` alone.
fn disk_b_entries(solver: &mut SteadySolver, k_max: usize) -> Vec<f64> {
    let h = 1e-5;
    (2..=k_max)
        .map(|k| {
            let i = k_max + k - 1;
            let mut z = vec![0.0; 2 * k_max];
            z[i] = h;
            let plus = solver.residual(&z)[i];
            z[i] = -h;
            let minus = solver.residual(&z)[i];
            (plus - minus) / (2.0 * h)
        })
        .collect()
}

/// The `eta_t` at which the drift along x of a resting state has a zero eigenvalue, from the
/// `lambda = 0` Jacobian `c` of [`SteadySolver::residual_x`] taken there with `eta_t = 0`
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

/// Largest eigenvalue of a real 2 x 2 matrix with real eigenvalues (else its real part).
fn top_eigenvalue(m: [[f64; 2]; 2]) -> f64 {
    let tr = m[0][0] + m[1][1];
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let disc = tr * tr / 4.0 - det;
    tr / 2.0 + disc.max(0.0).sqrt()
}

/// The `eta_t` below which the 2-mode ID state on `mirror` at `kappa2` starts to move, with
/// its shape amplitude, or `None` where there is no ID state.
pub fn id_onset(
    solver: &mut TwoModeSolver,
    mirror: MirrorLine,
    kappa2: f64,
    seed: f64,
) -> Option<(f64, f64)> {
    let eta_t = solver.params().eta_t;
    solver.set_control(eta_t, kappa2);
    let st = solver.newton_on(mirror, 0.0, seed, 1e-12).ok()?;
    if st.a2.abs() < 1e-4 {
        return None;
    }
    let z = mirror.two_mode_state(0.0, st.a2);
    let j = Linearization::of_two_modes(solver, z).jacobian0();
    let k = [[j[0][0] + eta_t, j[0][1]], [j[1][0], j[1][1] + eta_t]];
    Some((top_eigenvalue(k), st.a2))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::roots::balances::Balances;
    use crate::roots::named_state::{find, StateKind};

    #[test]
    fn the_resting_disks_thresholds_are_where_its_eigenvalues_cross_zero() {
        let th = ic_thresholds(&ModelParams::at(0.085, 0.13), 192, 2).unwrap();
        // Bracketed by the reference eigenvalues of docs/model.md: drift +0.001445 at eta_t = 0.0763 and
        // -0.004036 at 0.077; shape > 0 at kappa2 = 0.112, < 0 at 0.13.
        assert!(th.eta_t > 0.0763 && th.eta_t < 0.077, "{th:?}");
        for k in [th.kappa2_a2, th.kappa2_b2] {
            assert!(k > 0.112 && k < 0.13, "{th:?}");
        }
        // The same numbers whatever the other parameter.
        let other = ic_thresholds(&ModelParams::at(0.1, 0.16), 192, 2).unwrap();
        assert!((other.eta_t - th.eta_t).abs() < 1e-9, "{other:?}");
        assert!((other.kappa2_a2 - th.kappa2_a2).abs() < 1e-9, "{other:?}");
        // At the threshold the drift pair's eigenvalue is zero, the shape's at its own.
        let at = |eta_t, kappa2| {
            find(
                &mut Balances::new(ModelParams::at(eta_t, kappa2), 192).unwrap(),
                StateKind::IC,
                MirrorLine::X,
                None,
            )
            .unwrap()
            .eigenvalues
        };
        let drift = at(th.eta_t, 0.13);
        assert!(
            drift[0].re.abs() < 1e-8 && drift[1].re.abs() < 1e-8,
            "{drift:?}"
        );
        let shape = at(0.085, th.kappa2_b2.max(th.kappa2_a2));
        assert!(shape[0].re.abs() < 1e-8, "{shape:?}");
    }

    #[test]
    fn the_disks_mode_thresholds_are_the_analytic_ones_up_to_the_box() {
        let p = ModelParams::at(0.085, 0.13);
        let th = ic_thresholds(&p, 192, 6).unwrap();
        let two = ic_thresholds(&p, 192, 2).unwrap();
        // K = 2: the 2-mode model's thresholds (its a2 onset; the drift alone).
        assert!(
            (th.kappa2_a2 - two.kappa2_a2).abs() < 1e-7,
            "{th:?} {two:?}"
        );
        // And its diagonal (b2) onset, which the box puts above the axis one.
        assert!(
            (th.kappa2_b2 - two.kappa2_b2).abs() < 1e-7 && two.kappa2_b2 > two.kappa2_a2 + 1e-4,
            "{th:?} {two:?}"
        );
        let general_two = disk_thresholds(&mut SteadySolver::new(p, 192).unwrap(), 2);
        assert!((general_two.eta_t - two.eta_t).abs() < 1e-7);
        // Each mode's onset is the sharp-interface, unbounded-plane value to within the box's
        // and the smoothing's 1.1 % (1.0 % for k = 2), closer as k grows (the field of a
        // higher mode decays faster, so the images matter less).
        let mut last = f64::INFINITY;
        for k in 2..=6 {
            let exact = 4.0 * analytic_kappa_c(k, 1.0) / (k * k) as f64;
            let rel = (th.kappa2_a[k - 2] - exact).abs() / exact;
            assert!(
                rel < 0.011 && rel < last + 1e-4,
                "k = {k}: {} vs {exact}",
                th.kappa2_a[k - 2]
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
