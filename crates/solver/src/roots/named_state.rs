//! The steady states the paper names, computed as roots and linearised, for shape modes
//! `2..K`: the resting disk (IC), the resting deformed droplet (ID) and the droplet moving
//! along its minor axis (MD), each on a mirror axis of the box (motion along x or along the
//! diagonal). With two modes Newton starts from the reduced model's state (Sect. 5) unless a
//! seed is given; with modes `2..K` from the 2-mode state on the x axis with one mode added at
//! a time, and on the diagonal from that state turned by 45 degrees and solved again on all
//! `2K` balances (the two differ by the box's anisotropy; the mirror symmetry keeps Newton on
//! the diagonal).
use crate::error::SolverError;
use crate::model::mirror::MirrorLine;
use crate::model::params::ModelParams;
use crate::model::state::turned;
use crate::numerics::newton::{self, NewtonOptions};
use crate::reduced::bifurcation::md_states;
use crate::reduced::coefficients::Coefficients;
use crate::roots::balances::Balances;
use crate::roots::steady_solver::TwoModeSolver;
use crate::roots::steady_solver::{on_x_axis, MirrorState, SteadySolver};
use crate::roots::verdict::Verdict;
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
    /// `(vx, vy, a_2..a_K, b_2..b_K)`; with two modes `(vx, vy, a2, b2)`.
    pub z: Vec<f64>,
    /// Max norm of the force balance at `z`.
    pub residual: f64,
    /// Eigenvalues with `Re > -1`, decreasing real part.
    pub eigenvalues: Vec<Complex64>,
    /// What they say: the rotation mode identified and set aside
    /// ([`crate::roots::verdict::assess`]).
    pub verdict: Verdict,
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

/// Finds `kind` on `axis` with the balances' shape modes and grid (Newton to 1e-12; with two
/// modes from `seed` or from the reduced model's state, with more from the 2-mode state, see
/// the module; from `seed`, `(v, a2)` along the axis, at any `K`: the higher modes then start
/// from 0), then linearises it. Needs inertia `m > 0`.
pub fn find(
    balances: &mut Balances,
    kind: StateKind,
    axis: MirrorLine,
    seed: Option<(f64, f64)>,
) -> Result<NamedState, SolverError> {
    let mass = balances.params().mass;
    crate::error::require(
        mass > 0.0,
        "mass",
        mass,
        "a finite number > 0 for the linearisation (the overdamped velocity has no dynamics)",
    )?;
    let (z, residual) = match balances {
        Balances::Two(solver) => {
            let (z, residual) = two_mode_root(solver, kind, axis, seed)?;
            (z.to_vec(), residual)
        }
        Balances::General(solver) => {
            let z = general_root(solver, kind, axis, seed)?;
            let residual = solver
                .residual(&z)
                .iter()
                .fold(0.0f64, |m, r| m.max(r.abs()));
            (z, residual)
        }
    };
    let verdict = balances.verdict(&z);
    Ok(NamedState {
        residual,
        eigenvalues: verdict
            .eigenvalues
            .iter()
            .map(|[re, im]| Complex64::new(*re, *im))
            .collect(),
        z,
        verdict,
    })
}

