//! The slow flow of a droplet's orientation (numerics 8): where a run leaning from a mirror
//! line's root turns.
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
//! line and the run says whether the run turns back to the line.
//!
//! The flow is bumpy: the box's anisotropy at N = 192 puts unstable roots 0.6 to 5 degrees
//! off lines whose own root is stable in rotation (at (0.096, 0.1) the resting deformed
//! droplet on the x axis, rotation eigenvalue -1.1e-3, has an unstable root 0.57 degrees off
//! it; a run leaning 12 degrees turns on to the diagonal, as long time stepping shows).
use crate::model::dynamics;
use crate::numerics::newton::{self, NewtonOptions};
use crate::roots::steady_solver::SteadySolver;
use crate::runs::orientation::orientation;

/// Largest spacing (radians) of the orientations at which [`turns_back`] samples the flow:
/// a bump of the flow narrower than this between two samples is not seen.
pub const SAMPLE_SPACING: f64 = 0.5 * std::f64::consts::PI / 180.0;

/// Most samples of one [`turns_back`].
const MAX_SAMPLES: usize = 48;

/// `(x, y)` turned by `angle`.
fn turn(x: f64, y: f64, angle: f64) -> (f64, f64) {
    let (c, s) = (angle.cos(), angle.sin());
    (c * x - s * y, s * x + c * y)
}

/// The orientation's flow at the absolute orientation `phi` (direction of motion, or long
/// axis at rest): the fast balances solved from `guess` (speed and the shape in the frame
/// of `phi`; at rest the deformation alone), and the balance left across them (its sign is
/// that of `dphi/dt`). `None` when Newton does not converge.
fn flow_at(
    solver: &mut SteadySolver,
    moving: bool,
    phi: f64,
    guess: &[f64],
) -> Option<(f64, Vec<f64>)> {
    let p = *solver.params();
    let mut balance = |y: &[f64]| -> [f64; 4] {
        let (v, c, d) = if moving {
            (y[0], y[1], y[2])
        } else {
            (0.0, y[0], 0.0)
        };
        let (vx, vy) = turn(v, 0.0, phi);
        let (a2, b2) = turn(c, d, 2.0 * phi);
        let f = solver.forces(vx, vy, a2, b2);
        let r = dynamics::force_balance(&p, [vx, vy, a2, b2], &f);
        let (along, across) = turn(r[0], r[1], -phi);
        let (sc, sd) = turn(r[2], r[3], -2.0 * phi);
        [along, across, sc, sd]
    };
    let opts = NewtonOptions {
        tol: 1e-11,
        max_iter: 12,
        fd_step: 1e-6,
        max_step: vec![0.2; guess.len()],
    };
    let fast = |y: &[f64]| {
        let r = balance(y);
        if moving {
            vec![r[0], r[2], r[3]]
        } else {
            vec![r[2]]
        }
    };
    let y = newton::solve(fast, guess, &opts).ok()?.x;
    let r = balance(&y);
    Some((if moving { r[1] } else { r[3] }, y))
}

/// Whether a run leaning by `lean` (radians) from the root `root` on a mirror line turns back
/// to it: the orientation's flow, sampled from the root out to the run's orientation at most
/// [`SAMPLE_SPACING`] apart, points back towards the line at every sample. `false` also when
/// the fast balances cannot be solved at some sample (the run is not near that family).
pub fn turns_back(solver: &mut SteadySolver, root: &[f64; 4], lean: f64) -> bool {
    let moving = root[0].hypot(root[1]) > 1e-9;
    let phi0 = orientation(root);
    let (c0, d0) = turn(root[2], root[3], -2.0 * phi0);
    let mut guess = if moving {
        vec![root[0].hypot(root[1]), c0, d0]
    } else {
        vec![c0.hypot(d0)]
    };
    let samples = ((lean.abs() / SAMPLE_SPACING).ceil() as usize).clamp(1, MAX_SAMPLES);
    (1..=samples).all(|j| {
        let theta = lean * j as f64 / samples as f64;
        match flow_at(solver, moving, phi0 + theta, &guess) {
            Some((drift, y)) => {
                guess = y;
                drift * lean.signum() < 0.0
            }
            None => false,
        }
    })
}
