//! The full model's phase boundaries in a window of any two model parameters `(x, y)`, the
//! others fixed, each curve continued in that pair (in the paper's plane they are the curves
//! of [`crate::continuation::boundaries`], which the tests check):
//!
//! - **IC onsets of motion and of deformation** (axis, diagonal): where the resting disk's
//!   drift eigenvalue `eta_c - eta_t` or a shape eigenvalue `kappa_c - kappa2` vanishes. The
//!   thresholds `eta_c`, `kappa_c` depend on the geometry (`radius`, `sigma`, `box_len`) only
//!   ([`crate::roots::thresholds::ic_thresholds`]), so a window without a geometric axis
//!   computes them once.
//! - **ID onsets of motion** (on each mirror axis): where the top eigenvalue of the drift block
//!   of the resting deformed droplet's Jacobian vanishes, ID solved by Newton at each point
//!   (it depends on `kappa2` and the geometry only); the curve ends where ID does (it meets
//!   IC at the deformation onset).
//!
//!   Each of these is the zero set of one scalar function, traced by
//!   [`crate::continuation::level_set`]. An onset is drawn where its eigenvalue crosses zero,
//!   also where another eigenvalue is already positive.
//! - **MD saddle-node** ([`crate::continuation::fold_curve`]) and **MC onset** (the moving state
//!   with `a2 = -0.01`, continued in `(v, qx, qy)` while it is stable, the rotation mode aside,
//!   its ends located to ~1e-8 of the window),
//!   both started on MD branches followed in `x` at `y` = 1/2, 1, 1/4, 3/4, 0 of the window
//!   (until both are found).
//!
//! A window of two rate-only parameters (`eta2`, `mass`) has no boundary: they move no steady
//! state and no real eigenvalue through zero.
use crate::continuation::arclength::{last_where, start, ArclengthOptions, Stepper};
use crate::continuation::branch::Branch;
use crate::continuation::fold_curve::{fold_curve_from, fold_of, md_branch};
use crate::continuation::level_set::{zero_set, LevelSetOptions};
use crate::continuation::window::Window;
use crate::error::SolverError;
use crate::model::classify::CLASS_THRESHOLD;
use crate::model::mirror::MirrorLine;
use crate::model::params::ModelParams;
use crate::reduced::boundaries::Boundary;
use crate::roots::linearisation::Linearization;
use crate::roots::steady_solver::TwoModeSolver;
use crate::roots::thresholds::id_onset;

/// Moves `solver` to `(qx, qy)` of the window; false where the parameters are invalid there.
fn place(w: &Window, solver: &mut TwoModeSolver, qx: f64, qy: f64) -> bool {
    solver.set_param(w.x.param, w.x.value(qx)).is_ok()
        && solver.set_param(w.y.param, w.y.value(qy)).is_ok()
}

fn level_set_options(w: &Window) -> LevelSetOptions {
    LevelSetOptions {
        samples: w.samples.max(4),
        ..LevelSetOptions::default()
    }
}

/// The last few values of an expensive function of a few parameters (the finite differences
/// of the tracer revisit them, and most conditions ignore one axis).
struct Memo<T> {
    entries: Vec<([u64; 4], T)>,
}

impl<T: Clone> Memo<T> {
    const SIZE: usize = 32;

    fn new() -> Self {
        Self {
            entries: Vec::new(),
        }
    }

    fn get(&mut self, key: [f64; 4], f: impl FnOnce() -> T) -> T {
        let key = key.map(f64::to_bits);
        if let Some((_, v)) = self.entries.iter().find(|(k, _)| *k == key) {
            return v.clone();
        }
        let v = f();
        if self.entries.len() == Self::SIZE {
            self.entries.remove(0);
        }
        self.entries.push((key, v.clone()));
        v
    }
}

fn geometry(p: &ModelParams) -> [f64; 3] {
    [p.radius, p.sigma, p.box_len]
}

