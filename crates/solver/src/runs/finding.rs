//! What a Newton try at a run's state found (the root, its verdict, whether the run must turn
//! to reach it), and the diagnosis of a run that did not settle: a typed reason, the class it
//! was heading to, and a sentence for the `diagnosis` column.
use crate::contract::outcome::Unsettled;
use crate::model::classify::StateClass;
use crate::roots::verdict::Verdict;
use crate::runs::orientation::{class_of, invariant_distance};

/// What a Newton try found: the root, its stability, and whether it is the turned root.
#[derive(Debug, Clone, PartialEq)]
pub struct Finding {
    /// The root, `(vx, vy, a_2..a_K, b_2..b_K)`.
    pub z: Vec<f64>,
    pub verdict: Verdict,
    /// For the root of a turned state (the run is to turn there): the root near the run,
    /// unstable only in its rotation mode, whose speed and deformation the run settles to
    /// before it turns. `None`: the root is the one near the run.
    pub turned_from: Option<Vec<f64>>,
}

impl Finding {
    /// Whether the root is that of a turned state, not the one near the run.
    pub fn turned(&self) -> bool {
        self.turned_from.is_some()
    }

    /// Largest real part of all eigenvalues, the rotation mode included.
    pub fn slowest(&self) -> f64 {
        self.verdict.slowest()
    }

    /// Every eigenvalue decays (the rotation mode included).
    pub fn stable(&self) -> bool {
        self.verdict.decays()
    }

    /// Why a run stopped at `z` (the state Newton started from) is not settled on this root.
    pub fn reason(&self, z: &[f64]) -> Unsettled {
        if self.verdict.unstable > 0 {
            Unsettled::BesideSaddle
        } else if self
            .verdict
            .rotation
            .is_some_and(|r| r >= self.verdict.max_re)
            && invariant_distance(z, &self.z) <= SETTLED_WITHIN
            && class_of(z) == class_of(&self.z)
        {
            Unsettled::Turning
        } else {
            Unsettled::Converging
        }
    }

    /// The class of the root, if it is stable (rotation mode aside): where a run near it
    /// is heading.
    pub fn heading(&self) -> Option<StateClass> {
        (self.verdict.unstable == 0).then(|| class_of(&self.z))
    }

    /// A sentence for the `diagnosis` column of a run stopped at `z` (the state Newton started
    /// from). Only the rotation mode slow and the run's speed and deformation within
    /// [`SETTLED_WITHIN`] of the root's, with its class: [`SETTLED`] (the run only turns).
    pub fn describe(&self, z: &[f64]) -> String {
        let rot = self.verdict.rotation;
        if self.verdict.unstable > 0 {
            format!(
                "{BESIDE_UNSTABLE} ({} growing mode(s), largest {:+.2e})",
                self.verdict.unstable, self.verdict.max_re
            )
        } else if let Some(r) = rot.filter(|r| *r >= self.verdict.max_re) {
            let d = invariant_distance(z, &self.z);
            if d <= SETTLED_WITHIN && class_of(z) == class_of(&self.z) {
                format!(
                    "rotation mode {r:+.2e}: the direction of motion / long axis turns slowly (box effect); {SETTLED}"
                )
            } else {
                format!(
                    "rotation mode {r:+.2e} slowest, but v and s are {d:.1e} from the root's: still on the way"
                )
            }
        } else {
            format!(
                "slowest eigenvalue {:+.2e}: converging slowly",
                self.slowest()
            )
        }
    }
}

/// Largest difference in speed or deformation between a run and the root it is taken to be
/// approaching.
pub const MAX_SETTLED: f64 = 0.05;

/// Largest difference in speed or deformation between a run and its root for the run to be
/// settled (with the root's class) when only the rotation mode is slow: [`MAX_SETTLED`], the
/// bound for a run approaching a root (a run turning between the box's mirror lines differs
/// from the root on one by the box's anisotropy, up to 2e-2 in `v` for the fastest MD).
pub const SETTLED_WITHIN: f64 = MAX_SETTLED;

/// The end of a diagnosis whose run has settled in speed and deformation (only its direction
/// still turns, at the box's slow rotation rate): its class is that of its final state.
pub const SETTLED: &str = "v and s are settled";

/// The start of a diagnosis whose run stopped beside an unstable steady state.
pub const BESIDE_UNSTABLE: &str = "near an unstable steady state";

/// What a run that did not finish was doing when it stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnosis {
    /// A sentence (the `diagnosis` column).
    pub text: String,
    pub reason: Unsettled,
    /// The class of the stable root it was heading to, if one is known.
    pub heading: Option<StateClass>,
}
