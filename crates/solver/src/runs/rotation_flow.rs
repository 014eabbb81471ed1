//! The slow flow of a droplet's orientation (setting `orientation_flow`): where a run leaning
//! from a mirror line's root turns.
//!
//! A moving or deformed droplet on a mirror line of the periodic box has a near-neutral
//! rotation mode (the box's anisotropy is weak), so once its speed and shape have settled its
//! orientation is the last slow coordinate. Fix the orientation at an angle `theta` from the
//! line's root, solve the fast balances at that orientation (paper eqs. 36-38 at steady field):
//! for a moving droplet the speed along `theta` and both shape amplitudes in the frame turned
//! by `theta` (the balance along the motion and of the shape), for a resting one the
//! deformation along its long axis at `theta`; what is left, the force across the motion
//! (the torque on the long axis at rest), is the flow of the orientation:
//! `m v dtheta/dt = F_perp` (`2 eta2 c dtheta/dt = G_perp` at rest). Its sign between the
//! line and the run says whether the run turns back to the line ([`FlowScan`]), and its
//! first zero the way it points is where a run leaning from a root unstable in rotation turns
//! to ([`flow_zero`]; numerics 8).
//!
//! The flow is bumpy: the box's anisotropy at N = 192 puts unstable roots 0.6 to 5 degrees
//! off lines whose own root is stable in rotation (at (0.096, 0.1) the resting deformed
//! droplet on the x axis, rotation eigenvalue -1.1e-3, has an unstable root 0.57 degrees off
//! it; a run leaning 12 degrees turns on to the diagonal, as long time stepping shows).
use crate::model::state::turned;
use crate::numerics::newton::{self, NewtonOptions};
use crate::roots::balances::Balances;
use crate::runs::orientation::orientation;

/// Largest spacing (radians) of the orientations at which [`FlowScan::extend`] samples the flow:
/// a bump of the flow narrower than this between two samples is not seen.
pub const SAMPLE_SPACING: f64 = 0.5 * std::f64::consts::PI / 180.0;

/// Most samples of one [`FlowScan::extend`].
const MAX_SAMPLES: usize = 48;

/// The largest lean a scan of a model with more than two shape modes samples (numerics
/// `modes-13`; 5 degrees), its samples at most [`LINEAR_LEAN`] apart (on its grids the
/// lattice holds roots 0.2 to 0.5 degrees off the mirror lines, between two samples of
/// [`SAMPLE_SPACING`]); a lean beyond the reach its caller asks for is not sampled, and
/// licenses nothing ([`FlowScan::extend`]).
pub const FINE_REACH: f64 = 101.0 * LINEAR_LEAN;

/// The reach of such a scan for a run leaving the resting disk (numerics `modes-14`; 8
/// degrees): the disk has no orientation for the lattice to hold, so the run leaves in the
/// direction its initial condition gave it, `atan(0.1)` = 5.71 degrees off the box's axes
/// for the paper's four; at FINE_REACH such runs waited to turn within 5 degrees first, for
/// up to 2000 time units.
pub const DEPARTURE_REACH: f64 = 161.0 * LINEAR_LEAN;

/// Leans (radians, 0.05 degrees) within which the root's own rotation eigenvalue decides: the
/// flow there is its linearisation (the nearest bump measured is 0.57 degrees off its root),
/// and at smaller angles the flow, `O(lambda lean)`, approaches the accuracy of the solve.
pub const LINEAR_LEAN: f64 = 0.05 * std::f64::consts::PI / 180.0;

