//! The full model's phase boundaries in the `(eta_t, kappa2)` plane, for the model with shape
//! modes `2..K`, each point a solution of an equation (no grid between two samples):
//!
//! - **IC onset of motion / of deformation** (pitchforks of the resting disk): at the disk the
//!   linearisation decouples and neither threshold depends on the other parameter, so each is
//!   one number ([`crate::roots::thresholds::ic_thresholds`]): a vertical and a horizontal line
//!   (with `K > 2` the box couples the drift to the odd modes, and the onset of motion, taken
//!   at the window's bottom and top, may lean by < 1e-6). Each is drawn where it crosses the
//!   window, the onset of motion above the deformation onsets (below them the disk deforms).
//! - **ID onset of motion** (axis ID and diagonal ID) and **MC onset**: sampled in `kappa2`
//!   ([`crate::continuation::onset_lines`]).
//! - **MD saddle-node** (the fold that bounds the bistable bands): continued in
//!   `(eta_t, kappa2)` from a fold located on a one-parameter branch
//!   ([`crate::continuation::fold_curve`]).
//!
//! Every curve takes its [`Balances`] from one place: for `K = 2` the 2-mode fast path. The
//! general solver gives the 2-mode curves at `K = 2` (tested).
use crate::continuation::fold_curve::md_fold_curve;
use crate::continuation::onset_lines::{id_line, mc_line};
use crate::continuation::window::Window;
use crate::error::SolverError;
use crate::model::mirror::MirrorLine;
use crate::reduced::boundaries::Boundary;
use crate::roots::balances::Balances;
use crate::roots::steady_solver::SteadySolver;
use crate::roots::thresholds::{disk_thresholds, two_mode_thresholds, IcThresholds};

/// Makes the balances of the window's model, once per curve (each curve on its own thread).
type Make<'a> = &'a (dyn Fn() -> Result<Balances, SolverError> + Sync);

/// The disk's thresholds at the window's bottom and top `kappa2` (with two modes one
/// computation: then they do not depend on `kappa2` at all).
fn disk_at_ends(make: Make, w: &Window) -> Result<(IcThresholds, IcThresholds), SolverError> {
    match make()? {
        Balances::Two(mut solver) => {
            let th = two_mode_thresholds(&mut solver);
            Ok((th.clone(), th))
        }
        Balances::General(mut solver) => {
            let modes = solver.params().modes;
            solver.set_control(w.base.eta_t, w.y.range.0);
            let low = disk_thresholds(&mut solver, modes);
            solver.set_control(w.base.eta_t, w.y.range.1);
            Ok((low, disk_thresholds(&mut solver, modes)))
        }
    }
}

/// The resting disk's lines where they cross the window (see the module).
fn disk_lines(w: &Window, low: &IcThresholds, high: &IcThresholds) -> Vec<Boundary> {
    let (e0, e1) = w.x.range;
    let (k0, k1) = w.y.range;
    let inside = |x: f64, (lo, hi): (f64, f64)| (lo..=hi).contains(&x);
    let bottom = low.kappa2_a2.max(low.kappa2_b2).max(k0);
    let mut out = Vec::new();
    if (inside(low.eta_t, w.x.range) || inside(high.eta_t, w.x.range)) && bottom < k1 {
        out.push(Boundary {
            name: "IC onset of motion",
            points: vec![(low.eta_t, bottom), (high.eta_t, k1)],
        });
    }
    for (name, k) in [
        ("IC onset of deformation (b2, diagonal)", low.kappa2_b2),
        ("IC onset of deformation (a2, axis)", low.kappa2_a2),
    ] {
        if inside(k, w.y.range) && low.eta_t.max(e0) < e1 {
            out.push(Boundary {
                name,
                points: vec![(low.eta_t.max(e0), k), (e1, k)],
            });
        }
    }
    out
}

/// Every boundary in the window, named like the reduced model's: in the paper's plane as the
/// module says, for every `K`; in any other plane each curve traced in that plane
/// ([`crate::continuation::plane`], two shape modes). A window [`Window::check`] refuses is
/// refused here.
pub fn boundaries(w: &Window) -> Result<Vec<Boundary>, SolverError> {
    w.check()?;
    if !w.in_paper_plane() {
        return crate::continuation::plane::traced(w);
    }
    boundaries_with(w, &|| Balances::new(w.base, w.n))
}

/// [`boundaries`] from the general solver at every `K`, 2 included: one computation for
/// every `K` (the truncation study compares them), and at `K = 2` an independent check of the
/// fast path (tested). The fold curve is the one computation of every `K` either way.
/// In the paper's plane only (another window is refused).
pub fn general_boundaries(w: &Window) -> Result<Vec<Boundary>, SolverError> {
    w.check()?;
    if !w.in_paper_plane() {
        return Err(SolverError::InvalidChoice {
            name: "window",
            value: format!("{} x {}", w.x.param.name(), w.y.param.name()),
            allowed: "the paper's plane, eta_t x kappa2".into(),
        });
    }
    boundaries_with(w, &|| {
        Ok(Balances::General(SteadySolver::new(w.base, w.n)?))
    })
}

