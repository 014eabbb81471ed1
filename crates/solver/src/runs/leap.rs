//! Leaping along a departure from an unstable steady state (setting `leap_departures`).
//!
//! A run that starts near a saddle `z*` (the resting disk just past the onset of motion, say)
//! leaves it along the growing mode: once the decaying modes have died out, its displacement
//! from `z*` (field and `(vx, vy, a2, b2)` alike) is `e^(lambda t) e` for the mode `e` with
//! growth rate `lambda`, up to terms of second order in the displacement. At small growth
//! rates this linear stretch takes most of the run (at `(0.07625, 0.14)` from IC iii,
//! `lambda = 1.8e-3`: `v` grows from 0.006 to 0.05 in 1100 of the 1900 time units the run
//! takes to its MD state). The time stepper only reproduces the exponential there; the leap
//! does it in one go: displacement times `G = e^(lambda T)`, centre moved by the integral of
//! the velocity, `t` advanced by `T`.
//!
//! When: two Newton tries of the run, at `t1 < t2`, find the same unstable root `z*`, and the
//! run's displacements `d1 = z1 - z*`, `d2 = z2 - z*` (max over `vx, vy, a_2..a_K, b_2..b_K`,
//! any `K`) follow one
//! real growing eigenvalue `lambda` of `z*`: `|d2 - e^(lambda (t2 - t1)) d1| <= LEAP_TOL
//! |d2 - d1|`, i.e. the run's change between the tries is the mode's to within [`LEAP_TOL`].
//! The leap then takes `|d2|` to [`LEAP_TO`] (at most to `t_max`).
//!
//! Error: the state after the leap is off the unstable manifold by the second-order terms,
//! `O(LEAP_TO^2)` (the deformation of a departing disk grows like `v^2`, and the leap scales
//! it like `v`); those relax at the decaying modes' rates within a few time units, and the
//! run goes on by time stepping. The final state is the root that the Newton finish or the
//! paper's test ends the run at, so `v` and `s` are unaffected. The leap grows the run at the
//! linearisation's own rate, which the default time steps (`dt_max = 0.25`) miss by a few per
//! cent: at `(0.07625, 0.14)` from IC iii (N = 96) the leap lands 0.2 % from accurate time
//! stepping (`dt_max = 0.05`, `tol = 1e-6`) in `v`, the default steps are 5.4 % off at that
//! time (test `a_leap_lands_on_the_time_steppers_departure`). `RunOutcome::t_leapt` records
//! the leapt time; `t_end` also moves with the Newton tries' schedule after the leap.
use crate::model::state::max_distance;

/// Largest displacement from the saddle (max over the state's unknowns) a leap reaches: in the
/// departures from the resting disk near the onset of motion the growth rate is within 4 %
/// of the linear one up to here (20 % at 0.1).
pub const LEAP_TO: f64 = 0.05;

/// Largest misfit of the run's change between two tries to the growing mode's, as a fraction
/// of that change, for the run to be on the mode.
pub const LEAP_TOL: f64 = 0.05;

/// Shortest leap worth taking (time units); shorter ones are left to the time stepper.
pub const MIN_LEAP: f64 = 10.0;

/// A leap along the growing mode of the saddle `root`.
#[derive(Debug, Clone, PartialEq)]
pub struct Leap {
    /// The saddle `(vx, vy, a_2..a_K, b_2..b_K)`.
    pub root: Vec<f64>,
    /// Growth rate of the mode.
    pub rate: f64,
    /// Leapt time `T`.
    pub duration: f64,
}

impl Leap {
    /// The displacement's factor `e^(rate T)`.
    pub fn factor(&self) -> f64 {
        (self.rate * self.duration).exp()
    }

    /// How far the centre moves during the leap from a run moving at `(vx, vy)`: the integral
    /// of `v* + e^(rate t) (v - v*)` over the leap.
    pub fn shift(&self, vx: f64, vy: f64) -> [f64; 2] {
        let grown = (self.factor() - 1.0) / self.rate;
        [
            self.root[0] * self.duration + grown * (vx - self.root[0]),
            self.root[1] * self.duration + grown * (vy - self.root[1]),
        ]
    }
}

/// One try's record: its time, the run's state and the root found (`(vx, vy, a_2..a_K,
/// b_2..b_K)`).
#[derive(Debug, Clone, PartialEq)]
pub struct Sighting {
    pub t: f64,
    pub z: Vec<f64>,
    pub root: Vec<f64>,
}