/// The orientation's flow at the absolute orientation `phi` (direction of motion, or long
/// axis at rest) of states with `k_max` shape modes: the fast balances solved from `guess`
/// (speed and the shape in the frame of `phi`; at rest the shape with mode 2 along `phi`),
/// and the balance left across them (its sign is that of `dphi/dt`). `None` when Newton does
/// not converge.
fn flow_at(
    balances: &mut Balances,
    (moving, k_max): (bool, usize),
    phi: f64,
    guess: &[f64],
    jac: &mut Option<Vec<Vec<f64>>>,
) -> Option<(f64, Vec<f64>)> {
    // The balance in the frame of `phi`: along and across the motion, each shape mode's.
    let mut balance =
        |y: &[f64]| turned(&balances.residual(&state_at((moving, k_max), phi, y)), -phi);
    let opts = NewtonOptions {
        tol: 1e-11,
        max_iter: 8,
        fd_step: 1e-6,
        max_step: vec![0.2; guess.len()],
        one_sided: false,
        backtrack: false,
    };
    // Moving: all but the balance across the motion; at rest: the shape's, but mode 2's
    // across its long axis (the velocity's vanish with the odd modes of a resting state).
    let left = if moving { 1 } else { k_max + 1 };
    let mut fast = |y: &[f64]| {
        let r = balance(y);
        let from = if moving { 0 } else { 2 };
        (from..r.len())
            .filter(|&i| i != left)
            .map(|i| r[i])
            .collect::<Vec<f64>>()
    };
    // The chord method with the Jacobian of the previous sample (samples are at most half a
    // degree apart), else Newton, whose root's Jacobian the next sample then uses.
    let chorded = jac
        .as_ref()
        .and_then(|j| newton::chord(&mut fast, guess, j, &opts).ok());
    let y = match chorded {
        Some(found) => found.x,
        None => {
            let y = newton::solve(&mut fast, guess, &opts).ok()?.x;
            *jac = Some(newton::fd_jacobian(&mut fast, &y, opts.fd_step));
            y
        }
    };
    let r = balance(&y);
    Some((r[left], y))
}

/// The state `(vx, vy, a_2..a_K, b_2..b_K)` at the absolute orientation `phi` whose fast
/// variables in the frame of `phi` are `y` ([`flow_at`]'s unknowns): moving, the speed and
/// every shape amplitude; at rest, the shape with `b2 = 0` (mode 2 along `phi`).
fn state_at((moving, k_max): (bool, usize), phi: f64, y: &[f64]) -> Vec<f64> {
    let mut frame = vec![0.0; 2 * k_max];
    if moving {
        frame[0] = y[0];
        frame[2..].copy_from_slice(&y[1..]);
    } else {
        frame[2..=k_max].copy_from_slice(&y[..k_max - 1]);
        frame[k_max + 2..].copy_from_slice(&y[k_max - 1..]);
    }
    turned(&frame, phi)
}

/// The fast variables of `root` in the frame of its own orientation: the guess of [`flow_at`],
/// whether it moves, its shape modes and its orientation.
fn fast_guess(root: &[f64]) -> ((bool, usize), f64, Vec<f64>) {
    let k_max = root.len() / 2;
    let moving = root[0].hypot(root[1]) > 1e-9;
    let phi0 = orientation(root);
    let frame = turned(root, -phi0);
    let guess = if moving {
        std::iter::once(root[0].hypot(root[1]))
            .chain(frame[2..].iter().copied())
            .collect()
    } else {
        std::iter::once(frame[2].hypot(frame[k_max + 1]))
            .chain(frame[3..=k_max].iter().copied())
            .chain(frame[k_max + 2..].iter().copied())
            .collect()
    };
    ((moving, k_max), phi0, guess)
}

