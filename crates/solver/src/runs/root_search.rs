//! Which stable root a run that Newton near it cannot end will reach: the first stable root
//! on the side a run leans to when its own is unstable only in rotation
//! ([`NewtonFinish::stable_root`]), the root its one-dimensional slow flow lands on
//! ([`NewtonFinish::landing_root`]), the stable one of two roots a run turning between mirror
//! lines is caught between ([`NewtonFinish::turn_root`]), and the root on the nearest mirror
//! line ([`NewtonFinish::aligned_root`]); and when the landing ends a run
//! ([`NewtonFinish::land_now`]).
use crate::contract::ending::Ending;
use crate::contract::profile::{self, Part};
use crate::model::classify::CLASS_THRESHOLD;
use crate::model::state::{reflected, speed_and_deformation, turned};
use crate::runs::finding::{Finding, MAX_SETTLED};
use crate::runs::finish::{Decision, NewtonFinish, LEAN_GROWTH};
use crate::runs::landing::landings;
use crate::runs::orientation::{
    angle_to, class_of, invariant_distance, lean_from_mirror_line, modulo_half_turn,
    next_mirror_line, orientation, unoriented, LEAN_FLOOR, TURN_SEARCH,
};
use crate::runs::rotation_flow::LINEAR_LEAN;

impl NewtonFinish {
    /// The root the run at `z` ends at, if Newton finds one, and whether it may
    /// end there: the root near `z`, if every eigenvalue decays. If that root is unstable only
    /// in its rotation mode (an orientation the box turns away from), the run turns away only
    /// if it leans at all (a lean `phi` grows like `phi exp(lambda_rot t)`, however long that
    /// takes: before numerics 4 a run that could not turn by 0.01 rad before `t_max` ended
    /// on the unstable line, `v` off by the box's anisotropy from where longer stepping
    /// lands); a run that started mirror-symmetric (`phi = 0`, [`NewtonFinish::starting_at`])
    /// ends at the root like the paper's test would, any other turns even at a lean of
    /// round-off (numerics 7). A run that can turn goes to the root of
    /// the state turned by 45 degrees (motion and long axis together, towards the side it
    /// leans to), where the box's other mirror line is, if that root is stable. With
    /// `orientation_flow` (numerics 8) the orientation's flow says first where it turns to
    /// ([`Self::flow_turn`]), and a root stable in rotation holds a leaning run only inside
    /// the stretch its flow turns back from ([`Self::within_rotation_basin`]). That check,
    /// for the root near `z` when it is stable, is left to the caller: it samples the flow,
    /// and is needed only when the run would end there (`basin_left`: the root is that one).
    pub fn stable_root(&mut self, z: &[f64]) -> Option<(Finding, bool, bool)> {
        let near = match self.root_near(z) {
            Ok(near) => near,
            Err(_) => self.aligned_root(z)?,
        };
        if near.stable() {
            return Some((near, true, true));
        }
        let lean = angle_to(z, &near.z);
        let (found, may_end) = self.settle(near, lean, false);
        Some((found, may_end, false))
    }