/// The resting disk's three onsets, each a zero set.
fn disk_onsets(w: &Window) -> Result<Vec<Boundary>, SolverError> {
    let mut solver = TwoModeSolver::new(w.base, w.n)?;
    let mut memo: Memo<[f64; 3]> = Memo::new();
    let names = [
        "IC onset of motion",
        "IC onset of deformation (b2, diagonal)",
        "IC onset of deformation (a2, axis)",
    ];
    let mut out = Vec::new();
    for (i, name) in names.into_iter().enumerate() {
        let mut g = |qx: f64, qy: f64| {
            if !place(w, &mut solver, qx, qy) {
                return f64::NAN;
            }
            let p = *solver.params();
            let [r, s, l] = geometry(&p);
            // eta_c, kappa_c (diagonal), kappa_c (axis).
            let th = memo.get([r, s, l, 0.0], || {
                let j0 = Linearization::of_two_modes(&mut solver, [0.0; 4]).jacobian0();
                [j0[0][0] + p.eta_t, j0[3][3] + p.kappa2, j0[2][2] + p.kappa2]
            });
            match i {
                0 => th[0] - p.eta_t,
                _ => th[i] - p.kappa2,
            }
        };
        for curve in zero_set(&mut g, &level_set_options(w)) {
            out.push(Boundary {
                name,
                points: curve.into_iter().map(|q| w.point(q)).collect(),
            });
        }
    }
    Ok(out)
}

/// The ID onset of motion on `mirror`: a zero set.
fn id_onsets(w: &Window, mirror: MirrorLine) -> Result<Vec<Boundary>, SolverError> {
    let mut solver = TwoModeSolver::new(w.base, w.n)?;
    let mut memo: Memo<Option<f64>> = Memo::new();
    let mut seed = 0.3;
    let mut g = |qx: f64, qy: f64| {
        if !place(w, &mut solver, qx, qy) {
            return f64::NAN;
        }
        let p = *solver.params();
        let [r, s, l] = geometry(&p);
        let top = memo.get([p.kappa2, r, s, l], || {
            let coef = crate::reduced::coefficients::Coefficients::new(
                p.radius,
                crate::contract::settings::H0_PAPER,
            );
            let fresh = crate::roots::named_state::id_seed(&coef, &p);
            let (k, c) = [seed, fresh]
                .into_iter()
                .find_map(|s0| id_onset(&mut solver, mirror, p.kappa2, s0))?;
            seed = c;
            Some(k)
        });
        top.map_or(f64::NAN, |k| k - p.eta_t)
    };
    let name = match mirror {
        MirrorLine::Diagonal => "ID onset of motion (diagonal ID)",
        MirrorLine::X => "ID onset of motion (axis ID)",
    };
    Ok(zero_set(&mut g, &level_set_options(w))
        .into_iter()
        .map(|curve| Boundary {
            name,
            points: curve.into_iter().map(|q| w.point(q)).collect(),
        })
        .collect())
}

/// Where the moving states of `branch` (followed in `x` at `y = at`) cross `a2 = -0.01`
/// between two stable states: `(v, x, y)`, interpolated.
fn mc_crossing(branch: &Branch, at: f64) -> Option<(f64, f64, f64)> {
    branch.points.windows(2).find_map(|p| {
        let (c0, c1) = (p[0].z[2] + CLASS_THRESHOLD, p[1].z[2] + CLASS_THRESHOLD);
        let stable = p[0].verdict.stable() && p[1].verdict.stable();
        (stable && c0 * c1 <= 0.0 && c0 != c1).then(|| {
            let t = c0 / (c0 - c1);
            (
                p[0].z[0] + t * (p[1].z[0] - p[0].z[0]),
                p[0].at + t * (p[1].at - p[0].at),
                at,
            )
        })
    })
}

