//! The phase boundaries of the `K`-mode model in a window of `(eta_t, kappa2)`, for the states
//! on the x axis ([`crate::roots::steady_solver`]: motion along x, `b_k = 0`), each point a
//! solution of its equations:
//!
//! - **IC onset of motion**: the disk's drift threshold with the odd modes it couples to in
//!   the box ([`crate::roots::thresholds::disk_thresholds`]), at the window's bottom and top.
//! - **IC onset of deformation (a2, axis)** and **(b2, diagonal)**: the disk's mode-2
//!   thresholds (modes decouple at the circle but for the box's weak `k +- 4` coupling, left
//!   out); the onset of motion starts from the higher of the two. Each of the disk's lines is
//!   drawn only where it crosses the window, as the 2-mode model's.
//! - **ID onset of motion (axis ID)**: the resting deformed state elongated along y (`v = 0`,
//!   its odd modes 0 by the mirror `x -> -x`) solved by Newton at each `kappa2`, and the `eta_t`
//!   at which its drift along x, its minor axis (the speed and the odd modes), has a zero
//!   eigenvalue: a Schur complement of the `lambda = 0` Jacobian, as for the disk.
//! - **MD saddle-node (x axis)**: pseudo-arclength continuation in `(v, a_2..a_K, qe, qk)` of
//!   `R = 0, det dR/d(v, a) = 0` ([`crate::continuation::fold_curve`], every `K`), started
//!   from the first fold of the MD branch at the middle `kappa2`.
//!
//! - **MC onset, s = 0.01 (x axis)**: the moving state with `a2 = -0.01` solves the `K` steady
//!   equations on the x axis for `(v, a_3..a_K, eta_t)` at each `kappa2`, from the window's top
//!   down, continued from the last sample, on the stretch where that state is stable (the
//!   rotation mode aside), as the 2-mode model's line ([`crate::continuation::boundaries`]).
//!
//! - **ID onset of motion (diagonal ID)**: the same for the resting deformed state elongated
//!   along a diagonal, drifting along the other: every x-axis computation in the frame turned
//!   by 45 degrees ([`SteadySolver::set_axis`]); the box's square symmetry tells it from the
//!   axis ID (for `K = 2`, as in the 2-mode model; from `K = 4` also through mode 4, which the
//!   turn flips).
use crate::continuation::fold_curve::{md_fold_curve, FoldModel};
use crate::continuation::window::{PlaneAxis, Window};
use crate::error::SolverError;
use crate::model::classify::CLASS_THRESHOLD;
use crate::model::param::ModelParam;
use crate::model::params::ModelParams;
use crate::numerics::newton::{fd_jacobian, NewtonOptions};
use crate::reduced::boundaries::Boundary;
use crate::roots::linearisation::Linearization;
use crate::roots::named_state::{id_state, rest_shape};
use crate::roots::steady_solver::{MirrorAxis, SteadySolver};
use crate::roots::thresholds::{disk_thresholds, drift_threshold};