    /// Where a run leaning by `lean` from the root `near` ends, and whether it may end there
    /// ([`Self::stable_root`]). `turning_in`: the run is still far from the root's family (a
    /// landing from a departure) and its lean shrinks; it turns on its way as the departure
    /// turns it, which the orientation's flow on the family ([`Self::flow_turn`]) does not
    /// know: with `orientation_flow`, a root unstable in rotation does not end it unless its
    /// lean is within [`LINEAR_LEAN`].
    fn settle(&mut self, near: Finding, lean: f64, turning_in: bool) -> (Finding, bool) {
        if near.verdict.rotation.is_none() || near.stable() {
            let ok = near.stable() && self.within_rotation_basin(&near, lean);
            return (near, ok);
        }
        if near.verdict.unstable > 0 {
            return (near, false);
        }
        // Below LEAN_FLOOR a lean is the round-off of a mirror-symmetric run: none.
        let lean = if lean.abs() < LEAN_FLOOR { 0.0 } else { lean };
        if lean == 0.0 && self.mirror_symmetric {
            // A mirror-symmetric run stays on its line for ever.
            return (near, true);
        }
        // Any other run turns, however small its lean (round-off grows too); at a lean below
        // the floor either side, the two turned roots being mirror images (same v and s).
        let side = if lean >= 0.0 { 1.0 } else { -1.0 };
        if self.orientation_flow {
            // The run turns the way the orientation's flow takes it (away from `near`
            // within LINEAR_LEAN of it, where the rotation eigenvalue decides).
            let away = lean.abs() < LINEAR_LEAN;
            if turning_in && !away {
                // The lean the run arrives with is not known: while it is still leaving the
                // resting ID its orientation relaxes as the ID's does. (0.088, 0.1095) iii
                // lands 13 degrees off the diagonal MD, where the flow on the family points
                // to the y axis, and arrives 1 degree off it; (0.08625, 0.1135) iii lands 9.9
                // degrees off it, next to a stable zero of the flow, and arrives on the
                // diagonal with a lean of round-off. Such a run steps on.
                return (near, false);
            }
            let from = if away { side * LINEAR_LEAN } else { lean };
            if let Some(found) = self.flow_turn(&near, from, away) {
                return (found, true);
            }
        }
        // The run turns away from `near` towards the side it leans to, and ends on the first
        // stable root that way: where the unstable line's root lost its rotational stability
        // in a pitchfork, a pair of roots a few degrees to either side; else the root on the
        // box's next mirror line, 45 degrees away. Newton from the state turned by growing
        // angles finds the nearest first.
        let quarter = std::f64::consts::FRAC_PI_4;
        for (i, degrees) in TURN_SEARCH.into_iter().enumerate() {
            let Some(mut other) = self.turned_root(&near.z, side, i, degrees) else {
                continue;
            };
            // A root the run turns to differs from `near` by the box's anisotropy only (its
            // class may differ where `s` is near the threshold: MD on one line, MC on the
            // other); one further away (a resting state, say) is not where a turn ends.
            let mut turn = side * angle_to(&other.z, &near.z);
            let to_line = next_mirror_line(orientation(&near.z), side);
            if self.beyond_two_modes() && turn > to_line + 1e-6 && turn < to_line + quarter {
                // Past the next mirror line (45 degrees from a root on a line, nearer from a
                // root of the lattice between two): its mirror image in that line is a root
                // as stable, on the run's side of the line. Modes 2..3, N = 192, (0.085,
                // 0.112) from iv, turning from the lattice's root at 111.65 degrees
                // (unstable in rotation) to the one at 132.75 where pure stepping ends: the
                // search finds its image at 137.25 first.
                let line = orientation(&near.z) + side * to_line;
                if let Ok(image) = self.root_near(&reflected(&other.z, line)) {
                    turn = side * angle_to(&image.z, &near.z);
                    other = image;
                }
            }
            if other.stable()
                && invariant_distance(&other.z, &near.z) <= MAX_SETTLED
                && turn > 1e-6
                && turn <= quarter + 1e-6
                && self.within_rotation_basin(&other, lean - side * turn)
            {
                return (
                    Finding {
                        turned_from: Some(near.z.clone()),
                        ..other
                    },
                    true,
                );
            }
        }
        (near, false)
    }

    /// The root Newton finds from the root `near` turned by `degrees` (the `i`-th of
    /// [`TURN_SEARCH`]) to the side `side` (+1 or -1), as an earlier try found it from the
    /// same root ([`NewtonFinish::same_root`]) if one did: a run's tries beside one root
    /// search the same turns.
    fn turned_root(&mut self, near: &[f64], side: f64, i: usize, degrees: f64) -> Option<Finding> {
        let known = self
            .turn_searches
            .iter()
            .position(|(root, s, _)| *s == (side > 0.0) && self.same_root(root, near));
        if let Some(found) = known.and_then(|k| self.turn_searches[k].2[i].clone()) {
            return found;
        }
        let found = self
            .root_near(&turned(near, side * degrees.to_radians()))
            .ok();
        let k = match known {
            Some(k) => k,
            None => {
                self.turn_searches
                    .push((near.to_vec(), side > 0.0, vec![None; TURN_SEARCH.len()]));
                self.turn_searches.len() - 1
            }
        };
        self.turn_searches[k].2[i] = Some(found.clone());
        found
    }

