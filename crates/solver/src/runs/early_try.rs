//! The early try of a run with more than two shape modes: its own trigger
//! ([`crate::runs::finish::TRIGGER_FACTOR`] steady tolerances of `|dz/dt|`) is ten times
//! stricter than the 2-mode runs', for the orientation of moving and deformed roots (with the
//! 2-mode trigger such runs had ended on roots of the grid's lattice that pure time stepping
//! does not reach, 9 to 27 degrees from the run; results/k-mode-endings). From
//! [`crate::runs::early_tries::EARLY_FACTOR`] of its triggers down (three times the 2-mode
//! runs' rate, numerics `modes-15`) a run is tried early, and ends only where its orientation
//! is not in doubt:
//! - on the resting disk, which has none (numerics `modes-11`): Newton from the run finds the
//!   disk, stable, and the run has settled on it, or the landing's slow flow takes the run to
//!   the disk from the disk not yet settled on or from no root at all (a run passing a
//!   saddle-node's ghost);
//! - on a root with an orientation (numerics `modes-14`), stable in every mode (the rotation
//!   mode included), the run settled on it (as [`NewtonFinish::consider`] asks), not turning,
//!   and leaning from it by at most [`EARLY_LEAN`]: within
//!   [`crate::runs::rotation_flow::LINEAR_LEAN`] of it (where its rotation eigenvalue
//!   decides), or turning towards it since the last early try (made one window after the
//!   first that found it so), with its speed and shape those of the root's family at its own
//!   orientation and the orientation's flow on that family pointing back at every sample
//!   from the root out to the run ([`NewtonFinish::settled_beside`]): on the root's branch of
//!   the fast balances, with no root of the lattice between it and the root.
//!
//! A try that does not end the run changes none of the finish's other decisions (its tries
//! and their clock, the turns, the sightings; what it learns of a root's verdict and flow is
//! what a later try would learn, kept; the Jacobian it keeps may start a later solve, which
//! then ends on the same root to Newton's tolerance). It is repeated after `max(10, t / 4)`
//! (or one window, above). A landing costs tens of Newton solves: once one has found the slow
//! flow going elsewhere than the disk, the run is tried early once more, below
//! [`LATE_EARLY_FACTOR`] triggers, and then no more.
use crate::contract::ending::Ending;
use crate::runs::early_tries::LATE_EARLY_FACTOR;
use crate::runs::finding::MAX_SETTLED;
use crate::runs::finish::{retry_after, Decision, NewtonFinish};
use crate::runs::orientation::{angle_to, invariant_distance, unoriented};
use crate::runs::rotation_flow::LINEAR_LEAN;

/// The largest lean (radians) from a root with an orientation at which an early try ends a
/// run there: one degree, twice the spacing of the lattice's roots beside the box's mirror
/// lines at N = 192 (0.2 to 0.5 degrees), a fifth of the reach of a K-mode flow's scan.
pub const EARLY_LEAN: f64 = std::f64::consts::PI / 180.0;

impl NewtonFinish {
    /// The early try at time `t` of a run at `z` whose change (`(all, across)`, as
    /// [`NewtonFinish::consider`] has it) is below the early tries' factor of triggers
    /// ([`crate::runs::early_tries::EarlyTries`]) but not yet below its own (module doc).
    /// Runs: (0.077, 0.1405), modes 2..4, from i, creeping onto the disk, ended at t = 1767
    /// by its own trigger and at t = 38 by this try (numerics `modes-11`); the Fig. 1c run
    /// from ii, modes 2..4, turning back to the x-axis MD 0.17 degrees off it, at t = 71 and
    /// t = 42 (`modes-14`) and 27.4 (`modes-15`).
    pub(super) fn try_early(&mut self, t: f64, z: &[f64], (all, change): (f64, f64)) -> Decision {
        if !self.beyond_two_modes()
            || t < self.early.next
            || change >= self.early.factor * self.trigger
        {
            return Decision::Continue;
        }
        self.early.next = retry_after(t);
        // Beside the root the last try found in speed and shape but leaning beyond EARLY_LEAN
        // from it, the run is not ended there, and Newton from it finds that root again (the
        // Fig. 1c run from i, modes 2..4, 6.9 to 7.0 degrees off the x-axis MD at five
        // tries): no solve. A skipped try only leaves the run to a later one (module doc); a
        // run leaving that root (for the disk) is tried.
        if let Some((root, _)) = &self.early.last {
            if angle_to(z, root).abs() > EARLY_LEAN && invariant_distance(z, root) <= MAX_SETTLED {
                return Decision::Continue;
            }
        }
        match self.newton_root(z) {
            // The disk: its verdict.
            Ok(root) if unoriented(&root) => {
                let f = self.assess(root);
                if !f.stable() {
                    return Decision::Continue;
                }
                if invariant_distance(z, &f.z) <= self.settled_within(&f, change) {
                    return Decision::End(Ending::Newton, f.z);
                }
            }
            // No root near: a run passing a saddle-node's ghost.
            Err(_) => {}
            // A root with an orientation: only where the run is beside it, not turning.
            Ok(root) => {
                if all >= self.early.factor * self.trigger {
                    return Decision::Continue;
                }
                return match self.settled_early(t, z, root, change) {
                    Some(root) => Decision::End(Ending::Newton, root),
                    None => Decision::Continue,
                };
            }
        }
        if !self.landing {
            return Decision::Continue;
        }
        match self.flow_root(z, false) {
            Some(found) if unoriented(&found.z) => Decision::End(Ending::Landing, found.z),
            _ => {
                // The slow flow does not take the run to the disk: one more early try nearer
                // the disk, then no more.
                if self.early.factor > LATE_EARLY_FACTOR {
                    self.early.factor = LATE_EARLY_FACTOR;
                } else {
                    self.early.next = f64::INFINITY;
                }
                Decision::Continue
            }
        }
    }

    /// The root with an orientation Newton found from the run at `z` at time `t` (change
    /// across the rotation `change`), if an early try ends the run there (module doc). A run
    /// that would end there but for its turn, not yet seen, is tried again one window later
    /// (a chord solve from the root's kept Jacobian; the root's verdict is kept). The lean is
    /// asked first: a run leaning beyond [`EARLY_LEAN`] costs no eigenvalue problem.
    fn settled_early(
        &mut self,
        t: f64,
        z: &[f64],
        root: Vec<f64>,
        change: f64,
    ) -> Option<Vec<f64>> {
        let lean = angle_to(z, &root);
        let before = self.early.last.replace((root.clone(), lean.abs()));
        if lean.abs() > EARLY_LEAN {
            return None;
        }
        let f = self.assess(root);
        if !f.stable() || f.verdict.rotation.is_none() {
            return None;
        }
        let bound = self.settled_within(&f, change);
        if invariant_distance(z, &f.z) > bound {
            return None;
        }
        let seen = before.filter(|(r, _)| self.same_root(r, &f.z));
        if lean.abs() <= LINEAR_LEAN {
            return Some(f.z);
        }
        let Some((_, lean_before)) = seen else {
            self.early.next = t + self.window;
            return None;
        };
        (lean.abs() < lean_before && self.settled_beside(z, &f, lean, bound)).then_some(f.z)
    }
}