/// The MC onset on the x axis through `(v, x, y)` (near it): the moving state with
/// `a2 = -0.01`, corrected at fixed `y`, then continued both ways in `(v, qx, qy)` while it is
/// stable (the rotation mode aside), inside the window and moving.
fn mc_curve(w: &Window, (v, x, y): (f64, f64, f64)) -> Result<Vec<(f64, f64)>, SolverError> {
    let mut solver = TwoModeSolver::new(w.base, w.n)?;
    let c = -CLASS_THRESHOLD;
    let mut f = |u: &[f64]| {
        if !place(w, &mut solver, u[1], u[2]) {
            return vec![f64::NAN; 2];
        }
        solver.residual_on(MirrorLine::X, u[0], c).to_vec()
    };
    let qy = w.y.q(y);
    let newton = crate::numerics::newton::NewtonOptions {
        tol: 1e-12,
        max_iter: 30,
        fd_step: 1e-7,
        max_step: vec![0.05, 0.05],
        one_sided: false,
        backtrack: false,
    };
    let Ok(sol) = crate::numerics::newton::solve(|u| f(&[u[0], u[1], qy]), &[v, w.x.q(x)], &newton)
    else {
        return Ok(Vec::new());
    };
    let y0 = [sol.x[0], sol.x[1], qy];
    let opts = ArclengthOptions {
        tol: 1e-10,
        ds: 0.01,
        ds_max: 0.04,
        max_iter: 10,
        ..ArclengthOptions::default()
    };
    let Some(t0) = start(&mut f, &y0, &[0.0, 0.0, 1.0], &opts)
        .or_else(|| start(&mut f, &y0, &[0.0, 1.0, 0.0], &opts))
    else {
        return Ok(Vec::new());
    };
    let mut check = TwoModeSolver::new(w.base, w.n)?;
    let mut stable = |u: &[f64]| {
        place(w, &mut check, u[1], u[2]) && {
            let z = [u[0], 0.0, c, 0.0];
            Linearization::of_two_modes(&mut check, z)
                .verdict()
                .stable()
        }
    };
    let inside =
        |u: &[f64]| u[0] > 0.0 && (0.0..=1.0).contains(&u[1]) && (0.0..=1.0).contains(&u[2]);
    let mut halves: Vec<Vec<(f64, f64)>> = Vec::new();
    for sign in [-1.0, 1.0] {
        let prev: Vec<f64> = t0.tangent.iter().map(|t| sign * t).collect();
        let Some(mut p) = start(&mut f, &y0, &prev, &opts) else {
            continue;
        };
        let mut stepper = Stepper::new(opts.clone());
        let mut pts = vec![(p.y[1], p.y[2])];
        for _ in 0..400 {
            let Some(step) = stepper.advance(&mut f, &p) else {
                break;
            };
            if !inside(&step.point.y) || !stable(&step.point.y) {
                let mut ok = |u: &[f64]| inside(u) && stable(u);
                let last = last_where(&mut f, &p, step.ds, &mut ok, &opts);
                pts.push((last.y[1], last.y[2]));
                break;
            }
            p = step.point;
            pts.push((p.y[1], p.y[2]));
        }
        halves.push(pts);
    }
    if !stable(&y0) {
        return Ok(Vec::new());
    }
    Ok(joined(w, &halves))
}

/// A curve from its two halves traced from one start (window coordinates): the first
/// reversed, then the second without the shared start, in the plane's coordinates.
fn joined(w: &Window, halves: &[Vec<(f64, f64)>]) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    if let Some(back) = halves.first() {
        out.extend(back.iter().rev().map(|&q| w.point(q)));
    }
    if let Some(fwd) = halves.get(1) {
        out.extend(fwd.iter().skip(1).map(|&q| w.point(q)));
    }
    out.dedup();
    out
}

/// The MD fold and the MC onset, both started on MD branches followed in `x`.
/// The 2-mode model of `base` (a plane's curves are the paper's model's).
fn two(base: &ModelParams) -> ModelParams {
    base.with_modes(2)
}

fn moving_curves(w: &Window) -> Result<Vec<Boundary>, SolverError> {
    let mut fold = None;
    let mut mc = None;
    // The middle first (the fold), then the top (where the MC onset is stable in the paper's
    // window), then the rest.
    for f in [0.5, 1.0, 0.25, 0.75, 0.0] {
        let at = w.y.value(f);
        let Ok(branch) = md_branch(&two(&w.base), w.n, MirrorLine::X, w.x, w.y, at) else {
            continue;
        };
        fold = fold.or_else(|| fold_of(&branch, MirrorLine::X, at));
        mc = mc.or_else(|| mc_crossing(&branch, at));
        if fold.is_some() && mc.is_some() {
            break;
        }
    }
    let mut out = Vec::new();
    if let Some(first) = fold {
        out.push(Boundary {
            name: "MD saddle-node (x axis)",
            points: fold_curve_from(&two(&w.base), w.n, MirrorLine::X, (w.x, w.y), first)?,
        });
    }
    if let Some(seed) = mc {
        out.push(Boundary {
            name: "MC onset, s = 0.01 (x axis)",
            points: mc_curve(w, seed)?,
        });
    }
    out.retain(|b| b.points.len() > 1);
    Ok(out)
}