/// Where the orientation's flow takes a run leaning `lean` (radians) from `root`, a root on
/// a mirror line: the orientation moves the way the flow at the run's orientation points
/// (away from the root when `away`: a lean within [`LINEAR_LEAN`] of a root unstable in
/// rotation, where the root's eigenvalue decides) and stops at the first zero of the flow
/// that way, the first sample whose flow points back, refined by bisection to 1e-8 rad, or
/// the next mirror line of the box (45 degrees apart), where the flow vanishes by symmetry.
/// Samples at most [`SAMPLE_SPACING`] apart. Returns the state there (the fast balances
/// solved, the flow about zero): a guess for Newton on all four balances; or, where the fast
/// balances cannot be solved, the error names that orientation (its lean from `root`).
pub fn flow_zero(
    balances: &mut Balances,
    root: &[f64],
    lean: f64,
    away: bool,
) -> Result<Vec<f64>, f64> {
    let (moving, phi0, mut guess) = fast_guess(root);
    let start = phi0 + lean;
    let mut jac = None;
    let (drift, y) = flow_at(balances, moving, start, &guess, &mut jac).ok_or(lean)?;
    let dir = if away { lean.signum() } else { drift.signum() };
    guess = y;
    let quarter = std::f64::consts::FRAC_PI_4;
    let line = if dir > 0.0 {
        ((start / quarter).floor() + 1.0) * quarter
    } else {
        ((start / quarter).ceil() - 1.0) * quarter
    };
    let samples = ((line - start).abs() / SAMPLE_SPACING).ceil().max(1.0) as usize;
    let mut before = (start, guess.clone());
    for j in 1..=samples {
        let phi = start + (line - start) * j as f64 / samples as f64;
        if j == samples {
            return Ok(state_at(moving, line, &before.1));
        }
        let (drift, y) = flow_at(balances, moving, phi, &before.1, &mut jac).ok_or(phi - phi0)?;
        if drift * dir <= 0.0 {
            let (mut lo, mut hi, mut ylo) = (before.0, phi, before.1);
            while (hi - lo).abs() > 1e-8 {
                let mid = 0.5 * (lo + hi);
                let (d, ym) = flow_at(balances, moving, mid, &ylo, &mut jac).ok_or(mid - phi0)?;
                if d * dir > 0.0 {
                    (lo, ylo) = (mid, ym);
                } else {
                    hi = mid;
                }
            }
            return Ok(state_at(moving, 0.5 * (lo + hi), &ylo));
        }
        before = (phi, y);
    }
    Err(line - phi0)
}

/// The state on the slow manifold of `root`'s family at the lean `lean` (radians) from it:
/// the fast balances solved at that orientation from the root's own fast variables (a state
/// that turns slowly has its speed and shape there, not the root's: the box's anisotropy
/// moves them by `O(lean^2)`). `None` where Newton does not converge. `jac` is left with the
/// fast balances' Jacobian at that state, for the chord steps of a [`FlowScan`] out to the
/// same lean.
pub fn state_leaning(
    balances: &mut Balances,
    root: &[f64],
    lean: f64,
    jac: &mut Option<Vec<Vec<f64>>>,
) -> Option<Vec<f64>> {
    let (moving, phi0, guess) = fast_guess(root);
    let phi = phi0 + lean;
    *jac = None;
    let (_, y) = flow_at(balances, moving, phi, &guess, jac)?;
    Some(state_at(moving, phi, &y))
}

/// What is known of the orientation's flow on one side of a root stable in rotation: it
/// points back to the root at every sample out to `back_to` (radians from the root), and
/// outward at `outward_at`, if a sample showed that.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlowScan {
    pub back_to: f64,
    pub outward_at: Option<f64>,
}

impl FlowScan {
    /// Nothing sampled beyond [`LINEAR_LEAN`], where the root's rotation eigenvalue decides.
    pub fn new() -> Self {
        Self {
            back_to: LINEAR_LEAN,
            outward_at: None,
        }
    }

    /// Whether a run leaning `|lean|` turns back: `None` if that is not yet sampled.
    pub fn verdict(&self, lean: f64) -> Option<bool> {
        if self.outward_at.is_some_and(|at| lean.abs() >= at) {
            Some(false)
        } else if lean.abs() <= self.back_to {
            Some(true)
        } else {
            None
        }
    }

