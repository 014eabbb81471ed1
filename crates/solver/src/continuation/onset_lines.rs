//! The two onset lines of a window of the paper's plane (`x` is `eta_t`, `y` is `kappa2`)
//! that are sampled in `kappa2`, for the
//! model with shape modes `2..K` (each with its fast path for `K = 2`, chosen by the
//! [`Balances`] it is given):
//!
//! - **ID onset of motion** (pitchfork of the resting deformed droplet into MD): the ID state
//!   does not depend on `eta_t` (it does not move), and at a mirror-symmetric ID the drift
//!   block of the `lambda = 0` Jacobian is `-eta_t I + K(kappa2)` (decoupled from the shape by
//!   the two mirror symmetries; with more modes, a Schur complement over the odd modes the
//!   drift couples to), so the threshold is one Newton solve and one linearisation per
//!   `kappa2`, exact at the grid. For the ID whose minor axis is the mirror line (the x axis,
//!   or the diagonal: the box's square symmetry tells them apart), from the window's bottom up
//!   to where that ID meets the disk (denser there, where ID's amplitude goes like a square
//!   root).
//! - **MC onset** (where the moving branch's deformation crosses the class threshold, so its
//!   states change from MD to MC): on the x axis the moving state with `a2 = -0.01` (a moving
//!   droplet is elongated across its motion) solves the steady equations for `(v, a_3..a_K,
//!   eta_t)` at each `kappa2`: one Newton solve per sample, from the window's top down,
//!   continued from the last, while Newton converges inside the window and the state there is
//!   stable (the rotation mode aside): below the point where the onset of motion turns
//!   subcritical the `s = 0.01` state lies on the unstable part of the branch, and no label
//!   can change there.
use crate::continuation::window::Window;
use crate::error::SolverError;
use crate::model::classify::CLASS_THRESHOLD;
use crate::model::mirror::MirrorLine;
use crate::numerics::newton::{fd_jacobian, NewtonOptions};
use crate::roots::balances::Balances;
use crate::roots::linearisation::Linearization;
use crate::roots::named_state::{id_state, rest_shape};
use crate::roots::steady_solver::{SteadySolver, TwoModeSolver};
use crate::roots::thresholds::{drift_threshold, id_onset};

/// The ID onset line on `mirror`: `(eta_t, kappa2)` for `kappa2` from the window's bottom up
/// to (not including) `top`, where that ID meets the disk; none when the window lies above
/// `top`.
pub fn id_line(
    balances: Balances,
    w: &Window,
    mirror: MirrorLine,
    top: f64,
) -> Result<Vec<(f64, f64)>, SolverError> {
    match balances {
        Balances::Two(solver) => two_mode_id_line(solver, w, mirror, top),
        Balances::General(solver) => general_id_line(solver, w, mirror, top),
    }
}

/// The MC onset line on the x axis (see the module), from the disk's onset of motion
/// `onset_eta_t` at the window's top down.
pub fn mc_line(
    balances: Balances,
    w: &Window,
    onset_eta_t: f64,
) -> Result<Vec<(f64, f64)>, SolverError> {
    match balances {
        Balances::Two(solver) => two_mode_mc_line(solver, w, onset_eta_t),
        Balances::General(solver) => general_mc_line(solver, w, onset_eta_t),
    }
}

/// The 2-mode ID line: Newton on the shape balance on `mirror`, each sample from the last
/// one's amplitude, and the drift block's top eigenvalue
/// ([`crate::roots::thresholds::id_onset`]).
fn two_mode_id_line(
    mut solver: TwoModeSolver,
    w: &Window,
    mirror: MirrorLine,
    hi: f64,
) -> Result<Vec<(f64, f64)>, SolverError> {
    let lo = w.y.range.0;
    if hi <= lo {
        return Ok(Vec::new());
    }
    let mut seed = 0.3;
    let mut pts = Vec::new();
    let m = w.samples.max(2);
    for i in 0..m {
        // Denser towards the IC end, where ID's amplitude goes like a square root.
        let t = i as f64 / (m - 1) as f64;
        let k = hi - (hi - lo) * (1.0 - t).powi(2) * 0.999_999 - 1e-9;
        let k = if i == 0 { lo } else { k.max(lo) };
        if let Some((eta, c)) = id_onset(&mut solver, mirror, k, seed) {
            seed = c;
            pts.push((eta, k));
        }
    }
    Ok(pts)
}

