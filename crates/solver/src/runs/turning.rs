//! The Newton finish's questions to the orientation's slow flow
//! ([`crate::runs::rotation_flow`], setting `orientation_flow`): whether a run leaning from a
//! stable root turns back to it, to which stable root a run leaning from a root unstable in
//! rotation turns, and whether a run with more shape modes (whose finish has no such flow)
//! has settled beside a stable root it turns back to.
use crate::contract::profile::{self, Part};
use crate::runs::finding::{Finding, MAX_SETTLED};
use crate::runs::finish::NewtonFinish;
use crate::runs::orientation::{angle_to, invariant_distance, LEAN_FLOOR};
use crate::runs::rotation_flow::{
    flow_zero, state_leaning, FlowScan, DEPARTURE_REACH, FINE_REACH, LINEAR_LEAN,
};

/// The finish's questions to the flow: whether a leaning run turns back to a stable root
/// ([`NewtonFinish::within_rotation_basin`]) and where it turns to from an unstable one
/// ([`NewtonFinish::flow_turn`]), each flow sampled once per root and side.
impl NewtonFinish {
    /// Whether a run leaning by `lean` from the stable root `near` on a mirror line turns
    /// back to it (setting `orientation_flow`; without it, always): the orientation's slow
    /// flow points back to the line all the way from the run
    /// ([`crate::runs::rotation_flow::FlowScan`]). A root stable in
    /// rotation is not enough: the box's anisotropy can put an unstable root between the
    /// line and the run (at (0.072, 0.132) 4.8 degrees off the x-axis MD; a run leaning 6.5
    /// degrees turns on to the stable root at 8.7). A lean below
    /// [`crate::runs::rotation_flow::LINEAR_LEAN`], or a root with no orientation, always
    /// holds.
    pub(super) fn within_rotation_basin(&mut self, near: &Finding, lean: f64) -> bool {
        if !self.orientation_flow || near.verdict.rotation.is_none() || lean.abs() < LEAN_FLOOR {
            return true;
        }
        self.scan_turns_back(near, lean, FINE_REACH, None)
    }

    /// Whether the orientation's flow beside `near` points back to it at every sample out
    /// to `lean` ([`FlowScan`]; each root's scan is kept and extended as the run's lean
    /// grows). A lean beyond `reach` ([`FINE_REACH`], or
    /// [`crate::runs::rotation_flow::DEPARTURE_REACH`]) does not turn back in a model with
    /// more shape modes, whatever a wider scan asked for elsewhere found.
    /// `jac`: a Jacobian of the fast balances near the run's lean, if one is known (the scan's
    /// first sample takes chord steps from it).
    fn scan_turns_back(
        &mut self,
        near: &Finding,
        lean: f64,
        reach: f64,
        jac: Option<Vec<Vec<f64>>>,
    ) -> bool {
        if self.beyond_two_modes() && lean.abs() > reach {
            return false;
        }
        // What earlier tries learnt of this root's flow on this side (a run's later tries find
        // the same root at a similar lean; the flow is sampled once).
        let side = lean > 0.0;
        let known = self
            .flows
            .iter()
            .position(|(z, s, _)| *s == side && self.same_root(z, &near.z));
        let mut scan = known.map_or_else(FlowScan::new, |i| self.flows[i].2);
        if let Some(verdict) = scan.verdict(lean) {
            return verdict;
        }
        let Ok(balances) = self.balances() else {
            return true;
        };
        let timed = profile::enter(Part::Flow);
        scan.extend(balances, &near.z, lean, reach, jac);
        drop(timed);
        match known {
            Some(i) => self.flows[i].2 = scan,
            None => self.flows.push((near.z.clone(), side, scan)),
        }
        scan.verdict(lean).unwrap_or(!self.beyond_two_modes())
    }

    /// Whether a run with more than two shape modes, leaning by `lean` from the stable root
    /// `near` on a mirror line, has settled beside it: its speed and shape within `bound` of
    /// the state of `near`'s family at its own orientation ([`state_leaning`]), where a
    /// slowly turning run has them (the root's differ by the box's anisotropy, `O(lean^2)`:
    /// 1.2e-4 at 4.8 degrees from the x-axis MD at (0.07625, 0.14425), modes 2..4, whose
    /// run turns back at a rate of 5.7e-5 and would settle on the root only after 18 000
    /// time units more). Its turn back is then the orientation's slow flow, sampled out to
    /// the run ([`FlowScan`]): every sample must point back. 2-mode runs keep their own rule
    /// (numerics 10).
    pub(super) fn settled_beside(
        &mut self,
        z: &[f64],
        near: &Finding,
        lean: f64,
        bound: f64,
    ) -> bool {
        if !self.beyond_two_modes()
            || !near.stable()
            || near.verdict.rotation.is_none()
            || lean.abs() <= LINEAR_LEAN
        {
            return false;
        }
        let Ok(balances) = self.balances() else {
            return false;
        };
        // The scan out to the run starts from the Jacobian of the state at the run's lean.
        let mut jac = None;
        let beside = {
            let _timed = profile::enter(Part::Flow);
            state_leaning(balances, &near.z, lean, &mut jac)
        };
        beside.is_some_and(|b| invariant_distance(z, &b) <= bound)
            && self.scan_turns_back(near, lean, FINE_REACH, jac)
    }