    /// Samples the flow of `solver` beside `root` on the side of `lean` from `back_to` out to
    /// `|lean|`, at most [`SAMPLE_SPACING`] apart (at most [`MAX_SAMPLES`]), stopping at the
    /// first sample that points outward. Where the fast balances cannot be solved the scan
    /// stops and counts the stretch out to `|lean|` as turning back: the root's eigenvalues
    /// decide there, as without the setting. With more than two shape modes the samples are
    /// at most [`LINEAR_LEAN`] apart, none beyond `reach` ([`FINE_REACH`] or
    /// [`DEPARTURE_REACH`]: a lean beyond it stays unsampled), and a sample where the fast
    /// balances cannot be solved counts as pointing outward: their flow is asked only to
    /// license an end that time stepping has not reached yet. `jac`, if given, is a Jacobian
    /// of the fast balances near the samples (e.g. [`state_leaning`]'s at the run's lean),
    /// and the first sample takes chord steps from it instead of Newton's from scratch.
    pub fn extend(
        &mut self,
        balances: &mut Balances,
        root: &[f64],
        lean: f64,
        reach: f64,
        mut jac: Option<Vec<Vec<f64>>>,
    ) {
        let (from, to, side) = (self.back_to, lean.abs(), lean.signum());
        if to <= from || self.outward_at.is_some() {
            return;
        }
        let fine = balances.modes() > 2;
        if fine && to > reach {
            return;
        }
        let (spacing, most) = if fine {
            // One sample fewer than the reach holds: the first is one LINEAR_LEAN out.
            (
                LINEAR_LEAN,
                ((reach / LINEAR_LEAN).round() as usize).max(2) - 1,
            )
        } else {
            (SAMPLE_SPACING, MAX_SAMPLES)
        };
        let (moving, phi0, mut guess) = fast_guess(root);
        let samples = (((to - from) / spacing).ceil() as usize).clamp(1, most);
        for j in 1..=samples {
            let theta = from + (to - from) * j as f64 / samples as f64;
            let phi = phi0 + side * theta;
            let Some((drift, y)) = flow_at(balances, moving, phi, &guess, &mut jac) else {
                if fine {
                    self.outward_at = Some(theta);
                } else {
                    self.back_to = to;
                }
                return;
            };
            guess = y;
            if drift * side >= 0.0 {
                self.outward_at = Some(theta);
                return;
            }
            self.back_to = theta;
        }
    }
}

impl Default for FlowScan {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::ModelParams;
    use crate::model::state::four;
    use crate::roots::steady_solver::TwoModeSolver;

    /// Whether a run leaning by `lean` (radians) from `root` (stable in rotation) turns back
    /// to it: one [`FlowScan`] from the root out to the run, as a run's first try asks it.
    fn turns_back(balances: &mut Balances, root: &[f64], lean: f64) -> bool {
        let mut scan = FlowScan::new();
        scan.extend(balances, root, lean, FINE_REACH, None);
        scan.verdict(lean).unwrap_or(true)
    }

    /// The 2-mode balances at `(eta_t, kappa2)`, N = 192.
    fn two(eta_t: f64, kappa2: f64) -> Balances {
        Balances::Two(TwoModeSolver::new(ModelParams::at(eta_t, kappa2), 192).unwrap())
    }

    /// Their steady solver.
    fn solver(b: &mut Balances) -> &mut TwoModeSolver {
        match b {
            Balances::Two(s) => s,
            Balances::General(_) => unreachable!("made with two modes"),
        }
    }

    #[test]
    fn the_flow_turns_a_run_back_only_inside_the_bump_that_bounds_the_basin() {
        // (0.096, 0.1), N = 192: the resting deformed droplet on the x axis is stable in
        // rotation (-1.1e-3) and an unstable root lies 0.571 degrees off it (Newton from
        // the root turned by 6 degrees finds it). Inside, the flow turns a run back; beyond,
        // it does not.
        let mut b = two(0.096, 0.1);
        let root = solver(&mut b).newton(0.0, 0.37, 1e-12).unwrap();
        let root = [0.0, 0.0, root.a2, 0.0];
        for lean in [0.3f64, -0.3] {
            assert!(turns_back(&mut b, &root, lean.to_radians()), "{lean}");
        }
        for lean in [1.0f64, -1.0, -12.0] {
            assert!(!turns_back(&mut b, &root, lean.to_radians()), "{lean}");
        }
        // The flow vanishes at the unstable root: Newton on all four balances from the root
        // turned by 6 degrees converges 0.571 degrees off the axis, between the samples that
        // disagree.
        let off = solver(&mut b)
            .root_from(
                four(&turned(&root, -6f64.to_radians())),
                &NewtonOptions {
                    tol: 1e-12,
                    max_iter: 20,
                    fd_step: 1e-6,
                    max_step: vec![f64::INFINITY, f64::INFINITY, 0.2, 0.2],
                    one_sided: false,
                    backtrack: false,
                },
            )
            .unwrap();
        let angle = orientation(&off).to_degrees().abs();
        assert!((angle - 0.571).abs() < 1e-3, "{angle}");
        assert!(turns_back(&mut b, &root, -(0.9 * angle).to_radians()));
        assert!(!turns_back(&mut b, &root, -(1.1 * angle).to_radians()));
    }