/// [`boundaries`] with the balances `make` gives.
fn boundaries_with(w: &Window, make: Make) -> Result<Vec<Boundary>, SolverError> {
    let (low, high) = disk_at_ends(make, w)?;
    let mut out = disk_lines(w, &low, &high);
    let (k0, k1) = w.y.range;
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
        let diag = scope.spawn(|| id_line(make()?, w, MirrorLine::Diagonal, low.kappa2_b2));
        let axis = scope.spawn(|| id_line(make()?, w, MirrorLine::X, low.kappa2_a2));
        let fold = scope.spawn(|| md_fold_curve(&w.base, w.n, MirrorLine::X, (w.x, w.y), &starts));
        let mc = mc_line(make()?, w, high.eta_t);
        let join = |h: std::thread::ScopedJoinHandle<'_, Curve>| {
            h.join().expect("a boundary curve's thread panicked")
        };
        Ok::<_, SolverError>((join(diag), join(axis), join(fold), mc))
    })?;
    for (name, points) in [
        ("ID onset of motion (diagonal ID)", diag?),
        ("ID onset of motion (axis ID)", axis?),
        ("MD saddle-node (x axis)", fold?),
        ("MC onset, s = 0.01 (x axis)", mc?),
    ] {
        out.push(Boundary { name, points });
    }
    out.retain(|b| !b.points.is_empty());
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::continuation::onset_lines::id_line;
    use crate::continuation::polyline::distance_to_polyline;
    use crate::model::params::ModelParams;
    use crate::numerics::newton::NewtonOptions;
    use crate::roots::linearisation::Linearization;
    use crate::roots::named_state::id_state;

    #[test]
    fn the_diagonal_ids_onset_is_where_its_full_eigenproblem_gains_a_growing_mode() {
        // Modes 2..4 at N = 96, kappa2 = 0.105: the diagonal ID's onset of motion from the
        // lambda = 0 Schur complement, against the 2K x 2K eigenproblem with the field of the
        // diagonal ID (Newton on all 2K balances from the turned axis ID, so the frame turned
        // back is not used) either side of it: one more growing mode below it.
        let k = 0.105;
        let w = Window::paper(
            ModelParams::at(0.08, k).with_modes(4),
            96,
            (0.06, 0.1),
            (k, k + 1e-3),
            2,
        );
        let diagonal = std::f64::consts::FRAC_PI_4;
        let general = || Balances::new(w.base, w.n).unwrap();
        let line = id_line(general(), &w, MirrorLine::Diagonal, 0.118).unwrap();
        let axis = id_line(general(), &w, MirrorLine::X, 0.118).unwrap();
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
                one_sided: false,
                backtrack: false,
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
        let w = Window::paper(
            ModelParams::at(0.075, 0.125),
            96,
            (0.075, 0.085),
            (0.125, 0.135),
            4,
        );
        let names = |b: Vec<Boundary>| -> Vec<&'static str> {
            let mut v: Vec<_> = b.iter().map(|c| c.name).collect();
            v.sort_unstable();
            v
        };
        let mine = names(general_boundaries(&w).unwrap());
        let disk: Vec<_> = mine.iter().filter(|n| n.starts_with("IC onset")).collect();
        assert_eq!(disk, [&"IC onset of motion"], "{mine:?}");
        assert_eq!(mine, names(boundaries(&w).unwrap()));
    }

    #[test]
    fn a_window_at_rest_on_its_middle_line_has_no_fold_curve() {
        // Modes 2..3 at N = 64, right of the onset of motion and above kappa2 = 0.14: no
        // moving state at the middle line's start (Newton from the 2-mode state fails there).
        // That is a window without a fold curve, not a failed computation (it was one).
        let w = Window::paper(
            ModelParams::at(0.08, 0.14).with_modes(3),
            64,
            (0.08, 0.1),
            (0.14, 0.17),
            4,
        );
        let curves = boundaries(&w).unwrap();
        let names: Vec<_> = curves.iter().map(|c| c.name).collect();
        assert!(!names.contains(&"MD saddle-node (x axis)"), "{names:?}");
        assert!(names.contains(&"ID onset of motion (axis ID)"), "{names:?}");
    }

    #[test]
    fn with_two_modes_they_are_the_two_mode_boundaries() {
        let (e, k) = ((0.07, 0.1), (0.1, 0.17));
        let base = ModelParams::at(0.07, 0.1);
        let n = 96;
        let w = Window::paper(base, n, e, k, 30);
        let mine = general_boundaries(&w).unwrap();
        let two = boundaries(&Window::paper(base, n, e, k, 30)).unwrap();
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