/// The general ID line: the resting deformed state with every even mode, from the first
/// `kappa2` where it is found (with mode 2 alone, then one mode at a time) to where Newton
/// loses it, and its drift's zero eigenvalue by a Schur complement of the `lambda = 0`
/// Jacobian over the odd modes, as for the disk
/// ([`crate::roots::thresholds::drift_threshold`]).
fn general_id_line(
    mut solver: SteadySolver,
    w: &Window,
    mirror: MirrorLine,
    top: f64,
) -> Result<Vec<(f64, f64)>, SolverError> {
    let k_max = solver.params().modes;
    let axis = mirror.angle();
    solver.set_axis(axis);
    let (lo, hi) = (w.y.range.0, top.min(w.y.range.1));
    // The window lies above where this ID meets the disk.
    if hi <= lo {
        return Ok(Vec::new());
    }
    let m = w.samples.max(2);
    let mut shape: Option<Vec<f64>> = None;
    let mut pts = Vec::new();
    for i in 0..m {
        // Denser towards the IC end, where ID's amplitude goes like a square root.
        let t = i as f64 / (m - 1) as f64;
        let k = hi - (hi - lo) * (1.0 - t).powi(2) * 0.999_999 - 1e-9;
        let k = if i == 0 { lo } else { k.max(lo) };
        solver.set_control(0.0, k);
        let next = match &shape {
            Some(s) => rest_shape(&mut solver, s),
            // ID elongated along y (a2 < 0): it starts to move along x, its minor axis, which
            // the x-axis states describe (the one elongated along x is its quarter turn).
            // Found on the x axis and then turned, so that both lines follow one family of
            // states (from 0 a mode may also converge to another one, as with K = 6).
            None => {
                solver.set_axis(0.0);
                let axis_id = id_state(&mut solver, k_max, -0.3);
                solver.set_axis(axis);
                axis_id.and_then(|s| rest_shape(&mut solver, &s))
            }
        };
        match next {
            Some(s) => shape = Some(s),
            None if shape.is_some() => break,
            None => continue,
        }
        let y0: Vec<f64> = std::iter::once(0.0)
            .chain(shape.iter().flatten().copied())
            .collect();
        let c = fd_jacobian(&mut |y: &[f64]| solver.residual_x(y), &y0, 1e-6);
        pts.push((drift_threshold(&c), k));
    }
    Ok(pts)
}

/// The 2-mode MC line: Newton on `(v, eta_t)`, every sample's verdict.
fn two_mode_mc_line(
    mut solver: TwoModeSolver,
    w: &Window,
    onset_eta_t: f64,
) -> Result<Vec<(f64, f64)>, SolverError> {
    let c = -crate::model::classify::CLASS_THRESHOLD;
    let opts = crate::numerics::newton::NewtonOptions {
        tol: 1e-12,
        max_iter: 30,
        fd_step: 1e-7,
        max_step: vec![0.05, 0.002],
        one_sided: false,
        backtrack: false,
    };
    // a2 ~ -0.18 v^2 on the moving branch near the onset of motion (docs/model.md, "Where a slow run lands").
    let mut guess = [(-c / 0.18f64).sqrt(), onset_eta_t];
    let (k0, k1) = w.y.range;
    let m = w.samples.max(2);
    let mut pts = Vec::new();
    for i in 0..m {
        let k = k1 - (k1 - k0) * i as f64 / (m - 1) as f64;
        let Ok(sol) = crate::numerics::newton::solve(
            |x| {
                solver.set_control(x[1], k);
                solver.residual_on(MirrorLine::X, x[0], c).to_vec()
            },
            &guess,
            &opts,
        ) else {
            break;
        };
        let (v, eta) = (sol.x[0], sol.x[1]);
        if v <= 0.0 || !(w.x.range.0..=w.x.range.1).contains(&eta) {
            break;
        }
        guess = [v, eta];
        solver.set_control(eta, k);
        let z = [v, 0.0, c, 0.0];
        if !Linearization::of_two_modes(&mut solver, z)
            .verdict()
            .stable()
        {
            break;
        }
        pts.push((eta, k));
    }
    Ok(pts)
}

