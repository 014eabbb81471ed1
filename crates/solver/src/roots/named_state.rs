//! The steady states the paper names, computed as roots and linearised: the resting disk (IC),
//! the resting deformed droplet (ID) and the droplet moving along its minor axis (MD), each on
//! a mirror axis of the box (motion along x or along the diagonal). Newton starts from the
//! reduced model's state (Sect. 5) unless a seed is given.
use crate::error::SolverError;
use crate::model::params::ModelParams;
use crate::reduced::bifurcation::md_states;
use crate::reduced::coefficients::Coefficients;
use crate::roots::linearisation::Linearization;
use crate::roots::steady_solver::{MirrorAxis, SteadySolver};
use crate::roots::verdict::{assess, Verdict};
use rustfft::num_complex::Complex64;
use serde::Serialize;

/// Which state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum StateKind {
    IC,
    ID,
    MD,
}

impl std::str::FromStr for StateKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "ic" => Ok(Self::IC),
            "id" => Ok(Self::ID),
            "md" => Ok(Self::MD),
            other => Err(format!("unknown state `{other}`: ic, id or md")),
        }
    }
}

/// A steady state with its leading eigenvalues.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedState {
    /// `(vx, vy, a2, b2)`.
    pub z: [f64; 4],
    /// Max norm of the force balance at `z`.
    pub residual: f64,
    /// Eigenvalues with `Re > -1`, decreasing real part ([`Linearization::eigenvalues`]).
    pub eigenvalues: Vec<Complex64>,
    /// What they say: the rotation mode identified and set aside
    /// ([`crate::roots::verdict::assess`]).
    pub verdict: Verdict,
}

/// `(speed along the axis, shape amplitude on it)` -> `(vx, vy, a2, b2)`.
fn on_axis(axis: MirrorAxis, v: f64, c: f64) -> [f64; 4] {
    match axis {
        MirrorAxis::X => [v, 0.0, c, 0.0],
        MirrorAxis::Diagonal => {
            let d = v * std::f64::consts::FRAC_1_SQRT_2;
            [d, d, 0.0, c]
        }
    }
}

/// Newton's start for an ID state: the reduced model's amplitude (at least 0.05), positive
/// (long axis along x on the x axis, along the diagonal on the diagonal).
pub fn id_seed(c: &Coefficients, params: &ModelParams) -> f64 {
    ((c.g0t - params.kappa2).max(0.0) / c.h0).sqrt().max(0.05)
}

/// Newton's starts for MD states moving along the minor (`sign = -1`) or major (`+1`) axis:
/// the reduced model's states `(v, sign s)`, largest deformation first.
pub fn md_seeds(c: &Coefficients, params: &ModelParams, sign: f64) -> Vec<(f64, f64)> {
    md_states(c, params.eta_t, params.kappa2, sign)
        .into_iter()
        .rev()
        .map(|(v, s)| (v, sign * s))
        .collect()
}

/// Finds `kind` at `params` on `axis` with an `n x n` grid (Newton to 1e-12 from `seed`, or
/// from the reduced model's state), then linearises it. Needs inertia `m > 0`.
pub fn find(
    params: &ModelParams,
    n: usize,
    kind: StateKind,
    axis: MirrorAxis,
    seed: Option<(f64, f64)>,
) -> Result<NamedState, SolverError> {
    crate::error::require(
        params.mass > 0.0,
        "mass",
        params.mass,
        "a finite number > 0 for the linearisation (the overdamped velocity has no dynamics)",
    )?;
    let mut solver = SteadySolver::new(*params, n)?;
    let c = Coefficients::new(params.radius, crate::contract::settings::H0_PAPER);
    let id_seed = id_seed(&c, params);
    let (v, shape, residual) = match kind {
        StateKind::IC => (0.0, 0.0, 0.0),
        StateKind::ID | StateKind::MD => {
            let seeds: Vec<(f64, f64)> = match (seed, kind) {
                (Some(s), _) => vec![s],
                (None, StateKind::ID) => vec![(0.0, id_seed)],
                _ => {
                    let mut v = md_seeds(&c, params, -1.0);
                    v.extend([(0.6, -0.27), (0.9, -0.35), (0.3, -0.1)]);
                    v
                }
            };
            let mut last = None;
            let mut found = None;
            for (v0, c0) in seeds {
                let v0 = if kind == StateKind::ID { 0.0 } else { v0 };
                match solver.newton_on(axis, v0, c0, 1e-12) {
                    Ok(st) if kind == StateKind::ID || st.v.abs() > 1e-6 => {
                        found = Some((st.v, st.a2, st.residual));
                        break;
                    }
                    Ok(st) => {
                        last = Some(SolverError::RestingRoot {
                            residual: st.residual,
                            iterations: st.iterations,
                            v: st.v.abs(),
                        })
                    }
                    Err(e) => last = Some(e),
                }
            }
            found.ok_or_else(|| {
                last.unwrap_or(SolverError::NewtonFailed {
                    residual: f64::NAN,
                    iterations: 0,
                })
            })?
        }
    };
    let z = on_axis(axis, v, shape);
    let verdict = assess(&Linearization::at(&mut solver, z), &z);
    Ok(NamedState {
        z,
        residual,
        eigenvalues: verdict
            .eigenvalues
            .iter()
            .map(|[re, im]| Complex64::new(*re, *im))
            .collect(),
        verdict,
    })
}

