//! The full model's phase boundaries in the `(eta_t, kappa2)` plane, each point a solution of
//! an equation (no grid between two samples):
//!
//! - **IC onset of motion / of deformation** (pitchforks of the resting disk): at the disk the
//!   linearisation decouples and neither threshold depends on the other parameter, so each is
//!   one number ([`crate::roots::thresholds::ic_thresholds`]): a vertical and a horizontal line.
//! - **ID onset of motion** (pitchfork of the resting deformed droplet into MD): the ID state
//!   does not depend on `eta_t` (it does not move), and at a mirror-symmetric ID the drift
//!   block of the `lambda = 0` Jacobian is `-eta_t I + K(kappa2)` (decoupled from the shape
//!   by the two mirror symmetries), so the threshold is the largest eigenvalue of `K`: one
//!   Newton solve and one linearisation per `kappa2`, exact at the grid.
//! - **MD saddle-node** (the fold that bounds the bistable bands): continued in
//!   `(eta_t, kappa2)` from a fold located on a one-parameter branch
//!   ([`crate::continuation::fold_curve`]).
//! - **MC onset** (where the moving branch's deformation crosses the class threshold, so its
//!   states change from MD to MC): on the x axis the moving state with `a2 = -0.01` (a moving
//!   droplet is elongated across its motion) solves the two steady equations for `(v,
//!   eta_t)` at each `kappa2`: one Newton solve per sample, continued from the last. Whether
//!   MC is also stable there is the verdict's business; this line only says where a label
//!   must change between MD and MC.
use crate::continuation::fold_curve::{md_fold_curve, FoldModel};
use crate::continuation::window::PlaneAxis;
use crate::continuation::window::Window;
use crate::error::SolverError;
use crate::model::param::ModelParam;
use crate::reduced::boundaries::Boundary;
use crate::roots::linearisation::TwoModeLinearization;
use crate::roots::steady_solver::{MirrorAxis, TwoModeSolver};
use crate::roots::thresholds::{ic_thresholds, id_onset};