/// The ID onset of motion at each of `w.id_samples` values of `kappa2` from the window's
/// bottom up to where ID meets the disk (the mode-2 onset `top`), from the first `kappa2`
/// where ID is found (with mode 2 alone, then adding one mode at a time) to where Newton
/// loses it (none when the window lies above `top`), for the ID whose minor axis is the mirror line at angle `axis` to x (0: the
/// axis ID; `pi / 4`: the diagonal ID, [`SteadySolver::set_axis`]).
fn id_line(w: &Window, top: f64, axis: f64) -> Result<Vec<(f64, f64)>, SolverError> {
    let mut solver = SteadySolver::new(w.base, w.n)?;
    solver.set_axis(axis);
    let k_max = w.modes;
    let (lo, hi) = (w.kappa2.0, top.min(w.kappa2.1));
    // The window lies above where this ID meets the disk.
    if hi <= lo {
        return Ok(Vec::new());
    }
    let m = w.id_samples.max(2);
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

/// The MD fold curve: continued both ways from the fold on the middle `kappa2`
/// ([`md_fold_curve`], the one fold curve of every `K`); none where the middle line has no
/// moving state at its start or no fold.
fn fold_curve(w: &Window) -> Result<Vec<(f64, f64)>, SolverError> {
    let mid = 0.5 * (w.kappa2.0 + w.kappa2.1);
    let x = PlaneAxis::new(ModelParam::EtaT, w.eta_t);
    let y = PlaneAxis::new(ModelParam::Kappa2, w.kappa2);
    let model = FoldModel {
        n: w.n,
        modes: w.modes,
    };
    md_fold_curve(&w.base, model, MirrorAxis::X, (x, y), &[mid])
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

/// The MC onset line on the x axis (see the module doc), from the top of the window down
/// while Newton converges inside it, cut where the states turn unstable: below the point
/// where the onset of motion turns subcritical the `s = 0.01` state lies on the unstable
/// part of the branch, and no label changes there. The stability is decided at the line's
/// two ends and by bisection between them (one change of stability along the line; each
/// verdict is a `2K x 2K` eigenproblem with the field, seconds at N = 192).
fn mc_line(w: &Window, onset_eta_t: f64) -> Result<Vec<(f64, f64)>, SolverError> {
    let mut solver = SteadySolver::new(w.base, w.n)?;
    let k_max = w.modes;
    let opts = NewtonOptions {
        tol: 1e-12,
        max_iter: 30,
        fd_step: 1e-7,
        max_step: [vec![0.05; k_max - 1], vec![0.002]].concat(),
    };
    // a2 ~ -0.18 v^2 on the 2-mode moving branch near the onset of motion.
    let mut guess = vec![0.0; k_max];
    guess[0] = (CLASS_THRESHOLD / 0.18f64).sqrt();
    guess[k_max - 1] = onset_eta_t;
    let (k0, k1) = w.kappa2;
    let m = w.id_samples.max(2);
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
        if v <= 0.0 || !(w.eta_t.0..=w.eta_t.1).contains(&eta) {
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

/// The `K`-mode model's boundaries in the window (see the module doc; `K = w.modes`), named
/// like the 2-mode model's. [`crate::continuation::boundaries::boundaries`] comes here for
/// `K > 2`; with `K = 2` this general computation gives the 2-mode curves (tested).
pub fn mode_boundaries(w: &Window) -> Result<Vec<Boundary>, SolverError> {
    crate::contract::limits::check_modes(&w.base, w.n, w.modes)?;
    let (e0, e1) = w.eta_t;
    let (k0, k1) = w.kappa2;
    let mut disk = SteadySolver::new(
        ModelParams {
            kappa2: k0,
            ..w.base
        },
        w.n,
    )?;
    let low = disk_thresholds(&mut disk, w.modes);
    disk.set_control(w.base.eta_t, k1);
    let high = disk_thresholds(&mut disk, w.modes);
    let shape_onset = low.kappa2_a2;
    let diagonal_onset = low.kappa2_b2;
    type Curve = Result<Vec<(f64, f64)>, SolverError>;
    let diagonal = std::f64::consts::FRAC_PI_4;
    let (id, id_diagonal, fold, mc): (Curve, Curve, Curve, Curve) = std::thread::scope(|scope| {
        let id = scope.spawn(|| id_line(w, shape_onset, 0.0));
        let id_diagonal = scope.spawn(|| id_line(w, diagonal_onset, diagonal));
        let mc = scope.spawn(|| mc_line(w, high.eta_t));
        let fold = fold_curve(w);
        let id = id.join().expect("the ID line's thread panicked");
        let id_diagonal = id_diagonal.join().expect("the ID line's thread panicked");
        (
            id,
            id_diagonal,
            fold,
            mc.join().expect("the MC line's thread panicked"),
        )
    });
    // The resting disk's onsets are straight lines (the onset of motion all but straight),
    // drawn where they cross the window, as the 2-mode model's: the onset of motion above
    // the disk's deformation onsets (below them the disk deforms).
    let inside = |x: f64, (lo, hi): (f64, f64)| (lo..=hi).contains(&x);
    let bottom = shape_onset.max(diagonal_onset).max(k0);
    let motion = inside(low.eta_t, w.eta_t) || inside(high.eta_t, w.eta_t);
    let deformation = |k: f64| inside(k, w.kappa2) && low.eta_t.max(e0) < e1;
    let mut out = vec![
        Boundary {
            name: "IC onset of motion",
            points: if motion && bottom < k1 {
                vec![(low.eta_t, bottom), (high.eta_t, k1)]
            } else {
                Vec::new()
            },
        },
        Boundary {
            name: "IC onset of deformation (b2, diagonal)",
            points: if deformation(diagonal_onset) {
                vec![(low.eta_t.max(e0), diagonal_onset), (e1, diagonal_onset)]
            } else {
                Vec::new()
            },
        },
        Boundary {
            name: "IC onset of deformation (a2, axis)",
            points: if deformation(shape_onset) {
                vec![(low.eta_t.max(e0), shape_onset), (e1, shape_onset)]
            } else {
                Vec::new()
            },
        },
        Boundary {
            name: "ID onset of motion (diagonal ID)",
            points: id_diagonal?,
        },
        Boundary {
            name: "ID onset of motion (axis ID)",
            points: id?,
        },
        Boundary {
            name: "MD saddle-node (x axis)",
            points: fold?,
        },
        Boundary {
            name: "MC onset, s = 0.01 (x axis)",
            points: mc?,
        },
    ];
    out.retain(|b| b.points.len() > 1);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::continuation::boundaries::boundaries;
    use crate::continuation::polyline::distance_to_polyline;

    #[test]
    fn the_diagonal_ids_onset_is_where_its_full_eigenproblem_gains_a_growing_mode() {
        // Modes 2..4 at N = 96, kappa2 = 0.105: the diagonal ID's onset of motion from the
        // lambda = 0 Schur complement, against the 2K x 2K eigenproblem with the field of the
        // diagonal ID (Newton on all 2K balances from the turned axis ID, so the frame turned
        // back is not used) either side of it: one more growing mode below it.
        let k = 0.105;
        let w = Window {
            base: ModelParams::at(0.08, k),
            n: 96,
            modes: 4,
            eta_t: (0.06, 0.1),
            kappa2: (k, k + 1e-3),
            id_samples: 2,
        };
        let diagonal = std::f64::consts::FRAC_PI_4;
        let line = id_line(&w, 0.118, diagonal).unwrap();
        let axis = id_line(&w, 0.118, 0.0).unwrap();
        assert_eq!((line[0].1, axis[0].1), (k, k));
        let onset = line[0].0;
        let mut solver = SteadySolver::new(w.base, w.n).unwrap();
        let shape = id_state(&mut solver, 4, -0.3).unwrap();
        let unstable = |solver: &mut SteadySolver, eta: f64| {
            solver.set_control(eta, k);
            let z = crate::model::state::turned(
                &crate::roots::steady_solver::on_x_axis(0.0, &shape),
                diagonal,
            );
            let opts = NewtonOptions {
                tol: 1e-12,
                max_iter: 30,
                fd_step: 1e-7,
                max_step: vec![0.05; z.len()],
            };
            let z = crate::numerics::newton::solve(|y| solver.residual(y), &z, &opts)
                .unwrap()
                .x;
            assert!(
                z[0].abs() < 1e-10 && z[2].abs() < 1e-10,
                "on the diagonal: {z:?}"
            );
            Linearization::at(solver, &z).verdict().unstable
        };
        let (above, below) = (
            unstable(&mut solver, onset + 2e-4),
            unstable(&mut solver, onset - 2e-4),
        );
        assert_eq!(
            below,
            above + 1,
            "onset {onset}: {above} above, {below} below"
        );
        // The box tells the two IDs apart.
        assert!((onset - axis[0].0).abs() > 1e-6, "{onset} vs {}", axis[0].0);
    }

    #[test]
    fn the_disks_lines_are_drawn_only_where_they_cross_the_window() {
        // The truncation test's window around kappa2 = 0.13 at N = 96: it holds the onset of
        // motion (0.0765) and lies above the deformation onsets (about 0.119), so the only
        // line of the resting disk is the onset of motion, as with the 2-mode computation.
        let w = Window {
            base: ModelParams::at(0.075, 0.125),
            n: 96,
            modes: 2,
            eta_t: (0.075, 0.085),
            kappa2: (0.125, 0.135),
            id_samples: 4,
        };
        let names = |b: Vec<Boundary>| -> Vec<&'static str> {
            let mut v: Vec<_> = b.iter().map(|c| c.name).collect();
            v.sort_unstable();
            v
        };
        let mine = names(mode_boundaries(&w).unwrap());
        let disk: Vec<_> = mine.iter().filter(|n| n.starts_with("IC onset")).collect();
        assert_eq!(disk, [&"IC onset of motion"], "{mine:?}");
        assert_eq!(mine, names(boundaries(&w).unwrap()));
    }

    #[test]
    fn a_window_at_rest_on_its_middle_line_has_no_fold_curve() {
        // Modes 2..3 at N = 64, right of the onset of motion and above kappa2 = 0.14: no
        // moving state at the middle line's start (Newton from the 2-mode state fails there).
        // That is a window without a fold curve, not a failed computation (it was one).
        let w = Window {
            base: ModelParams::at(0.08, 0.14),
            n: 64,
            modes: 3,
            eta_t: (0.08, 0.1),
            kappa2: (0.14, 0.17),
            id_samples: 4,
        };
        let curves = mode_boundaries(&w).unwrap();
        let names: Vec<_> = curves.iter().map(|c| c.name).collect();
        assert!(!names.contains(&"MD saddle-node (x axis)"), "{names:?}");
        assert!(names.contains(&"ID onset of motion (axis ID)"), "{names:?}");
    }

    #[test]
    fn with_two_modes_they_are_the_two_mode_boundaries() {
        let (e, k) = ((0.07, 0.1), (0.1, 0.17));
        let base = ModelParams::at(0.07, 0.1);
        let n = 96;
        let mine = mode_boundaries(&Window {
            base,
            n,
            modes: 2,
            eta_t: e,
            kappa2: k,
            id_samples: 30,
        })
        .unwrap();
        let two = boundaries(&Window {
            base,
            n,
            modes: 2,
            eta_t: e,
            kappa2: k,
            id_samples: 30,
        })
        .unwrap();
        let scaled = |p: (f64, f64)| ((p.0 - e.0) / (e.1 - e.0), (p.1 - k.0) / (k.1 - k.0));
        assert_eq!(mine.len(), 7, "{mine:?}");
        for b in &mine {
            let other = two.iter().find(|c| c.name == b.name).expect(b.name);

            let line: Vec<(f64, f64)> = other.points.iter().map(|&p| scaled(p)).collect();
            let worst = b
                .points
                .iter()
                .map(|&p| distance_to_polyline(scaled(p), &line))
                .fold(0.0f64, f64::max);
            assert!(worst < 1e-4, "{}: {worst:e}", b.name);
        }
    }
}