/// The 2-mode state `kind` on `axis` and its residual: Newton from `seed`, or from the reduced
/// model's states in turn (MD: then three fixed starts) until one is of the kind.
fn two_mode_root(
    solver: &mut TwoModeSolver,
    kind: StateKind,
    axis: MirrorLine,
    seed: Option<(f64, f64)>,
) -> Result<([f64; 4], f64), SolverError> {
    if kind == StateKind::IC {
        return Ok((axis.two_mode_state(0.0, 0.0), 0.0));
    }
    let params = *solver.params();
    let c = Coefficients::new(params.radius, crate::contract::settings::H0_PAPER);
    let seeds: Vec<(f64, f64)> = match (seed, kind) {
        (Some(s), _) => vec![s],
        (None, StateKind::ID) => vec![(0.0, id_seed(&c, &params))],
        _ => {
            let mut v = md_seeds(&c, &params, -1.0);
            v.extend([(0.6, -0.27), (0.9, -0.35), (0.3, -0.1)]);
            v
        }
    };
    let mut last = None;
    for (v0, c0) in seeds {
        let v0 = if kind == StateKind::ID { 0.0 } else { v0 };
        match solver.newton_on(axis, v0, c0, 1e-12) {
            Ok(st) if kind == StateKind::ID || st.v.abs() > 1e-6 => {
                return Ok((axis.two_mode_state(st.v, st.a2), st.residual));
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
    Err(last.unwrap_or(SolverError::NewtonFailed {
        residual: f64::NAN,
        iterations: 0,
    }))
}

/// The state `kind` of the solver's model (shape modes `2..=K`) on `axis` (see the module).
fn general_root(
    solver: &mut SteadySolver,
    kind: StateKind,
    axis: MirrorLine,
    seed: Option<(f64, f64)>,
) -> Result<Vec<f64>, SolverError> {
    let k_max = solver.params().modes;
    let lost = || SolverError::NewtonFailed {
        residual: f64::NAN,
        iterations: 0,
    };
    let (v, shape) = match (kind, seed) {
        (StateKind::IC, _) => (0.0, ic_state(solver, k_max).ok_or_else(lost)?),
        (StateKind::ID, seed) => {
            let a2 = seed.map_or(0.3, |(_, a2)| a2);
            (0.0, id_state(solver, k_max, a2).ok_or_else(lost)?)
        }
        (StateKind::MD, None) => {
            let st = md_state(solver, k_max)?;
            (st.v, st.a)
        }
        // From the seed with the modes 3..K at 0: on the x axis Newton there; off it the seed
        // is turned onto the axis and solved there on all 2K balances (the box's anisotropy
        // makes the states of the two lines differ).
        (StateKind::MD, Some((v, a2))) => {
            let mut a = vec![0.0; k_max - 1];
            a[0] = a2;
            if axis != MirrorLine::X {
                (v, a)
            } else {
                let guess: Vec<f64> = std::iter::once(v).chain(a).collect();
                let st = solver.newton_x(&guess, 1e-11)?;
                (st.v, st.a)
            }
        }
    };
    let z = on_x_axis(v, &shape);
    if axis == MirrorLine::X {
        return Ok(z);
    }
    let opts = NewtonOptions {
        tol: 1e-11,
        max_iter: 30,
        fd_step: 1e-7,
        max_step: vec![0.2; z.len()],
        one_sided: false,
        backtrack: false,
    };
    let turned = turned(&z, std::f64::consts::FRAC_PI_4);
    Ok(newton::solve(|y| solver.residual(y), &turned, &opts)?.x)
}

/// Where Newton starts a mode added to a state: 0, then either side of it.
const NEW_MODE_SEEDS: [f64; 3] = [0.0, 0.05, -0.05];

/// The MD state of the `k_max`-mode model at the solver's parameters, moving along +x: the
/// 2-mode model's ([`find`], from the reduced model's states), then one mode at a time, each
/// from `a_k = 0`.
pub fn md_state(solver: &mut SteadySolver, k_max: usize) -> Result<MirrorState, SolverError> {
    let two = find(
        &mut Balances::new(solver.params().with_modes(2), solver.n())?,
        StateKind::MD,
        MirrorLine::X,
        None,
    )?;
    md_state_from(solver, k_max, two.z[0], two.z[2])
}

/// The moving state of the `k_max`-mode model on the solver's axis from the 2-mode one
/// `(v, a2)` (moving along its minor axis, `a2 < 0`, or its major axis): Newton on modes
/// `2..=2`, then one mode at a time, each from `a_k = 0` (then either side of it).
pub fn md_state_from(
    solver: &mut SteadySolver,
    k_max: usize,
    v: f64,
    a2: f64,
) -> Result<MirrorState, SolverError> {
    let mut guess = vec![v, a2];
    let mut st = solver.newton_x(&guess, 1e-11)?;
    for _ in 3..=k_max {
        let mut next = None;
        for &a in &NEW_MODE_SEEDS {
            guess = std::iter::once(st.v)
                .chain(st.a.iter().copied())
                .chain([a])
                .collect();
            match solver.newton_x(&guess, 1e-11) {
                Ok(found) => {
                    next = Some(Ok(found));
                    break;
                }
                Err(e) => next = Some(Err(e)),
            }
        }
        st = next.expect("seeds")?;
    }
    Ok(st)
}

/// Newton on the shape balance of a resting state (`v = 0`, `b_k = 0`) from `seed`, with
/// steps of at most 0.05 per mode.
fn rest_root(solver: &mut SteadySolver, seed: &[f64]) -> Option<Vec<f64>> {
    let opts = NewtonOptions {
        tol: 1e-12,
        max_iter: 40,
        fd_step: 1e-7,
        max_step: vec![0.05; seed.len()],
        one_sided: false,
        backtrack: false,
    };
    newton::solve(
        |a| {
            let y: Vec<f64> = std::iter::once(0.0).chain(a.iter().copied()).collect();
            solver.residual_x(&y)[1..].to_vec()
        },
        seed,
        &opts,
    )
    .ok()
    .map(|sol| sol.x)
}

/// The shape `a_2..a_(len+1)` of a resting deformed state by Newton on the shape balance from
/// `seed`; `None` where Newton fails or lands on the disk (`|a2| <= 1e-4`).
pub fn rest_shape(solver: &mut SteadySolver, seed: &[f64]) -> Option<Vec<f64>> {
    rest_root(solver, seed).filter(|x| x[0].abs() > 1e-4)
}

/// The resting deformed state (ID) of the `k_max`-mode model on the x axis, `a_2..a_K`: with
/// mode 2 alone from `a2 = seed` (> 0: elongated along x), then one mode at a time from 0.
pub fn id_state(solver: &mut SteadySolver, k_max: usize, seed: f64) -> Option<Vec<f64>> {
    let two = rest_shape(solver, &[seed])?;
    (3..=k_max).try_fold(two, |s, _| {
        // From 0, else from either side of it (Newton from exactly 0 can miss a mode the
        // shape drives strongly: a4 = 0.07 at kappa2 = 0.105).
        NEW_MODE_SEEDS.iter().find_map(|&a| {
            let next: Vec<f64> = s.iter().copied().chain([a]).collect();
            rest_shape(solver, &next)
        })
    })
}

/// The resting disk of the `k_max`-mode model on the x axis, `a_2..a_K`: round but for the
/// box and the grid, whose square symmetry drives mode 4 (and 8, ...) a little (a4 ~ 5e-4 at
/// N = 96).
pub fn ic_state(solver: &mut SteadySolver, k_max: usize) -> Option<Vec<f64>> {
    rest_root(solver, &vec![0.0; k_max - 1]).filter(|x| x[0].abs() < 1e-4)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two(eta_t: f64, kappa2: f64, n: usize) -> Balances {
        Balances::new(ModelParams::at(eta_t, kappa2), n).unwrap()
    }

    #[test]
    fn md_from_the_reduced_models_seed_is_the_time_steppers_state() {
        // Fig. 1c: the time stepper's steady MD state is v = 0.592462, s = 0.270056 (README).
        let st = find(
            &mut two(0.085, 0.112, 192),
            StateKind::MD,
            MirrorLine::X,
            None,
        )
        .unwrap();
        assert!((st.z[0] - 0.592462).abs() < 1e-6, "{st:?}");
        assert!((st.z[2] + 0.270056).abs() < 1e-6, "{st:?}");
        assert!(st.eigenvalues.iter().all(|l| l.re < 0.0), "{st:?}");
        let id = find(&mut two(0.1, 0.105, 96), StateKind::ID, MirrorLine::X, None).unwrap();
        assert!(id.z[2] > 0.1 && id.z[0] == 0.0, "{id:?}");
    }

    #[test]
    fn the_general_balances_with_mode_two_alone_find_the_two_mode_states() {
        // The general solver and its 2K x 2K eigenproblem at K = 2 against the 2-mode solver
        // and its 4 x 4 one: the same states and the same leading eigenvalues.
        let p = ModelParams::at(0.085, 0.112);
        for (kind, axis) in [
            (StateKind::MD, MirrorLine::X),
            (StateKind::MD, MirrorLine::Diagonal),
            (StateKind::IC, MirrorLine::X),
        ] {
            let fast = find(&mut Balances::new(p, 96).unwrap(), kind, axis, None).unwrap();
            let mut general = Balances::General(SteadySolver::new(p, 96).unwrap());
            let st = find(&mut general, kind, axis, None).unwrap();
            let dz =
                st.z.iter()
                    .zip(&fast.z)
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(
                dz < 1e-8 && st.residual < 1e-10,
                "{kind:?} {axis:?}: {st:?} {fast:?}"
            );
            assert_eq!(
                st.verdict.unstable, fast.verdict.unstable,
                "{st:?} {fast:?}"
            );
            for (a, b) in st.eigenvalues.iter().zip(&fast.eigenvalues).take(3) {
                assert!((a - b).norm() < 1e-6, "{kind:?} {axis:?}: {a} vs {b}");
            }
        }
    }

    #[test]
    fn with_three_modes_the_md_states_lie_on_their_mirror_lines_also_from_a_seed() {
        let mut b = Balances::new(ModelParams::at(0.085, 0.112).with_modes(3), 96).unwrap();
        let x = find(&mut b, StateKind::MD, MirrorLine::X, None).unwrap();
        assert_eq!(x.z.len(), 6);
        assert!(x.z[1] == 0.0 && x.z[4] == 0.0 && x.z[5] == 0.0, "{x:?}");
        assert!(x.verdict.stable() && x.residual < 1e-10, "{x:?}");
        // On the diagonal: Newton on all six balances from the axis state turned by 45
        // degrees stays on the mirror line (here on a slower state: mode 3 turned by 45
        // degrees is not the axis state's mode 3, and the box tells them apart).
        let d = find(&mut b, StateKind::MD, MirrorLine::Diagonal, None).unwrap();
        assert!(
            (d.z[0] - d.z[1]).abs() < 1e-9 && d.residual < 1e-10,
            "{d:?}"
        );
        assert!(d.z[0] > 0.1, "{d:?}");
        // From a seed near it, mode 3 from 0: the same state.
        let seeded = find(&mut b, StateKind::MD, MirrorLine::X, Some((0.35, -0.2))).unwrap();
        assert!((seeded.z[0] - x.z[0]).abs() < 1e-8, "{seeded:?} {x:?}");
        assert!((seeded.z[3] - x.z[3]).abs() < 1e-8, "{seeded:?} {x:?}");
    }
}