/// The state `(vx, vy, a_2..a_K, b_2..b_K)` on the x axis with `a2 = -CLASS_THRESHOLD` from
/// the MC line's unknowns `x = (v, a_3..a_K, eta_t)`.
fn mc_state(x: &[f64]) -> Vec<f64> {
    let k_max = x.len();
    let mut z = vec![x[0], 0.0, -CLASS_THRESHOLD];
    z.extend(&x[1..k_max - 1]);
    z.extend(std::iter::repeat_n(0.0, k_max - 1));
    z
}

/// The general MC line: Newton on `(v, a_3..a_K, eta_t)` with `a2 = -CLASS_THRESHOLD`; the
/// stability decided at the line's two ends and by bisection between them (one change of
/// stability along the line; each verdict a `2K x 2K` eigenproblem with the field, seconds at
/// N = 192).
fn general_mc_line(
    mut solver: SteadySolver,
    w: &Window,
    onset_eta_t: f64,
) -> Result<Vec<(f64, f64)>, SolverError> {
    let k_max = solver.params().modes;
    let opts = NewtonOptions {
        tol: 1e-12,
        max_iter: 30,
        fd_step: 1e-7,
        max_step: [vec![0.05; k_max - 1], vec![0.002]].concat(),
        one_sided: false,
        backtrack: false,
    };
    // a2 ~ -0.18 v^2 on the 2-mode moving branch near the onset of motion.
    let mut guess = vec![0.0; k_max];
    guess[0] = (CLASS_THRESHOLD / 0.18f64).sqrt();
    guess[k_max - 1] = onset_eta_t;
    let (k0, k1) = w.y.range;
    let m = w.samples.max(2);
    let mut line: Vec<(f64, f64, Vec<f64>)> = Vec::new();
    for i in 0..m {
        let k = k1 - (k1 - k0) * i as f64 / (m - 1) as f64;
        let balance = |x: &[f64]| {
            solver.set_control(x[k_max - 1], k);
            let z = mc_state(x);
            let mut y = vec![z[0]];
            y.extend(&z[2..k_max + 1]);
            solver.residual_x(&y)
        };
        let Ok(sol) = crate::numerics::newton::solve(balance, &guess, &opts) else {
            break;
        };
        let (v, eta) = (sol.x[0], sol.x[k_max - 1]);
        if v <= 0.0 || !(w.x.range.0..=w.x.range.1).contains(&eta) {
            break;
        }
        guess = sol.x.clone();
        line.push((eta, k, mc_state(&sol.x)));
    }
    let mut stable = |i: usize| {
        let (eta, k, z) = &line[i];
        solver.set_control(*eta, *k);
        Linearization::at(&mut solver, z).verdict().stable()
    };
    let kept = match line.len() {
        0 => 0,
        _ if !stable(0) => 0,
        len if stable(len - 1) => len,
        len => {
            // stable(good), unstable(bad): the last stable sample lies in good..bad.
            let (mut good, mut bad) = (0, len - 1);
            while bad - good > 1 {
                let mid = (good + bad) / 2;
                if stable(mid) {
                    good = mid;
                } else {
                    bad = mid;
                }
            }
            good + 1
        }
    };
    Ok(line[..kept].iter().map(|(e, k, _)| (*e, *k)).collect())
}