    /// The stable root the run at `z` lands on along its slow flow
    /// ([`crate::runs::landing`]): the flow's root on its mirror line, confirmed by Newton on
    /// all four equations (the same speed and deformation to 1e-6, on the line) and by its
    /// eigenvalues. If that root is unstable in its rotation mode only, the run, arriving
    /// with its lean (the caller lands only runs whose lean does not grow on the way), turns
    /// there as [`Self::stable_root`] says: to the first stable root on the side it leans to
    /// (either side for a lean of round-off), or nowhere if it is mirror-symmetric.
    /// Failing that, a run caught turning between two mirror lines ends where it turns to
    /// ([`Self::turn_root`]).
    /// `lean_shrinking`: the run's lean from its line shrank since the last try (numerics 9
    /// then lets it end on a turn only once it is on the family, [`Self::settle`]).
    /// `before`: the run's orientation at the last try, if it had the same kind (moving or
    /// at rest).
    pub fn landing_root(
        &mut self,
        z: &[f64],
        lean_shrinking: bool,
        before: Option<f64>,
    ) -> Option<Finding> {
        self.flow_root(z, lean_shrinking)
            .or_else(|| self.turn_root(z, before))
    }

    /// [`Self::landing_root`] along the slow flow alone (no [`Self::turn_root`]).
    pub fn flow_root(&mut self, z: &[f64], lean_shrinking: bool) -> Option<Finding> {
        let found = {
            let _timed = profile::enter(Part::Landing);
            self.balances().ok()?;
            let balances = self.solver.as_mut().expect("made above");
            landings(balances, z, &mut self.walks)
        };
        // A run with the resting disk's shape (round to the class threshold), leaving it or
        // beside a saddle near it: no deformation for the lattice to hold its orientation by.
        let from_disk = speed_and_deformation(z).1 <= CLASS_THRESHOLD;
        for landing in found {
            let Ok(near) = self.root_near(&landing.on_line) else {
                continue;
            };
            let flows_own = angle_to(&near.z, &landing.on_line).abs() < 1e-6
                && invariant_distance(&near.z, &landing.on_line) <= 1e-6
                && class_of(&near.z) == class_of(&landing.on_line);
            if !flows_own {
                continue;
            }
            let lean = angle_to(&landing.z, &landing.on_line);
            if near.stable()
                && !self.landing_holds(&near, lean, false)
                && !self.arrives_turning_back(&near, lean, from_disk)
            {
                // Without the orientation's flow the run steps on.
                continue;
            }
            let far = invariant_distance(z, &near.z) > MAX_SETTLED;
            let (found, may_end) = self.settle(near, lean, far && lean_shrinking);
            if may_end {
                return Some(found);
            }
        }
        None
    }