    /// Whether a run with more than two shape modes that the landing's slow flow takes to
    /// `near`, a root stable in rotation on a mirror line, leaning by `lean` beyond
    /// [`LINEAR_LEAN`] (its lean not growing: [`NewtonFinish::land_now`]), turns back to the
    /// line once it arrives (numerics `modes-13`): the orientation's flow on `near`'s family
    /// points back at every sample, at most [`LINEAR_LEAN`] apart, from the root out to the
    /// run ([`FlowScan`]), so that no root of the lattice lies between the line and the
    /// run's lean. (0.08725, 0.115), modes 2..4, N = 192, from iii: the run leaves the
    /// diagonal ID (its drift growing at 2.1e-4) leaning 0.56 degrees, its lean shrinking
    /// at 4e-5, and pure time stepping reaches the diagonal's slow MD (v = 0.0213) at
    /// t = 28 500. The scan reaches [`FINE_REACH`], or [`DEPARTURE_REACH`] for a run leaving
    /// the resting disk (`from_disk`, numerics `modes-14`): (0.07625, 0.13725), modes 2..4,
    /// N = 192, from iv leaves the disk along the x axis leaning 5.76 degrees, its lean
    /// unchanged while its speed grows from 0.006 to 0.1, and landed on the x-axis MD at
    /// t = 1965, once turned within 5 degrees, instead of t = 19. A run leaving a deformed
    /// resting state leaves at the orientation the lattice holds that state at: modes 2..3,
    /// N = 96, (0.088, 0.1095) from iv rests 5.3 degrees off the diagonal and turns on to
    /// the MD 5.9 degrees off it, not to the diagonal's.
    pub(super) fn arrives_turning_back(
        &mut self,
        near: &Finding,
        lean: f64,
        from_disk: bool,
    ) -> bool {
        let reach = if from_disk {
            DEPARTURE_REACH
        } else {
            FINE_REACH
        };
        self.beyond_two_modes()
            && near.stable()
            && near.verdict.rotation.is_some()
            && self.scan_turns_back(near, lean, reach, None)
    }

    /// With `orientation_flow`: the stable root that the orientation's flow takes a run
    /// leaning `lean` from `near` to ([`flow_zero`]; `away` as there), confirmed by Newton on
    /// all four balances (at the flow's zero to 1e-4 rad) and by its eigenvalues; a root of
    /// the run's family (within [`MAX_SETTLED`] of `near`), not `near` itself.
    pub(super) fn flow_turn(&mut self, near: &Finding, lean: f64, away: bool) -> Option<Finding> {
        if !self.orientation_flow {
            return None;
        }
        // The flow was followed from `from` to `to` (its zero, or where the fast balances
        // failed), pointing that way all along: a run leaning in between (a later try, as
        // the run turns) ends the same way.
        let between = |from: f64, to: f64| {
            lean * from > 0.0 && lean.abs() >= from.abs() && lean.abs() < to.abs()
        };
        if let Some((.., found)) = self
            .turns
            .iter()
            .find(|(root, from, to, _)| self.same_root(root, &near.z) && between(*from, *to))
        {
            return found.clone();
        }
        let zero = {
            let _timed = profile::enter(Part::Flow);
            flow_zero(self.balances().ok()?, &near.z, lean, away)
        };
        let z = match zero {
            Ok(z) => z,
            Err(failed_at) => {
                self.turns.push((near.z.clone(), lean, failed_at, None));
                return None;
            }
        };
        let found = self.root_near(&z).ok()?;
        let to = angle_to(&z, &near.z);
        let ends = found.stable()
            && angle_to(&found.z, &z).abs() < 1e-4
            && angle_to(&found.z, &near.z).abs() > 1e-6
            && invariant_distance(&found.z, &near.z) <= MAX_SETTLED;
        let found = ends.then_some(Finding {
            turned_from: Some(near.z.clone()),
            ..found
        });
        self.turns.push((near.z.clone(), lean, to, found.clone()));
        found
    }
}