/// The ID onset line on `mirror` for `kappa2` from `lo` up to (not including) `hi`, where ID
/// meets IC; none when the window lies above `hi`.
fn id_line(w: &Window, mirror: MirrorAxis, hi: f64) -> Result<Vec<(f64, f64)>, SolverError> {
    let mut solver = TwoModeSolver::new(w.base, w.n)?;
    let lo = w.kappa2.0;
    if hi <= lo {
        return Ok(Vec::new());
    }
    let mut seed = 0.3;
    let mut pts = Vec::new();
    let m = w.id_samples.max(2);
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

/// The MC onset line on the x axis: `(eta_t, kappa2)` where the moving branch has
/// `a2 = -CLASS_THRESHOLD`, from the top of the window down while Newton on `(v, eta_t)`
/// converges inside it and the moving state there is stable (the rotation mode aside): below
/// the point where the onset of motion turns subcritical the `s = 0.01` state lies on the
/// unstable part of the branch, and no label can change there.
pub fn mc_line(w: &Window, onset_eta_t: f64) -> Result<Vec<(f64, f64)>, SolverError> {
    let mut solver = TwoModeSolver::new(w.base, w.n)?;
    let c = -crate::model::classify::CLASS_THRESHOLD;
    let opts = crate::numerics::newton::NewtonOptions {
        tol: 1e-12,
        max_iter: 30,
        fd_step: 1e-7,
        max_step: vec![0.05, 0.002],
    };
    // a2 ~ -0.18 v^2 on the moving branch near the onset of motion (docs/model.md, "Where a slow run lands").
    let mut guess = [(-c / 0.18f64).sqrt(), onset_eta_t];
    let (k0, k1) = w.kappa2;
    let m = w.id_samples.max(2);
    let mut pts = Vec::new();
    for i in 0..m {
        let k = k1 - (k1 - k0) * i as f64 / (m - 1) as f64;
        let Ok(sol) = crate::numerics::newton::solve(
            |x| {
                solver.set_control(x[1], k);
                solver.residual_on(MirrorAxis::X, x[0], c).to_vec()
            },
            &guess,
            &opts,
        ) else {
            break;
        };
        let (v, eta) = (sol.x[0], sol.x[1]);
        if v <= 0.0 || !(w.eta_t.0..=w.eta_t.1).contains(&eta) {
            break;
        }
        guess = [v, eta];
        solver.set_control(eta, k);
        let z = [v, 0.0, c, 0.0];
        if !crate::roots::verdict::assess(&TwoModeLinearization::at(&mut solver, z), &z).stable() {
            break;
        }
        pts.push((eta, k));
    }
    Ok(pts)
}

/// Every boundary in the window (see the module doc), named like the reduced model's.
pub fn boundaries(w: &Window) -> Result<Vec<Boundary>, SolverError> {
    if w.modes != 2 {
        return crate::continuation::mode_boundaries::mode_boundaries(w);
    }
    let th = ic_thresholds(&w.base, w.n, 2)?;
    let (e0, e1) = w.eta_t;
    let (k0, k1) = w.kappa2;
    let k_shape = th.kappa2_a2.max(th.kappa2_b2);
    // The resting disk's onsets are straight lines, drawn where they cross the window: the
    // onset of motion above the disk's deformation onsets (below them the disk deforms).
    let inside = |x: f64, (lo, hi): (f64, f64)| (lo..=hi).contains(&x);
    let mut out = Vec::new();
    if inside(th.eta_t, w.eta_t) && k_shape.max(k0) < k1 {
        out.push(Boundary {
            name: "IC onset of motion",
            points: vec![(th.eta_t, k_shape.max(k0)), (th.eta_t, k1)],
        });
    }
    for (name, k) in [
        ("IC onset of deformation (b2, diagonal)", th.kappa2_b2),
        ("IC onset of deformation (a2, axis)", th.kappa2_a2),
    ] {
        if inside(k, w.kappa2) && th.eta_t.max(e0) < e1 {
            out.push(Boundary {
                name,
                points: vec![(th.eta_t.max(e0), k), (e1, k)],
            });
        }
    }
    let mid = 0.5 * (k0 + k1);
    let starts = [
        0.13f64.clamp(k0, k1),
        mid,
        k0 + 0.25 * (k1 - k0),
        k0 + 0.75 * (k1 - k0),
    ];
    // The four continued curves are independent: one thread each (a window at N = 384 takes
    // the time of its slowest curve, not of all four).
    type Curve = Result<Vec<(f64, f64)>, SolverError>;
    let (diag, axis, fold, mc): (Curve, Curve, Curve, Curve) = std::thread::scope(|scope| {
        let diag = scope.spawn(|| id_line(w, MirrorAxis::Diagonal, th.kappa2_b2));
        let axis = scope.spawn(|| id_line(w, MirrorAxis::X, th.kappa2_a2));
        let fold = scope.spawn(|| {
            let x = PlaneAxis::new(ModelParam::EtaT, w.eta_t);
            let y = PlaneAxis::new(ModelParam::Kappa2, w.kappa2);
            md_fold_curve(
                &w.base,
                FoldModel { n: w.n, modes: 2 },
                MirrorAxis::X,
                (x, y),
                &starts,
            )
        });
        let mc = mc_line(w, th.eta_t);
        let join = |h: std::thread::ScopedJoinHandle<'_, Curve>| {
            h.join().expect("a boundary curve's thread panicked")
        };
        (join(diag), join(axis), join(fold), mc)
    });
    out.push(Boundary {
        name: "ID onset of motion (diagonal ID)",
        points: diag?,
    });
    out.push(Boundary {
        name: "ID onset of motion (axis ID)",
        points: axis?,
    });
    out.push(Boundary {
        name: "MD saddle-node (x axis)",
        points: fold?,
    });
    out.push(Boundary {
        name: "MC onset, s = 0.01 (x axis)",
        points: mc?,
    });
    out.retain(|b| !b.points.is_empty());
    Ok(out)
}
