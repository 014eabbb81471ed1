//! The full model's phase boundaries in the `(eta_t, kappa2)` plane, each point a solution of
//! an equation (no grid between two samples):
//!
//! - **IC onset of motion / of deformation** (pitchforks of the resting disk): at the disk the
//!   linearisation decouples and neither threshold depends on the other parameter, so each is
//!   one number ([`crate::roots::named_state::ic_thresholds`]): a vertical and a horizontal line.
//! - **ID onset of motion** (pitchfork of the resting deformed droplet into MD): the ID state
//!   does not depend on `eta_t` (it does not move), and at a mirror-symmetric ID the drift
//!   block of the `lambda = 0` Jacobian is `-eta_t I + K(kappa2)` (decoupled from the shape
//!   by the two mirror symmetries), so the threshold is the largest eigenvalue of `K`: one
//!   Newton solve and one linearisation per `kappa2`, exact at the grid.
//! - **MD saddle-node** (the fold that bounds the bistable bands): pseudo-arclength
//!   continuation in `(v, c, eta_t, kappa2)` of the extended system
//!   `R(v, c; eta_t, kappa2) = 0, det dR/d(v, c) = 0`, started from a fold located on a
//!   one-parameter branch. It ends where it leaves the window or where `v -> 0` (the fold
//!   reaches the onset of motion: there the pitchfork changes from sub- to supercritical).
//! - **MC onset** (where the moving branch's deformation crosses the class threshold, so its
//!   states change from MD to MC): on the x axis the moving state with `a2 = -0.01` (a moving
//!   droplet is elongated across its motion) solves the two steady equations for `(v,
//!   eta_t)` at each `kappa2`: one Newton solve per sample, continued from the last. Whether
//!   MC is also stable there is the verdict's business; this line only says where a label
//!   must change between MD and MC.
use crate::continuation::arclength::{start, ArclengthOptions, CurvePoint, Stepper};
use crate::continuation::branch::{follow, Line};
use crate::continuation::problem::Family;
use crate::error::SolverError;
use crate::model::param::ModelParam;
use crate::model::params::ModelParams;
use crate::numerics::newton::fd_jacobian;
use crate::reduced::boundaries::Boundary;
use crate::roots::linearisation::Linearization;
use crate::roots::named_state::ic_thresholds;
use crate::roots::steady_solver::{MirrorAxis, SteadySolver};

/// The window and resolution of [`boundaries`].
#[derive(Debug, Clone)]
pub struct Window {
    /// Model parameters (`eta_t` and `kappa2` are varied).
    pub base: ModelParams,
    pub n: usize,
    pub eta_t: (f64, f64),
    pub kappa2: (f64, f64),
    /// Samples of the ID onset line in `kappa2`.
    pub id_samples: usize,
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

/// The ID onset line on `mirror` for `kappa2` from `lo` up to (not including) `hi`, where ID
/// meets IC.
fn id_line(w: &Window, mirror: MirrorAxis, hi: f64) -> Result<Vec<(f64, f64)>, SolverError> {
    let mut solver = SteadySolver::new(w.base, w.n)?;
    let lo = w.kappa2.0;
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
    let mut solver = SteadySolver::new(w.base, w.n)?;
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
        if !crate::roots::verdict::assess(&Linearization::at(&mut solver, z), z).stable() {
            break;
        }
        pts.push((eta, k));
    }
    Ok(pts)
}

/// The extended system of the MD fold: `y = (v, c, qe, qk)` with the parameters scaled to the
/// window.
struct FoldSystem {
    solver: SteadySolver,
    mirror: MirrorAxis,
    eta: (f64, f64),
    kappa: (f64, f64),
    /// Scale of `det` (the Jacobian's size squared at the start).
    det_scale: f64,
}

impl FoldSystem {
    fn control(&self, y: &[f64]) -> (f64, f64) {
        (
            self.eta.0 + y[2] * (self.eta.1 - self.eta.0),
            self.kappa.0 + y[3] * (self.kappa.1 - self.kappa.0),
        )
    }

    /// `dR/d(v, c)` at `y`.
    fn jac(&mut self, y: &[f64]) -> Vec<Vec<f64>> {
        let (e, k) = self.control(y);
        self.solver.set_control(e, k);
        let mirror = self.mirror;
        let solver = &mut self.solver;
        fd_jacobian(
            &mut |x: &[f64]| solver.residual_on(mirror, x[0], x[1]).to_vec(),
            &y[..2],
            1e-6,
        )
    }

    fn residual(&mut self, y: &[f64]) -> Vec<f64> {
        let (e, k) = self.control(y);
        self.solver.set_control(e, k);
        let r = self.solver.residual_on(self.mirror, y[0], y[1]);
        let j = self.jac(y);
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        vec![r[0], r[1], det / self.det_scale]
    }
}