    /// The root a run turning between the box's two mirror lines next to it ends on. The
    /// run's orientation is the slow coordinate (the near-neutral rotation mode); the
    /// roots on the two lines are the zeros of its flow next to it (by the box's symmetry).
    /// If one is stable and the other unstable in its rotation mode only, the run turns
    /// away from the second towards the first and ends there, provided that both roots have
    /// the run's class and the run's speed and deformation lie between theirs (within
    /// [`crate::runs::landing::FAMILY_TOL`]): it is on the circle of states joining them. Both
    /// stable (two orientations, each with its basin) or both unstable: no decision. The
    /// run must also be turning that way since its last try (`before`, its orientation then)
    /// where nothing else checks that the stable root's basin reaches it
    /// ([`Self::landing_holds`]).
    pub fn turn_root(&mut self, z: &[f64], before: Option<f64>) -> Option<Finding> {
        let quarter = std::f64::consts::FRAC_PI_4;
        let phi = orientation(z);
        let nearest = (phi / quarter).round() * quarter;
        let other = nearest + if phi >= nearest { quarter } else { -quarter };
        let class = class_of(z);
        let mut roots = Vec::with_capacity(2);
        for target in [nearest, other] {
            let found = self.root_near(&turned(z, target - phi)).ok()?;
            let on_line = (orientation(&found.z) - target).sin().abs() < 1e-6;
            if !on_line || class_of(&found.z) != class || found.verdict.unstable > 0 {
                return None;
            }
            roots.push(found);
        }
        let (b, a) = (roots.pop()?, roots.pop()?);
        let (run, ra, rb) = (
            speed_and_deformation(z),
            speed_and_deformation(&a.z),
            speed_and_deformation(&b.z),
        );
        let tol = crate::runs::landing::FAMILY_TOL;
        let between = |x: f64, p: f64, q: f64| x >= p.min(q) - tol && x <= p.max(q) + tol;
        if !(between(run.0, ra.0, rb.0) && between(run.1, ra.1, rb.1)) {
            return None;
        }
        let found = match (a.stable(), b.stable()) {
            (true, false) => a,
            (false, true) => b,
            _ => return None,
        };
        let lean = angle_to(z, &found.z);
        let turning_to = before
            .is_some_and(|phi| lean.abs() < modulo_half_turn(phi - orientation(&found.z)).abs());
        (self.landing_holds(&found, lean, turning_to) && self.within_rotation_basin(&found, lean))
            .then_some(found)
    }

    /// With `landing`, the end of the run at `z` on the stable root its slow flow
    /// lands on ([`Self::landing_root`]).
    /// The flow walks along a mirror line with the run's lean held fixed, so it lands only a
    /// run whose lean is not growing (numerics 7): below the floor, or on the same side of
    /// the same line as at the previous landing try and grown since by at most
    /// [`LEAN_GROWTH`] times the relative change of the run's coordinate (its speed, or its
    /// deformation at rest), so that over the whole departure the lean changes by a small
    /// power of the coordinate's change. A run
    /// turning away from its line (the family's states unstable in rotation on the way) may
    /// end on another orientation than the flow's; it goes on by time stepping, or ends
    /// where it is caught turning to ([`Self::turn_root`]). The first try knows no growth
    /// and lands only a run without lean. Landings on the resting disk (no orientation)
    /// need none of this.
    pub(super) fn land_now(&mut self, z: &[f64]) -> Option<Decision> {
        if !self.landing {
            return None;
        }
        let (line, lean) = lean_from_mirror_line(z);
        let (v, s) = speed_and_deformation(z);
        let coordinate = if v > 1e-9 { v } else { s };
        let before = self.last_lean.replace((line, lean, coordinate));
        let lean_shrinking = before.is_some_and(|(line_before, lean_before, _)| {
            line_before == line && lean.abs() < lean_before.abs()
        });
        let turning_away = lean.abs() >= LEAN_FLOOR
            && before.is_none_or(|(line_before, lean_before, coordinate_before)| {
                line_before != line
                    || lean.signum() != lean_before.signum()
                    || (lean / lean_before).ln()
                        > LEAN_GROWTH * (coordinate / coordinate_before).ln().abs()
            });
        // A landing on the resting disk, which has no orientation, needs no lean.
        let quarter = std::f64::consts::FRAC_PI_4;
        let orientation_before = before
            .filter(|((_, moved), _, _)| *moved == line.1)
            .map(|((multiple, _), lean_before, _)| multiple as f64 * quarter + lean_before);
        let found = if turning_away {
            match self.flow_root(z, false) {
                Some(found) if unoriented(&found.z) => found,
                _ => self.turn_root(z, orientation_before)?,
            }
        } else {
            self.landing_root(z, lean_shrinking, orientation_before)?
        };
        Some(Decision::End(Ending::Landing, found.z))
    }