/// Where the resting disk loses stability, at the grid and box of `params` (its other
/// parameters fixed). At the disk the linearisation decouples (drift `(vx, vy)`, shape `a2`,
/// shape `b2`) and neither block depends on the other parameter, so each threshold is one
/// number, read off the `lambda = 0` Jacobian `-T(0)`: its drift entry is `-eta_t + c` with
/// `c` the field's feedback, so the drift pair crosses zero at `eta_t = c`; likewise the shape
/// entries give the `kappa2` at which an `a2` (axis-aligned) or a `b2` (diagonal) deformation
/// sets in. Real crossings: pitchforks (the eigenvalues here are real).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct IcThresholds {
    /// Onset of motion: the disk is unstable to drift for `eta_t` below this.
    pub eta_t: f64,
    /// Onset of an `a2` deformation: unstable for `kappa2` below this.
    pub kappa2_a2: f64,
    /// Onset of a `b2` deformation (long axis on the box diagonal).
    pub kappa2_b2: f64,
}

/// The resting disk's thresholds (see [`IcThresholds`]); `params.eta_t` and `params.kappa2`
/// do not matter.
pub fn ic_thresholds(params: &ModelParams, n: usize) -> Result<IcThresholds, SolverError> {
    let mut solver = SteadySolver::new(*params, n)?;
    let j0 = Linearization::at(&mut solver, [0.0; 4]).jacobian0();
    Ok(IcThresholds {
        eta_t: j0[0][0] + params.eta_t,
        kappa2_a2: j0[2][2] + params.kappa2,
        kappa2_b2: j0[3][3] + params.kappa2,
    })
}

/// Largest eigenvalue of a real 2 x 2 matrix with real eigenvalues (else its real part).
fn top_eigenvalue(m: [[f64; 2]; 2]) -> f64 {
    let tr = m[0][0] + m[1][1];
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let disc = tr * tr / 4.0 - det;
    tr / 2.0 + disc.max(0.0).sqrt()
}

/// The `eta_t` below which the ID state on `mirror` at `kappa2` starts to move, with its
/// shape amplitude, or `None` where there is no ID state.
pub fn id_onset(
    solver: &mut SteadySolver,
    mirror: MirrorAxis,
    kappa2: f64,
    seed: f64,
) -> Option<(f64, f64)> {
    let eta_t = solver.params().eta_t;
    solver.set_control(eta_t, kappa2);
    let st = solver.newton_on(mirror, 0.0, seed, 1e-12).ok()?;
    if st.a2.abs() < 1e-4 {
        return None;
    }
    let z = match mirror {
        MirrorAxis::X => [0.0, 0.0, st.a2, 0.0],
        MirrorAxis::Diagonal => [0.0, 0.0, 0.0, st.a2],
    };
    let j = Linearization::at(solver, z).jacobian0();
    let k = [[j[0][0] + eta_t, j[0][1]], [j[1][0], j[1][1] + eta_t]];
    Some((top_eigenvalue(k), st.a2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn md_from_the_reduced_models_seed_is_the_time_steppers_state() {
        // Fig. 1c: the time stepper's steady MD state is v = 0.592462, s = 0.270056 (README).
        let st = find(
            &ModelParams::at(0.085, 0.112),
            192,
            StateKind::MD,
            MirrorAxis::X,
            None,
        )
        .unwrap();
        assert!((st.z[0] - 0.592462).abs() < 1e-6, "{st:?}");
        assert!((st.z[2] + 0.270056).abs() < 1e-6, "{st:?}");
        assert!(st.eigenvalues.iter().all(|l| l.re < 0.0), "{st:?}");
        let id = find(
            &ModelParams::at(0.1, 0.105),
            96,
            StateKind::ID,
            MirrorAxis::X,
            None,
        )
        .unwrap();
        assert!(id.z[2] > 0.1 && id.z[0] == 0.0, "{id:?}");
    }

    #[test]
    fn the_resting_disks_thresholds_are_where_its_eigenvalues_cross_zero() {
        let th = ic_thresholds(&ModelParams::at(0.085, 0.13), 192).unwrap();
        // Bracketed by the reference eigenvalues of docs/model.md: drift +0.001445 at eta_t = 0.0763 and
        // -0.004036 at 0.077; shape > 0 at kappa2 = 0.112, < 0 at 0.13.
        assert!(th.eta_t > 0.0763 && th.eta_t < 0.077, "{th:?}");
        for k in [th.kappa2_a2, th.kappa2_b2] {
            assert!(k > 0.112 && k < 0.13, "{th:?}");
        }
        // The same numbers whatever the other parameter.
        let other = ic_thresholds(&ModelParams::at(0.1, 0.16), 192).unwrap();
        assert!((other.eta_t - th.eta_t).abs() < 1e-9, "{other:?}");
        assert!((other.kappa2_a2 - th.kappa2_a2).abs() < 1e-9, "{other:?}");
        // At the threshold the drift pair's eigenvalue is zero, the shape's at its own.
        let at = |eta_t, kappa2| {
            find(
                &ModelParams::at(eta_t, kappa2),
                192,
                StateKind::IC,
                MirrorAxis::X,
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
}