/// The leap from the run at `now` (the saddle `now.root`, whose eigenvalues are `eigenvalues`
/// as `[re, im]`) given the try `before` on the same saddle, if the run is on one real growing
/// mode of it between the two tries; at most to `t_max`.
pub fn leap(
    before: &Sighting,
    now: &Sighting,
    eigenvalues: &[[f64; 2]],
    t_max: f64,
) -> Option<Leap> {
    let dt = now.t - before.t;
    if max_distance(&before.root, &now.root) >= 1e-9 || dt <= 0.0 {
        return None;
    }
    let (n1, n2) = (
        max_distance(&before.z, &now.root),
        max_distance(&now.z, &now.root),
    );
    if !(n2 > n1 && n2 < LEAP_TO) {
        return None;
    }
    let change = max_distance(&now.z, &before.z);
    let rate = eigenvalues
        .iter()
        .filter(|[re, im]| *re > 0.0 && *im == 0.0)
        .map(|[re, _]| *re)
        .find(|re| {
            // The run at `now` against its state at `before` grown by the mode.
            let g = (re * dt).exp();
            let grown: Vec<f64> = now
                .root
                .iter()
                .zip(&before.z)
                .map(|(r, z)| r + g * (z - r))
                .collect();
            max_distance(&now.z, &grown) <= LEAP_TOL * change
        })?;
    let duration = ((LEAP_TO / n2).ln() / rate).min(t_max - now.t);
    (duration >= MIN_LEAP).then(|| Leap {
        root: now.root.clone(),
        rate,
        duration,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn on_mode(t: f64, rate: f64) -> Sighting {
        let g = (rate * t).exp();
        Sighting {
            t,
            z: vec![1e-3 * g, 2e-4 * g, 0.0, 0.0],
            root: vec![0.0; 4],
        }
    }

    #[test]
    fn a_run_on_the_growing_mode_leaps_to_leap_to() {
        let eig = [[1.8e-3, 0.0], [1.8e-3, 0.0], [-0.5, 0.0]];
        let (a, b) = (on_mode(100.0, 1.8e-3), on_mode(125.0, 1.8e-3));
        let l = leap(&a, &b, &eig, 5000.0).unwrap();
        let after = b.z[0] * l.factor();
        assert!((after - LEAP_TO).abs() < 1e-12, "{l:?}");
        // Capped at t_max.
        let l = leap(&a, &b, &eig, 200.0).unwrap();
        assert!((l.duration - 75.0).abs() < 1e-12, "{l:?}");
        // Not within MIN_LEAP of t_max.
        assert!(leap(&a, &b, &eig, 130.0).is_none());
    }

    #[test]
    fn no_leap_off_the_mode_or_past_leap_to_or_for_another_root() {
        let eig = [[1.8e-3, 0.0], [-0.5, 0.0]];
        let (a, mut b) = (on_mode(100.0, 1.8e-3), on_mode(125.0, 1.8e-3));
        // A decaying part 10 % of the change between the tries: not on the mode.
        let change = b.z[0] - a.z[0];
        b.z[2] += 0.1 * change;
        assert!(leap(&a, &b, &eig, 2000.0).is_none());
        // Growing at another rate than the saddle's.
        let b = on_mode(125.0, 3e-3);
        assert!(leap(&on_mode(100.0, 3e-3), &b, &eig, 2000.0).is_none());
        // Already past LEAP_TO.
        let far = |s: Sighting| Sighting {
            z: s.z.iter().map(|x| x * 100.0).collect(),
            ..s
        };
        assert!(leap(&far(a.clone()), &far(on_mode(125.0, 1.8e-3)), &eig, 2000.0).is_none());
        // Another root.
        let mut c = on_mode(125.0, 1.8e-3);
        c.root[0] = 1e-6;
        assert!(leap(&a, &c, &eig, 2000.0).is_none());
        // A complex pair (an oscillating departure) is not leapt.
        assert!(leap(&a, &on_mode(125.0, 1.8e-3), &[[1.8e-3, 0.1]], 2000.0).is_none());
    }

    #[test]
    fn the_shift_integrates_the_velocity() {
        let l = Leap {
            root: vec![0.1, 0.0, 0.0, 0.0],
            rate: 0.01,
            duration: 50.0,
        };
        // v(t) = 0.1 + 0.001 e^(0.01 t): integral 5 + 0.1 (e^0.5 - 1).
        let [dx, dy] = l.shift(0.101, 0.0);
        assert!((dx - (5.0 + 0.1 * (0.5f64.exp() - 1.0))).abs() < 1e-12);
        assert_eq!(dy, 0.0);
    }
}