    /// Whether the landing may end a run leaning by `lean` on `near`, a root stable in
    /// rotation (the one rule of [`Self::flow_root`] and [`Self::turn_root`]): 2-mode runs
    /// always (the orientation's flow then checks the basin); runs with more shape modes,
    /// which have no flow, within [`LINEAR_LEAN`] of it (or on a root with no orientation),
    /// or, caught turning between two mirror lines, if they turn towards it
    /// (`turning_to`). On their grids the lattice puts roots between the box's mirror
    /// lines, so the root stable in rotation on the line next to a run need not be where it
    /// turns to: modes 2..3, N = 96, (0.088, 0.1095) from iv ends 5.9 degrees off the
    /// diagonal, where the slow flow of the diagonal's family lands it (its lean shrinking
    /// towards that root, not the line: a shrinking lean is no licence either, and the
    /// 4-mode map at N = 192 has roots of the lattice 0.2 to 0.5 degrees off the lines); modes 2..3, N = 192,
    /// (0.085, 0.112) from iv, 28 degrees past the y-axis MD (stable in rotation) and
    /// turning away from it, turns on to a root 2.25 degrees short of the diagonal.
    fn landing_holds(&self, near: &Finding, lean: f64, turning_to: bool) -> bool {
        near.verdict.rotation.is_none() || self.lean_holds(lean, turning_to)
    }

    /// The rule on a run's lean shared by the landing ([`Self::landing_holds`]) and the
    /// Newton finish's turned roots: 2-mode runs always; runs with more shape modes within
    /// [`LINEAR_LEAN`] (where the root's own rotation eigenvalue decides), or if they are
    /// turning towards the root (`turning_to`).
    pub(super) fn lean_holds(&self, lean: f64, turning_to: bool) -> bool {
        !self.beyond_two_modes() || lean.abs() <= LINEAR_LEAN || turning_to
    }

    /// The root of a run caught mid-turn, between the box's mirror lines, where Newton from
    /// the run's own state need not converge: Newton from the state turned onto the nearest
    /// mirror line (motion or long axis at a multiple of 45 degrees), then onto the next one
    /// on the other side; the first stable root, else the first root found.
    pub fn aligned_root(&mut self, z: &[f64]) -> Option<Finding> {
        let quarter = std::f64::consts::FRAC_PI_4;
        let phi = orientation(z);
        let nearest = (phi / quarter).round() * quarter;
        let other = nearest + if phi >= nearest { quarter } else { -quarter };
        let mut first = None;
        for target in [nearest, other] {
            let Ok(found) = self.root_near(&turned(z, target - phi)) else {
                continue;
            };
            if found.stable() {
                return Some(found);
            }
            first.get_or_insert(found);
        }
        first
    }
}

#[cfg(test)]
mod tests {
    use crate::contract::settings::SolverSettings;
    use crate::model::params::ModelParams;
    use crate::model::state::speed_and_deformation;
    use crate::runs::finish::NewtonFinish;
    use crate::runs::orientation::orientation;

    #[test]
    fn a_k_mode_run_between_mirror_lines_lands_on_the_stable_ones_root_only_turning_to_it() {
        // Modes 2..3, N = 192, (0.085, 0.112): pure time stepping from iv at t = 1500, 121
        // degrees, between the y-axis MD (stable in rotation) and the diagonal's (unstable in
        // rotation), turning on to a root 2.25 degrees short of the diagonal (t = 18 210).
        let p = ModelParams::at(0.085, 0.112).with_modes(3);
        let settings = SolverSettings {
            n: 192,
            ..SolverSettings::default()
        };
        let mut f = NewtonFinish::new(&p, &settings);
        let z = [
            -0.13618994343820798,
            0.22656697591483954,
            0.08324112946895097,
            -0.039973868618470174,
            0.1593975130540181,
            -0.0020022723949766944,
        ];
        let phi = orientation(&z);
        let degree = 1f64.to_radians();
        assert!(f.turn_root(&z, Some(phi - 0.5 * degree)).is_none());
        assert!(f.turn_root(&z, None).is_none());
        // Turning towards the y axis, it would land there (the MD of results/truncation).
        let y_axis = f
            .turn_root(&z, Some(phi + 0.5 * degree))
            .expect("turning to it");
        assert!(
            (orientation(&y_axis.z) - 90.0 * degree).abs() < 1e-6,
            "{y_axis:?}"
        );
        let (v, _) = speed_and_deformation(&y_axis.z);
        assert!((v - 0.2706023).abs() < 1e-6, "{v}");
    }
}