/// Every boundary in the window (see the module doc), named like the paper plane's; a
/// condition whose zero set has several pieces gives one curve per piece, under one name.
/// Called by [`crate::continuation::boundaries::boundaries`] for a window off the paper's
/// plane, after its checks.
pub(crate) fn traced(w: &Window) -> Result<Vec<Boundary>, SolverError> {
    if !w.x.moves_states() && !w.y.moves_states() {
        return Ok(Vec::new());
    }
    type Curves = Result<Vec<Boundary>, SolverError>;
    // Independent: one thread each, as in the paper's plane.
    let (disk, diag, axis, moving): (Curves, Curves, Curves, Curves) =
        std::thread::scope(|scope| {
            let disk = scope.spawn(|| disk_onsets(w));
            let diag = scope.spawn(|| id_onsets(w, MirrorLine::Diagonal));
            let axis = scope.spawn(|| id_onsets(w, MirrorLine::X));
            let moving = moving_curves(w);
            let join = |h: std::thread::ScopedJoinHandle<'_, Curves>| {
                h.join().expect("a boundary curve's thread panicked")
            };
            (join(disk), join(diag), join(axis), moving)
        });
    let mut out = disk?;
    out.extend(diag?);
    out.extend(axis?);
    out.extend(moving?);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::continuation::boundaries::boundaries;
    use crate::continuation::polyline::distance_to_polyline;

    /// In the paper's plane every curve traced lies on the paper plane's
    /// curve of the same name, computed there by other means (the thresholds as numbers, the
    /// ID lines sampled in `kappa2` up to the linear threshold, the MC line by Newton per
    /// sample), and covers it.
    #[test]
    fn in_the_paper_plane_the_curves_are_the_paper_planes() {
        let (e, k) = ((0.07, 0.10), (0.10, 0.17));
        let base = ModelParams::at(e.0, k.0);
        // N = 96: the two computations of one curve agree at any grid (at N = 192 too, 3x slower).
        let n = 96;
        let paper = boundaries(&Window::paper(base, n, e, k, 60)).unwrap();
        // The same window traced, as any other plane is.
        let plane = traced(&Window::paper(base, n, e, k, 16)).unwrap();
        let th = crate::roots::thresholds::ic_thresholds(&base, n, 2).unwrap();
        let names: Vec<&str> = plane.iter().map(|b| b.name).collect();
        assert_eq!(names.len(), 7, "{names:?}");
        for c in &paper {
            assert!(names.contains(&c.name), "{} missing: {names:?}", c.name);
        }
        let scaled = |p: (f64, f64)| ((p.0 - e.0) / (e.1 - e.0), (p.1 - k.0) / (k.1 - k.0));
        for b in &plane {
            let span_y = |pts: &[(f64, f64)]| {
                pts.iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                        (l.min(p.1), h.max(p.1))
                    })
            };
            // The IC onsets: straight across the whole window, at the thresholds.
            let level = match b.name {
                "IC onset of motion" => Some((0, th.eta_t)),
                "IC onset of deformation (b2, diagonal)" => Some((1, th.kappa2_b2)),
                "IC onset of deformation (a2, axis)" => Some((1, th.kappa2_a2)),
                _ => None,
            };
            if let Some((axis, at)) = level {
                let off = b.points.iter().map(|p| ([p.0, p.1][axis] - at).abs());
                assert!(off.fold(0.0, f64::max) < 1e-9, "{}: {:?}", b.name, b.points);
                let ends = [b.points[0], *b.points.last().unwrap()].map(scaled);
                let other = 1 - axis;
                let mut ends = ends.map(|q| [q.0, q.1][other]);
                ends.sort_by(f64::total_cmp);
                assert!(
                    ends[0] < 1e-12 && ends[1] > 1.0 - 1e-12,
                    "{}: {ends:?}",
                    b.name
                );
                continue;
            }
            let reference = paper.iter().find(|c| c.name == b.name).unwrap();
            let line: Vec<(f64, f64)> = reference.points.iter().map(|&p| scaled(p)).collect();
            let mine: Vec<(f64, f64)> = b.points.iter().map(|&p| scaled(p)).collect();
            // Apart by the chords only (the polylines' points differ; ~5e-5 measured).
            let (lo, hi) = span_y(&reference.points);
            let worst = b
                .points
                .iter()
                .filter(|p| p.1 >= lo && p.1 <= hi)
                .map(|&p| distance_to_polyline(scaled(p), &line))
                .fold(0.0f64, f64::max);
            assert!(worst < 2e-4, "{}: {worst:e}", b.name);
            // ... and covers it, but for the last 2e-6 in kappa2 of an ID line: there ID's
            // amplitude (below 2e-3) is fixed by Newton only to ~1e-3 relative, too noisy
            // for the tracer's differences, where the paper plane's samples go on.
            let reach = span_y(&b.points).1;
            assert!(reach > hi - 1e-6, "{}: ends at {reach}, not {hi}", b.name);
            let uncovered = reference
                .points
                .iter()
                .filter(|p| p.1 <= reach - 1e-6)
                .map(|&p| distance_to_polyline(scaled(p), &mine))
                .fold(0.0f64, f64::max);
            // (The tracer's chords, up to 0.04 of the window long, sag up to ~3e-4 from
            // its curve where that bends.)
            assert!(uncovered < 5e-4, "{}: {uncovered:e}", b.name);
        }
    }
}