/// The MD fold on the first of the lines `kappa2 = starts[i]` (eta_t across the window) that
/// has one: `(v, shape amplitude, eta_t, kappa2)` there.
fn first_fold(w: &Window, mirror: MirrorAxis, starts: &[f64]) -> Option<(f64, f64, f64, f64)> {
    for &k in starts {
        let line = Line {
            base: ModelParams {
                kappa2: k,
                ..w.base
            },
            n: w.n,
            parameter: ModelParam::EtaT,
            from: w.eta_t.0,
            to: w.eta_t.1,
            max_points: 400,
            opts: ArclengthOptions::default(),
        };
        let Ok(branch) = follow(&line, Family::MdMinor, mirror) else {
            continue;
        };
        if let Some(e) = branch.events.iter().find(|e| e.kind == "SN") {
            let (v, c) = match mirror {
                MirrorAxis::X => (e.point.z[0], e.point.z[2]),
                MirrorAxis::Diagonal => (e.point.v, e.point.z[3]),
            };
            return Some((v, c, e.point.eta_t, k));
        }
    }
    None
}

/// The MD saddle-node curve on `mirror`: located on the one-parameter MD branch at the first
/// `kappa2` of `starts` that has a fold, then continued both ways in `(eta_t, kappa2)`.
pub fn md_fold_curve(
    w: &Window,
    mirror: MirrorAxis,
    starts: &[f64],
) -> Result<Vec<(f64, f64)>, SolverError> {
    let first = first_fold(w, mirror, starts);
    let Some((v, c, eta, kappa)) = first else {
        return Ok(Vec::new());
    };
    let mut sys = FoldSystem {
        solver: SteadySolver::new(w.base, w.n)?,
        mirror,
        eta: w.eta_t,
        kappa: w.kappa2,
        det_scale: 1.0,
    };
    let scale = |lo: f64, hi: f64, x: f64| (x - lo) / (hi - lo);
    let y0 = vec![
        v,
        c,
        scale(w.eta_t.0, w.eta_t.1, eta),
        scale(w.kappa2.0, w.kappa2.1, kappa),
    ];
    let j = sys.jac(&y0);
    let size = j.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    sys.det_scale = size * size;
    let opts = ArclengthOptions {
        // det dR/d(v, c) comes from central differences (relative noise ~1e-10), so the
        // corrector stops at 1e-9; the folds it finds agree with the one-parameter
        // location by tangent to 1e-15 (measured).
        tol: 1e-9,
        fd_step: 1e-5,
        ds: 0.01,
        ds_max: 0.04,
        max_iter: 10,
        ..ArclengthOptions::default()
    };
    // The located fold satisfies the extended system to the accuracy of its location; one
    // correction at fixed kappa2 puts it exactly on it.
    let mut halves = Vec::new();
    for sign in [-1.0, 1.0] {
        let prev = [0.0, 0.0, 0.0, sign];
        let Some(mut p) = start(&mut |y: &[f64]| sys.residual(y), &y0, &prev, &opts) else {
            continue;
        };
        let mut stepper = Stepper::new(opts.clone());
        let mut pts = vec![p.clone()];
        for _ in 0..400 {
            let Some(step) = stepper.advance(&mut |y: &[f64]| sys.residual(y), &p) else {
                break;
            };
            let y = &step.point.y;
            let inside = (0.0..=1.0).contains(&y[2]) && (0.0..=1.0).contains(&y[3]);
            if !inside || y[0] < 1e-3 {
                pts.push(step.point);
                break;
            }
            p = step.point;
            pts.push(p.clone());
        }
        halves.push(pts);
    }
    let to_plane = |p: &CurvePoint| sys.control(&p.y);
    let mut out: Vec<(f64, f64)> = Vec::new();
    if let Some(back) = halves.first() {
        out.extend(back.iter().rev().map(to_plane));
    }
    if let Some(fwd) = halves.get(1) {
        out.extend(fwd.iter().skip(1).map(to_plane));
    }
    Ok(out)
}

/// Every boundary in the window (see the module doc), named like the reduced model's.
pub fn boundaries(w: &Window) -> Result<Vec<Boundary>, SolverError> {
    let th = ic_thresholds(&w.base, w.n)?;
    let (e0, e1) = w.eta_t;
    let (k0, k1) = w.kappa2;
    let k_shape = th.kappa2_a2.max(th.kappa2_b2);
    let mut out = vec![
        Boundary {
            name: "IC onset of motion",
            points: vec![(th.eta_t, k_shape.max(k0)), (th.eta_t, k1)],
        },
        Boundary {
            name: "IC onset of deformation (b2, diagonal)",
            points: vec![(th.eta_t.max(e0), th.kappa2_b2), (e1, th.kappa2_b2)],
        },
        Boundary {
            name: "IC onset of deformation (a2, axis)",
            points: vec![(th.eta_t.max(e0), th.kappa2_a2), (e1, th.kappa2_a2)],
        },
    ];
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
        let fold = scope.spawn(|| md_fold_curve(w, MirrorAxis::X, &starts));
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
