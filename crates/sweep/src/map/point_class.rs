//! Point classification from the runs of one point (paper Sect. 3), numerics 4.
//!
//! Rules:
//! - only a run that ended `steady` counts, with its class (IC, ID, MD, MC): with the default
//!   `steady: newton` it ended on a steady state whose eigenvalues (the rotation mode aside)
//!   all decay, so the class names an attractor;
//! - every other run (`t_max`, `step_limit`, `saddle`) is unsettled: it has no class, counts
//!   in `n_unsettled` (and `n_t_max`), and makes its point untrusted
//!   ([`PointClass::settled`]): refinement splits its cells, `status` counts it, the picture
//!   marks it;
//! - a `diverged` run has no class and does not count; it is counted in `n_diverged`;
//! - one distinct class -> that class; two -> a bistable pair written in the order
//!   IC, ID, MD, MC (`IC/MD`, `ID/MD`, `IC/MC`, ...); three or more -> `not classified`;
//!   no class at all: `unsettled` when a run is unsettled, `diverged` when every run
//!   diverged, `missing` when there are no runs.
use crate::store::run_store::RunRecord;
use droplet_solver::contract::ending::Ending;
use droplet_solver::{contract::outcome::RunStatus, model::classify::StateClass};
use std::collections::BTreeSet;

/// Label of a point whose runs gave three or more classes.
pub const NOT_CLASSIFIED: &str = "not classified";
/// Label of a point whose runs all diverged.
pub const DIVERGED: &str = "diverged";
/// Label of a point without finished runs.
pub const MISSING: &str = "missing";
/// Label of a point none of whose runs ended on a stable state (and of such a run in the
/// points table's per-initial-condition columns).
pub const UNSETTLED: &str = "unsettled";

/// Classification of one point.
#[derive(Debug, Clone, PartialEq)]
pub struct PointClass {
    pub label: String,
    pub n_runs: usize,
    pub n_steady: usize,
    /// Runs that stopped at `t_max`, the step cap or beside a saddle.
    pub n_t_max: usize,
    /// Runs that did not end on a stable state (diverged ones aside): all of `n_t_max`.
    pub n_unsettled: usize,
    pub n_diverged: usize,
    /// Steady runs certified without stepping (`refine.certify_midpoints`,
    /// [`crate::map::certify`]).
    pub n_certified: usize,
}

impl PointClass {
    /// Every run of the point ended on a stable state or diverged: its label is trusted.
    pub fn settled(&self) -> bool {
        self.n_unsettled == 0
    }
}

/// Classifies a point from its runs (any order).
pub fn classify_point<'a>(runs: impl IntoIterator<Item = &'a RunRecord>) -> PointClass {
    let mut classes = BTreeSet::new();
    let (mut n_runs, mut n_steady, mut n_t_max, mut n_diverged) = (0, 0, 0, 0);
    let mut n_certified = 0;
    for r in runs {
        n_runs += 1;
        n_certified += usize::from(r.outcome.ended_by == Some(Ending::Certified));
        match r.outcome.status {
            RunStatus::Steady => {
                n_steady += 1;
                if let Some(c) = r.outcome.class {
                    classes.insert(c);
                }
            }
            RunStatus::TMax | RunStatus::StepLimit | RunStatus::Saddle => n_t_max += 1,
            RunStatus::Diverged => n_diverged += 1,
        }
    }
    let label = label_of(&classes, n_runs, n_diverged, n_t_max);
    PointClass {
        label,
        n_runs,
        n_steady,
        n_t_max,
        n_unsettled: n_t_max,
        n_diverged,
        n_certified,
    }
}

/// The label of a point from the classes of its steady runs and its run counts (the rules
/// above; also what `droplet audit` expects of a points table).
pub(crate) fn label_of(
    classes: &BTreeSet<StateClass>,
    n_runs: usize,
    n_diverged: usize,
    n_unsettled: usize,
) -> String {
    let names: Vec<&str> = classes.iter().map(|c| c.as_str()).collect();
    match names.len() {
        0 if n_runs == 0 => MISSING.into(),
        0 if n_unsettled > 0 => UNSETTLED.into(),
        0 if n_diverged > 0 => DIVERGED.into(),
        0 => MISSING.into(),
        1 | 2 => names.join("/"),
        _ => NOT_CLASSIFIED.into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use droplet_solver::{
        contract::outcome::RunOutcome, contract::settings::SolverSettings,
        model::initial::InitialCondition, model::params::ModelParams,
    };

    fn rec(status: RunStatus, class: Option<StateClass>) -> RunRecord {
        RunRecord {
            key: String::new(),
            params: ModelParams::default(),
            ic: InitialCondition::parse("i").unwrap(),
            settings: SolverSettings::default(),
            solver_version: String::new(),
            outcome: RunOutcome {
                status,
                class,
                state: Default::default(),
                v: 0.0,
                s: 0.0,
                t_end: 0.0,
                t_steady: None,
                steps: 0,
                rejected: 0,
                max_step_error: None,
                wall_s: 0.0,
                ended_by: None,
                diagnosis: None,
                t_leapt: 0.0,
                t_projected: 0.0,
                unsettled: None,
                heading: None,
                higher_modes: vec![],
                series: vec![],
                higher_series: vec![],
                profile: Default::default(),
            },
        }
    }

    #[test]
    fn single_bistable_not_classified_and_divergence() {
        use RunStatus::*;
        use StateClass::*;
        let p = |v: Vec<RunRecord>| classify_point(&v).label;
        assert_eq!(p(vec![rec(Steady, Some(IC)); 4]), "IC");
        assert_eq!(
            p(vec![
                rec(Steady, Some(MD)),
                rec(Steady, Some(IC)),
                rec(Steady, Some(IC))
            ]),
            "IC/MD"
        );
        assert_eq!(
            p(vec![rec(Steady, Some(MD)), rec(Steady, Some(ID))]),
            "ID/MD"
        );
        assert_eq!(
            p(vec![
                rec(Steady, Some(MC)),
                rec(Steady, Some(IC)),
                rec(Steady, Some(MD))
            ]),
            NOT_CLASSIFIED
        );
        assert_eq!(p(vec![rec(Diverged, None); 4]), DIVERGED);
        assert_eq!(p(vec![]), MISSING);
    }

    #[test]
    fn unsettled_runs_never_count_and_flag_their_point() {
        use RunStatus::*;
        use StateClass::*;
        // A record from before numerics 4 carried the class of where a t_max run stopped:
        // it does not count either.
        let mixed = vec![
            rec(Steady, Some(ID)),
            rec(Diverged, None),
            rec(TMax, Some(MD)),
            rec(Saddle, None),
        ];
        let c = classify_point(&mixed);
        assert_eq!(
            (
                c.label.as_str(),
                c.n_diverged,
                c.n_t_max,
                c.n_steady,
                c.n_unsettled
            ),
            ("ID", 1, 2, 1, 2)
        );
        assert!(!c.settled());
        let all = classify_point(&[rec(TMax, None), rec(StepLimit, None)]);
        assert_eq!(all.label, UNSETTLED);
        let ok = classify_point(&[rec(Steady, Some(IC)), rec(Diverged, None)]);
        assert!(ok.settled() && ok.label == "IC");
    }
}