    #[test]
    fn from_a_root_unstable_in_rotation_the_flow_leads_to_its_first_stable_zero() {
        // (0.076, 0.1535): the x-axis MD is unstable in rotation; the flow points away from
        // it out to 22.15 degrees (a stable MD off the lines, v = 0.530204), back from there
        // to 34 degrees (unstable), and on to the diagonal beyond.
        let mut b = two(0.076, 0.1535);
        let md = solver(&mut b).newton(0.528, -0.049, 1e-12).unwrap();
        let root = [md.v, 0.0, md.a2, 0.0];
        let opts = NewtonOptions {
            tol: 1e-12,
            max_iter: 20,
            fd_step: 1e-6,
            max_step: vec![f64::INFINITY, f64::INFINITY, 0.2, 0.2],
            one_sided: false,
            backtrack: false,
        };
        for (lean, away) in [(LINEAR_LEAN, true), (4f64.to_radians(), false)] {
            let z = flow_zero(&mut b, &root, lean, away).unwrap();
            assert!(
                (orientation(&z).to_degrees() - 22.151).abs() < 1e-2,
                "{z:?}"
            );
            let found = solver(&mut b).root_from(four(&z), &opts).unwrap();
            let v = found[0].hypot(found[1]);
            assert!((v - 0.530204).abs() < 1e-6, "{found:?}");
        }
        // From 30 degrees the flow points back to the stable zero; from 40, on to the diagonal.
        let z = flow_zero(&mut b, &root, 30f64.to_radians(), false).unwrap();
        assert!(
            (orientation(&z).to_degrees() - 22.151).abs() < 1e-2,
            "{z:?}"
        );
        let z = flow_zero(&mut b, &root, 40f64.to_radians(), false).unwrap();
        assert!((orientation(&z).to_degrees() - 45.0).abs() < 1e-9, "{z:?}");
    }

    #[test]
    fn the_state_leaning_from_a_root_solves_its_fast_balances_at_that_orientation() {
        // (0.072, 0.132): the x-axis MD. At no lean it is the root; at 3 degrees its motion
        // and long axis are turned by 3 degrees, every balance but the one across the motion
        // holds, and its speed and shape differ from the root's by the box's anisotropy only.
        let mut b = two(0.072, 0.132);
        let md = solver(&mut b).newton(1.17, -0.21, 1e-12).unwrap();
        let root = [md.v, 0.0, md.a2, 0.0];
        let at_root = state_leaning(&mut b, &root, 0.0, &mut None).unwrap();
        for (x, r) in at_root.iter().zip(&root) {
            assert!((x - r).abs() < 1e-9, "{at_root:?}");
        }
        let lean = 3f64.to_radians();
        let z = state_leaning(&mut b, &root, lean, &mut None).unwrap();
        assert!((orientation(&z) - lean).abs() < 1e-12, "{z:?}");
        let frame = turned(&b.residual(&z), -lean);
        assert!(
            frame[0].abs() < 1e-9 && frame[2..].iter().all(|r| r.abs() < 1e-9),
            "{frame:?}"
        );
        assert!(
            frame[1].abs() > 1e-7,
            "the flow across the motion: {frame:?}"
        );
        let d = crate::runs::orientation::invariant_distance(&z, &root);
        assert!(d > 1e-9 && d < 1e-2, "{d}");
    }

    #[test]
    fn a_moving_droplet_inside_its_basin_turns_back_and_beyond_it_turns_on() {
        // (0.072, 0.132): the x-axis MD, stable in rotation, with an unstable root 4.8
        // degrees off it and a stable one at 8.7.
        let mut b = two(0.072, 0.132);
        let md = solver(&mut b).newton(1.17, -0.21, 1e-12).unwrap();
        let root = [md.v, 0.0, md.a2, 0.0];
        assert!(turns_back(&mut b, &root, 3f64.to_radians()));
        assert!(!turns_back(&mut b, &root, 6.5f64.to_radians()));
    }
}
